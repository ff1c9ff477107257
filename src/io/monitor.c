/* The monitor file: a CSV time series a user plots without a script (see io.h). The first line
 * names the columns as "name [unit]"; each row is one monitored time, written by rank 0 and
 * flushed, so a running or killed run leaves every finished row readable. Values are printed with
 * %.17g, so a row holds the doubles of the run exactly. The columns are declared by the drivers
 * before the first row; a row gives a value for every column. At a restart into the same file (by
 * its absolute path, recorded in the checkpoint) the file is cut back to the rows of the
 * checkpoint (MonCheckpointRead) and continued, so that a preempted run leaves one series as if it
 * had never stopped; a restart into another file (another -io_dir or -io_prefix, or -mon_file)
 * starts a new series there from the checkpoint's time, leaving the old file as it is. Options:
 * -mon_interval (s, 0 = no monitor), -mon_file. */
#include "io/io_private.h"
#include <errno.h>
#include <libgen.h>
#include <limits.h>
#include <stdlib.h>
#include <unistd.h>
#include <sys/stat.h>

#define MON_MAX_COLS 1024

struct _p_Mon {
  MPI_Comm  comm;
  PetscReal interval, next;
  char      path[PETSC_MAX_PATH_LEN];
  char      name[MON_MAX_COLS][64], unit[MON_MAX_COLS][24];
  PetscInt  ncol, rows;
  long long bytes; /* rank 0: length of the file after the last row */
  FILE     *fp;    /* rank 0, open from the first row on */
  PetscBool open, resumed;
};

