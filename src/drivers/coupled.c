/* The coupled driver: a run is coupled when any -cpl_ or -fluid_ option is given (main.c keeps
 * the dry path otherwise). It builds the Fluid and the coupling beside the driver's Dem, prints
 * the modules and the pre-flight figures, runs to -cpl_t_end, writes particles and fluid in the
 * same output frames, and reports the pressure drop across the column against the bed's buoyant
 * weight per area (the fluidization check), averaged over the second half of the run, and with
 * -cpl_probe_z the packed-bed figures (dp/L between two heights, the porosity there and the drag
 * law's own prediction). Gravity is along z. */
#include "coupling/coupling_impl.h"
#include "drivers/drivers.h"

PetscErrorCode CplRequested(PetscBool *on)
{
  char *all;

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsGetAll(NULL, &all));
  *on = (PetscBool)(!strncmp(all, "-cpl_", 5) || !strncmp(all, "-fluid_", 7) || strstr(all, " -cpl_") || strstr(all, " -fluid_"));
  PetscCall(PetscFree(all));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Buoyant weight of the bed per cross-section area (Pa), gravity along z. */
static PetscErrorCode CplBedWeight(Cpl cpl, PetscReal *w)
{
  DemArrays pa;
  PetscReal loc = 0;

  PetscFunctionBeginUser;
  PetscCall(DemGetArrays(cpl->dem, &pa));
  for (PetscInt p = 0; p < pa.nlocal; p++) loc += (cpl->mass[pa.shape[p]] - cpl->rho * cpl->vol[pa.shape[p]]) * PetscAbsReal(cpl->g[2]);
  PetscCall(MPIU_Allreduce(&loc, w, 1, MPIU_REAL, MPIU_SUM, cpl->comm));
  *w /= cpl->dom->len[0] * cpl->dom->len[1];
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode CplColumnDrop(Cpl cpl, PetscReal *dp)
{
  PetscReal p0, p1, e, u;

  PetscFunctionBeginUser;
  PetscCall(CplGetLayer(cpl, 2, cpl->dom->lo[2], NULL, &p0, &e, &u));
  PetscCall(CplGetLayer(cpl, 2, cpl->dom->hi[2], NULL, &p1, &e, &u));
  *dp = p0 - p1;
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode CplProbeReport(Cpl cpl)
{
  PetscReal p0, p1, e0, e1, u0, u1, eps, pred, dpdl, z0, z1;

  PetscFunctionBeginUser;
  PetscCall(CplGetLayer(cpl, 2, cpl->probe[0], &z0, &p0, &e0, &u0));
  PetscCall(CplGetLayer(cpl, 2, cpl->probe[1], &z1, &p1, &e1, &u1));
  PetscCall(CplMeanPorosity(cpl, 2, z0, z1, &eps));
  dpdl = (p0 - p1) / (z1 - z0);
  pred = CplPackedBedGradient(cpl->law, eps, u0, cpl->diam[0], cpl->rho, cpl->mu);
  PetscCall(PetscPrintf(cpl->comm, "packed bed: dp/L %.15g Pa/m, porosity %.15f, superficial velocity %.6g m/s, drag law predicts %.6g Pa/m (ratio %.5f)\n", (double)dpdl, (double)eps, (double)u0, (double)pred, (double)(dpdl / pred)));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode CplOutput(Cpl cpl, Io io)
{
  PetscFunctionBeginUser;
  if (!cpl->frozen) { /* never write a diverged state */
    DemStats ds;
    PetscCall(DemGetStats(cpl->dem, &ds));
    PetscCall(DemCheckHealth(cpl->dem, &ds));
  }
  PetscCall(IoFrameBegin(io, cpl->t, cpl->step));
  PetscCall(DemWriteOutput(cpl->dem, io));
  PetscCall(FluidWriteOutput(cpl->fl, io));
  PetscCall(IoFrameEnd(io));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. The run's length and cadences: its steps are coupling steps, and the counter
 * that must hold them the DEM's (substeps per coupling step) or, frozen, the fluid's. */
static PetscErrorCode CplCheckRunLength(Cpl cpl, Io io)
{
  char           dtopt[64];
  PetscReal      dtd;
  PetscInt       s0;
  SableRunLength r = {"cpl", "coupling step", dtopt, cpl->frozen ? "-fluid_dt" : "-dem_dt", cpl->frozen ? "fluid steps" : "DEM steps", cpl->t_end_set, cpl->t, cpl->t_end, cpl->dt, cpl->progress_dt, 0, cpl->frozen ? 1 : cpl->substeps, cpl->step};

  PetscFunctionBeginUser;
  PetscCall(DemGetTimeStep(cpl->dem, &dtd));
  PetscCall(DemGetTime(cpl->dem, NULL, &s0));
  r.counter = PetscMax(s0, cpl->step);
  if (cpl->frozen) PetscCall(PetscSNPrintf(dtopt, sizeof dtopt, "-fluid_dt"));
  else PetscCall(PetscSNPrintf(dtopt, sizeof dtopt, "-cpl_substeps %d x -dem_dt %g s", (int)cpl->substeps, (double)dtd));
  PetscCall(IoGetInterval(io, &r.io_dt));
  PetscCall(SableCheckRunLength(cpl->comm, &r));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode CplRunLoop(Cpl cpl, Balance lb, Io io)
{
  PetscLogDouble t0, now;
  PetscReal      next = cpl->progress_dt, w, dp = 0, avg = 0, davg = 0;
  PetscInt       navg = 0;
  PetscBool      due;
  CplStats       st;

  PetscFunctionBeginUser;
  PetscCall(CplCheckRunLength(cpl, io));
  PetscCall(CplBedWeight(cpl, &w));
  PetscCall(PetscTime(&t0));
  PetscCall(IoDue(io, cpl->t, &due));
  if (due) PetscCall(CplOutput(cpl, io));
  while (cpl->t < cpl->t_end - 0.5 * cpl->dt) {
    int         sig;
    const char *index;
    PetscCall(SableStopPoll(cpl->comm, &sig));
    if (sig) {
      PetscCall(IoGetIndexPath(io, &index));
      PetscCall(SableStopError(cpl->comm, sig, cpl->t, cpl->step, index));
    }
    PetscCall(CplStep(cpl, &st));
    PetscCall(BalanceCheck(lb, PETSC_FALSE, NULL));
    PetscCall(IoDue(io, cpl->t, &due));
    if (due) PetscCall(CplOutput(cpl, io));
    PetscCall(CplColumnDrop(cpl, &dp));
    if (cpl->t > 0.5 * cpl->t_end) {
      avg += dp;
      davg += st.drag[2];
      navg++;
    }
    if (cpl->progress_dt > 0 && cpl->t >= next - 0.5 * cpl->dt) {
      DemStats ds;
      PetscCall(DemGetStats(cpl->dem, &ds));
      PetscCall(PetscTime(&now));
      const double rate = cpl->step / PetscMax(now - t0, 1e-9);
      PetscCall(PetscPrintf(cpl->comm, "t %.5g  step %" PetscInt_FMT "  %.1f steps/s  ETA %.0f s  KE %.4g  contacts %" PetscInt_FMT "  eps_min %.3f  clipped %" PetscInt_FMT "  Poisson its %" PetscInt_FMT "  dp/W %.4f  drag/W %.4f  |owed| %.3g\n", (double)cpl->t, cpl->step, rate, PetscMax(0.0, (cpl->t_end - cpl->t) / cpl->dt / rate), (double)ds.ke, ds.contacts + ds.wall_contacts, (double)st.eps_min, cpl->clipped_total, st.fluid.poisson_its, (double)(dp / w), (double)(st.drag[2] / (w * cpl->dom->len[0] * cpl->dom->len[1])), (double)st.owed_norm));
      if (!cpl->frozen) PetscCall(DemCheckHealth(cpl->dem, &ds));
      next += cpl->progress_dt;
    }
  }
  PetscCall(IoDueFinal(io, cpl->t, &due));
  if (due) PetscCall(CplOutput(cpl, io));
  PetscCall(PetscPrintf(cpl->comm, "column: pressure drop / bed buoyant weight per area %.9f, drag on the particles / buoyant weight %.9f (means over the second half of the run; weight per area %.6g Pa); porosity clipped %" PetscInt_FMT " cell-steps\n", navg ? (double)(avg / navg / w) : 0.0, navg ? (double)(davg / navg / (w * cpl->dom->len[0] * cpl->dom->len[1])) : 0.0, (double)w, cpl->clipped_total));
  if (cpl->probe_set) PetscCall(CplProbeReport(cpl));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CplRunCase(Domain *dom, Dem dem, Io io, PetscBool help)
{
  Fluid          fl;
  Cpl            cpl;
  Balance        lb;
  PetscBool      frozen, convex;
  PetscLogDouble t0, t1;
  const char    *index;

  PetscFunctionBeginUser;
  PetscCall(FluidCreate(dom, &fl));
  PetscCall(FluidSetFromOptions(fl));
  PetscCall(CplCreate(dom, dem, fl, &cpl));
  PetscCall(CplSetFromOptions(cpl));
  PetscCall(BalanceCreate(dom, dem, cpl, &lb));
  PetscCall(BalanceSetFromOptions(lb));
  if (!help) {
    const char *dry[2] = {"-dem_t_end", "-dem_progress_interval"}, *wet[2] = {"-cpl_t_end", "-cpl_progress_interval"};
    for (int k = 0; k < 2; k++) { /* the DEM reads them, but the coupled loop runs on its own clock */
      PetscBool set;
      PetscCall(PetscOptionsHasName(NULL, NULL, dry[k], &set));
      PetscCheck(!set, PETSC_COMM_WORLD, PETSC_ERR_ARG_INCOMP, "%s applies to dry runs; this run is coupled (it has -fluid_ or -cpl_ options): use %s", dry[k], wet[k]);
    }
    PetscCall(SableCheckOptionsUsed(PETSC_COMM_WORLD));
    PetscCall(DemGetFrozen(dem, &frozen));
    PetscCall(DemHasConvexShapes(dem, &convex));
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "modules: DEM on%s; fluid on; coupling on; convex shapes %s; process grid %" PetscInt_FMT " x %" PetscInt_FMT " x %" PetscInt_FMT ", fluid grid %" PetscInt_FMT " x %" PetscInt_FMT " x %" PetscInt_FMT "\n", frozen ? " (frozen: no particle integration)" : "", convex ? "on (libccd)" : "off", dom->nranks[0], dom->nranks[1], dom->nranks[2], dom->cells[0], dom->cells[1], dom->cells[2]));
    PetscCall(DemSetUp(dem));
    PetscCall(FluidSetUp(fl));
    PetscCall(CplSetUp(cpl));
    PetscCall(DemView(dem, PETSC_VIEWER_STDOUT_WORLD));
    PetscCall(CplView(cpl, PETSC_VIEWER_STDOUT_WORLD));
    PetscCall(BalanceSetUp(lb));
    PetscCall(PetscTime(&t0));
    PetscCall(CplRunLoop(cpl, lb, io));
    PetscCall(PetscTime(&t1));
    PetscCall(BalanceView(lb, PETSC_VIEWER_STDOUT_WORLD));
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "done: t = %g, %" PetscInt_FMT " fluid steps in %.3f s\n", (double)cpl->t, cpl->step, t1 - t0));
    PetscCall(IoGetIndexPath(io, &index));
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, index ? "output: %s (open it in ParaView)\n" : "output: none (-io_interval 0)\n", index));
    PetscCall(SableWarnOptionsUnused(PETSC_COMM_WORLD));
  }
  PetscCall(BalanceDestroy(&lb));
  PetscCall(CplDestroy(&cpl));
  PetscCall(FluidDestroy(&fl));
  PetscFunctionReturn(PETSC_SUCCESS);
}
