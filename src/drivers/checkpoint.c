/* The drivers' checkpoints (see drivers.h): the options, the cadence, the file names and the
 * rotation that keeps the newest -io_checkpoint_keep; what goes into a checkpoint is the
 * driver's (its write callback). Files: <io_dir>/<prefix>_checkpoint_<step>.h5. */
#include "drivers/drivers.h"

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
  char        suffix[64];
  PetscMPIInt rank;
  IoCkpt      ck;

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
  PetscCall(IoCkptCreate(c->comm, c->files[c->n], &ck));
  PetscCall(write(ctx, ck));
  PetscCall(IoCkptClose(&ck));
  PetscCall(PetscPrintf(c->comm, "checkpoint: %s\n", c->files[c->n]));
  c->n++;
  c->step = step;
  PetscFunctionReturn(PETSC_SUCCESS);
}
