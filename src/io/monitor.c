/* The monitor file: a CSV time series a user plots without a script (see io.h). The first line
 * names the columns as "name [unit]"; each row is one monitored time, written by rank 0 and
 * flushed, so a running or killed run leaves every finished row readable. Values are printed with
 * %.17g, so a row holds the doubles of the run exactly. The columns are declared by the drivers
 * before the first row; a row gives a value for every column. At a restart the file is cut back to
 * the rows of the checkpoint (MonCheckpointRead) and continued, so that a preempted run leaves one
 * series as if it had never stopped. Options: -mon_interval (s, 0 = no monitor), -mon_file. */
#include "io/io_private.h"
#include <errno.h>
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
  PetscCall(PetscOptionsString("-mon_file", "Monitor file (CSV); default <io_dir>/<io_prefix>_monitor.csv", NULL, mon->path, mon->path, sizeof mon->path, NULL));
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
  PetscCheck(mon->ncol < MON_MAX_COLS, mon->comm, PETSC_ERR_SUP, "monitor: more than %d columns", MON_MAX_COLS);
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

PetscErrorCode MonCheckpointWrite(Mon mon, IoCkpt ck)
{
  double s[4];

  PetscFunctionBeginUser;
  s[0] = mon->next;
  s[1] = (double)mon->rows;
  s[2] = (double)mon->bytes;
  s[3] = (double)mon->ncol;
  PetscCallMPI(MPI_Bcast(&s[2], 1, MPI_DOUBLE, 0, mon->comm)); /* rank 0 knows the length */
  PetscCall(IoCkptWriteShared(ck, "mon/state", IO_CKPT_REAL, 4, s));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode MonCheckpointRead(Mon mon, IoCkpt ck)
{
  double      s[4];
  PetscBool   has;
  const char *path;

  PetscFunctionBeginUser;
  PetscCall(IoCkptHas(ck, "mon/state", &has));
  if (!has) PetscFunctionReturn(PETSC_SUCCESS); /* written without a monitor: start one now */
  PetscCall(IoCkptReadShared(ck, "mon/state", IO_CKPT_REAL, 4, s));
  if (mon->interval <= 0 || s[1] == 0) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(IoCkptGetPath(ck, &path));
  PetscCheck((PetscInt)s[3] == mon->ncol, mon->comm, PETSC_ERR_FILE_UNEXPECTED, "-restart %s: the dataset mon/state says %d monitor columns, this run has %d", path, (int)s[3], (int)mon->ncol);
  {
    PetscMPIInt rank;
    int         err = 0;
    struct stat st;
    PetscCallMPI(MPI_Comm_rank(mon->comm, &rank));
    if (!rank && (stat(mon->path, &st) != 0 || (long long)st.st_size < (long long)s[2])) err = 1;
    PetscCallMPI(MPI_Bcast(&err, 1, MPI_INT, 0, mon->comm));
    PetscCheck(!err, mon->comm, PETSC_ERR_FILE_UNEXPECTED, "-restart %s: the monitor file %s is missing or shorter than the checkpoint's %lld bytes (give the run's -mon_file, or another one to start a new series)", path, mon->path, (long long)s[2]);
  }
  mon->next    = s[0];
  mon->rows    = (PetscInt)s[1];
  mon->bytes   = (long long)s[2];
  mon->resumed = PETSC_TRUE;
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
