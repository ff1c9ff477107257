/* The fluid's state before the first coupling step (-cpl_init_fluid). A fluid at rest under an
 * inlet that blows at U (or through a bed that it should already carry) is not the state the
 * flow starts from: the first coupling step's drag then sees u = 0 at the particles, and a
 * particle falls freely for one fluid step before the drag reacts. The choices:
 *   rest    u = 0 (the inlet's value on its own faces): the state of every run before these
 *           options, kept bit for bit;
 *   uniform u_f = U / eps_f at every face (fluid/init.c), U the inlet's superficial velocity at
 *           t = 0: exact for a dilute or one-way run in a uniform column, a start a bed's first
 *           projection corrects;
 *   steady  pseudo steps of the coupling step's length through the initial bed held fixed (the
 *           drag of the particles at rest or at their initial velocity, recomputed each pseudo
 *           step), from the uniform state, until a step changes the velocity by less than
 *           -cpl_init_fluid_rtol of its maximum (-cpl_init_fluid_max_steps at most: otherwise an
 *           error). The fluid's clock and step count are put back (FluidSetClock) after each
 *           pseudo step, so each sees the inlet the first real step sees and the run starts at
 *           t = 0 with the first-step advection. Nothing is owed to the fluid: the particles do
 *           not move, so no momentum passes between the sides.
 * A run continued from a checkpoint takes the checkpoint's fluid instead (CplSetRestarting). */
#include "coupling/coupling_impl.h"

static PetscErrorCode CplUniformFluid(Cpl cpl)
{
  PetscReal U[3];
  PetscInt  n;

  PetscFunctionBeginUser;
  PetscCall(FluidGetInletVelocity(cpl->fl, U, &n));
  PetscCheck(n > 0, cpl->comm, PETSC_ERR_ARG_INCOMP, "-cpl_init_fluid %s: the fluid has no inlet face (-fluid_bc_<side> inlet) to take the velocity from; use -cpl_init_fluid rest", cpl->start.init == CPL_INIT_STEADY ? "steady" : "uniform");
  PetscCall(FluidSetSuperficialVelocity(cpl->fl, U));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode CplSteadyFluid(Cpl cpl)
{
  Vec        u, prev;
  PetscReal  t0, change = 0, umax = 0;
  PetscInt   n0;
  FluidStats fs;

  PetscFunctionBeginUser;
  PetscCall(FluidGetVelocity(cpl->fl, &u));
  PetscCall(VecDuplicate(u, &prev));
  PetscCall(FluidGetClock(cpl->fl, &t0, &n0));
  for (cpl->start.its = 1; cpl->start.its <= cpl->start.max_steps; cpl->start.its++) {
    PetscCall(VecCopy(u, prev));
    PetscCall(CplSetParticleDrag(cpl));
    if (cpl->drag.mode == CPL_MODE_TWOWAY) PetscCall(CplSetFluidDrag(cpl));
    PetscCall(FluidStep(cpl->fl, cpl->clock.dt, &fs));
    PetscCall(FluidSetClock(cpl->fl, t0, n0));
    PetscCall(VecAXPY(prev, -1.0, u));
    PetscCall(VecNorm(prev, NORM_INFINITY, &change));
    PetscCall(VecNorm(u, NORM_INFINITY, &umax));
    if (change <= cpl->start.rtol * umax) break;
  }
  PetscCall(VecDestroy(&prev));
  PetscCheck(change <= cpl->start.rtol * umax, cpl->comm, PETSC_ERR_NOT_CONVERGED, "-cpl_init_fluid steady: a pseudo step still changed the velocity by %g of its maximum %g m/s after -cpl_init_fluid_max_steps %d, above -cpl_init_fluid_rtol %g: raise one of them", (double)(umax > 0 ? change / umax : change), (double)umax, (int)cpl->start.max_steps, (double)cpl->start.rtol);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CplInitFluidState(Cpl cpl)
{
  PetscFunctionBeginUser;
  if (cpl->start.init == CPL_INIT_REST) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(CplUniformFluid(cpl));
  if (cpl->start.init == CPL_INIT_STEADY) PetscCall(CplSteadyFluid(cpl));
  PetscFunctionReturn(PETSC_SUCCESS);
}
