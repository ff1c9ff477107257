/* Fluid life cycle: options, grids, fields and accessors (the equations are in fluid.h, the
 * step in step.c). The cell DMDA copies the ownership ranges of the domain's DMDA so the fluid
 * lives on the one decomposition of the run; the face DMDA has the same ranges plus one point
 * on the last rank along non-periodic axes (the upper boundary faces). Options -fluid_density,
 * -fluid_viscosity, -fluid_dt, -fluid_gravity, -fluid_pressure_gradient, -fluid_advection,
 * -fluid_viscous, -fluid_cfl_max, -fluid_viscous_number_max, -fluid_adaptive_dt, and the
 * preconditioner lag of the Poisson solve -fluid_poisson_pc_lag, -fluid_poisson_pc_lag_growth
 * (poisson.c); boundary options in bc.c, inlet tables in inlet.c. */
#include "fluid/fluid_impl.h"

static const char *const FluidAdvectionNames[] = {"central", "tvd", "none", "FluidAdvection", "FLUID_ADV_", NULL};
static const char *const FluidViscousNames[]   = {"explicit", "implicit", "FluidViscous", "FLUID_VISC_", NULL};

/* One class id and one log event per phase for the whole run, registered on first use. */
static PetscErrorCode FluidRegisterEvents(Fluid fl)
{
  static PetscBool     done = PETSC_FALSE;
  static PetscClassId  cid;
  static PetscLogEvent ev[3];

  PetscFunctionBeginUser;
  if (!done) {
    PetscCall(PetscClassIdRegister("Fluid", &cid));
    PetscCall(PetscLogEventRegister("FluidPredict", cid, &ev[0]));
    PetscCall(PetscLogEventRegister("FluidPoisson", cid, &ev[1]));
    PetscCall(PetscLogEventRegister("FluidCorrect", cid, &ev[2]));
    done = PETSC_TRUE;
  }
  fl->ev.predict = ev[0];
  fl->ev.poisson = ev[1];
  fl->ev.correct = ev[2];
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FluidCreate(Domain *dom, Fluid *fluid)
{
  Fluid fl;

  PetscFunctionBeginUser;
  PetscCall(PetscNew(&fl));
  PetscCall(PetscObjectGetComm((PetscObject)dom->da, &fl->comm));
  fl->dom            = dom;
  fl->prop.rho       = 1000.0;
  fl->prop.mu        = 1.0e-3;
  fl->clock.dt       = 1.0e-3;
  fl->bc.p_out       = 0.0;
  fl->mom.adv        = FLUID_ADV_CENTRAL;
  fl->mom.visc       = FLUID_VISC_EXPLICIT;
  fl->clock.cfl_max  = 0.5;
  fl->clock.visc_max = 0.5;
  fl->pois.pc_lag    = 20;
  fl->pois.pc_growth = 1.5;
  for (int d = 0; d < 3; d++)
    for (int s = 0; s < 2; s++) fl->bc.face[d][s].type = dom->periodic[d] ? FLUID_BC_PERIODIC : FLUID_BC_WALL;
  PetscCall(FluidRegisterEvents(fl));
  *fluid = fl;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FluidSetFromOptions(Fluid fl)
{
  PetscInt adv = fl->mom.adv, visc = fl->mom.visc;

  PetscFunctionBeginUser;
  PetscOptionsBegin(fl->comm, NULL, "Fluid (porosity-averaged Navier-Stokes)", NULL);
  PetscCall(SableOptionsReal("-fluid_density", "Fluid density rho_f", "kg/m^3", "(0,inf)", fl->prop.rho, &fl->prop.rho, NULL));
  PetscCall(SableOptionsReal("-fluid_viscosity", "Dynamic viscosity mu", "Pa s", "(0,inf)", fl->prop.mu, &fl->prop.mu, NULL));
  PetscCall(SableOptionsReal("-fluid_dt", "Fluid time step", "s", "(0,inf)", fl->clock.dt, &fl->clock.dt, &fl->clock.dt_set));
  PetscCall(SableOptionsRealN("-fluid_gravity", "Gravity g, acts as rho eps g", "m/s^2", fl->prop.gravity, 3, 3, NULL));
  PetscCall(SableOptionsRealN("-fluid_pressure_gradient", "Imposed mean pressure gradient G, acts as the force -G per unit volume", "Pa/m", fl->prop.dpdx, 3, 3, NULL));
  PetscCall(SableOptionsEnum("-fluid_advection", "Advection scheme: central (2nd order), tvd (van Leer limited upwind), none (Stokes)", FluidAdvectionNames, 3, adv, &adv, NULL));
  fl->mom.adv = (FluidAdvection)adv;
  PetscCall(SableOptionsEnum("-fluid_viscous", "Viscous term: explicit or implicit (backward Euler, component-wise; cross terms explicit)", FluidViscousNames, 2, visc, &visc, NULL));
  fl->mom.visc = (FluidViscous)visc;
  PetscCall(SableOptionsReal("-fluid_cfl_max", "Largest advective CFL number dt*sum|u_d|/h_d allowed", NULL, "(0,1]", fl->clock.cfl_max, &fl->clock.cfl_max, NULL));
  PetscCall(SableOptionsReal("-fluid_viscous_number_max", "Largest explicit viscous number 2 dt nu sum 1/h_d^2 allowed (stability needs <= 1)", NULL, "(0,1]", fl->clock.visc_max, &fl->clock.visc_max, NULL));
  PetscCall(SableOptionsInt("-fluid_poisson_pc_lag", "Keep the Poisson preconditioner for up to this many matrix changes (0: rebuild at every change)", NULL, "[0,inf)", fl->pois.pc_lag, &fl->pois.pc_lag, NULL));
  PetscCall(SableOptionsReal("-fluid_poisson_pc_lag_growth", "Rebuild a lagged preconditioner earlier when the iterations exceed growth x those after its build + 1", NULL, "[1,inf)", fl->pois.pc_growth, &fl->pois.pc_growth, NULL));
  PetscCall(SableOptionsBool("-fluid_adaptive_dt", "Lower dt to the stability limit instead of stopping", fl->clock.adaptive, &fl->clock.adaptive, NULL));
  PetscOptionsEnd();
  PetscCall(FluidSetFromOptionsBC(fl));
  PetscCall(FluidSetFromOptionsInlet(fl));
  PetscCall(FluidSetFromOptionsVessel(fl));
  PetscCall(FluidSetFromOptionsPatch(fl));
  PetscCall(FluidSetFromOptionsDistributor(fl));
  PetscCall(KSPDestroy(&fl->pois.ksp));
  PetscCall(KSPDestroy(&fl->vimp.ksp));
  PetscCall(FluidPoissonCreateKSP(fl));
  if (fl->mom.visc == FLUID_VISC_IMPLICIT) PetscCall(FluidViscousCreateKSP(fl));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Every rank must own at least two cells per axis: the stencils reach two cells. */
static PetscErrorCode FluidCheckDecomposition(Fluid fl, const PetscInt *l[3], const PetscInt np[3])
{
  const char *ax = "xyz";

  PetscFunctionBeginUser;
  for (int d = 0; d < 3; d++)
    for (PetscInt r = 0; r < np[d]; r++)
      PetscCheck(l[d][r] >= 2, fl->comm, PETSC_ERR_ARG_OUTOFRANGE, "fluid grid of %d cells along %c cannot be split over %d ranks: every rank needs >= 2 cells (rank column %d has %d); change -da_grid_%c or -da_processors_%c", (int)fl->dom->cells[d], ax[d], (int)np[d], (int)r, (int)l[d][r], ax[d], ax[d]);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FluidCreateDMs(Fluid fl)
{
  const PetscInt *l[3];
  PetscInt       *lf[3], np[3], N[3];
  DMBoundaryType  bt[3];
  FluidGrid      *g = &fl->g;

  PetscFunctionBeginUser;
  PetscCall(DMDAGetInfo(fl->dom->da, NULL, &N[0], &N[1], &N[2], &np[0], &np[1], &np[2], NULL, NULL, NULL, NULL, NULL, NULL));
  PetscCall(DMDAGetOwnershipRanges(fl->dom->da, &l[0], &l[1], &l[2]));
  PetscCall(FluidCheckDecomposition(fl, l, np));
  for (int d = 0; d < 3; d++) {
    bt[d] = FluidPeriodic(fl, d) ? DM_BOUNDARY_PERIODIC : DM_BOUNDARY_GHOSTED;
    PetscCall(PetscMalloc1(np[d], &lf[d]));
    for (PetscInt r = 0; r < np[d]; r++) lf[d][r] = l[d][r];
    if (!FluidPeriodic(fl, d)) lf[d][np[d] - 1]++;
    g->N[d]  = N[d];
    g->h[d]  = fl->dom->h[d];
    g->lo[d] = fl->dom->lo[d];
  }
  PetscCall(DMDACreate3d(fl->comm, bt[0], bt[1], bt[2], DMDA_STENCIL_BOX, N[0], N[1], N[2], np[0], np[1], np[2], 1, 2, l[0], l[1], l[2], &fl->g.cda));
  PetscCall(DMSetUp(fl->g.cda));
  PetscCall(DMDACreate3d(fl->comm, bt[0], bt[1], bt[2], DMDA_STENCIL_BOX, N[0] + (bt[0] == DM_BOUNDARY_PERIODIC ? 0 : 1), N[1] + (bt[1] == DM_BOUNDARY_PERIODIC ? 0 : 1), N[2] + (bt[2] == DM_BOUNDARY_PERIODIC ? 0 : 1), np[0], np[1], np[2], 3, 2, lf[0], lf[1], lf[2], &fl->g.fda));
  PetscCall(DMSetUp(fl->g.fda));
  for (int d = 0; d < 3; d++) PetscCall(PetscFree(lf[d]));
  PetscCall(DMDAGetCorners(fl->g.cda, &g->xs[0], &g->xs[1], &g->xs[2], &g->xm[0], &g->xm[1], &g->xm[2]));
  PetscCall(DMDAGetGhostCorners(fl->g.cda, &g->gcs[0], &g->gcs[1], &g->gcs[2], &g->gcm[0], &g->gcm[1], &g->gcm[2]));
  PetscCall(DMDAGetCorners(fl->g.fda, NULL, NULL, NULL, &g->fxm[0], &g->fxm[1], &g->fxm[2]));
  PetscCall(DMDAGetGhostCorners(fl->g.fda, &g->gfs[0], &g->gfs[1], &g->gfs[2], &g->gfm[0], &g->gfm[1], &g->gfm[2]));
  g->cs[0] = 1;
  g->cs[1] = g->gcm[0];
  g->cs[2] = g->gcm[0] * g->gcm[1];
  g->fs[0] = 3;
  g->fs[1] = 3 * g->gfm[0];
  g->fs[2] = 3 * g->gfm[0] * g->gfm[1];
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The ghosted local work vectors of the current DMDAs. */
PetscErrorCode FluidCreateLocals(Fluid fl)
{
  PetscFunctionBeginUser;
  PetscCall(DMCreateLocalVector(fl->g.cda, &fl->fld.ploc));
  PetscCall(VecDuplicate(fl->fld.ploc, &fl->fld.epsloc));
  PetscCall(VecDuplicate(fl->fld.ploc, &fl->fld.epsoldloc));
  fl->fld.epsold_state = -1;
  PetscCall(VecDuplicate(fl->fld.ploc, &fl->pois.philoc));
  PetscCall(DMCreateLocalVector(fl->g.fda, &fl->fld.uloc));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The matrices, null space and star-stencil DMDAs of the Poisson and viscous solves (they
 * belong to one layout; the KSPs and their options stay). */
PetscErrorCode FluidSolversDestroy(Fluid fl)
{
  PetscFunctionBeginUser;
  PetscCall(MatNullSpaceDestroy(&fl->pois.nsp));
  PetscCall(MatDestroy(&fl->pois.A));
  PetscCall(PetscFree(fl->pois.coo_v));
  fl->pois.ncoo = 0;
  PetscCall(DMDestroy(&fl->pois.pda));
  PetscCall(MatDestroy(&fl->vimp.V));
  PetscCall(DMDestroy(&fl->vimp.da));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FluidSetUp(Fluid fl)
{
  PetscFunctionBeginUser;
  PetscCall(FluidCreateDMs(fl));
  PetscCall(DMCreateGlobalVector(fl->g.cda, &fl->fld.p));
  PetscCall(VecDuplicate(fl->fld.p, &fl->fld.eps));
  PetscCall(VecDuplicate(fl->fld.p, &fl->fld.eps_old));
  PetscCall(VecDuplicate(fl->fld.p, &fl->pois.phi));
  PetscCall(VecDuplicate(fl->fld.p, &fl->pois.rhs));
  PetscCall(VecSet(fl->fld.eps, 1.0));
  PetscCall(VecSet(fl->fld.eps_old, 1.0));
  PetscCall(DMCreateGlobalVector(fl->g.fda, &fl->fld.u));
  PetscCall(VecDuplicate(fl->fld.u, &fl->fld.beta));
  PetscCall(VecDuplicate(fl->fld.u, &fl->fld.us));
  PetscCall(VecDuplicate(fl->fld.u, &fl->fld.src));
  PetscCall(VecDuplicate(fl->fld.u, &fl->mom.uhat));
  PetscCall(VecDuplicate(fl->fld.u, &fl->mom.adv_old));
  PetscCall(VecDuplicate(fl->fld.u, &fl->mom.advn));
  PetscCall(VecDuplicate(fl->fld.u, &fl->mom.vis));
  if (fl->ckpt) {
    PetscCall(VecDuplicate(fl->fld.p, &fl->pois.eps_pc));
    PetscCall(VecDuplicate(fl->fld.u, &fl->pois.beta_pc));
  }
  PetscCall(FluidCreateLocals(fl));
  PetscCall(FluidVesselSetUp(fl));
  PetscCall(FluidSetUpPatches(fl));
  if (fl->patch && fl->ves.cut) PetscCall(FluidVesselSetUp(fl)); /* the wall links and closed cells again, now that the patches' faces are known (the fractions come out the same) */
  PetscCall(FluidBoundaryFaceValues(fl, fl->fld.u));
  PetscCheck(fl->pois.ksp, fl->comm, PETSC_ERR_ORDER, "call FluidSetFromOptions before FluidSetUp");
  PetscCall(FluidPoissonSetUp(fl));
  if (fl->vimp.ksp) PetscCall(FluidViscousSetUp(fl));
  fl->setup = PETSC_TRUE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FluidDestroy(Fluid *fluid)
{
  Fluid fl = *fluid;

  PetscFunctionBeginUser;
  if (!fl) PetscFunctionReturn(PETSC_SUCCESS);
  Vec *v[] = {&fl->fld.u, &fl->fld.p, &fl->fld.eps, &fl->fld.eps_old, &fl->fld.beta, &fl->fld.us, &fl->fld.src, &fl->fld.uloc, &fl->fld.ploc, &fl->fld.epsloc, &fl->fld.epsoldloc, &fl->mom.uhat, &fl->mom.advn, &fl->mom.adv_old, &fl->mom.vis, &fl->pois.coef, &fl->pois.coefloc, &fl->vimp.bc, &fl->vimp.phiu, &fl->pois.phi, &fl->pois.rhs, &fl->pois.philoc, &fl->pois.eps_pc, &fl->pois.beta_pc};
  for (size_t i = 0; i < sizeof v / sizeof v[0]; i++) PetscCall(VecDestroy(v[i]));
  PetscCall(FluidSolversDestroy(fl));
  PetscCall(FluidVesselDestroy(fl));
  PetscCall(KSPDestroy(&fl->pois.ksp));
  PetscCall(KSPDestroy(&fl->vimp.ksp));
  PetscCall(DMDestroy(&fl->g.cda));
  PetscCall(DMDestroy(&fl->g.fda));
  PetscCall(PetscFree(fl->mom.advbuf));
  PetscCall(FluidDestroyPatches(fl));
  PetscCall(FluidFaceShiftDestroy(fl));
  PetscCall(VecDestroy(&fl->plate.beff));
  PetscCall(PetscFree(*fluid));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FluidSetCheckpointing(Fluid fl, PetscBool on)
{
  PetscFunctionBeginUser;
  PetscCheck(!fl->setup, fl->comm, PETSC_ERR_ORDER, "call FluidSetCheckpointing before FluidSetUp");
  fl->ckpt = on;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FluidGetTimeStep(Fluid fl, PetscReal *dt, PetscBool *given)
{
  PetscFunctionBeginUser;
  *dt = fl->clock.dt;
  if (given) *given = fl->clock.dt_set;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FluidGetDensity(Fluid fl, PetscReal *rho)
{
  PetscFunctionBeginUser;
  *rho = fl->prop.rho;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FluidGetViscosity(Fluid fl, PetscReal *mu)
{
  PetscFunctionBeginUser;
  *mu = fl->prop.mu;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FluidGetGravity(Fluid fl, PetscReal g[3])
{
  PetscFunctionBeginUser;
  for (int d = 0; d < 3; d++) g[d] = fl->prop.gravity[d];
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FluidGetDMs(Fluid fl, DM *cda, DM *fda)
{
  PetscFunctionBeginUser;
  PetscCheck(fl->setup, fl->comm, PETSC_ERR_ORDER, "call FluidSetUp before FluidGetDMs");
  if (cda) *cda = fl->g.cda;
  if (fda) *fda = fl->g.fda;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FluidGetPorosity(Fluid fl, Vec *v)
{
  PetscFunctionBeginUser;
  *v = fl->fld.eps;
  PetscFunctionReturn(PETSC_SUCCESS);
}
PetscErrorCode FluidGetPorosityOld(Fluid fl, Vec *v)
{
  PetscFunctionBeginUser;
  *v = fl->fld.eps_old;
  PetscFunctionReturn(PETSC_SUCCESS);
}
PetscErrorCode FluidGetDragCoefficient(Fluid fl, Vec *v)
{
  PetscFunctionBeginUser;
  *v = fl->fld.beta;
  PetscFunctionReturn(PETSC_SUCCESS);
}
PetscErrorCode FluidGetSolidVelocity(Fluid fl, Vec *v)
{
  PetscFunctionBeginUser;
  *v = fl->fld.us;
  PetscFunctionReturn(PETSC_SUCCESS);
}
PetscErrorCode FluidGetMomentumSource(Fluid fl, Vec *v)
{
  PetscFunctionBeginUser;
  *v = fl->fld.src;
  PetscFunctionReturn(PETSC_SUCCESS);
}
PetscErrorCode FluidGetVelocity(Fluid fl, Vec *v)
{
  PetscFunctionBeginUser;
  *v = fl->fld.u;
  PetscFunctionReturn(PETSC_SUCCESS);
}
PetscErrorCode FluidGetPressure(Fluid fl, Vec *v)
{
  PetscFunctionBeginUser;
  *v = fl->fld.p;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FluidGetLocalFields(Fluid fl, Vec *uloc, Vec *ploc)
{
  PetscFunctionBeginUser;
  if (uloc) {
    PetscCall(FluidLocalPorosityOld(fl, PETSC_FALSE));
    PetscCall(FluidLocalVelocity(fl, fl->fld.u, fl->fld.uloc, fl->fld.epsoldloc));
    *uloc = fl->fld.uloc;
  }
  if (ploc) {
    PetscCall(FluidLocalCell(fl, fl->fld.p, fl->fld.ploc, FLUID_GHOST_PRESSURE, fl->bc.p_out));
    *ploc = fl->fld.ploc;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FluidApplyBoundaryValues(Fluid fl)
{
  PetscFunctionBeginUser;
  PetscCall(FluidBoundaryFaceValues(fl, fl->fld.u));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FluidInitPorosity(Fluid fl)
{
  PetscFunctionBeginUser;
  PetscCall(VecCopy(fl->fld.eps, fl->fld.eps_old));
  if (fl->setup) PetscCall(FluidInletFaceValues(fl, fl->fld.u)); /* u's level is this porosity: its inlet faces U_n / eps_f */
  PetscFunctionReturn(PETSC_SUCCESS);
}
