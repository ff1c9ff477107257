/* The drivers' checkpoints (see drivers.h): the options, the cadence, the file names and the
 * rotation that keeps the newest -io_checkpoint_keep; what goes into a checkpoint is the
 * driver's (its write callback), plus the run's own parts both drivers share (DriverCkptWriteRun:
 * the output's continuation under io/, the options the run was given under run/options, the
 * string of PetscOptionsGetAll). At a restart the recorded options are compared with the current
 * ones: a physics option changed, added or removed is one warning line naming it; options of the
 * run's length, output, checkpoints, progress and logging may change silently (a longer
 * -dem_t_end or -cpl_t_end extends a run). On a stop signal the drivers write a checkpoint at the
 * step the ranks agreed on before ending (DriverCkptStop). Files: <io_dir>/<prefix>_checkpoint_<step>.h5.
 * With -io_checkpoint_interval 0 (the default) a run writes none, neither on the way nor at
 * the end, but a stop signal still writes one (a preempted job must be able to continue).
 * Each write is announced by "checkpoint: PATH" and a line with its wall time and size, a
 * restart by "restart: PATH", the time of reading it with the set-up (tools/bench_checkpoint.sh
 * reads both) and where its output goes: the same place goes on, another -io_dir, -io_prefix
 * or -mon_file starts a new series there (IoViewRestart). */
#include <sys/stat.h>

#include "drivers/drivers.h"
#include <ctype.h>
#include <strings.h>

/* The size of file path in MB (0 when it cannot be read). */
static double DriverFileMB(const char *path)
{
  struct stat st;
  return stat(path, &st) ? 0.0 : (double)st.st_size / 1048576.0;
}

