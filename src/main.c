/* sable: the driver. Reads the options, builds the one decomposition (Domain), decides which
 * modules the scene needs and hands them to a driver (src/drivers): -sable_solver dry or coupled,
 * or by default (auto) a coupled CFD-DEM run when the case gives any -cpl_ or -fluid_ option (a
 * typo of one is named first), a dry DEM run otherwise. -help reads every driver's options and
 * opens no file. User mistakes end with one line
 *   sable: error: <what, which option, which value, which range>
 * and exit status 1 (PETSc's traceback is kept for internal errors, with -sable_traceback). */
#include "sable.h"
#include "domain.h"
#include "dem/dem.h"
#include "io/io.h"
#include "drivers/drivers.h"
#include <ctype.h>
#include <stdarg.h>
#include <errno.h>
#include <sys/stat.h>
#include <signal.h>
#include <unistd.h>
#include <time.h>

static PetscBool sable_traceback = PETSC_FALSE;

/* The first error of this process: its message and whether it was printed. One raised on a
 * communicator smaller than the world's (one rank's error, which the others may not share) is
 * printed at the end, once it is known whether every rank failed. */
static struct {
  char           msg[600];
  PetscErrorCode code;
  int            printed;
} sable_err;
static MPI_Comm sable_end_comm = MPI_COMM_NULL; /* the end-of-run agreement's own communicator */

static void SablePrintError(int rank)
{
  if (sable_err.code == PETSC_ERR_SIG) fprintf(stderr, "sable: stopped: %s\n", sable_err.msg);
  else if (rank >= 0) fprintf(stderr, "sable: error (rank %d): %s\n", rank, sable_err.msg);
  else fprintf(stderr, "sable: error: %s\n", sable_err.msg);
  fflush(stderr);
  sable_err.printed = 1;
}

/* PETSc's messages for a value it cannot parse ("Input string 1,2 has no numeric value",
 * "Unknown logical value: 4") name no option: find the option given that value and name it.
 * Returns 1 when buf holds the completed message. */
static int SableNameParsedOption(const char *mess, char *buf, size_t len)
{
  const char *pre[] = {"Input string ", "Unknown logical value: "};
  char        val[256], *all = NULL, *tok, *save = NULL, *prev = NULL;
  int         found = 0;

  if (!mess) return 0;
  for (int k = 0; k < 2 && !found; k++) {
    size_t n = strlen(pre[k]), m;
    if (strncmp(mess, pre[k], n)) continue;
    snprintf(val, sizeof val, "%s", mess + n);
    m      = k ? strlen(val) : (size_t)(strstr(val, " has no") ? strstr(val, " has no") - val : 0);
    val[m] = 0;
    while (m && isspace((unsigned char)val[m - 1])) val[--m] = 0;
    if (!m || PetscOptionsGetAll(NULL, &all)) return 0;
    for (tok = strtok_r(all, " ", &save); tok && !found; prev = tok, tok = strtok_r(NULL, " ", &save))
      if (prev && prev[0] == '-' && !strcmp(tok, val)) found = snprintf(buf, len, "option %s %s: %s", prev, tok, mess) > 0;
    PetscFree(all);
  }
  return found;
}

static PetscErrorCode SableErrorHandler(MPI_Comm comm, int line, const char *func, const char *file, PetscErrorCode n, PetscErrorType p, const char *mess, void *ctx)
{
  PetscMPIInt rank = 0, size = 1, wsize = 1;

  (void)ctx;
  if (sable_traceback) return PetscTraceBackErrorHandler(comm, line, func, file, n, p, mess, NULL);
  if (p != PETSC_ERROR_INITIAL || sable_err.code) return n;
  MPI_Comm_size(comm, &size);
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &wsize);
  sable_err.code = n;
  if (n == PETSC_ERR_MEM || (func && (strstr(func, "MallocAlign") || strstr(func, "ReallocAlign")))) /* PETSc's message names only the caller */
    snprintf(sable_err.msg, sizeof sable_err.msg, "out of memory in %s: the scene needs more memory than this machine gives one rank (fewer particles or fluid cells, or more ranks)", mess && mess[0] ? mess : (func ? func : "?"));
  else if (!SableNameParsedOption(mess, sable_err.msg, sizeof sable_err.msg)) snprintf(sable_err.msg, sizeof sable_err.msg, "%s", mess && mess[0] ? mess : "unknown error");
  if (wsize == 1 || (size == wsize && !rank)) SablePrintError(-1); /* the other ranks print only if rank 0 turns out not to share it */
  return n;
}

/* The end of a failed run on several ranks. When every rank failed (a mistake all of them see),
 * they agree within SABLE_END_WAIT seconds, one line has been (or is now) printed by rank 0, and
 * all finalize and exit with the same status (Open MPI's mpiexec adds its own note of the
 * non-zero exit; mpiexec -q leaves it out). Otherwise this rank's error is its own: it prints its
 * line with its rank and aborts, the one way to have the launcher end the ranks still waiting
 * at once (a plain exit costs a second more) at the price of Open MPI's MPI_ABORT notice; those
 * ranks, blocked, end on the launcher's SIGTERM without a line of their own (stop.c). */
