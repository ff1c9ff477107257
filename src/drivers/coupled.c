/* The coupled driver: builds the Fluid and the coupling beside the given Dem, prints the modules
 * and the pre-flight figures, runs to -cpl_t_end (simulated seconds) with a progress line every
 * -cpl_progress_interval, writes particles and fluid in the same output frames, and reports the
 * column figures: the pressure drop across the domain along gravity against the bed's buoyant
 * weight per cross-section area (the fluidization check) and the drag on the particles against
 * the same weight, averaged over the second half of the run (the weight is taken again whenever
 * sources or outlets changed the particle set: the means use the weight at the end); with
 * -cpl_probe_z, the packed-bed figures (dp/L between two heights, the porosity there and the
 * drag law's own prediction).
 * The bed: at the start, its height (95% of the solids mass below, the monitor's bed_height_95),
 * its porosity between the 5% and 95% heights, the minimum fluidization velocity of the drag law
 * at that porosity and of Wen & Yu, and the inlet's superficial velocity over them; at the end,
 * the height at the start, its mean over the progress lines of the second half, and at the end.
 * A one-way run (-cpl_mode oneway) has no bed lines: its fluid sees no porosity.
 * With -fluid_adaptive_dt the coupling steps vary in whole DEM steps (coupling/exchange.c): the
 * loop's end and cadences are then judged to half a DEM step (the run ends at the first step
 * end from -cpl_t_end on, as the steps do not look at the end: restarts stay exact).
 * A run is coupled when -sable_solver says so, or (auto, the default) when any -cpl_ or -fluid_
 * option is given (DriverIsCoupled).
 * Checkpoints (-io_checkpoint_interval, simulated seconds, 0 = none; drivers/checkpoint.c): the
 * DEM's, the fluid's and the coupling's exact state, and the driver's own (run/coupled: the sums
 * of the column figures and the next progress and checkpoint times), every interval and at the
 * end, and on a stop signal; -restart PATH continues from one, so the restarted run's frames and
 * summary are those of the uninterrupted run. Its "done:" line counts this run's fluid steps and
 * wall time, and names the restart's time and step and the step reached. */
#include "drivers/average.h"
#include "drivers/drivers.h"

struct _p_CoupledRun {
  MPI_Comm   comm;
  Domain    *dom;
  PetscReal  t_end, progress_dt, probe[2]; /* s, s, m */
  PetscBool  t_end_set, probe_set;
  DriverCkpt ckpt;
  DriverMon  mon;
  DriverAvg  avg; /* time averages (-avg_start) */
};

/* The solver mode, -sable_solver: auto (coupled when any -fluid_ or -cpl_ option is given), dry
 * or coupled. A -fluid_ or -cpl_ name that Sable does not know (a typo) is named first, so that
 * it never decides the mode; then an option of the other mode is refused, saying why the run is
 * what it is. Under -help the mode is only read (both drivers list their options). */
static const char *const DriverSolverNames[] = {"auto", "dry", "coupled"};

