/* One fluid time step, fractional-step projection of eqs. (9)-(10):
 *   predictor, at every active face (eps_f^n, eps_f^{n+1} the face porosities of the two levels)
 *     (rho eps_f^{n+1}/dt + beta) u^ - [L(u^) if implicit]
 *        = rho eps_f^n u^n/dt - A* + V - grad p^n + rho eps_f^n g - G + f + beta u_s
 *   with the advection A* extrapolated by second-order Adams-Bashforth (Euler on the first
 *   step, variable-step coefficients when dt changes), the viscous term V explicit (forward
 *   Euler) or split (viscous.c), G the imposed mean pressure gradient;
 *   projection and pressure update (poisson.c).
 * Before the predictor the step is checked against the advective limit
 * CFL = dt max_cells sum_d |u_d|/h_d <= -fluid_cfl_max and, for the explicit viscous term,
 * 2 dt (mu/rho) (eps ratio) sum_d 1/h_d^2 <= -fluid_viscous_number_max; with a vessel, also the
 * rows of the faces next to its wall, whose wall distance stiffens them (vessel.c). */
#include "fluid/fluid_impl.h"

typedef struct {
  PetscReal cfl, vis; /* local maxima */
  PetscInt  ccell[3], vcell[3];
} FluidLimits;

static void FluidLocalLimits(Fluid fl, PetscReal dt, const PetscScalar *u, const PetscScalar *eps, FluidLimits *lim)
{
  const FluidGrid *g = &fl->g;
  PetscInt         idx[3], c, o;
  PetscReal        ih2 = 0;

  for (int d = 0; d < 3; d++) ih2 += 1.0 / (g->h[d] * g->h[d]);
  lim->cfl = lim->vis = -1;
  FLUID_FOR_OWNED_CELLS(g, idx, c, o)
  {
    const PetscInt f   = FluidFaceOff(g, idx[0], idx[1], idx[2]);
    PetscReal      cfl = 0, emax = eps[c], emin = eps[c];
    for (int d = 0; d < 3; d++) {
      cfl += dt * PetscMax(PetscAbsScalar(u[f + d]), PetscAbsScalar(u[f + g->fs[d] + d])) / g->h[d];
      for (int s = -1; s <= 1; s += 2) {
        emax = PetscMax(emax, eps[c + s * g->cs[d]]);
        emin = PetscMin(emin, eps[c + s * g->cs[d]]);
      }
    }
    const PetscReal vis = 2 * dt * fl->prop.mu / fl->prop.rho * ih2 * emax / emin;
    if (cfl > lim->cfl) {
      lim->cfl = cfl;
      for (int d = 0; d < 3; d++) lim->ccell[d] = idx[d];
    }
    if (vis > lim->vis) {
      lim->vis = vis;
      for (int d = 0; d < 3; d++) lim->vcell[d] = idx[d];
    }
  }
  if (fl->ves.cut) { /* the wall links' rows (vessel.c) */
    PetscInt        cell[3];
    const PetscReal vis = FluidVesselViscousNumber(fl, dt, eps, cell);
    if (vis > lim->vis) {
      lim->vis = vis;
      for (int d = 0; d < 3; d++) lim->vcell[d] = cell[d];
    }
  }
}

