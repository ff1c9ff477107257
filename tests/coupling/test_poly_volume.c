/* Spheres of their own sizes in a coupled run: the closed periodic box of test_conserve.opts
 * (64 spheres, fluid at rest, no gravity) with every sphere given its own radius, a function of
 * its id between 0.35 and 0.65 (the material shape's radius is 0.5). The cube kernel spreads each
 * sphere's own volume 4/3 pi r_i^3 (DemArrays.r) and the drag takes its own diameter. References,
 * exact identities of the scheme:
 *  1. the particles' volume equals sum_i 4/3 pi r_i^3 computed here from the ids, to 1e-12
 *     relative (not 64 x 4/3 pi 0.5^3, which differs by percents);
 *  2. the solid volume on the grid (sum of (1 - eps) V_cell) equals it to 1e-12 relative, after
 *     1 and after 40 coupling steps (the spheres move, on 1 and 2 ranks through ghost cells);
 *  3. particle + fluid + owed momentum is constant to 1e-10 of sum |m_i v_i| over 40 steps with
 *     each sphere's own mass. */
/* ranks: 1 2 */
#include "cpl_common.h"

static double RadiusOf(PetscInt id)
{
  const double u = 0.6180339887498949 * (double)(id + 1);
  return 0.35 + 0.3 * (u - PetscFloorReal(u));
}

static PetscErrorCode Declare(Dem dem)
{
  PetscFunctionBeginUser;
  PetscCall(DemSetOwnSizes(dem, 0.35, 0.65));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Gives every local sphere its own radius; returns sum_i 4/3 pi r_i^3 over all (collective). */
static PetscErrorCode Resize(TestCpl *t, PetscReal *vol)
{
  PetscInt  n;
  PetscReal v = 0;

  PetscFunctionBeginUser;
  PetscCall(DemGetLocalCount(t->dem, &n));
  for (PetscInt i = 0; i < n; i++) {
    DemParticle p = {0};
    PetscCall(DemGetParticle(t->dem, i, &p));
    p.r = RadiusOf(p.id);
    PetscCall(DemSetParticle(t->dem, i, &p));
    v += 4.0 / 3.0 * PETSC_PI * p.r * p.r * p.r;
  }
  PetscCall(MPIU_Allreduce(&v, vol, 1, MPIU_REAL, MPIU_SUM, PETSC_COMM_WORLD));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode Momentum(TestCpl *t, PetscReal P[3], PetscReal *scale)
{
  PetscReal pp[3], pf[3], ow[3], s = 0;
  DemArrays pa;

  PetscFunctionBeginUser;
  PetscCall(CplGetMomentum(t->cpl, pp, pf, ow));
  for (int k = 0; k < 3; k++) P[k] = pp[k] + pf[k] + ow[k];
  PetscCall(DemGetArrays(t->dem, &pa));
  for (PetscInt p = 0; p < pa.nlocal; p++) {
    const PetscReal m = 2 * 4.0 / 3.0 * PETSC_PI * pa.r[p] * pa.r[p] * pa.r[p];
    s += m * PetscSqrtReal(pa.v[3 * p] * pa.v[3 * p] + pa.v[3 * p + 1] * pa.v[3 * p + 1] + pa.v[3 * p + 2] * pa.v[3 * p + 2]);
  }
  PetscCall(MPIU_Allreduce(&s, scale, 1, MPIU_REAL, MPIU_SUM, PETSC_COMM_WORLD));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  TestCpl   t;
  CplStats  st;
  PetscReal vref, g, p, P0[3], P1[3], s0, s1, err = 0;

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(TestCplCreateScene("test_conserve.opts", "-dem_lattice_jitter 0.3", Declare, &t));
  PetscCall(Resize(&t, &vref));
  PetscCall(TestCplRun(&t, 1, &st));
  PetscCall(CplGetSolidVolume(t.cpl, &g, &p));
  PetscCall(CheckClose("own sizes: the particles' volume vs sum 4/3 pi r_i^3 of their radii", p, vref, 1e-12));
  PetscCall(CheckClose("own sizes: solid volume on the grid vs the particles', after 1 step", g, p, 1e-12));
  CheckDetail("bound 1e-12; the material shape's 64 x 4/3 pi 0.5^3 would be off by %.2e", PetscAbsReal(64 * 4.0 / 3.0 * PETSC_PI * 0.125 - vref) / vref);
  PetscCall(CheckBelow("own sizes: relative difference of sum 4/3 pi r_i^3 from 64 equal spheres (the sizes are used)", -PetscAbsReal(64 * 4.0 / 3.0 * PETSC_PI * 0.125 - vref) / vref, -1e-3));
  PetscCall(Momentum(&t, P0, &s0));
  PetscCall(TestCplRun(&t, 40, &st));
  PetscCall(CplGetSolidVolume(t.cpl, &g, &p));
  PetscCall(Momentum(&t, P1, &s1));
  for (int k = 0; k < 3; k++) err = PetscMax(err, PetscAbsReal(P1[k] - P0[k]) / s0);
  PetscCall(CheckClose("own sizes: solid volume on the grid vs the particles', after 41 steps", g, p, 1e-12));
  PetscCall(CheckClose("own sizes: the particles' volume after 41 steps vs sum 4/3 pi r_i^3", p, vref, 1e-12));
  PetscCall(CheckBelow("own sizes: particle + fluid + owed momentum over 40 steps: max change / sum|m_i v_i|", err, 1e-10));
  PetscCall(TestCplDestroy(&t));
  PetscCall(PetscFinalize());
  return check_failures ? 1 : 0;
}
