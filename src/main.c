/* sable: the driver. Reads the options, builds the one decomposition (Domain), decides which
 * modules the scene needs, runs, reports. A case with any -cpl_ or -fluid_ option is a coupled
 * CFD-DEM run (src/coupling/run.c); otherwise the dry DEM path below. User mistakes end with one line
 *   sable: error: <what, which option, which value, which range>
 * and exit status 1 (PETSc's traceback is kept for internal errors, with -sable_traceback). */
#include "sable.h"
#include "domain.h"
#include "dem/dem.h"
#include "io/io.h"
#include "coupling/coupling.h"
#include <ctype.h>
#include <stdarg.h>
#include <errno.h>
#include <sys/stat.h>
#include <sys/resource.h>

static PetscBool sable_traceback = PETSC_FALSE;

static PetscErrorCode SableErrorHandler(MPI_Comm comm, int line, const char *func, const char *file, PetscErrorCode n, PetscErrorType p, const char *mess, void *ctx)
{
  PetscMPIInt rank = 0, size = 1, wsize = 1;

  (void)ctx;
  if (sable_traceback) return PetscTraceBackErrorHandler(comm, line, func, file, n, p, mess, NULL);
  if (p != PETSC_ERROR_INITIAL) return n;
  MPI_Comm_size(comm, &size);
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &wsize);
  if (!rank || size == 1) {
    char        buf[512];
    const char *what = mess;
    if (n == PETSC_ERR_MEM || (func && (strstr(func, "MallocAlign") || strstr(func, "ReallocAlign")))) { /* PETSc's message names only the caller */
      snprintf(buf, sizeof buf, "out of memory in %s: the scene needs more memory than this machine gives one rank (fewer particles or fluid cells, or more ranks)", mess && mess[0] ? mess : (func ? func : "?"));
      what = buf;
    }
    if (size == 1 && wsize > 1) { /* one rank's error: say which */
      int wr = 0;
      MPI_Comm_rank(MPI_COMM_WORLD, &wr);
      fprintf(stderr, "sable: error (rank %d): %s\n", wr, what ? what : "unknown error");
    } else fprintf(stderr, "sable: error: %s\n", what ? what : "unknown error");
    fflush(stderr);
  }
  return n;
}

/* An error before MPI starts: printed by the first process only (under mpiexec every process
 * checks the same files). */
static void SableEarlyError(const char *fmt, ...)
{
  const char *r = getenv("OMPI_COMM_WORLD_RANK");
  va_list     ap;

  if (!r) r = getenv("PMI_RANK");
  if (r && strcmp(r, "0")) return;
  fputs("sable: error: ", stderr);
  va_start(ap, fmt);
  vfprintf(stderr, fmt, ap);
  va_end(ap);
  fputc('\n', stderr);
}

/* Splits a line of an options file into at most 3 tokens, as PETSc does: blanks separate, a
 * double-quoted string is one token. Returns the count (3 means "3 or more"). */
static int SableOptionsTokens(char *line, char *tok[3])
{
  int n = 0;
  for (char *c = line; *c && n < 3;) {
    while (*c && isspace((unsigned char)*c)) c++;
    if (!*c) break;
    if (*c == '"') {
      tok[n++] = ++c;
      while (*c && *c != '"') c++;
    } else {
      tok[n++] = c;
      while (*c && !isspace((unsigned char)*c)) c++;
    }
    if (*c) *c++ = 0;
  }
  return n;
}

/* A command-line token is an option's name when it is a dash and a letter (or two dashes and a
 * letter, as PETSc allows); "-1.5" is a value. */
static int SableIsKey(const char *t)
{
  if (t[0] == '-' && t[1] == '-') t++;
  return t[0] == '-' && isalpha((unsigned char)t[1]);
}

/* PETSc's test of a key (PetscOptionsValidKey), which its options-file reader applies to a
 * line's second token: as SableIsKey, but "-inf" and "-nan" are numbers. */
static int SablePetscKey(const char *t)
{
  char *end;
  if (!SableIsKey(t)) return 0;
  if (t[1] == '-') t++;
  (void)strtod(t, &end);
  return end == t || *end == '_' || isalnum((unsigned char)*end);
}

