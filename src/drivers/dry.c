/* The dry driver: a DEM run without fluid. It owns the run's length and cadence (-dem_t_end,
 * -dem_progress_interval: simulated seconds), sets the DEM and the balancer up, steps to the end
 * with a progress line (time, step, steps/s, ETA, kinetic energy, contacts, largest overlap over
 * the radius), writes the frames io asks for, stops cleanly on SIGTERM, SIGINT or SIGUSR1
 * (agreed in the DEM step's own reduction; a checkpoint of that step is written first, also
 * without -io_checkpoint_interval, when the scene can be saved), and ends with the summary lines
 * "done:" (simulated time, this run's steps and wall time, after a restart the time and step it
 * started from and the step reached, peak memory), "bed:" (packing fraction, coordination number)
 * and "output:". Never writes a frame of a diverged state (DemCheckHealth first).
 * Checkpoints (-io_checkpoint_interval, simulated seconds; 0, the default: none): an exact
 * checkpoint of the DEM (dem/checkpoint.c) every interval and at the end,
 * <io_dir>/<prefix>_checkpoint_<step>.h5, the newest -io_checkpoint_keep of this run kept, with
 * the balancer's cuts and schedule, the output's continuation and the options
 * (DriverCkptWriteRun); -restart PATH continues from one instead of inserting the case's
 * particles (same options), the cuts restored before the DEM is set up; in the same output place
 * its frames are numbered on and its index grown, in another one a new series starts. */
#include "drivers/average.h"
#include "drivers/drivers.h"
#include <sys/resource.h>

struct _p_DryRun {
  MPI_Comm   comm;
  PetscReal  t_end, progress_dt; /* s */
  PetscBool  t_end_set;
  DriverCkpt ckpt;
  DriverMon  mon;
  DriverAvg  avg; /* time averages (-avg_start) */
  Dem        dem; /* what a checkpoint holds: the DEM's state, the balancer's and the run's (io, options) */
  Balance    lb;  /* may be NULL */
  Io         io;
};

