/* Packed bed: frozen spheres (d = 1) in a column with bi-periodic sides, uniform inflow U = 1
 * from below, outlet above (dimensionless, rho_f = 1, mu = 1/Re_p). Physics reference: in a
 * uniform bed the fluid momentum balance is -dp/dz = n K U/eps (n particles per volume, K the
 * drag coefficient of the law at the bed porosity and Re_p = rho d U/mu), i.e. the drag law's
 * own prediction; Ergun's equation is the empirical reference (Beetstra's low-Re limit
 * 180 (1-eps)^2/eps^3 lies 20% above Ergun's 150).
 *  1. Simple cubic lattice of touching spheres, one per cell: the porosity between the planes is
 *     1 - pi/6 (each sphere's kernel cube fills its own cell's solid share: 1e-12); Re_p = 1, 10,
 *     100: dp/L between two planes inside the bed within 2% of Beetstra (measured: 3e-12; the
 *     drag law itself is checked against its published formula in tests/coupling/test_drag_laws.c).
 *  2. The same against Ergun: within 25%; the Gidaspow and Di Felice options against their own
 *     prediction at Re_p = 10.
 *  3. A disordered bed (lattice of spacing 1.2 d, each sphere moved randomly by up to the gap,
 *     porosity 0.70 on average, varying cell to cell; a stand-in for a settled random packing,
 *     which needs a settle run) within 5% of Beetstra at the mean cell porosity between the
 *     planes (measured 1.1%).
 * Run on 1, 2 and 4 ranks (the fluid grid is split along z and y). The scene: packed_bed.opts. */
/* ranks: 1 2 4 */
#include "cpl_common.h"

static PetscErrorCode Bed(const char *extra, PetscReal mu, PetscReal z0, PetscReal z1, PetscReal *dpdl, PetscReal *eps, PetscReal *usup)
{
  TestCpl   t;
  CplStats  st;
  char      opts[2048];
  PetscReal p0, p1, e0, e1, u1, zc0, zc1;

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(opts, sizeof opts, "%s -fluid_viscosity %g", extra, (double)mu));
  PetscCall(TestCplCreateScene("packed_bed.opts", opts, NULL, &t));
  PetscCall(TestCplRun(&t, 60, &st));
  PetscCall(CplGetLayer(t.cpl, 2, z0, &zc0, &p0, &e0, usup));
  PetscCall(CplGetLayer(t.cpl, 2, z1, &zc1, &p1, &e1, &u1));
  PetscCall(CplMeanPorosity(t.cpl, 2, zc0, zc1, eps));
  *dpdl = (p0 - p1) / (zc1 - zc0);
  PetscCall(TestCplDestroy(&t));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscReal Ergun(PetscReal eps, PetscReal U, PetscReal mu)
{
  const PetscReal e3 = eps * eps * eps;
  return 150 * mu * PetscSqr(1 - eps) * U / e3 + 1.75 * (1 - eps) * U * U / e3;
}

int main(int argc, char **argv)
{
  const PetscReal re[3] = {1, 10, 100};

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  for (int k = 0; k < 3; k++) {
    PetscReal dpdl, eps, u, pred, erg, mu = 1 / re[k];
    PetscCall(Bed("-dem_lattice 4,4,12 -dem_lattice_spacing 1 -dem_lattice_origin 0,0,6", mu, 8.5, 15.5, &dpdl, &eps, &u));
    pred = CplPackedBedGradient(CPL_DRAG_BEETSTRA, eps, u, 1, 1, mu);
    erg  = Ergun(eps, u, mu);
    if (k == 0) PetscCall(CheckCloseAbs("lattice bed: porosity between the planes vs 1 - pi/6", eps, 1 - PETSC_PI / 6, 1e-12));
    PetscCall(CheckClose(CheckName("lattice bed Re_p %g: dp/L vs Beetstra at porosity %.4f", (double)re[k], (double)eps), dpdl, pred, 0.02));
    PetscCall(CheckClose(CheckName("lattice bed Re_p %g: dp/L vs Ergun", (double)re[k]), dpdl, erg, 0.25));
  }
  {
    const char      *name[2] = {"gidaspow", "difelice"};
    const CplDragLaw law[2]  = {CPL_DRAG_GIDASPOW, CPL_DRAG_DIFELICE};
    for (int k = 0; k < 2; k++) {
      PetscReal dpdl, eps, u, pred, mu = 0.1;
      char      extra[256];
      PetscCall(PetscSNPrintf(extra, sizeof extra, "-dem_lattice 4,4,12 -dem_lattice_spacing 1 -dem_lattice_origin 0,0,6 -cpl_drag %s", name[k]));
      PetscCall(Bed(extra, mu, 8.5, 15.5, &dpdl, &eps, &u));
      pred = CplPackedBedGradient(law[k], eps, u, 1, 1, mu);
      PetscCall(CheckClose(CheckName("lattice bed Re_p 10, -cpl_drag %s: dp/L vs the law's", name[k]), dpdl, pred, 0.02));
    }
  }
  {
    PetscReal dpdl, eps, u, pred, mu = 0.1;
    PetscCall(Bed("-dem_lattice 3,3,15 -dem_lattice_spacing 1.2 -dem_lattice_origin 0,0,3 -dem_lattice_jitter 1 -dem_seed 7 -da_grid_x 3 -da_grid_y 3 -da_grid_z 20 -domain_hi 3.6,3.6,24", mu, 6, 18, &dpdl, &eps, &u));
    pred = CplPackedBedGradient(CPL_DRAG_BEETSTRA, eps, u, 1, 1, mu);
    PetscCall(CheckClose(CheckName("disordered bed Re_p 10: dp/L vs Beetstra at porosity %.4f", (double)eps), dpdl, pred, 0.05));
  }
  PetscCall(PetscFinalize());
  return check_failures ? 1 : 0;
}
