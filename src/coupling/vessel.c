/* The coupling in a vessel that cuts the fluid grid (the fluid's FAVOR fractions, src/fluid):
 * vol_c the open-volume fraction of cell c, a_f the open-area fraction of face f.
 *   - deposits: a particle's kernel weights W_pc (kernel.c) are multiplied by vol_c and
 *     renormalised, W'_pc = W_pc vol_c / Z_p, Z_p = sum_c W_pc vol_c, so its whole volume lands in
 *     open volume; the porosity of the open part of a cell is then
 *     eps_c = 1 - V_solid,c / (vol_c V_cell) = 1 - sum_p V_p W_pc / (Z_p V_cell)  (vol_c cancels),
 *     clipped as in a box; closed cells keep eps = 1. Face fields (drag, impulses) alike: a face's
 *     momentum control volume is a_f V_cell (FAVOR), so Z_p^d = sum_f W_pf a_f per component and
 *     the density deposited on face f is K_p W_pf Z_p^-1 / V_cell (its share W_pf a_f / Z_p over
 *     its volume a_f V_cell); closed faces (a_f = 0, held at u = 0) weigh nothing. The fluid side
 *     of the exchange (exchange.c) and the gas momentum (diag.c) count each face as a_f V_cell, so
 *     sum_f a_f V_cell beta_f (u_f - us_f) = sum_p K_p (...): exact as in a box; and a layer's
 *     pressure drop holds the bed over sum_f a_f h^2 (about pi R^2 in a cylinder), not over a
 *     count of whole faces (which was several % off on cells of 2 to 4 diameters).
 *   - reads: the porosity and velocity at a particle are the same renormalised weights'
 *     averages (the transpose of the deposit), so nothing is read from closed cells or faces.
 * The per-particle 1/Z are kept in the stencils (CplStencil zc, zf). A kernel that meets no open
 * cell (a particle outside the vessel) keeps its box weights: its volume lands in closed cells
 * and is lost; counted, with one warning. Without a cut (or without a vessel) nothing of this
 * runs: the box path is the one of before, bit for bit. Not with the diffusion filter, the
 * porosity width or the self corrections (refused in one line). */
#include "coupling/coupling_impl.h"

/* Collective. The fluid's fractions (CplSetUp, before the first stencils; CplRedistribute, which
 * invalidates the stencils after). */
PetscErrorCode CplVesselSetUp(Cpl cpl)
{
  PetscFunctionBeginUser;
  PetscCall(CplVesselDestroy(cpl));
  PetscCall(FluidVesselActive(cpl->fl, &cpl->ves.on));
  if (!cpl->ves.on) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCheck(cpl->filt.width == 0, cpl->comm, PETSC_ERR_SUP, "-cpl_filter_width %g: the diffusion filter does not know the vessel that cuts the fluid grid (its fluxes would cross the walls); leave it out", (double)cpl->filt.width);
  PetscCheck(cpl->pw.width == 0, cpl->comm, PETSC_ERR_SUP, "-cpl_porosity_width %g: the smoothed porosity does not know the vessel that cuts the fluid grid; leave it out", (double)cpl->pw.width);
  PetscCheck(!cpl->self.eps && !cpl->self.u, cpl->comm, PETSC_ERR_SUP, "%s: the self corrections do not know the vessel that cuts the fluid grid; leave it out", cpl->self.eps ? "-cpl_self_porosity" : "-cpl_self_velocity");
  PetscCall(FluidGetOpenFractions(cpl->fl, &cpl->ves.vol, &cpl->ves.area));
  PetscCall(DMCreateLocalVector(cpl->cda, &cpl->ves.vloc));
  PetscCall(DMCreateLocalVector(cpl->fda, &cpl->ves.aloc));
  PetscCall(DMGlobalToLocal(cpl->cda, cpl->ves.vol, INSERT_VALUES, cpl->ves.vloc));
  PetscCall(DMGlobalToLocal(cpl->fda, cpl->ves.area, INSERT_VALUES, cpl->ves.aloc));
  PetscFunctionReturn(PETSC_SUCCESS); /* the stencils' shares: computed with the stencils, which the callers invalidate */
}

PetscErrorCode CplVesselDestroy(Cpl cpl)
{
  PetscFunctionBeginUser;
  PetscCall(VecDestroy(&cpl->ves.vloc));
  PetscCall(VecDestroy(&cpl->ves.aloc));
  cpl->ves.vol = cpl->ves.area = NULL;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Not collective. Zeroes the entries of a global cell Vec (face: a face Vec) in closed cells (faces). */
PetscErrorCode CplVesselMask(Cpl cpl, Vec v, PetscBool face)
{
  const PetscScalar *f;
  PetscScalar       *a;
  PetscInt           n;

  PetscFunctionBeginUser;
  PetscCall(VecGetLocalSize(v, &n));
  PetscCall(VecGetArrayRead(face ? cpl->ves.area : cpl->ves.vol, &f));
  PetscCall(VecGetArray(v, &a));
  for (PetscInt i = 0; i < n; i++)
    if (f[i] == 0) a[i] = 0;
  PetscCall(VecRestoreArray(v, &a));
  PetscCall(VecRestoreArrayRead(face ? cpl->ves.area : cpl->ves.vol, &f));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. The kernels of the last stencils that met no open cell: one warning, the first time. */
PetscErrorCode CplVesselLost(Cpl cpl)
{
  PetscInt lost = cpl->ves.lost;

  PetscFunctionBeginUser;
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &lost, 1, MPIU_INT, MPI_SUM, cpl->comm));
  if (lost > 0 && cpl->ves.lost_total == 0) PetscCall(PetscPrintf(cpl->comm, "warning: %" PetscInt_FMT " particle(s) lie wholly in the vessel's solid (their kernels meet no open cell): their volume and drag are lost to the fluid\n", lost));
  cpl->ves.lost_total += lost;
  PetscFunctionReturn(PETSC_SUCCESS);
}
