/* Moving the fluid onto a new decomposition (load balancing, DESIGN §1). The Domain has new
 * per-axis ownership ranges; the fluid rebuilds its cell and face DMDAs from them and moves
 * every field it keeps from one step to the next (velocity, pressure, porosity and its previous
 * value, drag coefficient, solid velocity, momentum source, the Adams-Bashforth history of the
 * advection term, the last pressure increment; with checkpoints the fields the Poisson
 * preconditioner was built from) through the natural ordering, so each value lands
 * bit for bit on the same grid point (DomainMoveVec). Work vectors are moved as well (cheaper to
 * move than to reason about which hold state). Matrices and the star-stencil DMDAs of the
 * Poisson and viscous solves are rebuilt on the new layout at their next use; the KSPs keep
 * their options. */
#include "fluid/fluid_impl.h"

PetscErrorCode FluidRedistribute(Fluid fl)
{
  DM   ocda = fl->g.cda, ofda = fl->g.fda;
  Vec *cell[] = {&fl->fld.p, &fl->fld.eps, &fl->fld.eps_old, &fl->pois.phi, &fl->pois.rhs};
  Vec *face[] = {&fl->fld.u, &fl->fld.beta, &fl->fld.us, &fl->fld.src, &fl->mom.uhat, &fl->mom.advn, &fl->mom.adv_old, &fl->mom.vis};
  Vec *work[] = {&fl->fld.uloc, &fl->fld.ploc, &fl->fld.epsloc, &fl->fld.epsoldloc, &fl->pois.philoc, &fl->pois.coef, &fl->pois.coefloc, &fl->vimp.bc, &fl->vimp.phiu};

  PetscFunctionBeginUser;
  PetscCheck(fl->setup, fl->comm, PETSC_ERR_ORDER, "call FluidSetUp before FluidRedistribute");
  for (size_t i = 0; i < sizeof work / sizeof work[0]; i++) PetscCall(VecDestroy(work[i]));
  PetscCall(FluidSolversDestroy(fl));
  fl->g.cda = fl->g.fda = NULL;
  PetscCall(FluidCreateDMs(fl));
  for (size_t i = 0; i < sizeof cell / sizeof cell[0]; i++) PetscCall(DomainMoveVec(ocda, fl->g.cda, cell[i]));
  for (size_t i = 0; i < sizeof face / sizeof face[0]; i++) PetscCall(DomainMoveVec(ofda, fl->g.fda, face[i]));
  if (fl->ckpt) {
    PetscCall(DomainMoveVec(ocda, fl->g.cda, &fl->pois.eps_pc));
    PetscCall(DomainMoveVec(ofda, fl->g.fda, &fl->pois.beta_pc));
  }
  PetscCall(DMDestroy(&ocda));
  PetscCall(DMDestroy(&ofda));
  PetscCall(FluidCreateLocals(fl));
  PetscCall(FluidVesselSetUp(fl));        /* the open fractions of the new owned boxes */
  PetscCall(VecDestroy(&fl->plate.beff)); /* the plate's and the patches' work Vecs: remade on the new layout at their next use */
  PetscCall(FluidPatchesRelayout(fl));
  PetscCall(KSPReset(fl->pois.ksp)); /* operators of another size follow */
  PetscCall(FluidPoissonSetUp(fl));
  if (fl->vimp.ksp) {
    PetscCall(KSPReset(fl->vimp.ksp));
    PetscCall(FluidViscousSetUp(fl));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}