PetscErrorCode MonCreate(MPI_Comm comm, Mon *mon)
{
  PetscFunctionBeginUser;
  PetscCall(PetscNew(mon));
  (*mon)->comm = comm;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode MonSetFromOptions(Mon mon)
{
  PetscFunctionBeginUser;
  PetscOptionsBegin(mon->comm, NULL, "Monitor (a CSV time series)", NULL);
  PetscCall(SableOptionsReal("-mon_interval", "Simulated time between monitor rows", "s; 0 = no monitor file", "[0,inf)", mon->interval, &mon->interval, NULL));
  PetscCall(SableOptionsString("-mon_file", "Monitor file (CSV); default <io_dir>/<io_prefix>_monitor.csv", mon->path, sizeof mon->path, NULL));
  PetscOptionsEnd();
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode MonSetUp(Mon mon, Io io)
{
  char dflt[PETSC_MAX_PATH_LEN];

  PetscFunctionBeginUser;
  if (mon->interval > 0 && !mon->path[0]) {
    PetscCall(IoGetFilePath(io, "monitor.csv", dflt, sizeof dflt));
    PetscCall(PetscStrncpy(mon->path, dflt, sizeof mon->path));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode MonIsActive(Mon mon, PetscBool *on)
{
  PetscFunctionBeginUser;
  *on = (PetscBool)(mon && mon->interval > 0);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode MonAddColumn(Mon mon, const char *name, const char *unit)
{
  PetscFunctionBeginUser;
  PetscCheck(!mon->open, mon->comm, PETSC_ERR_ORDER, "monitor column %s added after the first row", name);
  PetscCheck(mon->ncol < MON_MAX_COLS, mon->comm, PETSC_ERR_SUP, "monitor: more than %d columns: the -mon_ families give too many (fewer probes, boxes, lines or planes, or fewer -mon_average_fields)", MON_MAX_COLS);
  PetscCall(PetscStrncpy(mon->name[mon->ncol], name, sizeof mon->name[0]));
  PetscCall(PetscStrncpy(mon->unit[mon->ncol], unit, sizeof mon->unit[0]));
  mon->ncol++;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode MonGetColumnCount(Mon mon, PetscInt *n)
{
  PetscFunctionBeginUser;
  *n = mon->ncol;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode MonCheckColumn(Mon mon, PetscInt c, const char *name, const char *unit)
{
  PetscBool same_name = PETSC_FALSE, same_unit = PETSC_FALSE;

  PetscFunctionBeginUser;
  PetscCheck(c >= 0 && c < mon->ncol, PETSC_COMM_SELF, PETSC_ERR_PLIB, "monitor: a value for column %d (%s [%s]); the header has %d columns", (int)c, name, unit, (int)mon->ncol);
  PetscCall(PetscStrncmp(mon->name[c], name, sizeof mon->name[0], &same_name));
  PetscCall(PetscStrncmp(mon->unit[c], unit, sizeof mon->unit[0], &same_unit));
  PetscCheck(same_name && same_unit, PETSC_COMM_SELF, PETSC_ERR_PLIB, "monitor: the value of %s [%s] in column %d, whose header is %s [%s]", name, unit, (int)c, mon->name[c], mon->unit[c]);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode MonDue(Mon mon, PetscReal t, PetscBool *due)
{
  PetscFunctionBeginUser;
  /* the tolerance of IoDue: t is a sum of steps */
  *due = (PetscBool)(mon->interval > 0 && t >= mon->next - 1e-6 * mon->interval);
  if (*due) mon->next = (PetscFloorReal(t / mon->interval + 1e-6) + 1) * mon->interval;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Rank 0: opens the file (a new one, or the restarted run's, cut to its checkpoint's rows) and
 * writes the header of a new one. Returns an errno (0: fine). */
static int MonOpen(Mon mon)
{
  if (mon->resumed) {
    if (truncate(mon->path, (off_t)mon->bytes) != 0) return errno;
    mon->fp = fopen(mon->path, "a");
    return mon->fp ? 0 : errno;
  }
  mon->fp = fopen(mon->path, "w");
  if (!mon->fp) return errno;
  for (PetscInt c = 0; c < mon->ncol; c++) fprintf(mon->fp, "%s%s [%s]", c ? "," : "", mon->name[c], mon->unit[c]);
  fputc('\n', mon->fp);
  return 0;
}

PetscErrorCode MonWriteRow(Mon mon, const PetscReal *v)
{
  PetscMPIInt rank;
  int         err = 0;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(mon->comm, &rank));
  if (!rank) {
    if (!mon->open) err = MonOpen(mon);
    for (PetscInt c = 0; !err && c < mon->ncol; c++) fprintf(mon->fp, "%s%.17g", c ? "," : "", (double)v[c]);
    if (!err) {
      fputc('\n', mon->fp);
      if (fflush(mon->fp) != 0) err = errno ? errno : EIO;
      else mon->bytes = (long long)ftell(mon->fp);
    }
  }
  PetscCallMPI(MPI_Bcast(&err, 1, MPI_INT, 0, mon->comm));
  PetscCheck(!err, mon->comm, PETSC_ERR_FILE_WRITE, "-mon_file %s: cannot write (%s)", mon->path, strerror(err));
  if (!mon->open) PetscCall(PetscPrintf(mon->comm, "monitor: %s%s\n", mon->path, mon->resumed ? " (continued)" : ""));
  mon->open = PETSC_TRUE;
  mon->rows++;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode MonGetPath(Mon mon, const char **path)
{
  PetscFunctionBeginUser;
  *path = mon->interval > 0 ? mon->path : NULL;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Rank 0. The absolute form of path, whether the file exists or not: its directory resolved
 * (to "" when the directory does not exist either). */
static void mon_abspath(const char *path, char abs[PATH_MAX])
{
  char d[PATH_MAX], b[PATH_MAX], dir[PATH_MAX];

  abs[0] = 0;
  if (strlen(path) >= PATH_MAX) return;
  strcpy(d, path);
  strcpy(b, path);
  if (!realpath(dirname(d), dir)) return;
  if (strlen(dir) + strlen(basename(b)) + 2 > PATH_MAX) return;
  snprintf(abs, PATH_MAX, "%s/%s", dir, basename(b));
}

PetscErrorCode MonCheckpointWrite(Mon mon, IoCkpt ck)
{
  double      s[4];
  char        abs[PATH_MAX] = "";
  PetscMPIInt rank;

  PetscFunctionBeginUser;
  s[0] = mon->next;
  s[1] = (double)mon->rows;
  s[2] = (double)mon->bytes;
  s[3] = (double)mon->ncol;
  PetscCallMPI(MPI_Bcast(&s[2], 1, MPI_DOUBLE, 0, mon->comm)); /* rank 0 knows the length */
  PetscCall(IoCkptWriteShared(ck, "mon/state", IO_CKPT_REAL, 4, s));
  if (mon->interval > 0) {
    PetscCallMPI(MPI_Comm_rank(mon->comm, &rank));
    if (!rank) mon_abspath(mon->path, abs);
    PetscCallMPI(MPI_Bcast(abs, sizeof abs, MPI_CHAR, 0, mon->comm));
    if (abs[0]) PetscCall(IoCkptWriteShared(ck, "mon/file", IO_CKPT_BYTE, (PetscInt)strlen(abs), abs));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. Whether this run's monitor file is the one of the checkpoint's run: by the absolute
 * path it recorded; a checkpoint without one (an older format) counts as the same file when this
 * run's holds at least the checkpoint's bytes. */
static PetscErrorCode MonSameFile(Mon mon, IoCkpt ck, long long bytes, PetscBool *same)
{
  PetscBool   has;
  PetscMPIInt rank;
  char        abs[PATH_MAX];
  struct stat st;

  PetscFunctionBeginUser;
  PetscCall(IoCkptHas(ck, "mon/file", &has));
  PetscCallMPI(MPI_Comm_rank(mon->comm, &rank));
  if (has) {
    long long n;
    char     *old;
    PetscCall(IoCkptGetSize(ck, "mon/file", &n));
    PetscCall(PetscCalloc1(n + 1, &old));
    PetscCall(IoCkptReadShared(ck, "mon/file", IO_CKPT_BYTE, (PetscInt)n, old));
    if (!rank) mon_abspath(mon->path, abs);
    *same = (PetscBool)(!rank && abs[0] && !strcmp(abs, old));
    PetscCall(PetscFree(old));
  } else *same = (PetscBool)(!rank && stat(mon->path, &st) == 0 && (long long)st.st_size >= bytes);
  PetscCallMPI(MPI_Bcast(same, 1, MPIU_BOOL, 0, mon->comm));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode MonCheckpointRead(Mon mon, IoCkpt ck, PetscBool *resumed)
{
  double      s[4];
  PetscBool   has, same;
  const char *path;

  PetscFunctionBeginUser;
  if (resumed) *resumed = PETSC_FALSE;
  PetscCall(IoCkptHas(ck, "mon/state", &has));
  if (!has) PetscFunctionReturn(PETSC_SUCCESS); /* written without a monitor: start one now */
  PetscCall(IoCkptReadShared(ck, "mon/state", IO_CKPT_REAL, 4, s));
  if (mon->interval <= 0 || s[1] == 0) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(MonSameFile(mon, ck, (long long)s[2], &same));
  if (!same) PetscFunctionReturn(PETSC_SUCCESS); /* a new series: the header, then a row at once */
  PetscCall(IoCkptGetPath(ck, &path));
  PetscCheck((PetscInt)s[3] == mon->ncol, mon->comm, PETSC_ERR_FILE_UNEXPECTED, "-restart %s: the monitor file %s has %d columns, this run has %d (other -mon_ options, or a Sable that writes other columns): continue with the checkpoint's monitor options, or give another -mon_file, -io_dir or -io_prefix to start a new series", path, mon->path, (int)s[3], (int)mon->ncol);
  {
    PetscMPIInt rank;
    int         err = 0;
    struct stat st;
    PetscCallMPI(MPI_Comm_rank(mon->comm, &rank));
    if (!rank && (stat(mon->path, &st) != 0 || (long long)st.st_size < (long long)s[2])) err = 1;
    PetscCallMPI(MPI_Bcast(&err, 1, MPI_INT, 0, mon->comm));
    PetscCheck(!err, mon->comm, PETSC_ERR_FILE_UNEXPECTED, "-restart %s: the monitor file %s of the checkpoint's run is missing or shorter than the checkpoint's %lld bytes (give another -mon_file, -io_dir or -io_prefix to start a new series)", path, mon->path, (long long)s[2]);
  }
  mon->next    = s[0];
  mon->rows    = (PetscInt)s[1];
  mon->bytes   = (long long)s[2];
  mon->resumed = PETSC_TRUE;
  if (resumed) *resumed = PETSC_TRUE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode MonDestroy(Mon *mon)
{
  PetscFunctionBeginUser;
  if (!*mon) PetscFunctionReturn(PETSC_SUCCESS);
  if ((*mon)->fp) fclose((*mon)->fp);
  PetscCall(PetscFree(*mon));
  PetscFunctionReturn(PETSC_SUCCESS);
}
