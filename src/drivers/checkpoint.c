/* The drivers' checkpoints (see drivers.h): the options, the cadence, the file names and the
 * rotation that keeps the newest -io_checkpoint_keep; what goes into a checkpoint is the
 * driver's (its write callback). Files: <io_dir>/<prefix>_checkpoint_<step>.h5. Each write is
 * announced by "checkpoint: PATH" and a line with its wall time and size, a restart by
 * "restart: PATH" and the time of reading it with the set-up (tools/bench_checkpoint.sh reads
 * both). */
#include <sys/stat.h>
#include "drivers/drivers.h"

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
  PetscCall(SableOptionsReal("-io_checkpoint_interval", "Simulated time between exact checkpoints, and one at the end", "s; 0 = none", "[0,inf)", c->dt, &c->dt, &c->set));
  PetscCall(SableOptionsInt("-io_checkpoint_keep", "Newest checkpoints of this run kept (older ones removed)", "files", "[1,64]", c->keep, &c->keep, NULL));
  PetscCall(PetscOptionsString("-restart", "Continue from this checkpoint instead of inserting particles (the same case options)", NULL, c->restart, c->restart, sizeof c->restart, NULL));
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

PetscErrorCode DriverCkptRestarted(DriverCkpt *c, PetscLogDouble t0)
{
  PetscLogDouble t1;
  PetscMPIInt    rank;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(c->comm, &rank));
  PetscCall(PetscTime(&t1));
  PetscCall(PetscPrintf(c->comm, "restart: %s\n", c->restart));
  PetscCall(PetscPrintf(c->comm, "  read and set up in %.3f s, %.1f MB\n", t1 - t0, rank ? 0.0 : DriverFileMB(c->restart)));
  PetscFunctionReturn(PETSC_SUCCESS);
}