/* Global maximum of a local value and the cell where it occurs (lowest rank wins ties). */
static PetscErrorCode FluidMaxLoc(Fluid fl, PetscReal loc, const PetscInt cell[3], PetscReal *gmax, PetscInt gcell[3])
{
  PetscMPIInt rank;
  struct {
    double v;
    int    r;
  } in, out;
  PetscInt buf[3];

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(fl->comm, &rank));
  in.v = (double)loc;
  in.r = (int)rank;
  PetscCallMPI(MPI_Allreduce(&in, &out, 1, MPI_DOUBLE_INT, MPI_MAXLOC, fl->comm));
  for (int d = 0; d < 3; d++) buf[d] = cell[d];
  PetscCallMPI(MPI_Bcast(buf, 3, MPIU_INT, out.r, fl->comm));
  *gmax = (PetscReal)out.v;
  for (int d = 0; d < 3; d++) gcell[d] = buf[d];
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Checks dt against the limits; with -fluid_adaptive_dt lowers *dt to 0.9 of the limit. */
static PetscErrorCode FluidCheckStability(Fluid fl, PetscReal *dt, FluidStats *st)
{
  const PetscScalar *u, *eps;
  FluidLimits        lim;
  PetscInt           cc[3], vc[3];
  PetscReal          emin;
  PetscInt           imin;

  PetscFunctionBeginUser;
  PetscCall(VecMin(fl->fld.eps, &imin, &emin));
  PetscCheck(emin > 0 && emin <= 1, fl->comm, PETSC_ERR_ARG_OUTOFRANGE, "fluid porosity %g at global cell index %d is outside (0,1]", (double)emin, (int)imin);
  PetscCall(VecGetArrayRead(fl->fld.uloc, &u));
  PetscCall(VecGetArrayRead(fl->fld.epsloc, &eps));
  FluidLocalLimits(fl, *dt, u, eps, &lim);
  PetscCall(VecRestoreArrayRead(fl->fld.epsloc, &eps));
  PetscCall(VecRestoreArrayRead(fl->fld.uloc, &u));
  PetscCall(FluidMaxLoc(fl, lim.cfl, lim.ccell, &st->cfl, cc));
  PetscCall(FluidMaxLoc(fl, lim.vis, lim.vcell, &st->visc_number, vc));
  if (fl->mom.visc == FLUID_VISC_IMPLICIT) st->visc_number = 0;
  if (fl->clock.adaptive) {
    PetscReal scale = 1;
    if (st->cfl > fl->clock.cfl_max) scale = PetscMin(scale, 0.9 * fl->clock.cfl_max / st->cfl);
    if (st->visc_number > fl->clock.visc_max) scale = PetscMin(scale, 0.9 * fl->clock.visc_max / st->visc_number);
    *dt *= scale;
    st->cfl *= scale;
    st->visc_number *= scale;
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCheck(st->cfl <= fl->clock.cfl_max, fl->comm, PETSC_ERR_ARG_OUTOFRANGE, "fluid time step dt = %g s gives CFL number %g in cell (%d,%d,%d), above the limit -fluid_cfl_max %g: lower dt%s below %g s or use -fluid_adaptive_dt", (double)*dt, (double)st->cfl, (int)cc[0], (int)cc[1], (int)cc[2], (double)fl->clock.cfl_max, fl->clock.dt_name, (double)(*dt * fl->clock.cfl_max / st->cfl));
  PetscCheck(st->visc_number <= fl->clock.visc_max, fl->comm, PETSC_ERR_ARG_OUTOFRANGE, "fluid time step dt = %g s gives explicit viscous number %g in cell (%d,%d,%d), above the limit -fluid_viscous_number_max %g: lower dt%s below %g s, use -fluid_viscous implicit or -fluid_adaptive_dt", (double)*dt, (double)st->visc_number, (int)vc[0], (int)vc[1], (int)vc[2], (double)fl->clock.visc_max, fl->clock.dt_name, (double)(*dt * fl->clock.visc_max / st->visc_number));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FluidSetTimeStepName(Fluid fl, const char *name)
{
  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(fl->clock.dt_name, sizeof fl->clock.dt_name, " (%s)", name));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FluidGetStableTimeStep(Fluid fl, PetscReal *dtmax)
{
  const PetscScalar *u, *eps;
  FluidLimits        lim;
  PetscInt           cell[3];
  PetscReal          cfl, vis;

  PetscFunctionBeginUser;
  PetscCheck(fl->setup, fl->comm, PETSC_ERR_ORDER, "call FluidSetUp before FluidGetStableTimeStep");
  PetscCall(FluidLocalPorosityOld(fl, PETSC_FALSE));
  PetscCall(FluidLocalVelocity(fl, fl->fld.u, fl->fld.uloc, fl->fld.epsoldloc));
  PetscCall(FluidLocalCell(fl, fl->fld.eps, fl->fld.epsloc, PETSC_FALSE, 0.0));
  PetscCall(VecGetArrayRead(fl->fld.uloc, &u));
  PetscCall(VecGetArrayRead(fl->fld.epsloc, &eps));
  FluidLocalLimits(fl, 1.0, u, eps, &lim); /* both numbers are proportional to dt */
  PetscCall(VecRestoreArrayRead(fl->fld.epsloc, &eps));
  PetscCall(VecRestoreArrayRead(fl->fld.uloc, &u));
  PetscCall(FluidMaxLoc(fl, lim.cfl, lim.ccell, &cfl, cell));
  PetscCall(FluidMaxLoc(fl, lim.vis, lim.vcell, &vis, cell));
  *dtmax = PETSC_MAX_REAL;
  if (cfl > 0) *dtmax = fl->clock.cfl_max / cfl;
  if (fl->mom.visc == FLUID_VISC_EXPLICIT && vis > 0) *dtmax = PetscMin(*dtmax, fl->clock.visc_max / vis);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The predictor right-hand side into fl->uhat (active faces); fixed faces keep their value. */
static PetscErrorCode FluidPredictorRHS(Fluid fl, PetscReal dt, const PetscScalar *eps0, const PetscScalar *p)
{
  const FluidGrid   *g  = &fl->g;
  const PetscReal    r  = fl->clock.nsteps ? dt / fl->mom.dt_old : 0;
  const PetscReal    a1 = 1 + 0.5 * r, a0 = -0.5 * r;
  const PetscScalar *u, *A, *A0, *V, *beta, *us, *src;
  PetscScalar       *rhs;
  PetscInt           idx[3], f, c, o;

  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(fl->fld.u, &u));
  PetscCall(VecGetArrayRead(fl->mom.advn, &A));
  PetscCall(VecGetArrayRead(fl->mom.adv_old, &A0));
  PetscCall(VecGetArrayRead(fl->mom.vis, &V));
  PetscCall(VecGetArrayRead(fl->fld.beta, &beta));
  PetscCall(VecGetArrayRead(fl->fld.us, &us));
  PetscCall(VecGetArrayRead(fl->fld.src, &src));
  PetscCall(VecGetArray(fl->mom.uhat, &rhs));
  FLUID_FOR_OWNED_FACES(g, idx, f, c, o)
  for (int d = 0; d < 3; d++) {
    if (!FluidFaceActive(fl, d, idx)) {
      rhs[o + d] = u[o + d];
      continue;
    }
    const PetscScalar ef0 = 0.5 * (eps0[c] + eps0[c - g->cs[d]]);
    const PetscScalar gp  = (p[c] - p[c - g->cs[d]]) / g->h[d];
    rhs[o + d]            = fl->prop.rho * ef0 * u[o + d] / dt - (a1 * A[o + d] + a0 * A0[o + d]) + V[o + d] - gp + fl->prop.rho * ef0 * fl->prop.gravity[d] - fl->prop.dpdx[d] + src[o + d] + beta[o + d] * us[o + d];
  }
  PetscCall(VecRestoreArray(fl->mom.uhat, &rhs));
  PetscCall(VecRestoreArrayRead(fl->fld.src, &src));
  PetscCall(VecRestoreArrayRead(fl->fld.us, &us));
  PetscCall(VecRestoreArrayRead(fl->fld.beta, &beta));
  PetscCall(VecRestoreArrayRead(fl->mom.vis, &V));
  PetscCall(VecRestoreArrayRead(fl->mom.adv_old, &A0));
  PetscCall(VecRestoreArrayRead(fl->mom.advn, &A));
  PetscCall(VecRestoreArrayRead(fl->fld.u, &u));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Explicit predictor: u^ = rhs / (rho eps_f^{n+1}/dt + beta) on the active faces. */
static PetscErrorCode FluidPredictorDiagonal(Fluid fl, PetscReal dt, const PetscScalar *eps)
{
  const FluidGrid   *g = &fl->g;
  const PetscScalar *beta;
  PetscScalar       *uh;
  PetscInt           idx[3], f, c, o;

  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(FluidBetaOfSolve(fl), &beta)); /* with a distributor plate, its resistance too */
  PetscCall(VecGetArray(fl->mom.uhat, &uh));
  FLUID_FOR_OWNED_FACES(g, idx, f, c, o)
  for (int d = 0; d < 3; d++) {
    if (!FluidFaceActive(fl, d, idx)) continue;
    const PetscScalar ef1 = 0.5 * (eps[c] + eps[c - g->cs[d]]);
    uh[o + d] /= fl->prop.rho * ef1 / dt + beta[o + d];
  }
  PetscCall(VecRestoreArray(fl->mom.uhat, &uh));
  PetscCall(VecRestoreArrayRead(FluidBetaOfSolve(fl), &beta));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode FluidPredict(Fluid fl, PetscReal dt)
{
  const PetscScalar *u, *eps, *eps0, *p;
  PetscScalar       *A, *V;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(fl->ev.predict, 0, 0, 0, 0));
  PetscCall(FluidLocalCell(fl, fl->fld.p, fl->fld.ploc, FLUID_GHOST_PRESSURE, fl->bc.p_out));
  PetscCall(VecGetArrayRead(fl->fld.uloc, &u));
  PetscCall(VecGetArrayRead(fl->fld.epsloc, &eps));
  PetscCall(VecGetArrayRead(fl->fld.epsoldloc, &eps0));
  PetscCall(VecGetArrayRead(fl->fld.ploc, &p));
  PetscCall(VecGetArray(fl->mom.advn, &A));
  PetscCall(VecGetArray(fl->mom.vis, &V));
  PetscCall(FluidAdvectionTerm(fl, u, eps0, A));
  PetscCall(FluidViscousTerm(fl, u, eps0, (PetscBool)(fl->mom.visc == FLUID_VISC_IMPLICIT), V));
  PetscCall(VecRestoreArray(fl->mom.vis, &V));
  PetscCall(VecRestoreArray(fl->mom.advn, &A));
  PetscCall(FluidPredictorRHS(fl, dt, eps0, p));
  if (fl->mom.visc == FLUID_VISC_EXPLICIT) PetscCall(FluidPredictorDiagonal(fl, dt, eps));
  PetscCall(VecRestoreArrayRead(fl->fld.ploc, &p));
  PetscCall(VecRestoreArrayRead(fl->fld.epsoldloc, &eps0));
  PetscCall(VecRestoreArrayRead(fl->fld.epsloc, &eps));
  PetscCall(VecRestoreArrayRead(fl->fld.uloc, &u));
  if (fl->mom.visc == FLUID_VISC_IMPLICIT) PetscCall(FluidViscousSolve(fl, dt, fl->mom.uhat, fl->mom.uhat));
  PetscCall(VecCopy(fl->mom.advn, fl->mom.adv_old));
  PetscCall(PetscLogEventEnd(fl->ev.predict, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FluidStep(Fluid fl, PetscReal dt, FluidStats *st)
{
  PetscFunctionBeginUser;
  PetscCheck(fl->setup, fl->comm, PETSC_ERR_ORDER, "call FluidSetUp before FluidStep");
  PetscCheck(dt > 0, fl->comm, PETSC_ERR_ARG_OUTOFRANGE, "fluid time step %g must be > 0 (s)", (double)dt);
  PetscCall(PetscMemzero(st, sizeof *st));
  PetscCall(FluidLocalCell(fl, fl->fld.eps, fl->fld.epsloc, PETSC_FALSE, 0.0));
  PetscCall(FluidLocalPorosityOld(fl, PETSC_TRUE));
  PetscCall(FluidLocalVelocity(fl, fl->fld.u, fl->fld.uloc, fl->fld.epsoldloc)); /* u^n: inlets at eps^n */
  PetscCall(FluidCheckStability(fl, &dt, st));
  /* the inlets at the end of the step actually taken (adaptive stepping may have cut dt); a
   * changed inlet refills the ghosts, and the next step's check sees its velocity */
  PetscBool changed;
  PetscCall(FluidUpdateInlets(fl, fl->clock.time + dt, &changed));
  if (changed) PetscCall(FluidLocalVelocity(fl, fl->fld.u, fl->fld.uloc, fl->fld.epsoldloc));
  if (fl->plate.on || fl->ves.film) PetscCall(FluidResistanceUpdate(fl)); /* the vessel's films, the plate's resistance at u^n */
  PetscCall(FluidPredict(fl, dt));
  PetscCall(FluidProject(fl, dt, st));
  PetscCall(FluidDivergenceMax(fl, dt, &st->div_max));
  PetscCall(VecCopy(fl->fld.eps, fl->fld.eps_old));
  PetscCall(FluidInletsEndStep(fl)); /* u^{n+1}'s level is eps_old now */
  fl->mom.dt_old = dt;
  fl->clock.nsteps++;
  fl->clock.time += dt;
  st->dt = dt;
  PetscFunctionReturn(PETSC_SUCCESS);
}