/* PETSc's own messages for a bad options file are tracebacks: check each -options_file first
 * and say what is wrong in one line (file, line, text). A line is "-name [value]", "alias -a -b"
 * or blank; # starts a comment; a key may start with -- as PETSc allows. */
static int SableCheckOptionsFile(const char *path)
{
  struct stat st;
  char        line[4096];
  int         n = 0, bad = 0;
  FILE       *fp;

  if (stat(path, &st) == 0 && S_ISDIR(st.st_mode)) {
    SableEarlyError("-options_file %s: is a directory, not a file of options", path);
    return 1;
  }
  fp = fopen(path, "r");
  if (!fp) {
    SableEarlyError("-options_file %s: cannot open (%s)", path, strerror(errno));
    return 1;
  }
  while (!bad && fgets(line, sizeof line, fp)) {
    char *tok[3] = {NULL, NULL, NULL}, *c = strchr(line, '#');
    int   nt;
    n++;
    if (!strchr(line, '\n') && !feof(fp)) {
      SableEarlyError("-options_file %s, line %d: longer than 4095 characters", path, n);
      bad = 1;
      break;
    }
    if (c) *c = 0;
    nt = SableOptionsTokens(line, tok);
    if (!nt || !strcmp(tok[0], "alias")) continue;
    if (!SableIsKey(tok[0])) {
      SableEarlyError("-options_file %s, line %d: '%s' is not an option (a line is -name value)", path, n, tok[0]);
      bad = 1;
    } else if (nt > 2) {
      SableEarlyError("-options_file %s, line %d: %s has more than one value (lists are comma-separated; quote a value with blanks)", path, n, tok[0]);
      bad = 1;
    } else if (nt == 2 && SablePetscKey(tok[1])) { /* PETSc's reader stops with a traceback */
      SableEarlyError("-options_file %s, line %d: %s is followed by another option, %s (one option per line)", path, n, tok[0], tok[1]);
      bad = 1;
    }
  }
  fclose(fp);
  return bad;
}

/* PETSc ignores a second value after an option without a word ("-dem_restitution 0.5 0.9"):
 * refuse it, naming the option. */
static int SableCheckCommandLine(int argc, char **argv)
{
  for (int i = 1; i < argc; i++) {
    if (SableIsKey(argv[i])) continue;
    if (i == 1 || !SableIsKey(argv[i - 1])) {
      if (i == 1) SableEarlyError("'%s' is not an option (options are -name value)", argv[i]);
      else SableEarlyError("%s has more than one value ('%s' follows '%s'; lists are comma-separated)", argv[i - 2], argv[i], argv[i - 1]);
      return 1;
    }
  }
  return 0;
}

static int SableCheckOptionsFiles(int argc, char **argv)
{
  if (SableCheckCommandLine(argc, argv)) return 1;
  for (int i = 1; i < argc; i++)
    if (!strcmp(argv[i], "-options_file")) {
      if (i + 1 == argc || argv[i + 1][0] == 0) {
        SableEarlyError("-options_file needs a file name");
        return 1;
      }
      if (SableCheckOptionsFile(argv[i + 1])) return 1;
    }
  return 0;
}