PetscErrorCode DriverCkptSetFromOptions(DriverCkpt *c, MPI_Comm comm)
{
  PetscFunctionBeginUser;
  c->comm = comm;
  c->keep = 2;
  c->step = -1;
  PetscOptionsBegin(comm, NULL, "Checkpoints", NULL);
  PetscCall(SableOptionsReal("-io_checkpoint_interval", "Simulated time between exact checkpoints, and one at the end; a stop signal writes one in any case", "s; 0 = none", "[0,inf)", c->dt, &c->dt, NULL));
  PetscCall(SableOptionsInt("-io_checkpoint_keep", "Newest checkpoints of this run kept (older ones removed)", "files", "[1,64]", c->keep, &c->keep, NULL));
  PetscCall(SableOptionsString("-restart", "Continue from this checkpoint instead of inserting particles (the same case options)", c->restart, sizeof c->restart, NULL));
  PetscOptionsEnd();
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DriverCkptWrite(DriverCkpt *c, Io io, PetscInt step, DriverCkptWriter write, void *ctx)
{
  char           suffix[64];
  PetscMPIInt    rank;
  IoCkpt         ck;
  PetscLogDouble t0, t1;

  PetscFunctionBeginUser;
  if (!io || step == c->step) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCallMPI(MPI_Comm_rank(c->comm, &rank));
  if (c->n == c->keep) { /* the oldest goes */
    if (!rank) (void)remove(c->files[0]);
    for (PetscInt k = 1; k < c->n; k++) PetscCall(PetscStrcpy(c->files[k - 1], c->files[k]));
    c->n--;
  }
  PetscCall(PetscSNPrintf(suffix, sizeof suffix, "checkpoint_%06" PetscInt_FMT ".h5", step));
  PetscCall(IoGetFilePath(io, suffix, c->files[c->n], sizeof c->files[0]));
  PetscCallMPI(MPI_Barrier(c->comm)); /* the write's time, not the slowest rank's step */
  PetscCall(PetscTime(&t0));
  PetscCall(IoCkptCreate(c->comm, c->files[c->n], &ck));
  PetscCall(write(ctx, ck));
  PetscCall(IoCkptClose(&ck));
  PetscCall(PetscTime(&t1));
  PetscCall(PetscPrintf(c->comm, "checkpoint: %s\n", c->files[c->n]));
  PetscCall(PetscPrintf(c->comm, "  written in %.3f s, %.1f MB\n", t1 - t0, rank ? 0.0 : DriverFileMB(c->files[c->n])));
  c->n++;
  c->step = step;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DriverCkptStop(DriverCkpt *c, Io io, int sig, PetscReal t, PetscInt step, DriverCkptWriter write, void *ctx)
{
  const char *index = NULL, *ckpt = NULL;

  PetscFunctionBeginUser;
  if (c && io && write) {
    SableStopGraceCancel(); /* a large checkpoint may take longer than the grace */
    PetscCall(DriverCkptWrite(c, io, step, write, ctx));
    ckpt = c->files[c->n - 1]; /* this step's, written now or just before the signal */
  }
  if (io) PetscCall(IoGetIndexPath(io, &index));
  PetscCall(SableStopError(c ? c->comm : PETSC_COMM_WORLD, sig, t, step, ckpt, index));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DriverCkptWriteRun(Io io, IoCkpt ck)
{
  char *all;

  PetscFunctionBeginUser;
  PetscCall(IoCheckpointWrite(io, ck));
  PetscCall(PetscOptionsGetAll(NULL, &all));
  PetscCall(IoCkptWriteShared(ck, "run/options", IO_CKPT_BYTE, (PetscInt)strlen(all), all));
  PetscCall(PetscFree(all));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Whether an option (with its dash) may change at a restart without changing the physics: the
 * run's length, output and checkpoints, time averages, progress, diagnostics and logging, -restart and
 * -options_file. */
static PetscBool driver_option_is_run(const char *o)
{
  const char *pre[]   = {"-io_", "-mon_", "-avg_", "-log", "-info", "-malloc", "-options_", "-help", "-version", "-sable_", "-history", "-memory_view", "-objects_dump"};
  const char *exact[] = {"-restart", "-dem_t_end", "-cpl_t_end", "-dem_progress_interval", "-cpl_progress_interval", "-cpl_probe_z"};

  for (size_t k = 0; k < sizeof pre / sizeof pre[0]; k++)
    if (!strncasecmp(o, pre[k], strlen(pre[k]))) return PETSC_TRUE;
  for (size_t k = 0; k < sizeof exact / sizeof exact[0]; k++)
    if (!strcasecmp(o, exact[k])) return PETSC_TRUE;
  return PETSC_FALSE;
}

/* The options of a PetscOptionsGetAll string: names (with the dash) and values ("" for a flag),
 * pointing into s, which is cut in place; at most max. A name is a word starting with '-' and a
 * letter; a value is what follows it up to the next name ("-dem_gravity 0,0,-9.81", "-x -5"). */
static int driver_options_split(char *s, char **name, char **value, int max)
{
  int n = 0;

  while (*s && n < max) {
    while (*s == ' ') s++;
    if (!(s[0] == '-' && isalpha((unsigned char)s[1]))) { /* a stray word: skipped */
      while (*s && *s != ' ') s++;
      continue;
    }
    name[n] = s;
    while (*s && *s != ' ') s++;
    if (*s) *s++ = 0;
    value[n] = s + strlen(s); /* "" */
    while (*s == ' ') s++;
    if (s[0] == '-' && isalpha((unsigned char)s[1])) { /* a flag: the next name follows */
      n++;
      continue;
    }
    value[n] = s;
    while (*s && !(s[0] == ' ' && s[1] == '-' && isalpha((unsigned char)s[2]))) s++;
    if (*s) *s++ = 0;
    for (size_t l = strlen(value[n]); l && value[n][l - 1] == ' '; l--) value[n][l - 1] = 0;
    n++;
  }
  return n;
}

/* Whether two option values say the same: the same text, or item by item (comma-separated) the
 * same numbers ("0.5" and "5e-1") or the same words. */
static PetscBool driver_values_same(const char *a, const char *b)
{
  if (!strcasecmp(a, b)) return PETSC_TRUE;
  while (*a || *b) {
    char  *ea, *eb;
    double x = strtod(a, &ea), y = strtod(b, &eb);
    size_t la = strcspn(a, ","), lb = strcspn(b, ",");
    if (ea == a + la && eb == b + lb && la && lb) {
      if (x != y) return PETSC_FALSE;
    } else if (la != lb || strncasecmp(a, b, la)) return PETSC_FALSE;
    a += la + (a[la] == ',');
    b += lb + (b[lb] == ',');
  }
  return PETSC_TRUE;
}

/* Collective. One warning line per physics option whose value differs between the checkpoint's
 * run (old, a PetscOptionsGetAll string) and this one, or that only one of them has. */
static PetscErrorCode DriverCompareOptions(MPI_Comm comm, char *old)
{
  enum {
    MAXOPT = 1024
  };
  char *now, **on, **ov, **nn, **nv;
  int   no, nw;

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsGetAll(NULL, &now));
  PetscCall(PetscMalloc4(MAXOPT, &on, MAXOPT, &ov, MAXOPT, &nn, MAXOPT, &nv));
  no = driver_options_split(old, on, ov, MAXOPT);
  nw = driver_options_split(now, nn, nv, MAXOPT);
  for (int pass = 0; pass < 2; pass++) { /* the checkpoint's options, then those added */
    char **an = pass ? nn : on, **av = pass ? nv : ov, **bn = pass ? on : nn, **bv = pass ? ov : nv;
    int    na = pass ? nw : no, nb = pass ? no : nw;
    for (int i = 0; i < na; i++) {
      int j = 0;
      if (driver_option_is_run(an[i])) continue;
      while (j < nb && strcasecmp(an[i], bn[j])) j++;
      if (pass && j < nb) continue; /* compared in the first pass */
      if (j < nb && driver_values_same(av[i], bv[j])) continue;
      const char *was = pass ? "not given" : (av[i][0] ? av[i] : "given"), *is = pass ? (av[i][0] ? av[i] : "given") : (j < nb ? (bv[j][0] ? bv[j] : "given") : "not given");
      PetscCall(PetscPrintf(comm, "restart: %s was %s in the checkpoint's run, now %s: the continued run is not the same physics\n", an[i], was, is));
    }
  }
  PetscCall(PetscFree4(on, ov, nn, nv));
  PetscCall(PetscFree(now));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DriverCkptReadRun(DriverCkpt *c, Io io, Mon mon, IoCkpt ck)
{
  MPI_Comm  comm = c->comm;
  long long n;
  char     *old;

  PetscFunctionBeginUser;
  if (io) PetscCall(IoCheckpointRead(io, ck));
  if (mon) PetscCall(MonCheckpointRead(mon, ck, &c->mon_resumed));
  PetscCall(IoCkptGetSize(ck, "run/options", &n));
  PetscCall(PetscCalloc1(n + 1, &old));
  PetscCall(IoCkptReadShared(ck, "run/options", IO_CKPT_BYTE, (PetscInt)n, old));
  PetscCall(DriverCompareOptions(comm, old));
  PetscCall(PetscFree(old));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DriverCkptRestarted(DriverCkpt *c, PetscLogDouble t0, Io io, Mon mon, PetscReal t)
{
  PetscLogDouble t1;
  PetscMPIInt    rank;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(c->comm, &rank));
  PetscCall(PetscTime(&t1));
  PetscCall(PetscPrintf(c->comm, "restart: %s\n", c->restart));
  PetscCall(PetscPrintf(c->comm, "  read and set up in %.3f s, %.1f MB\n", t1 - t0, rank ? 0.0 : DriverFileMB(c->restart)));
  if (io) {
    const char *mpath = NULL;
    if (mon) PetscCall(MonGetPath(mon, &mpath));
    PetscCall(IoViewRestart(io, mpath, c->mon_resumed, t));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}