#define SABLE_END_WAIT 0.5
static int SableEndParallel(int status)
{
  MPI_Request req;
  int         done = 0, rank = 0;
  double      t0 = MPI_Wtime();

  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Ibarrier(sable_end_comm, &req);
  while (!done && MPI_Wtime() - t0 < SABLE_END_WAIT) {
    MPI_Test(&req, &done, MPI_STATUS_IGNORE);
    if (!done) nanosleep(&(struct timespec){0, 1000000}, NULL);
  }
  if (done) {
    if (!rank && !sable_err.printed) SablePrintError(-1);
    MPI_Comm_free(&sable_end_comm);
    PetscFinalize();
    return status;
  }
  if (!sable_err.printed) SablePrintError(rank);
  MPI_Abort(MPI_COMM_WORLD, status);
  _exit(status);
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

/* The bytes of line n (len bytes, newline removed) before it is split: a NUL or another
 * control byte (any but a tab or CR, which PETSc's reader blanks; a vertical tab or form feed
 * would stay in a token there) means a file that is not text (an HDF5 or image file given by
 * mistake), a byte-order mark an editor's UTF-8 header that PETSc would read as part of the first
 * name.
 * Returns 1 after printing the error. */
static int SableCheckLineBytes(const char *path, int n, const char *line, size_t len)
{
  if (memchr(line, 0, len)) {
    SableEarlyError("-options_file %s, line %d: contains a NUL byte (not a text file?)", path, n);
    return 1;
  }
  if (n == 1 && len >= 3 && !memcmp(line, "\xef\xbb\xbf", 3)) {
    SableEarlyError("-options_file %s, line 1: starts with a UTF-8 byte-order mark (save the file as plain text without it)", path);
    return 1;
  }
  for (size_t k = 0; k < len; k++) {
    const unsigned char c = (unsigned char)line[k];
    if ((c < 0x20 && c != '\t' && c != '\r') || c == 0x7f) {
      SableEarlyError("-options_file %s, line %d: contains the control byte 0x%02x at column %d (not a text file?)", path, n, c, (int)k + 1);
      return 1;
    }
  }
  if (len > 4095) {
    SableEarlyError("-options_file %s, line %d: longer than 4095 characters", path, n);
    return 1;
  }
  return 0;
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
  char       *line = NULL;
  size_t      cap  = 0;
  ssize_t     len;
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
  while (!bad && (len = getline(&line, &cap, fp)) >= 0) {
    char *tok[3] = {NULL, NULL, NULL}, *c;
    int   nt;
    n++;
    if (len > 0 && line[len - 1] == '\n') line[--len] = 0;
    if ((bad = SableCheckLineBytes(path, n, line, (size_t)len))) break;
    if ((c = strchr(line, '#'))) *c = 0;
    nt = SableOptionsTokens(line, tok);
    if (!nt || !strcmp(tok[0], "alias")) continue;
    if (!SableIsKey(tok[0])) { /* a dash pasted from a document is U+2013, U+2014 or U+2212 */
      const PetscBool dash = (PetscBool)(!strncmp(tok[0], "\xe2\x80\x93", 3) || !strncmp(tok[0], "\xe2\x80\x94", 3) || !strncmp(tok[0], "\xe2\x88\x92", 3));
      SableEarlyError("-options_file %s, line %d: '%s' is not an option (%s)", path, n, tok[0], dash ? "it starts with a typographic dash, not the ASCII '-'" : "a line is -name value");
      bad = 1;
    } else if (nt > 2) {
      SableEarlyError("-options_file %s, line %d: %s has more than one value (lists are comma-separated; quote a value with blanks)", path, n, tok[0]);
      bad = 1;
    } else if (nt == 2 && SablePetscKey(tok[1])) { /* PETSc's reader stops with a traceback */
      SableEarlyError("-options_file %s, line %d: %s is followed by another option, %s (one option per line)", path, n, tok[0], tok[1]);
      bad = 1;
    }
  }
  free(line);
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

/* The background grid of a dry run only decomposes space: its cell is 4 largest diameters by
 * default, so a rank box is never thinner than the halo (2 r_max + skin); with load balancing it
 * is the granularity of the cuts, 1.25 diameters (the balancer keeps boxes >= the halo). A
 * coupled run's grid is the fluid's (-da_grid_x/y/z or -domain_cell). */
static PetscErrorCode SableRun(void)
{
  Domain     dom;
  Dem        dem;
  Io         io;
  Balance    lb;
  DryRun     dry;
  CoupledRun wet;
  PetscBool  help, coupled, balanced;
  PetscReal  rmax;

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsHasHelp(NULL, &help));
  PetscOptionsBegin(PETSC_COMM_WORLD, NULL, "Sable driver", NULL);
  PetscCall(SableOptionsBool("-sable_traceback", "Print PETSc's full traceback on errors", sable_traceback, &sable_traceback, NULL));
  PetscOptionsEnd();
  if (!help) PetscCall(PetscPrintf(PETSC_COMM_WORLD, "Sable %s — CFD-DEM for fluidized beds and granular flows\n", SABLE_VERSION));
  PetscCall(DriverIsCoupled(&coupled)); /* before any module: an unknown -fluid_ or -cpl_ name must not decide it */
  PetscCall(DomainSetFromOptions(PETSC_COMM_WORLD, &dom));
  PetscCall(DemCreate(&dom, &dem));
  PetscCall(DemSetFromOptions(dem));
  PetscCall(DemExternalSetFromOptions(dem));
  PetscCall(IoCreate(PETSC_COMM_WORLD, &io));
  PetscCall(IoSetFromOptions(io));
  PetscCall(BalanceCreate(&dom, dem, NULL, &lb));
  PetscCall(BalanceSetFromOptions(lb));
  PetscCall(DemGetLargestRadius(dem, &rmax));
  PetscCall(BalanceIsActive(lb, &balanced));
  PetscCall(DomainSetUp(&dom, (balanced ? 2.5 : 8) * rmax + 1e-300, 1));
  if (coupled || help) { /* -help lists every driver's options */
    PetscCall(CoupledRunCreate(&dom, &wet));
    PetscCall(CoupledRunSetFromOptions(wet));
    PetscCall(CoupledRunCase(wet, dem, lb, io, help));
    PetscCall(CoupledRunDestroy(&wet));
  }
  if (!coupled || help) {
    PetscCall(DryRunCreate(PETSC_COMM_WORLD, &dry));
    PetscCall(DryRunSetFromOptions(dry));
    if (!help) PetscCall(DryRunCase(dry, &dom, dem, lb, io));
    PetscCall(DryRunDestroy(&dry));
  }
  PetscCall(BalanceDestroy(&lb));
  PetscCall(DemDestroy(&dem));
  PetscCall(IoDestroy(&io));
  PetscCall(DomainDestroy(&dom));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* What -help prints first (PETSc prints it when -help is given). */
static const char SableHelpHeader[] = "Sable " SABLE_VERSION ": parallel CFD-DEM for fluidized beds and granular flows. Particles (DEM: spheres,\n"
                                      "polyhedra, walls, meshes, sources, outlets) alone (a dry run), or coupled to an incompressible\n"
                                      "fluid on a Cartesian grid (a CFD-DEM run).\n"
                                      "Run a case:  mpiexec -n 4 bin/sable -options_file cases/settle/quick.opts [-name value ...]\n"
                                      "A case is a file of options, one \"-name value\" a line; the command line adds to it or overrides it.\n"
                                      "The run is coupled when any -fluid_ or -cpl_ option is given, dry otherwise (or as -sable_solver says).\n"
                                      "Below: Sable's options by prefix, each \"-name <default>: what (unit; range)\"; a value the case\n"
                                      "gives shows as <value (default ...)>; an indexed family (-dem_plane_<k>) is listed once with its\n"
                                      "index range, then the members the case gives. PETSc's options follow.\n"
                                      "The guide to the options, with examples: doc/options.md; the output files: doc/output.md.\n";

int main(int argc, char **argv)
{
  PetscErrorCode ierr;
  PetscMPIInt    size;
  int            status;

  if (SableCheckOptionsFiles(argc, argv)) return 1;
  SableHelpBegin(); /* -help: Sable's options first, grouped by prefix, then PETSc's (options.c) */
  PetscCall(PetscInitialize(&argc, &argv, NULL, SableHelpHeader));
  PetscCall(PetscPushErrorHandler(SableErrorHandler, NULL));
  PetscCallMPI(MPI_Comm_dup(MPI_COMM_WORLD, &sable_end_comm));
  ierr = SableSignalsInstall();
  if (!ierr) ierr = SableCheckOptionValues(PETSC_COMM_WORLD);
  if (!ierr) ierr = SableRun();
  if (ierr) {
    SableTempRemove(); /* a frame or index being written when the error came */
    status = ierr == PETSC_ERR_SIG ? 128 + (SableSignalCaught() ? SableSignalCaught() : SIGTERM) : 1;
    PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));
    if (size > 1) return SableEndParallel(status);
    PetscFinalize();
    return status;
  }
  PetscCall(SableHelpFlush()); /* -help: while the options are there to mark the values a case gave */
  PetscCallMPI(MPI_Comm_free(&sable_end_comm));
  PetscCall(PetscPopErrorHandler());
  PetscCall(PetscFinalize());
  return 0;
}
