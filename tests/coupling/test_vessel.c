/* The coupling in a vessel that cuts the fluid grid (src/coupling/vessel.c): the scene
 * vessel_cylinder.opts, 196 beads in a cylinder of radius 8 mm (-dem_cylinder, the gas inside) on
 * cells of 2 mm, air blown up at 0.5 m/s. The vessel's level function is the DEM's
 * (DemVesselSetUp, DemVesselLevel), given to the fluid before its set-up as the coupled driver
 * does. References are exact identities of the scheme:
 *  1. the vessel cuts the grid, and the cells and faces outside it are closed;
 *  2. the solid volume on the grid, sum over cells of (1 - eps) vol_c V_cell, equals the
 *     particles' volume to 1e-12 relative at the start and after 20 coupling steps (the outer
 *     beads' kernels reach cut cells: without the renormalisation by the open volume it would not);
 *  3. nothing lands in closed volume: eps = 1 exactly in every closed cell, the drag coefficient
 *     beta = 0 exactly on every closed face;
 *  4. the drag lands whole on the faces the fluid solves: per component, sum over faces of
 *     beta a_f V_cell (a face's momentum control volume) equals the particles' sum of K to 1e-12
 *     relative;
 *  5. no gas through the solid: u = 0 exactly on every closed face after 20 steps.
 * On 1 and 2 ranks (2: the cut z = 20 mm runs through the bed). About 3 s. */
/* ranks: 1 2 */
#include "cpl_common.h"

static PetscErrorCode Build(TestCpl *t)
{
  PetscBool vessel;

  PetscFunctionBeginUser;
  PetscCall(DomainCreate(PETSC_COMM_WORLD, 1.0, 1, &t->dom));
  PetscCall(DemCreate(&t->dom, &t->dem));
  PetscCall(DemSetFromOptions(t->dem));
  PetscCall(DemExternalSetFromOptions(t->dem));
  PetscCall(FluidCreate(&t->dom, &t->fl));
  PetscCall(FluidSetFromOptions(t->fl));
  PetscCall(CplCreate(&t->dom, t->dem, t->fl, &t->cpl));
  PetscCall(CplSetFromOptions(t->cpl));
  PetscCall(DemSetUp(t->dem));
  PetscCall(DemVesselSetUp(t->dem, &vessel));
  PetscCall(CheckTrue("the cylinder bounds the gas (DemVesselSetUp)", vessel, vessel ? "yes" : "no"));
  PetscCall(FluidSetVessel(t->fl, DemVesselLevel, t->dem));
  PetscCall(FluidSetUp(t->fl));
  PetscCall(CplSetUp(t->cpl));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Checks 2-5 at this time (label). */
static PetscErrorCode Check(TestCpl *t, const char *label, PetscBool flow)
{
  Vec                vol, area, eps, beta, u;
  const PetscScalar *v, *a, *e, *b, *w;
  PetscInt           nc, nf, nclosed[2] = {0, 0};
  PetscReal          g, p, bad[3] = {0, 0, 0}, sum[3] = {0, 0, 0}, ksum = 0, cv = t->dom.h[0] * t->dom.h[1] * t->dom.h[2];
  DemExternal        ex;
  DemArrays          pa;

  PetscFunctionBeginUser;
  PetscCall(FluidGetOpenFractions(t->fl, &vol, &area));
  PetscCall(FluidGetPorosity(t->fl, &eps));
  PetscCall(FluidGetDragCoefficient(t->fl, &beta));
  PetscCall(FluidGetVelocity(t->fl, &u));
  PetscCall(VecGetLocalSize(vol, &nc));
  PetscCall(VecGetLocalSize(area, &nf));
  PetscCall(VecGetArrayRead(vol, &v));
  PetscCall(VecGetArrayRead(area, &a));
  PetscCall(VecGetArrayRead(eps, &e));
  PetscCall(VecGetArrayRead(beta, &b));
  PetscCall(VecGetArrayRead(u, &w));
  for (PetscInt c = 0; c < nc; c++)
    if (v[c] == 0) nclosed[0]++, bad[0] = PetscMax(bad[0], PetscAbsReal(e[c] - 1));
  for (PetscInt f = 0; f < nf; f++) {
    sum[f % 3] += b[f] * a[f] * cv;
    if (a[f] == 0) nclosed[1]++, bad[1] = PetscMax(bad[1], PetscAbsReal(b[f])), bad[2] = PetscMax(bad[2], PetscAbsReal(w[f]));
  }
  PetscCall(VecRestoreArrayRead(u, &w));
  PetscCall(VecRestoreArrayRead(beta, &b));
  PetscCall(VecRestoreArrayRead(eps, &e));
  PetscCall(VecRestoreArrayRead(area, &a));
  PetscCall(VecRestoreArrayRead(vol, &v));
  PetscCall(DemGetArrays(t->dem, &pa));
  PetscCall(DemGetExternal(t->dem, &ex));
  for (PetscInt q = 0; q < pa.nlocal; q++) ksum += ex.k[q];
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, nclosed, 2, MPIU_INT, MPI_SUM, PETSC_COMM_WORLD));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, bad, 3, MPIU_REAL, MPIU_MAX, PETSC_COMM_WORLD));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, sum, 3, MPIU_REAL, MPIU_SUM, PETSC_COMM_WORLD));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &ksum, 1, MPIU_REAL, MPIU_SUM, PETSC_COMM_WORLD));
  PetscCall(CplGetSolidVolume(t->cpl, &g, &p));
  PetscCall(CheckAbove(CheckName("%s: closed cells (outside the cylinder)", label), (PetscReal)nclosed[0], 0));
  PetscCall(CheckBelow(CheckName("%s: solid volume on the grid vs the particles' (rel.)", label), PetscAbsReal(g - p) / p, 1e-12));
  PetscCall(CheckEqualReal(CheckName("%s: largest |eps - 1| in the %" PetscInt_FMT " closed cells", label, nclosed[0]), bad[0], 0));
  if (!flow) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(CheckEqualReal(CheckName("%s: largest |beta| on the %" PetscInt_FMT " closed faces", label, nclosed[1]), bad[1], 0));
  for (int d = 0; d < 3; d++) PetscCall(CheckBelow(CheckName("%s: sum of beta a_f V_cell over the %c faces vs the particles' sum of K (rel.)", label, "xyz"[d]), PetscAbsReal(sum[d] - ksum) / ksum, 1e-12));
  PetscCall(CheckEqualReal(CheckName("%s: largest |u| on the closed faces (no gas through the solid)", label), bad[2], 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  TestCpl   t;
  CplStats  st;
  PetscBool cut;

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(TestSceneLoad(PETSC_COMM_WORLD, "vessel_cylinder.opts", NULL));
  PetscCall(Build(&t));
  PetscCall(FluidVesselActive(t.fl, &cut));
  PetscCall(CheckTrue("the cylinder cuts the fluid grid", cut, cut ? "yes" : "no"));
  PetscCall(Check(&t, "start", PETSC_FALSE));
  for (int s = 0; s < 20; s++) PetscCall(CplStep(t.cpl, &st));
  PetscCall(Check(&t, "after 20 steps", PETSC_TRUE));
  PetscCall(CplDestroy(&t.cpl));
  PetscCall(FluidDestroy(&t.fl));
  PetscCall(TestDemDestroy(&t.dom, &t.dem));
  PetscCall(PetscFinalize());
  return 0;
}