PetscErrorCode DriverIsCoupled(PetscBool *on)
{
  const char *dry[2] = {"-dem_t_end", "-dem_progress_interval"}, *wet[2] = {"-cpl_t_end", "-cpl_progress_interval"};
  MPI_Comm    comm = PETSC_COMM_WORLD;
  PetscInt    mode = 0;
  PetscBool   help;
  char       *all, *tok, *save = NULL, first[128] = "", why[192];

  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, NULL, "Solver mode", NULL);
  PetscCall(SableOptionsEnum("-sable_solver", "The run: auto (a coupled CFD-DEM run when any -fluid_ or -cpl_ option is given, a dry DEM run otherwise), dry or coupled (options of the other mode are then refused)", DriverSolverNames, 3, 0, &mode, NULL));
  PetscOptionsEnd();
  PetscCall(PetscOptionsHasHelp(NULL, &help));
  if (!help) {
    PetscCall(SableCheckOptionsKnown(comm, "-fluid_"));
    PetscCall(SableCheckOptionsKnown(comm, "-cpl_"));
  }
  PetscCall(PetscOptionsGetAll(NULL, &all)); /* the first -fluid_ or -cpl_ option given */
  for (tok = strtok_r(all, " ", &save); tok && !first[0]; tok = strtok_r(NULL, " ", &save))
    if (!strncmp(tok, "-fluid_", 7) || !strncmp(tok, "-cpl_", 5)) PetscCall(PetscStrncpy(first, tok, sizeof first));
  PetscCall(PetscFree(all));
  *on = (PetscBool)(mode == 2 || (mode == 0 && first[0]));
  if (help) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCheck(mode != 1 || !first[0], comm, PETSC_ERR_ARG_INCOMP, "-sable_solver dry: %s is an option of coupled runs (remove it, or give -sable_solver coupled)", first);
  if (mode == 2) PetscCall(PetscStrncpy(why, "-sable_solver coupled", sizeof why));
  else PetscCall(PetscSNPrintf(why, sizeof why, "it has %s: remove it for a dry run", first));
  for (int k = 0; k < 2 && *on; k++) {
    PetscBool set;
    PetscCall(PetscOptionsHasName(NULL, NULL, dry[k], &set));
    PetscCheck(!set, comm, PETSC_ERR_ARG_INCOMP, "%s applies to dry runs; this run is coupled (%s): use %s", dry[k], why, wet[k]);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CoupledRunCreate(Domain *dom, CoupledRun *run)
{
  PetscFunctionBeginUser;
  PetscCall(PetscNew(run));
  (*run)->comm = dom->comm;
  (*run)->dom  = dom;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CoupledRunSetFromOptions(CoupledRun r)
{
  const Domain *dom = r->dom;

  PetscFunctionBeginUser;
  PetscOptionsBegin(r->comm, NULL, "Coupled run (CFD-DEM)", NULL);
  PetscCall(SableOptionsReal("-cpl_t_end", "Simulated time of a coupled run; a coupled run needs it", "s", "[0,inf)", -1, &r->t_end, &r->t_end_set));
  PetscCall(SableOptionsReal("-cpl_progress_interval", "Simulated time between progress lines", "s; 0 = no progress lines", "[0,inf)", r->progress_dt, &r->progress_dt, NULL));
  PetscCall(SableOptionsRealN("-cpl_probe_z", "Two heights z1,z2 between which the run reports dp/L, porosity and the drag law's prediction; default no report", "m", r->probe, 0, 2, &r->probe_set));
  PetscOptionsEnd();
  PetscCheck(!r->probe_set || (r->probe[0] >= dom->lo[2] && r->probe[0] < r->probe[1] && r->probe[1] <= dom->hi[2]), r->comm, PETSC_ERR_ARG_OUTOFRANGE, "-cpl_probe_z %g,%g: need lo <= z1 < z2 <= hi with the domain's z range [%g, %g] (m)", (double)r->probe[0], (double)r->probe[1], (double)dom->lo[2], (double)dom->hi[2]);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CoupledRunDestroy(CoupledRun *r)
{
  PetscFunctionBeginUser;
  if (*r) PetscCall(DriverMonDestroy(&(*r)->mon));
  if (*r) PetscCall(DriverAvgDestroy(&(*r)->avg));
  PetscCall(PetscFree(*r));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The column along gravity: its axis (the largest component of g; z when there is none), the
 * sign of g along it, and the cross-section area normal to it (m^2; in a vessel that cuts the
 * grid its open area at the column's bottom face, CplGetOpenArea). */
typedef struct {
  int       d;
  PetscReal down, area;
} Column;

static Column ColumnFromGravity(const Domain *dom, const PetscReal g[3])
{
  Column c = {2, -1, 0};

  for (int k = 1; k >= 0; k--)
    if (PetscAbsReal(g[k]) > PetscAbsReal(g[c.d])) c.d = k;
  c.down = g[c.d] > 0 ? 1 : -1;
  c.area = dom->len[(c.d + 1) % 3] * dom->len[(c.d + 2) % 3];
  return c;
}

/* Buoyant weight of the bed per cross-section area (Pa), along gravity. */
static PetscErrorCode CoupledBedWeight(Cpl cpl, const Column *c, PetscReal *w)
{
  PetscReal wv[3];

  PetscFunctionBeginUser;
  PetscCall(CplGetBuoyantWeight(cpl, wv));
  *w = PetscAbsReal(wv[c->d]) / c->area;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Pressure at the bottom of the column (upstream of gravity) less that at its top (Pa): along a
 * bounded axis the means over the open end faces (FluidFacePressure: the face pressure, not the
 * first cell centre's, so the drop does not depend on the height of the first cell); along a
 * periodic one the end layers' means. */
static PetscErrorCode CoupledColumnDrop(Cpl cpl, Fluid fl, const Domain *dom, const Column *c, PetscReal *dp)
{
  PetscReal p0, p1, e, u;

  PetscFunctionBeginUser;
  if (!dom->periodic[c->d] && dom->cells[c->d] >= 2) {
    PetscCall(FluidFacePressure(fl, c->d, 0, &p0));
    PetscCall(FluidFacePressure(fl, c->d, 1, &p1));
  } else {
    PetscCall(CplGetLayer(cpl, c->d, dom->lo[c->d], NULL, &p0, &e, &u));
    PetscCall(CplGetLayer(cpl, c->d, dom->hi[c->d], NULL, &p1, &e, &u));
  }
  *dp = c->down < 0 ? p0 - p1 : p1 - p0;
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode CoupledProbeReport(CoupledRun r, Cpl cpl)
{
  PetscReal p0, p1, e0, e1, u0, u1, eps, pred, dpdl, z0, z1;

  PetscFunctionBeginUser;
  PetscCall(CplGetLayer(cpl, 2, r->probe[0], &z0, &p0, &e0, &u0));
  PetscCall(CplGetLayer(cpl, 2, r->probe[1], &z1, &p1, &e1, &u1));
  PetscCall(CplMeanPorosity(cpl, 2, z0, z1, &eps));
  dpdl = (p0 - p1) / (z1 - z0);
  PetscCall(CplGetPackedBedGradient(cpl, eps, u0, &pred));
  PetscCall(PetscPrintf(r->comm, "packed bed: dp/L %.15g Pa/m, porosity %.15f, superficial velocity %.6g m/s, drag law predicts %.6g Pa/m (ratio %.5f)\n", (double)dpdl, (double)eps, (double)u0, (double)pred, (double)(dpdl / pred)));
  PetscFunctionReturn(PETSC_SUCCESS);
}
/* The objects of one coupled run, and what its loop carries from step to step. */
typedef struct {
  CoupledRun r;
  Dem        dem;
  Fluid      fl;
  Cpl        cpl;
  Balance    lb;
  Io         io;
  PetscBool  frozen; /* -dem_frozen: no DEM steps, the step is the fluid's */
  Column     col;
  PetscReal  avg, davg, navg;    /* sums over the second half of the run: pressure drop, drag, steps */
  PetscReal  h0, eps0, hsum, hn; /* bed at the start: height (m), porosity; height sum (m) and count over the second half's progress lines */
  PetscReal  next, next_ckpt;    /* simulated times of the next progress line and checkpoint */
  PetscInt   s0;                 /* the step the loop started from (the progress line's rate) */
  PetscInt   wflow;              /* particles inserted + removed when the bed's weight was last taken */
} Coupled;

#define COUPLED_CKPT_NRUN 10 /* run/coupled: avg, davg, navg, next, next_ckpt, the window's start, h0, eps0, hsum, hn */

static PetscErrorCode CoupledCheckpointWrite(void *ctx, IoCkpt ck)
{
  const Coupled  *c                    = (const Coupled *)ctx;
  const PetscReal v[COUPLED_CKPT_NRUN] = {c->avg, c->davg, c->navg, c->next, c->next_ckpt, 0.5 * c->r->t_end, c->h0, c->eps0, c->hsum, c->hn};

  PetscFunctionBeginUser;
  PetscCall(DemCheckpointWrite(c->dem, ck));
  PetscCall(FluidCheckpointWrite(c->fl, ck));
  PetscCall(CplCheckpointWrite(c->cpl, ck));
  PetscCall(BalanceCheckpointWrite(c->lb, ck));
  PetscCall(IoCkptWriteShared(ck, "run/coupled", IO_CKPT_REAL, COUPLED_CKPT_NRUN, v));
  PetscCall(DriverCkptWriteRun(c->io, ck));
  PetscCall(MonCheckpointWrite(c->r->mon.mon, ck));
  PetscCall(DriverAvgCheckpointWrite(c->r->avg, ck));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode CoupledCheckpoint(Coupled *c)
{
  PetscInt step;

  PetscFunctionBeginUser;
  PetscCall(CplGetTime(c->cpl, NULL, &step));
  PetscCall(DriverCkptWrite(&c->r->ckpt, c->io, step, CoupledCheckpointWrite, c));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. A monitor row when one is due (st: the last coupling step's, NULL before the first). */
static PetscErrorCode CoupledMonitor(const Coupled *c, const CplStats *st)
{
  DriverMonInput in = {0, 0, c->dem, c->fl, st};

  PetscFunctionBeginUser;
  PetscCall(CplGetTime(c->cpl, &in.t, &in.step));
  PetscCall(DriverMonRow(&c->r->mon, &in));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode CoupledOutput(const Coupled *c)
{
  PetscReal t;
  PetscInt  step;

  PetscFunctionBeginUser;
  if (!c->frozen) { /* never write a diverged state */
    DemStats ds;
    PetscCall(DemGetStats(c->dem, &ds));
    PetscCall(DemCheckHealth(c->dem, &ds));
  }
  PetscCall(CplGetTime(c->cpl, &t, &step));
  PetscCall(IoFrameBegin(c->io, t, step));
  PetscCall(DemWriteOutput(c->dem, c->io));
  PetscCall(FluidWriteOutput(c->fl, c->io));
  PetscCall(DriverAvgWriteOutput(c->r->avg, c->io));
  PetscCall(IoFrameEnd(c->io));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. The run's length and cadences: its steps are coupling steps, and the counter
 * that must hold them the DEM's (substeps per coupling step) or, frozen, the fluid's. */
static PetscErrorCode CoupledCheckRunLength(const Coupled *c)
{
  char           dtopt[64];
  PetscReal      dtd, t, dt;
  PetscInt       s0, step, substeps;
  SableRunLength len;

  PetscFunctionBeginUser;
  PetscCall(DemGetTimeStep(c->dem, &dtd));
  PetscCall(DemGetTime(c->dem, NULL, &s0));
  PetscCall(CplGetTime(c->cpl, &t, &step));
  PetscCall(CplGetTimeStep(c->cpl, &dt));
  PetscCall(CplGetSubsteps(c->cpl, &substeps));
  len         = (SableRunLength){"cpl", "coupling step", dtopt, c->frozen ? "-fluid_dt" : "-dem_dt", c->frozen ? "fluid steps" : "DEM steps", c->r->t_end_set, t, c->r->t_end, dt, c->r->progress_dt, 0, c->frozen ? 1 : substeps, step, NULL};
  len.counter = PetscMax(s0, step);
  if (c->frozen) PetscCall(PetscSNPrintf(dtopt, sizeof dtopt, "-fluid_dt"));
  else PetscCall(PetscSNPrintf(dtopt, sizeof dtopt, "-cpl_substeps %d x -dem_dt %g s", (int)substeps, (double)dtd));
  PetscCall(IoGetInterval(c->io, &len.io_dt, &len.io_opt));
  PetscCall(SableCheckRunLength(c->r->comm, &len));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode CoupledProgress(const Coupled *c, const CplStats *st, PetscLogDouble t0, PetscReal dp, PetscReal w)
{
  DemStats       ds;
  PetscLogDouble now;
  PetscReal      t, dt;
  PetscInt       step, clipped;

  PetscFunctionBeginUser;
  PetscCall(DemGetStats(c->dem, &ds));
  PetscCall(CplGetTime(c->cpl, &t, &step));
  PetscCall(CplGetTimeStep(c->cpl, &dt));
  PetscCall(CplGetClippedCount(c->cpl, &clipped));
  PetscCall(PetscTime(&now));
  const double rate = (step - c->s0) / PetscMax(now - t0, 1e-9);
  PetscCall(PetscPrintf(c->r->comm, "t %.5g  step %" PetscInt_FMT "  %.1f steps/s  ETA %.0f s  KE %.4g  contacts %" PetscInt_FMT "  eps_min %.3f  clipped %" PetscInt_FMT "  Poisson its %" PetscInt_FMT "  dp/W %.4f  drag/W %.4f  |owed| %.3g\n", (double)t, step, rate, PetscMax(0.0, (c->r->t_end - t) / dt / rate), (double)ds.ke, ds.contacts + ds.wall_contacts, (double)st->eps_min, clipped, st->fluid.poisson_its, (double)(dp / w), (double)(-c->col.down * st->drag[c->col.d] / (w * c->col.area)), (double)st->owed_norm));
  if (!c->frozen) PetscCall(DemCheckHealth(c->dem, &ds));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. The inlet's superficial velocity (m/s: the mean through the column's bottom face
 * layer) and the minimum fluidization velocities of the particles present (their Sauter mean
 * diameter and density) at the start's bed porosity if packed, else at -cpl_umf_porosity. */
static PetscErrorCode CoupledBedFluidization(const Coupled *c, PetscReal *u, CplFluidization *f, CplUmfPorosity *why)
{
  const Domain *dom = c->r->dom;
  PetscReal     p, e, d32, rhop, eps;

  PetscFunctionBeginUser;
  PetscCall(CplGetLayer(c->cpl, c->col.d, c->col.down < 0 ? dom->lo[c->col.d] : dom->hi[c->col.d], NULL, &p, &e, u));
  *u = PetscAbsReal(*u);
  PetscCall(CplGetBedDiameter(c->cpl, &d32, &rhop));
  *why = CplGetUmfPorosity(c->cpl, c->eps0, &eps);
  PetscCall(CplGetMinFluidization(c->cpl, eps, d32, rhop, f));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. The bed line at the start; a restarted run keeps the first run's start figures. */
static PetscErrorCode CoupledBedStart(Coupled *c)
{
  CplFluidization f;
  PetscReal       h5, h95, mean, u;
  char            inlet[128] = "", at[160] = "";
  CplUmfPorosity  why;
  CplMode         mode;

  PetscFunctionBeginUser;
  PetscCall(CplGetMode(c->cpl, &mode));
  if (mode == CPL_MODE_ONEWAY) PetscFunctionReturn(PETSC_SUCCESS); /* no bed in the fluid: porosity 1 */
  if (!c->r->ckpt.restart[0]) {
    PetscCall(DemGetBedHeights(c->dem, 0.05, &h5, &mean));
    PetscCall(DemGetBedHeights(c->dem, 0.95, &h95, &mean));
    if (h5 == 0 && h95 == 0) PetscFunctionReturn(PETSC_SUCCESS); /* no particles */
    c->h0 = h95;
    PetscCall(CplMeanPorosity(c->cpl, c->col.d, PetscMin(h5, h95), PetscMax(h5, h95), &c->eps0));
  }
  if (c->h0 == 0 && c->eps0 == 0) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(CoupledBedFluidization(c, &u, &f, &why));
  if (u > 0 && f.umf > 0) PetscCall(PetscSNPrintf(inlet, sizeof inlet, "; inlet superficial velocity %.4g m/s = %.3g U_mf (%.3g Wen-Yu)", (double)u, (double)(u / f.umf), (double)(u / f.umf_wy)));
  if (why == CPL_UMF_LOOSE) PetscCall(PetscSNPrintf(at, sizeof at, " (looser than a random packing, %g: U_mf is taken at the packed bed's -cpl_umf_porosity %g)", CPL_LOOSE_PACKING, (double)f.eps));
  else if (why == CPL_UMF_OPTION) PetscCall(PetscSNPrintf(at, sizeof at, " (U_mf is taken at -cpl_umf_porosity %g)", (double)f.eps));
  PetscCall(PetscPrintf(c->r->comm, "bed: 95%% of the solids mass below %c = %.5g m, porosity %.4f between the 5%% and 95%% heights%s; U_mf %.4g m/s at porosity %.4f and d32 %.4g m (the drag law), Wen-Yu %.4g m/s at d32 (Ar %.4g, Re_mf %.4g)%s\n", "xyz"[c->col.d], (double)c -> h0, (double)c -> eps0, at, (double)f.umf, (double)f.eps, (double)f.d, (double)f.umf_wy, (double)f.ar, (double)f.re_wy, inlet));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. The bed line at the end: its height at the start, over the second half, now. */
static PetscErrorCode CoupledBedEnd(const Coupled *c)
{
  CplFluidization f;
  CplUmfPorosity  why;
  PetscReal       h, mean, u;
  char            half[96] = "";

  PetscFunctionBeginUser;
  if (c->h0 == 0 && c->eps0 == 0) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(DemGetBedHeights(c->dem, 0.95, &h, &mean));
  PetscCall(CoupledBedFluidization(c, &u, &f, &why));
  if (c->hn > 0) PetscCall(PetscSNPrintf(half, sizeof half, ", %.5g m mean over the second half (%.0f progress lines)", (double)(c->hsum / c->hn), (double)c->hn));
  PetscCall(PetscPrintf(c->r->comm, "bed: 95%% of the solids mass below %c = %.5g m at the start%s, %.5g m at the end; U_mf %.4g m/s (drag law at porosity %.4f and d32 %.4g m), %.4g m/s (Wen-Yu); inlet %.4g m/s\n", "xyz"[c->col.d], (double)c -> h0, half, (double)h, (double)f.umf, (double)f.eps, (double)f.d, (double)f.umf_wy, (double)u));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. The bed's buoyant weight per area again when sources or outlets changed the
 * particle set since it was last taken (a run that starts empty and is poured into). */
static PetscErrorCode CoupledBedWeightUpdate(Coupled *c, PetscReal *w)
{
  DemFlowStats f;

  PetscFunctionBeginUser;
  PetscCall(DemGetFlow(c->dem, &f));
  if (f.inserted + f.removed == c->wflow) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(CoupledBedWeight(c->cpl, &c->col, w));
  c->wflow = f.inserted + f.removed;
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode CoupledRunLoop(Coupled *c)
{
  const CoupledRun r = c->r;
  PetscLogDouble   t0;
  PetscReal        w = 0, dp = 0, t, dt;
  PetscInt         step, clipped;
  PetscBool        due;
  CplStats         st;
  DemFlowStats     flow;

  PetscFunctionBeginUser;
  PetscCall(CoupledCheckRunLength(c));
  PetscCall(CoupledBedWeight(c->cpl, &c->col, &w));
  PetscCall(DemGetFlow(c->dem, &flow));
  c->wflow = flow.inserted + flow.removed;
  PetscCall(CplGetTime(c->cpl, &t, &c->s0));
  step = c->s0;
  PetscCall(CplGetStepQuantum(c->cpl, &dt)); /* the step, or the DEM step with adaptive steps */
  PetscCall(PetscTime(&t0));
  PetscCall(IoDue(c->io, t, &due));
  if (due) PetscCall(CoupledOutput(c));
  PetscCall(CoupledMonitor(c, NULL));
  while (t < r->t_end - 0.5 * dt) {
    int sig;
    PetscCall(SableStopPoll(r->comm, &sig));
    if (sig) PetscCall(DriverCkptStop(&r->ckpt, c->io, sig, t, step, CoupledCheckpointWrite, c)); /* a checkpoint of this step, then the stop */
    PetscCall(CplStep(c->cpl, &st));
    PetscCall(CplGetTime(c->cpl, &t, &step));
    PetscCall(CoupledBedWeightUpdate(c, &w));
    PetscCall(BalanceCheck(c->lb, PETSC_FALSE, NULL));
    PetscCall(DriverAvgSample(r->avg, t));
    PetscCall(IoDue(c->io, t, &due));
    if (due) PetscCall(CoupledOutput(c));
    PetscCall(CoupledMonitor(c, &st));
    PetscCall(CoupledColumnDrop(c->cpl, c->fl, r->dom, &c->col, &dp));
    if (t > 0.5 * r->t_end) {
      c->avg += dp;
      c->davg += -c->col.down * st.drag[c->col.d];
      c->navg++;
    }
    if (r->progress_dt > 0 && t >= c->next - 0.5 * dt) {
      PetscCall(CoupledProgress(c, &st, t0, dp, w));
      c->next += r->progress_dt;
      if (t > 0.5 * r->t_end) {
        PetscReal h, mean;
        PetscCall(DemGetBedHeights(c->dem, 0.95, &h, &mean));
        c->hsum += h;
        c->hn++;
      }
    }
    if (r->ckpt.dt > 0 && t >= c->next_ckpt - 0.5 * dt) {
      c->next_ckpt += r->ckpt.dt;
      PetscCall(CoupledCheckpoint(c));
    }
  }
  PetscCall(IoDueFinal(c->io, t, &due));
  if (due) PetscCall(CoupledOutput(c));
  if (r->ckpt.dt > 0) PetscCall(CoupledCheckpoint(c)); /* -io_checkpoint_interval 0: none at the end either */
  PetscCall(CplGetClippedCount(c->cpl, &clipped));
  PetscCall(PetscPrintf(r->comm, "column: pressure drop / bed buoyant weight per area %.9f, drag on the particles / buoyant weight %.9f (means over the second half of the run; weight per area %.6g Pa); porosity clipped %" PetscInt_FMT " cell-steps\n", c->navg > 0 ? (double)(c->avg / c->navg / w) : 0.0, c->navg > 0 ? (double)(c->davg / c->navg / (w * c->col.area)) : 0.0, (double)w, clipped));
  if (r->probe_set) PetscCall(CoupledProbeReport(r, c->cpl));
  PetscCall(CoupledBedEnd(c));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The driver's carried state from a checkpoint's run/coupled (after the coupling's clock). The
 * column sums cover the steps after 0.5 -cpl_t_end: when the checkpoint comes before this run's
 * window they are zero whatever the writer's end; inside it, they are the writer's only when
 * its window started at the same time (otherwise a warning: the means start at the restart). */
static PetscErrorCode CoupledRestoreColumn(Coupled *c, const PetscReal v[COUPLED_CKPT_NRUN])
{
  const PetscReal half = 0.5 * c->r->t_end;
  PetscReal       t;

  PetscFunctionBeginUser;
  PetscCall(CplGetTime(c->cpl, &t, NULL));
  c->next      = v[3];
  c->next_ckpt = v[4];
  c->h0        = v[6];
  c->eps0      = v[7];
  if (t > half && v[5] == half) {
    c->avg  = v[0];
    c->davg = v[1];
    c->navg = v[2];
    c->hsum = v[8];
    c->hn   = v[9];
  } else if (t > half) PetscCall(PetscPrintf(c->r->comm, "warning: -restart %s: the checkpoint's run averaged the column figures from t = %g, this one from %g (half of -cpl_t_end), before the checkpoint's t = %g: the means of the \"column:\" line cover t > %g only\n", c->r->ckpt.restart, (double)v[5], (double)half, (double)t, (double)t));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. Sets the Dem, the Fluid and the coupling up, from the checkpoint of -restart if
 * given (the DEM reads its part in DemSetUp, with the coupling's particle arrays switched on
 * first; the fluid and the coupling after the coupling's set-up, which sets the porosity). */
static PetscErrorCode CoupledSetUp(Coupled *c)
{
  DriverCkpt    *ck = &c->r->ckpt;
  IoCkpt         f  = NULL;
  PetscLogDouble t0;

  PetscFunctionBeginUser;
  c->next      = c->r->progress_dt;
  c->next_ckpt = ck->dt;
  PetscCall(PetscTime(&t0));
  if (ck->restart[0]) {
    PetscCall(IoCkptOpen(c->r->comm, ck->restart, &f));
    PetscCall(BalanceCheckpointRead(c->lb, f)); /* the checkpoint's cuts first: the per-rank state lives on them */
    PetscCall(DemSetRestart(c->dem, f));
    PetscCall(DemSetExternal(c->dem, PETSC_TRUE));
    PetscCall(CplSetRestarting(c->cpl, PETSC_TRUE)); /* the fluid is the checkpoint's: no -cpl_init_fluid */
  }
  PetscCall(DemSetUp(c->dem));
  { /* the vessel: the walls that bound the gas, one line each; the fluid's level function */
    PetscBool vessel;
    PetscCall(DemVesselSetUp(c->dem, &vessel));
    if (vessel) PetscCall(FluidSetVessel(c->fl, DemVesselLevel, c->dem));
  }
  PetscCall(BalanceDecompose(c->lb)); /* the process grid and cuts from the particles, before the fluid's layout */
  PetscCall(DemSetRestart(c->dem, NULL));
  PetscCall(FluidSetCheckpointing(c->fl, PETSC_TRUE)); /* also a stop signal writes a checkpoint */
  PetscCall(FluidSetUp(c->fl));
  PetscCall(CplSetUp(c->cpl));
  PetscCall(DriverMonSetUp(&c->r->mon, c->io));
  PetscCall(DriverAvgSetUp(c->r->avg, c->r->dom, c->dem, c->fl, c->io));
  if (f) {
    PetscReal v[COUPLED_CKPT_NRUN], t;
    PetscCall(FluidCheckpointRead(c->fl, f));
    PetscCall(CplCheckpointRead(c->cpl, f));
    PetscCall(IoCkptReadShared(f, "run/coupled", IO_CKPT_REAL, COUPLED_CKPT_NRUN, v));
    PetscCall(CoupledRestoreColumn(c, v));
    PetscCall(DriverCkptReadRun(ck, c->io, c->r->mon.mon, f)); /* refuses another run's frames before running */
    PetscCall(CplGetTime(c->cpl, &t, NULL));
    PetscCall(DriverAvgCheckpointRead(c->r->avg, f, t));
    PetscCall(IoCkptClose(&f));
    PetscCall(DriverCkptRestarted(ck, t0, c->io, c->r->mon.mon, t));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CoupledRunCase(CoupledRun r, Dem dem, Balance lb, Io io, PetscBool help)
{
  Domain        *dom = r->dom;
  Coupled        c   = {r, dem, NULL, NULL, lb, io, PETSC_FALSE, {2, -1, 0}, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
  PetscBool      convex;
  PetscReal      g[3], t, ts;
  PetscInt       step, step0;
  PetscLogDouble t0, t1;
  char           seg[160] = "";

  PetscFunctionBeginUser;
  PetscCall(FluidCreate(dom, &c.fl));
  PetscCall(FluidSetFromOptions(c.fl));
  PetscCall(CplCreate(dom, dem, c.fl, &c.cpl));
  PetscCall(CplSetFromOptions(c.cpl));
  PetscCall(BalanceSetCoupling(lb, c.cpl));
  if (!help) {
    PetscCall(DriverCkptSetFromOptions(&r->ckpt, r->comm)); /* here, not with the run's options: -help lists them once, with the dry run's */
    PetscCall(DriverMonSetFromOptions(&r->mon, r->comm, PETSC_TRUE));
    PetscCall(DriverAvgCreate(r->comm, &r->avg));
    PetscCall(DriverAvgSetFromOptions(r->avg));
    PetscCall(SableCheckOptionsUsed(r->comm));
    PetscCall(DemGetFrozen(dem, &c.frozen));
    PetscCall(DemHasConvexShapes(dem, &convex));
    PetscCall(PetscPrintf(r->comm, "modules: DEM on%s; fluid on; coupling on; convex shapes %s; fluid grid %" PetscInt_FMT " x %" PetscInt_FMT " x %" PetscInt_FMT "\n", c.frozen ? " (frozen: no particle integration)" : "", convex ? "on (libccd)" : "off", dom->cells[0], dom->cells[1], dom->cells[2]));
    PetscCall(CoupledSetUp(&c));
    PetscCall(DemGetGravity(dem, g));
    c.col = ColumnFromGravity(dom, g);
    /* a vessel's cross-section at the column's bottom: its first plane of faces with open area
       (a vessel fed by a source patch may close the bottom face itself) */
    for (PetscInt k = 0; k <= dom->cells[c.col.d]; k++) {
      const PetscReal z = c.col.down < 0 ? dom->lo[c.col.d] + k * dom->h[c.col.d] : dom->hi[c.col.d] - k * dom->h[c.col.d];
      PetscCall(CplGetOpenArea(c.cpl, c.col.d, z, &c.col.area));
      if (c.col.area > 0) break;
    }
    PetscCheck(c.col.area > 0, r->comm, PETSC_ERR_ARG_WRONG, "the vessel has no open cross-section along the column (axis %c): no gas can pass; check -dem_cylinder, -dem_mesh_<k>_fluid and -dem_plane_<k>_fluid", "xyz"[c.col.d]);
    PetscCall(DemView(dem, PETSC_VIEWER_STDOUT_WORLD));
    PetscCall(CplView(c.cpl, PETSC_VIEWER_STDOUT_WORLD));
    PetscCall(CoupledBedStart(&c));
    PetscCall(BalanceSetUp(lb));
    PetscCall(CplGetTime(c.cpl, &ts, &step0)); /* this run's segment: from here */
    PetscCall(PetscTime(&t0));
    PetscCall(CoupledRunLoop(&c));
    PetscCall(PetscTime(&t1));
    PetscCall(BalanceView(lb, PETSC_VIEWER_STDOUT_WORLD));
    PetscCall(CplGetTime(c.cpl, &t, &step));
    if (r->ckpt.restart[0]) PetscCall(PetscSNPrintf(seg, sizeof seg, " (this run from the restart at t = %g, step %" PetscInt_FMT ", to step %" PetscInt_FMT ")", (double)ts, step0, step));
    PetscCall(PetscPrintf(r->comm, "done: t = %g, %" PetscInt_FMT " fluid steps in %.3f s%s\n", (double)t, step - step0, t1 - t0, seg));
    PetscCall(DemFlowView(dem, PETSC_VIEWER_STDOUT_WORLD)); /* with sources or outlets: the balance */
    PetscCall(DemViewSources(c.dem, PETSC_VIEWER_STDOUT_WORLD));
    PetscCall(IoView(io, PETSC_VIEWER_STDOUT_WORLD)); /* the frames, their size and write time */
    PetscCall(SableWarnOptionsUnused(r->comm));
  }
  PetscCall(BalanceSetCoupling(lb, NULL));
  PetscCall(CplDestroy(&c.cpl));
  PetscCall(FluidDestroy(&c.fl));
  PetscFunctionReturn(PETSC_SUCCESS);
}