PetscErrorCode DryRunCreate(MPI_Comm comm, DryRun *run)
{
  PetscFunctionBeginUser;
  PetscCall(PetscNew(run));
  (*run)->comm = comm;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DryRunSetFromOptions(DryRun r)
{
  PetscBool help;

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsHasHelp(NULL, &help));
  PetscOptionsBegin(r->comm, NULL, "Dry run (DEM without fluid)", NULL);
  PetscCall(SableOptionsReal("-dem_t_end", "Simulated time to run to; a dry run needs it", "s", "[0,inf)", -1, &r->t_end, &r->t_end_set));
  PetscCall(SableOptionsReal("-dem_progress_interval", "Simulated time between progress lines", "s; 0 = no progress lines", "[0,inf)", r->progress_dt, &r->progress_dt, NULL));
  PetscOptionsEnd();
  PetscCall(DriverCkptSetFromOptions(&r->ckpt, r->comm));
  PetscCall(DriverMonSetFromOptions(&r->mon, r->comm, help)); /* -help lists the monitor's options once, here, with a coupled run's */
  PetscCall(DriverAvgCreate(r->comm, &r->avg));
  PetscCall(DriverAvgSetFromOptions(r->avg));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DryRunDestroy(DryRun *r)
{
  PetscFunctionBeginUser;
  if (*r) PetscCall(DriverMonDestroy(&(*r)->mon));
  if (*r) PetscCall(DriverAvgDestroy(&(*r)->avg));
  PetscCall(PetscFree(*r));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode DryOutput(Dem dem, DriverAvg avg, Io io)
{
  DemStats  st;
  PetscReal t;
  PetscInt  step;

  PetscFunctionBeginUser;
  PetscCall(DemGetStats(dem, &st)); /* never write a diverged state */
  PetscCall(DemCheckHealth(dem, &st));
  PetscCall(DemGetTime(dem, &t, &step));
  PetscCall(IoFrameBegin(io, t, step));
  PetscCall(DemWriteOutput(dem, io));
  PetscCall(DriverAvgWriteOutput(avg, io));
  PetscCall(IoFrameEnd(io));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode DryCheckpointWrite(void *ctx, IoCkpt ck)
{
  DryRun r = (DryRun)ctx;

  PetscFunctionBeginUser;
  PetscCall(DemCheckpointWrite(r->dem, ck));
  if (r->lb) PetscCall(BalanceCheckpointWrite(r->lb, ck));
  PetscCall(DriverCkptWriteRun(r->io, ck));
  PetscCall(MonCheckpointWrite(r->mon.mon, ck));
  PetscCall(DriverAvgCheckpointWrite(r->avg, ck));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. A checkpoint of the loop's objects (r->dem, r->lb, r->io) at the current step. */
static PetscErrorCode DryCheckpoint(DryRun r)
{
  PetscInt step;

  PetscFunctionBeginUser;
  PetscCall(DemGetTime(r->dem, NULL, &step));
  PetscCall(DriverCkptWrite(&r->ckpt, r->io, step, DryCheckpointWrite, r));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. A monitor row when one is due. */
static PetscErrorCode DryMonitor(DryRun r, Dem dem)
{
  DriverMonInput in = {0, 0, dem, NULL, NULL};

  PetscFunctionBeginUser;
  PetscCall(DemGetTime(dem, &in.t, &in.step));
  PetscCall(DriverMonRow(&r->mon, &in));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. The run's length and cadences, against the final time step (after -dem_dt_tc). */
static PetscErrorCode DryCheckRunLength(DryRun r, Dem dem, Io io)
{
  const char    *dtopt;
  PetscReal      t, dt;
  PetscInt       step;
  SableRunLength len;

  PetscFunctionBeginUser;
  PetscCall(DemGetTimeStepOption(dem, &dtopt));
  PetscCall(DemGetTime(dem, &t, &step));
  PetscCall(DemGetTimeStep(dem, &dt));
  len = (SableRunLength){"dem", "time step", dtopt, dtopt, "steps", r->t_end_set, t, r->t_end, dt, r->progress_dt, 0, 1, step, NULL};
  if (io) PetscCall(IoGetInterval(io, &len.io_dt, &len.io_opt));
  PetscCall(SableCheckRunLength(r->comm, &len));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode DryProgress(DryRun r, Dem dem, PetscLogDouble t0, PetscInt s0)
{
  DemStats       st;
  PetscLogDouble now;
  PetscReal      t, dt;
  PetscInt       step;

  PetscFunctionBeginUser;
  PetscCall(DemGetStats(dem, &st));
  PetscCall(DemGetTime(dem, &t, &step));
  PetscCall(DemGetTimeStep(dem, &dt));
  PetscCall(PetscTime(&now));
  const double rate = (step - s0) / PetscMax(now - t0, 1e-9);
  PetscCall(PetscPrintf(r->comm, "t %.4f s  step %" PetscInt_FMT "  %.0f steps/s  ETA %.0f s  KE %.4g J  contacts %" PetscInt_FMT "  max overlap/r %.3g\n", (double)t, step, rate, PetscMax(0.0, (r->t_end - t) / dt / rate), (double)(st.ke + st.ke_rot), st.contacts + st.wall_contacts, (double)st.max_overlap));
  PetscCall(DemCheckHealth(dem, &st));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. Steps from the DEM's time to -dem_t_end; lb may be NULL, io may be NULL (no
 * output). */
PetscErrorCode DryRunLoop(DryRun r, Dem dem, Balance lb, Io io)
{
  PetscLogDouble t0;
  PetscReal      t, dt, next, next_ckpt;
  PetscInt       s0;
  PetscBool      due;
  int            sig;

  PetscFunctionBeginUser;
  PetscCall(DryCheckRunLength(r, dem, io));
  r->dem = dem; /* what a checkpoint of this loop holds */
  r->lb  = lb;
  r->io  = io;
  PetscCall(DemGetTime(dem, &t, &s0));
  PetscCall(DemGetTimeStep(dem, &dt));
  next      = t + r->progress_dt;
  next_ckpt = t + r->ckpt.dt;
  PetscCall(PetscTime(&t0));
  if (io) {
    PetscCall(IoDue(io, t, &due));
    if (due) PetscCall(DryOutput(dem, r->avg, io));
  }
  PetscCall(DryMonitor(r, dem));
  while (t < r->t_end - 0.5 * dt) {
    PetscCall(DemGetStopSignal(dem, &sig)); /* agreed in the last step's reduction */
    if (sig) {                              /* a checkpoint of this step, then the stop */
      PetscInt step;
      PetscCall(DemGetTime(dem, NULL, &step));
      PetscCall(DriverCkptStop(&r->ckpt, io, sig, t, step, DryCheckpointWrite, r));
    }
    PetscCall(DemStep(dem));
    if (lb) PetscCall(BalanceCheck(lb, PETSC_FALSE, NULL));
    PetscCall(DemGetTime(dem, &t, NULL));
    PetscCall(DriverAvgSample(r->avg, t));
    if (io) {
      PetscCall(IoDue(io, t, &due));
      if (due) PetscCall(DryOutput(dem, r->avg, io));
    }
    PetscCall(DryMonitor(r, dem));
    if (r->progress_dt > 0 && t >= next - 0.5 * dt) {
      PetscCall(DryProgress(r, dem, t0, s0));
      next += r->progress_dt;
    }
    if (r->ckpt.dt > 0 && t >= next_ckpt - 0.5 * dt) {
      PetscCall(DryCheckpoint(r));
      next_ckpt += r->ckpt.dt;
    }
  }
  if (io) {
    PetscCall(IoDueFinal(io, t, &due));
    if (due) PetscCall(DryOutput(dem, r->avg, io));
  }
  if (r->ckpt.dt > 0) PetscCall(DryCheckpoint(r)); /* -io_checkpoint_interval 0: none at the end either */
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DryRunCase(DryRun r, Domain *dom, Dem dem, Balance lb, Io io)
{
  PetscBool      convex;
  PetscReal      phi, coord, t, ts;
  PetscInt       step, step0;
  char           seg[160] = "";
  PetscLogDouble t0, t1;
  struct rusage  ru;
  IoCkpt         ck = NULL;

  PetscFunctionBeginUser;
  PetscCall(SableCheckOptionsUsed(r->comm));
  PetscCall(DemHasConvexShapes(dem, &convex));
  PetscCall(PetscPrintf(r->comm, "modules: DEM on; fluid off (dry case); coupling off; convex shapes %s\n", convex ? "on (libccd)" : "off"));
  PetscCall(PetscTime(&t0));
  if (r->ckpt.restart[0]) {
    PetscCall(IoCkptOpen(r->comm, r->ckpt.restart, &ck));
    /* the checkpoint's cuts first: the DEM's per-rank state lives on them */
    if (lb) PetscCall(BalanceCheckpointRead(lb, ck));
    PetscCall(DemSetRestart(dem, ck));
  }
  PetscCall(DemSetUp(dem));                /* a checkpoint of another rank count or format is refused here */
  if (lb) PetscCall(BalanceDecompose(lb)); /* the process grid and cuts from the particles */
  PetscCall(DriverMonSetUp(&r->mon, io));
  PetscCall(DriverAvgSetUp(r->avg, dom, dem, NULL, io));
  if (ck) {
    PetscCall(DriverCkptReadRun(&r->ckpt, io, r->mon.mon, ck)); /* refuses another run's frames before running */
    PetscCall(DemGetTime(dem, &t, NULL));
    PetscCall(DriverAvgCheckpointRead(r->avg, ck, t));
    PetscCall(DemSetRestart(dem, NULL));
    PetscCall(IoCkptClose(&ck));
    PetscCall(DriverCkptRestarted(&r->ckpt, t0, io, r->mon.mon, t));
  }
  PetscCall(DemView(dem, PETSC_VIEWER_STDOUT_WORLD));
  if (lb) PetscCall(BalanceSetUp(lb));
  PetscCall(DemGetTime(dem, &ts, &step0)); /* this run's segment: from here */
  PetscCall(PetscTime(&t0));
  PetscCall(DryRunLoop(r, dem, lb, io));
  PetscCall(PetscTime(&t1));
  if (lb) PetscCall(BalanceView(lb, PETSC_VIEWER_STDOUT_WORLD));
  PetscCall(DemGetTime(dem, &t, &step));
  PetscCall(DemGetBedFigures(dem, &phi, &coord));
  getrusage(RUSAGE_SELF, &ru);
  if (r->ckpt.restart[0]) PetscCall(PetscSNPrintf(seg, sizeof seg, "this run from the restart at t = %g s, step %" PetscInt_FMT ", to step %" PetscInt_FMT "; ", (double)ts, step0, step));
  PetscCall(PetscPrintf(r->comm, "done: t = %g s, %" PetscInt_FMT " steps in %.3f s (%srank 0 peak memory %.1f MB)\n", (double)t, step - step0, t1 - t0, seg, ru.ru_maxrss / 1024.0));
  PetscCall(PetscPrintf(r->comm, "bed: packing fraction %.4f, mean coordination number %.3f\n", (double)phi, (double)coord));
  PetscCall(DemFlowView(dem, PETSC_VIEWER_STDOUT_WORLD)); /* with sources or outlets: the balance */
  PetscCall(DemViewSources(dem, PETSC_VIEWER_STDOUT_WORLD));
  PetscCall(IoView(io, PETSC_VIEWER_STDOUT_WORLD)); /* the frames, their size and write time */
  PetscFunctionReturn(PETSC_SUCCESS);
}
