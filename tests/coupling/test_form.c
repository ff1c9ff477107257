/* The momentum equations' two forms (-cpl_form; Zhou, Kuang, Chu & Yu 2010, J. Fluid Mech.
 * 661:482): B, the fluid feels -grad p and the drag law carries the whole fluid-particle force
 * but buoyancy; A, the fluid feels -eps grad p and the particles -V grad p besides eps times the
 * law's drag. In a steady uniform bed the two are the same force. Physics references:
 *  1. a packed lattice bed (tests/coupling/packed_bed.opts, frozen, bi-periodic, U = 1) at Re_p
 *     1, 10 and 100: dp/L between the layers at z = 8.5 and 15.5 in form A equals form B's to
 *     1e-6 and the drag law's (Beetstra) to 2%, as form B does (test_packed);
 *  2. a disordered packed bed (jittered lattice on cells of 1.2 d, Re_p 10): dp/L of the two
 *     forms within 1% (the porosity varies from cell to cell: the forms differ where the bed is
 *     not uniform);
 *  3. a homogeneous suspension (test_form_suspension.opts: 512 spheres on a lattice, porosity
 *     0.7319, fully periodic, the imposed mean gradient carrying their buoyant weight) settles at
 *     the slip w that solves K(eps, Re) w = (rho_p - rho_f) V g, Re = rho_f d eps w / mu: the
 *     superficial velocity eps w at which a homogeneous bed of that porosity stands (its
 *     expansion law). Both forms within 1e-8 of the law's w, and of each other, at Re_p 0.7
 *     and 38 (mu 0.1 and 0.01; measured 1e-11).
 * The momentum exchange of form A is exact (coupling/test_conserve, check 7). */
/* ranks: 1 2 */
#include "cpl_common.h"

static PetscErrorCode Bed(const char *extra, const char *form, PetscReal mu, PetscReal *dpdl, PetscReal *eps, PetscReal *usup)
{
  TestCpl   t;
  CplStats  st;
  char      opts[2048];
  PetscReal p0, p1, e0, e1, u1, zc0, zc1;

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(opts, sizeof opts, "%s -fluid_viscosity %g -cpl_form %s", extra, (double)mu, form));
  PetscCall(TestCplCreateScene("packed_bed.opts", opts, NULL, &t));
  PetscCall(TestCplRun(&t, 60, &st));
  PetscCall(CplGetLayer(t.cpl, 2, 8.5, &zc0, &p0, &e0, usup));
  PetscCall(CplGetLayer(t.cpl, 2, 15.5, &zc1, &p1, &e1, &u1));
  PetscCall(CplMeanPorosity(t.cpl, 2, zc0, zc1, eps));
  *dpdl = (p0 - p1) / (zc1 - zc0);
  PetscCall(TestCplDestroy(&t));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The suspension's mean slip (interstitial fluid less particles, along z) after n steps, and its
 * porosity. */
static PetscErrorCode Suspension(const char *form, PetscReal mu, PetscInt n, PetscReal *slip, PetscReal *eps)
{
  TestCpl   t;
  CplStats  st;
  char      opts[256];
  PetscReal pp[3], pf[3], ow[3], m;

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(opts, sizeof opts, "-fluid_viscosity %g -cpl_form %s", (double)mu, form));
  PetscCall(TestCplCreateScene("test_form_suspension.opts", opts, NULL, &t));
  PetscCall(TestCplRun(&t, n, &st));
  PetscCall(CplGetMomentum(t.cpl, pp, pf, ow));
  PetscCall(CplMeanPorosity(t.cpl, 2, 0, 10, eps));
  PetscCall(DemGetShape(t.dem, 0, NULL, &m));
  *slip = pf[2] / (*eps * 1000) - pp[2] / (512 * m); /* the scene's 512 spheres in 1000 m^3 */
  PetscCall(TestCplDestroy(&t));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The slip w of a homogeneous bed of Beetstra's law: K(eps, Re) w = (rho_p - rho_f) V g (d = 1,
 * rho_f = 1, rho_p = 2, g = 1), by bisection. */
static PetscReal LawSlip(PetscReal eps, PetscReal mu)
{
  const PetscReal wb = PETSC_PI / 6;
  PetscReal       lo = 1e-8, hi = 10;
  for (int it = 0; it < 200; it++) {
    const PetscReal w = 0.5 * (lo + hi), k = 3 * PETSC_PI * mu * CplDragFactor(CPL_DRAG_BEETSTRA, eps, eps * w / mu);
    if (k * w > wb) hi = w;
    else lo = w;
  }
  return 0.5 * (lo + hi);
}

int main(int argc, char **argv)
{
  const PetscReal re[3] = {1, 10, 100};

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  for (int k = 0; k < 3; k++) {
    PetscReal dA, dB, eps, u, mu = 1 / re[k];
    PetscCall(Bed("-dem_lattice 4,4,12 -dem_lattice_spacing 1 -dem_lattice_origin 0,0,6", "B", mu, &dB, &eps, &u));
    PetscCall(Bed("-dem_lattice 4,4,12 -dem_lattice_spacing 1 -dem_lattice_origin 0,0,6", "A", mu, &dA, &eps, &u));
    PetscCall(CheckClose(CheckName("lattice bed Re_p %g: dp/L, form A vs form B", (double)re[k]), dA, dB, 1e-6));
    PetscCall(CheckClose(CheckName("lattice bed Re_p %g: dp/L, form A vs Beetstra at porosity %.4f", (double)re[k], (double)eps), dA, CplPackedBedGradient(CPL_DRAG_BEETSTRA, eps, u, 1, 1, mu), 0.02));
  }
  {
    const char *jit = "-dem_lattice 3,3,15 -dem_lattice_spacing 1.2 -dem_lattice_origin 0,0,3 -dem_lattice_jitter 1 -dem_seed 7 -da_grid_x 3 -da_grid_y 3 -da_grid_z 20 -domain_hi 3.6,3.6,24";
    PetscReal   dA, dB, eps, u, mu = 0.1;
    PetscCall(Bed(jit, "B", mu, &dB, &eps, &u));
    PetscCall(Bed(jit, "A", mu, &dA, &eps, &u));
    PetscCall(CheckClose(CheckName("disordered bed Re_p 10: dp/L, form A vs form B"), dA, dB, 0.01));
  }
  {
    const PetscReal mus[2] = {0.1, 0.01};
    for (int k = 0; k < 2; k++) {
      PetscReal wA, wB, eA, eB, wl;
      PetscCall(Suspension("B", mus[k], 600, &wB, &eB));
      PetscCall(Suspension("A", mus[k], 600, &wA, &eA));
      wl = LawSlip(eB, mus[k]);
      PetscCall(CheckClose(CheckName("homogeneous suspension, porosity %.4f, mu %g: form B's slip vs Beetstra's homogeneous bed (Re_p %.3g)", (double)eB, (double)mus[k], (double)(eB * wl / mus[k])), wB, wl, 1e-8));
      PetscCall(CheckClose(CheckName("homogeneous suspension, porosity %.4f, mu %g: form A's slip vs Beetstra's homogeneous bed", (double)eA, (double)mus[k]), wA, wl, 1e-8));
      PetscCall(CheckClose(CheckName("homogeneous suspension, mu %g: form A's slip vs form B's", (double)mus[k]), wA, wB, 1e-8));
    }
  }
  PetscCall(PetscFinalize());
  return check_failures ? 1 : 0;
}
