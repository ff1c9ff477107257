/* Initial fluid states and the clock of a run that starts from one. A coupled run may start its
 * fluid moving instead of at rest (coupling/couple.c, -cpl_init_fluid):
 *   - uniform: the superficial velocity U of the inlet (-fluid_bc_<face>_velocity at t = 0) over
 *     the face porosity, u_f = U / eps_f, at every active face. Through every face layer normal
 *     to an axis the flux eps_f u_f is U's component, so div(eps u) = 0 holds exactly with a
 *     uniform porosity and within the porosity's variation otherwise (the first projection
 *     removes the rest);
 *   - steady: pseudo steps of the fluid through a fixed bed until the velocity stops changing;
 *     the fluid's clock and step count are then put back (FluidSetClock), so that the first real
 *     step starts at t = 0 with the first-step (Euler) advection and sees the inlet at dt.
 * FluidGetInletVelocity gives U (without an inlet face, the flow of the inlet patches on one box
 * face over its open area, patch.c); FluidSetClock the clock. Units SI. */
#include "fluid/fluid_impl.h"

PetscErrorCode FluidGetInletVelocity(Fluid fl, PetscReal U[3], PetscInt *ninlet)
{
  PetscInt n = 0;

  PetscFunctionBeginUser;
  for (int k = 0; k < 3; k++) U[k] = 0;
  for (int d = 0; d < 3; d++)
    for (int s = 0; s < 2; s++) {
      const FluidBC *bc = &fl->bc.face[d][s];
      if (bc->type != FLUID_BC_INLET) continue;
      PetscCheck(n == 0 || (bc->vel[0] == U[0] && bc->vel[1] == U[1] && bc->vel[2] == U[2]), fl->comm, PETSC_ERR_ARG_INCOMP, "-fluid_bc_%c%s_velocity %g,%g,%g differs from another inlet's %g,%g,%g: a uniform initial fluid needs one inlet velocity", "xyz"[d], s ? "hi" : "lo", (double)bc->vel[0], (double)bc->vel[1], (double)bc->vel[2], (double)U[0], (double)U[1], (double)U[2]);
      for (int k = 0; k < 3; k++) U[k] = bc->vel[k];
      n++;
    }
  if (!n) PetscCall(FluidPatchInletVelocity(fl, U, &n)); /* inlet patches on one face: their flow over its open area */
  *ninlet = n;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FluidSetSuperficialVelocity(Fluid fl, const PetscReal U[3])
{
  const FluidGrid   *g = &fl->g;
  const PetscScalar *eps;
  PetscScalar       *u;
  PetscInt           idx[3], f, c, o;

  PetscFunctionBeginUser;
  PetscCheck(fl->setup, fl->comm, PETSC_ERR_ORDER, "call FluidSetUp before FluidSetSuperficialVelocity");
  PetscCall(FluidLocalCell(fl, fl->fld.eps, fl->fld.epsloc, PETSC_FALSE, 0.0));
  PetscCall(VecGetArrayRead(fl->fld.epsloc, &eps));
  PetscCall(VecGetArray(fl->fld.u, &u));
  FLUID_FOR_OWNED_FACES(g, idx, f, c, o)
  for (int d = 0; d < 3; d++)
    if (FluidFaceActive(fl, d, idx)) u[o + d] = U[d] / (0.5 * (eps[c] + eps[c - g->cs[d]]));
  PetscCall(VecRestoreArray(fl->fld.u, &u));
  PetscCall(VecRestoreArrayRead(fl->fld.epsloc, &eps));
  PetscCall(FluidBoundaryFaceValues(fl, fl->fld.u));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FluidGetClock(Fluid fl, PetscReal *t, PetscInt *nsteps)
{
  PetscFunctionBeginUser;
  *t      = fl->clock.time;
  *nsteps = fl->clock.nsteps;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FluidSetClock(Fluid fl, PetscReal t, PetscInt nsteps)
{
  PetscFunctionBeginUser;
  fl->clock.time   = t;
  fl->clock.nsteps = nsteps;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FluidGetAdaptive(Fluid fl, PetscBool *on)
{
  PetscFunctionBeginUser;
  *on = fl->clock.adaptive;
  PetscFunctionReturn(PETSC_SUCCESS);
}
