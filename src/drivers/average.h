/* Time averages, shared by both drivers (average.c): from -avg_start, running means and RMS
 * fluctuations per cell of the Domain's grid (the fluid grid; a dry run's background grid) of
 * the solids fraction, the fluid velocity (coupled runs) and the mass-weighted particle
 * velocity, written into every frame as the cell fields avg_* and rms_*, carried by checkpoints.
 * Life cycle: DriverAvgCreate -> DriverAvgSetFromOptions -> DriverAvgSetUp -> (per step)
 * DriverAvgSample, (per frame) DriverAvgWriteOutput -> DriverAvgDestroy. Every call is a no-op
 * without -avg_start. All collective. */
#pragma once
#include "dem/dem.h"
#include "fluid/fluid.h"

typedef struct _p_DriverAvg *DriverAvg;
PetscErrorCode               DriverAvgCreate(MPI_Comm comm, DriverAvg *avg);
/* Reads -avg_start (s; default: no averages) and -avg_interval (s; 0 = every step). */
PetscErrorCode DriverAvgSetFromOptions(DriverAvg avg);
/* After the Dem (and the Fluid, NULL in a dry run) are set up: the accumulators on dom's grid;
 * announces the averages ("averages: ..."). io may be NULL. */
PetscErrorCode DriverAvgSetUp(DriverAvg avg, Domain *dom, Dem dem, Fluid fluid, Io io);
/* After a step that ended at simulated time t: a sample when one is due (t > -avg_start, and
 * -avg_interval since the last one). Follows the Domain when the balancer changed it. */
PetscErrorCode DriverAvgSample(DriverAvg avg, PetscReal t);
/* Into the open frame of io: the averages so far (nothing before the first sample). */
PetscErrorCode DriverAvgWriteOutput(DriverAvg avg, Io io);
/* The accumulators in a checkpoint (avg/state, avg/sums in the grid's natural ordering), and
 * back at a restart at time t, on any rank count: a checkpoint whose window started at the same
 * -avg_start continues its sums; otherwise the averages start at the restart (with a warning
 * when t is inside the window). */
PetscErrorCode DriverAvgCheckpointWrite(DriverAvg avg, IoCkpt ck);
PetscErrorCode DriverAvgCheckpointRead(DriverAvg avg, IoCkpt ck, PetscReal t);
PetscErrorCode DriverAvgDestroy(DriverAvg *avg);
