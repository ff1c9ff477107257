/* A random packed bed made by a settle run, then frozen: dimensionless d = 1, rho_p = 2, g = 1.
 * 1,080 spheres start on a jittered lattice (6 x 6 x 30, spacing 1.3 d) with random velocities
 * in an 8 x 8 box and settle under gravity onto a distributor at z = 2 (linear contacts,
 * e = 0.5, friction 0.3, frictionless side walls; a dry DEM run). The settled bed is then frozen
 * and fluid flows through it from below (rho_f = 1, mu = 0.1, U = 1: Re_p = 10; cells of 2 d,
 * free-slip side walls). Reference: the drag law's own prediction -dp/dz = n K U / eps at the
 * mean cell porosity between two planes inside the bed, within 5% (the required bound for a
 * random packing). The walls loosen the packing next to them, so the flow channels there a
 * little and the measured gradient falls below the prediction at the mean porosity (measured:
 * porosity 0.429, 0.7% below). The scenes: test_random_bed_dry.opts (the settle run) and
 * test_random_bed_wet.opts (the flow through the frozen bed). */
#include "cpl_common.h"

static DemParticle *Bed;
static PetscInt     Nbed;

static PetscErrorCode AddBed(Dem dem)
{
  PetscFunctionBeginUser;
  for (PetscInt p = 0; p < Nbed; p++) {
    DemParticle q = Bed[p];
    for (int k = 0; k < 3; k++) q.v[k] = q.w[k] = 0;
    PetscCall(DemAddParticle(dem, &q));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  Domain    dom;
  Dem       dem;
  TestCpl   t;
  CplStats  st;
  DemStats  ds;
  PetscReal zc0, zc1, p0, p1, e, u0, u1, eps, dpdl, pred, ztop = 0;

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(TestDemCreateScene("test_random_bed_dry.opts", NULL, &dom, &dem));
  PetscCall(DemSetUp(dem));
  for (PetscInt s = 0; s < 15000; s++) PetscCall(DemStep(dem));
  PetscCall(DemGetStats(dem, &ds));
  PetscCall(DemGetLocalCount(dem, &Nbed));
  PetscCall(PetscMalloc1(Nbed, &Bed));
  for (PetscInt p = 0; p < Nbed; p++) {
    PetscCall(DemGetParticle(dem, p, &Bed[p]));
    ztop = PetscMax(ztop, Bed[p].x[2] + 0.5);
  }
  PetscCall(TestDemDestroy(&dom, &dem));
  PetscCall(TestCplCreateScene("test_random_bed_wet.opts", NULL, AddBed, &t));
  PetscCall(TestCplRun(&t, 60, &st));
  /* planes: the second cell layer above the distributor and the layer two cells below the top */
  PetscCall(CplGetLayer(t.cpl, 2, 5.0, &zc0, &p0, &e, &u0));
  PetscCall(CplGetLayer(t.cpl, 2, ztop - 4.0, &zc1, &p1, &e, &u1));
  PetscCall(CplMeanPorosity(t.cpl, 2, zc0, zc1, &eps));
  dpdl = (p0 - p1) / (zc1 - zc0);
  pred = CplPackedBedGradient(CPL_DRAG_BEETSTRA, eps, u0, 1, 1, 0.1);
  CheckDetail("bound 1e-3 per sphere; %.2e per sphere, bed top at z = %.2f", (double)(ds.ke / Nbed), (double)ztop);
  PetscCall(CheckBelow(CheckName("settled: kinetic energy of the %" PetscInt_FMT " spheres", Nbed), ds.ke, 1e-3 * Nbed));
  PetscCall(CheckClose(CheckName("random bed Re_p 10: dp/L between z = %.0f and %.0f vs Beetstra at the mean porosity %.4f", (double)zc0, (double)zc1, (double)eps), dpdl, pred, 0.05));
  PetscCall(TestCplDestroy(&t));
  PetscCall(PetscFree(Bed));
  PetscCall(PetscFinalize());
  return check_failures ? 1 : 0;
}
