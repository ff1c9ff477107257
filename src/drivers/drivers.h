/* The run drivers: the dry loop (dry.c) and the coupled loop (coupled.c), their options (the
 * run's length and progress cadence), progress lines and summaries. main builds the Domain, the
 * Dem, the Balance and the Io, picks a driver and hands them over. Life cycle of each driver:
 * XRunCreate -> XRunSetFromOptions -> XRunCase (sets up, runs, reports) -> XRunDestroy.
 * All collective. */
#pragma once
#include "balance/balancer.h"

/* Whether the options ask for a coupled run: any -cpl_ or -fluid_ option given (the fluid has
 * defaults for all its properties, so one fluid option is enough to ask for it). */
PetscErrorCode DriverIsCoupled(PetscBool *on);

/* Checkpoints, shared by both drivers (checkpoint.c): -io_checkpoint_interval (s, 0 = none; one
 * also at the end), -io_checkpoint_keep (newest kept), -restart PATH. */
#define DRIVER_KEEP_MAX 64
typedef struct {
  MPI_Comm  comm;
  PetscReal dt; /* -io_checkpoint_interval (s; 0: none) */
  PetscBool set;
  PetscInt  keep, n, step;                              /* kept, written so far, step of the last one */
  char      files[DRIVER_KEEP_MAX][PETSC_MAX_PATH_LEN]; /* the newest ones written, oldest first */
  char      restart[PETSC_MAX_PATH_LEN];                /* -restart ("" for none) */
} DriverCkpt;
typedef PetscErrorCode (*DriverCkptWriter)(void *ctx, IoCkpt ck);
PetscErrorCode DriverCkptSetFromOptions(DriverCkpt *c, MPI_Comm comm);
/* Collective. Writes <io_dir>/<prefix>_checkpoint_<step>.h5 through write (once per step; not
 * without io), announces it ("checkpoint: PATH") and removes this run's checkpoints beyond the
 * newest -io_checkpoint_keep. */
PetscErrorCode DriverCkptWrite(DriverCkpt *c, Io io, PetscInt step, DriverCkptWriter write, void *ctx);
/* Collective. Announces the restart ("restart: PATH") and its wall time since t0 (PetscTime
 * before the checkpoint was opened) with the file's size. */
PetscErrorCode DriverCkptRestarted(DriverCkpt *c, PetscLogDouble t0);

/* The dry run: -dem_t_end (s, required), -dem_progress_interval (s, 0 = none). */
typedef struct _p_DryRun *DryRun;
PetscErrorCode            DryRunCreate(MPI_Comm comm, DryRun *run);
PetscErrorCode            DryRunSetFromOptions(DryRun run);
/* Sets up the Dem (options read) and the Balance, runs, prints the summary lines; lb and io
 * may be NULL (no balancing, no output). */
PetscErrorCode DryRunCase(DryRun run, Domain *dom, Dem dem, Balance lb, Io io);
/* The loop alone (the Dem set up): from the DEM's time to -dem_t_end; lb and io may be NULL. */
PetscErrorCode DryRunLoop(DryRun run, Dem dem, Balance lb, Io io);
PetscErrorCode DryRunDestroy(DryRun *run);

/* The coupled run: -cpl_t_end (s, required), -cpl_progress_interval (s), -cpl_probe_z z1,z2 (m). */
typedef struct _p_CoupledRun *CoupledRun;
PetscErrorCode                CoupledRunCreate(Domain *dom, CoupledRun *run);
PetscErrorCode                CoupledRunSetFromOptions(CoupledRun run);
/* Builds the Fluid and the coupling beside dem (options read, not set up), sets everything up,
 * runs and prints the summary. With help set it only reads the options (-help lists them). */
PetscErrorCode CoupledRunCase(CoupledRun run, Dem dem, Balance lb, Io io, PetscBool help);
PetscErrorCode CoupledRunDestroy(CoupledRun *run);