static PetscErrorCode SableRun(void)
{
  Domain    dom;
  Dem       dem;
  Io        io;
  PetscBool help, coupled, convex;
  PetscReal phi, coord, t;
  PetscInt  step;
  PetscLogDouble t0, t1;
  const char *index;
  Balance     lb;

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsHasHelp(NULL, &help));
  PetscOptionsBegin(PETSC_COMM_WORLD, NULL, "Sable driver", NULL);
  PetscCall(PetscOptionsBool("-sable_traceback", "Print PETSc's full traceback on errors", NULL, sable_traceback, &sable_traceback, NULL));
  PetscOptionsEnd();
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "Sable %s — CFD-DEM for fluidized beds and granular flows\n", SABLE_VERSION));
  /* dry case: the background grid only decomposes space; its cell is 4 largest diameters by
     default, so a rank box is never thinner than the halo (2 r_max + skin); with load balancing
     it is the granularity of the cuts, 1.25 diameters (the balancer keeps boxes >= the halo) */
  {
    PetscReal r[32], rmax = 0.0069;
    PetscInt  nr = 32;
    PetscBool set, no_lb;
    char      scheme[64] = "none";
    PetscCall(PetscOptionsGetRealArray(NULL, NULL, "-dem_radius", r, &nr, &set));
    if (set)
      for (PetscInt i = 0; i < nr; i++) rmax = i ? PetscMax(rmax, r[i]) : r[i];
    PetscCall(PetscOptionsGetString(NULL, NULL, "-lb_scheme", scheme, sizeof scheme, NULL));
    PetscCall(PetscStrcasecmp(scheme, "none", &no_lb));
    PetscCall(DomainCreate(PETSC_COMM_WORLD, (no_lb ? 8 : 2.5) * PetscAbsReal(rmax) + 1e-300, 1, &dom));
  }
  PetscCall(DemCreate(&dom, &dem));
  PetscCall(DemSetFromOptions(dem));
  PetscCall(DemExternalSetFromOptions(dem));
  PetscCall(IoCreate(PETSC_COMM_WORLD, &io));
  PetscCall(IoSetFromOptions(io));
  PetscCall(CplRequested(&coupled));
  if (coupled || help) { /* any -cpl_ or -fluid_ option: the coupled path (src/coupling/run.c); -help lists all */
    PetscCall(CplRunCase(&dom, dem, io, help));
    PetscCall(DemDestroy(&dem));
    PetscCall(IoDestroy(&io));
    PetscCall(DomainDestroy(&dom));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  if (help) { /* every object has printed its options */
    PetscCall(DemDestroy(&dem));
    PetscCall(IoDestroy(&io));
    PetscCall(DomainDestroy(&dom));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(BalanceCreate(&dom, dem, NULL, &lb));
  PetscCall(BalanceSetFromOptions(lb));
  PetscCall(SableCheckOptionsUsed(PETSC_COMM_WORLD));
  PetscCall(DemHasConvexShapes(dem, &convex));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "modules: DEM on; fluid off (dry case); coupling off; convex shapes %s; process grid %" PetscInt_FMT " x %" PetscInt_FMT " x %" PetscInt_FMT "\n", convex ? "on (libccd)" : "off", dom.nranks[0], dom.nranks[1], dom.nranks[2]));
  PetscCall(DemSetUp(dem));
  PetscCall(DemView(dem, PETSC_VIEWER_STDOUT_WORLD));
  PetscCall(BalanceSetUp(lb));
  PetscCall(BalanceAttach(lb));
  PetscCall(PetscTime(&t0));
  PetscCall(DemRun(dem, io));
  PetscCall(PetscTime(&t1));
  PetscCall(BalanceView(lb, PETSC_VIEWER_STDOUT_WORLD));
  PetscCall(BalanceDestroy(&lb));
  PetscCall(DemGetTime(dem, &t, &step));
  PetscCall(DemGetBedFigures(dem, &phi, &coord));
  {
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "done: t = %g s, %" PetscInt_FMT " steps in %.3f s (rank 0 peak memory %.1f MB)\n", (double)t, step, t1 - t0, ru.ru_maxrss / 1024.0));
  }
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "bed: packing fraction %.4f, mean coordination number %.3f\n", (double)phi, (double)coord));
  PetscCall(IoGetIndexPath(io, &index));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, index ? "output: %s (open it in ParaView)\n" : "output: none (-io_interval 0)\n", index));
  PetscCall(DemDestroy(&dem));
  PetscCall(IoDestroy(&io));
  PetscCall(DomainDestroy(&dom));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  PetscErrorCode ierr;
  PetscMPIInt    size;

  if (SableCheckOptionsFiles(argc, argv)) return 1;
  PetscCall(PetscInitialize(&argc, &argv, NULL, "sable: parallel CFD-DEM. Options: see -help.\n"));
  PetscCall(PetscPushErrorHandler(SableErrorHandler, NULL));
  ierr = SableCheckOptionValues(PETSC_COMM_WORLD);
  if (!ierr) ierr = SableRun();
  if (ierr) {
    PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));
    if (size > 1) MPI_Abort(PETSC_COMM_WORLD, 1); /* another rank may wait in a collective */
    PetscFinalize();
    return 1;
  }
  PetscCall(PetscPopErrorHandler());
  PetscCall(PetscFinalize());
  return 0;
}
