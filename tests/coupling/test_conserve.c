/* Conservation in a closed periodic box (dimensionless: d = 1, rho_f = 1, rho_p = 2, mu = 0.1,
 * no gravity, the fluid at rest, 64 spheres on a jittered lattice with random velocities).
 * References are exact identities of the scheme:
 *  1. solid volume on the grid (sum over cells of (1 - eps) V_cell) equals the particles'
 *     volume to 1e-12 relative, at the start and after the particles moved;
 *     and the particles' volume is 64 pi/6 (the cubes': 64 x 0.9^3);
 *  2. particle momentum + fluid momentum + the exchange still owed to the fluid is constant to
 *     1e-10 relative to sum |m v| over 40 coupling steps, while the fluid picks up momentum
 *     (the drag is implicit on both sides; couple.c explains the bookkeeping);
 *  2b. particle + fluid momentum alone (as the requirement words it) differ from their start by the owed
 *     part, the momentum in transit (the change of drag over one step): 2.5e-4 of sum |m v| after
 *     the first step, so that sum alone is NOT constant to 1e-10 at a step's end. The check: the
 *     owed part vanishes as the box relaxes, below 1e-2 of its first-step value after 400 steps
 *     (nothing stays in transit; it tracks the exchange itself, which falls ~150x meanwhile);
 *  3. the same on 2 and 4 ranks, where particles near a rank boundary spread into the
 *     neighbour's cells through the ghost cells;
 *  4. checks 1-2 with cubes (edge 0.9 d, random orientations): the kernel takes the true volume;
 *  5. check 2 with the self corrections on everywhere (-cpl_self_porosity -cpl_self_velocity,
 *     no fade): the drag coefficient changes (the particles keep more momentum than without,
 *     by more than 1e-3 of sum |m v|: the correction acts) and the exchange stays exact;
 *  6. the same with the drag's porosity smoothed over 2 d (-cpl_porosity_width 2: the drag sees
 *     the superficial velocity over that porosity, the fluid's face coefficient follows);
 *  7. the same in the pressure-gradient form (-cpl_form A): the particles' -V grad p comes back to
 *     the fluid face by face, so the exchange stays exact.
 * The Poisson solve of a fully periodic box is singular; hypre's default Gaussian elimination on the
 * coarsest level then fails now and then on 2 ranks (a fluid-side limitation, reported), so this
 * test relaxes the coarsest level instead. The scene: test_conserve.opts. */
/* ranks: 1 2 4 */
#include "cpl_common.h"

/* Largest component of the owed momentum and of P_p + P_f - P0. */
static PetscErrorCode Transit(TestCpl *t, const PetscReal P0[3], PetscReal *owed, PetscReal *gap)
{
  PetscReal pp[3], pf[3], ow[3];

  PetscFunctionBeginUser;
  PetscCall(CplGetMomentum(t->cpl, pp, pf, ow));
  *owed = *gap = 0;
  for (int k = 0; k < 3; k++) {
    *owed = PetscMax(*owed, PetscAbsReal(ow[k]));
    *gap  = PetscMax(*gap, PetscAbsReal(pp[k] + pf[k] - P0[k]));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Checks 5 and 6: the extra options (what) on; s_plain is sum |m v| after 40 steps without them. */
static PetscErrorCode Corrected(const char *what, const char *extra, PetscReal s_plain)
{
  TestCpl   t;
  CplStats  st;
  PetscReal P0[3], P1[3], pf, s0, s1, err = 0;

  PetscFunctionBeginUser;
  PetscCall(TestCplCreateScene("test_conserve.opts", extra, NULL, &t));
  PetscCall(TestCplMomentum(&t, P0, &pf, &s0));
  PetscCall(TestCplRun(&t, 40, &st));
  PetscCall(TestCplMomentum(&t, P1, &pf, &s1));
  for (int k = 0; k < 3; k++) err = PetscMax(err, PetscAbsReal(P1[k] - P0[k]) / s0);
  PetscCall(CheckBelow(CheckName("%s on: particle + fluid + owed momentum over 40 steps: max change / sum|m v|", what), err, 1e-10));
  CheckDetail("bound 1e-3 sum|m v|(0); with %.6g, without %.6g", (double)s1, (double)s_plain);
  PetscCall(CheckAbove(CheckName("%s on: they act, |sum|m v| - without| after 40 steps", what), PetscAbsReal(s1 - s_plain), 1e-3 * s0));
  PetscCall(TestCplDestroy(&t));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Check 2b. */
static PetscErrorCode OwedDecays(void)
{
  TestCpl   t;
  CplStats  st;
  PetscReal pp[3], pf[3], ow[3], P0[3], o1, g1, o2, g2, pn, s0;

  PetscFunctionBeginUser;
  PetscCall(TestCplCreateScene("test_conserve.opts", NULL, NULL, &t));
  PetscCall(TestCplMomentum(&t, P0, &pn, &s0));
  PetscCall(CplGetMomentum(t.cpl, pp, pf, ow));
  for (int k = 0; k < 3; k++) P0[k] = pp[k] + pf[k];
  PetscCall(TestCplRun(&t, 1, &st));
  PetscCall(Transit(&t, P0, &o1, &g1));
  PetscCall(TestCplRun(&t, 399, &st));
  PetscCall(Transit(&t, P0, &o2, &g2));
  CheckDetail("bound 1e-2 of the owed %.2e after 1 step; particle + fluid momentum alone off by %.2e after 1 step, %.2e after 400 (all / sum|m v|); decay %.1e", (double)(o1 / s0), (double)(g1 / s0), (double)(g2 / s0), (double)(o2 / o1));
  PetscCall(CheckBelow("particle + fluid momentum alone is off by the owed part, which decays: owed momentum after 400 steps", o2, 1e-2 * o1));
  PetscCall(TestCplDestroy(&t));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  TestCpl   t;
  CplStats  st;
  PetscReal g0, p0, g1, p1, P0[3], P1[3], pf0, pf1, s0, s1, err = 0;

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(TestCplCreateScene("test_conserve.opts", NULL, NULL, &t));
  PetscCall(CplGetSolidVolume(t.cpl, &g0, &p0));
  PetscCall(TestCplMomentum(&t, P0, &pf0, &s0));
  PetscCall(TestCplRun(&t, 40, &st));
  PetscCall(CplGetSolidVolume(t.cpl, &g1, &p1));
  PetscCall(TestCplMomentum(&t, P1, &pf1, &s1));
  for (int k = 0; k < 3; k++) err = PetscMax(err, PetscAbsReal(P1[k] - P0[k]) / s0);
  PetscCall(CheckClose("solid volume on the grid vs the particles', at the start", g0, p0, 1e-12));
  PetscCall(CheckClose("solid volume on the grid vs the particles', after 40 steps", g1, p1, 1e-12));
  PetscCall(CheckClose("the particles' volume vs 64 pi/6", p0, 64 * PETSC_PI / 6, 1e-12));
  PetscCall(CheckBelow("particle + fluid + owed momentum over 40 steps: max change / sum|m v|", err, 1e-10));
  CheckDetail("bound 0.01 sum|m v|(0); |P_fluid| / sum|m v|(0) = %.3f", (double)(pf1 / s0));
  PetscCall(CheckAbove("momentum went to the fluid: |P_fluid| after 40 steps", pf1, 1e-2 * s0));
  PetscCall(CheckBelow("the particles slowed: sum|m v| after 40 steps (bound: at the start)", s1, s0));
  PetscCall(TestCplDestroy(&t));
  PetscCall(Corrected("self corrections", "-cpl_self_porosity -cpl_self_velocity -cpl_self_fade 0", s1));
  PetscCall(Corrected("-cpl_porosity_width 2", "-cpl_porosity_width 2", s1));
  PetscCall(Corrected("-cpl_form A", "-cpl_form A", s1));
  PetscCall(OwedDecays());
  {
    PetscCall(TestSceneLoad(PETSC_COMM_WORLD, "test_conserve.opts", "-dem_shape cube -dem_shape_size 0.9 -dem_lattice_random_orientation"));
    PetscCall(PetscOptionsClearValue(NULL, "-dem_radius")); /* the cubes replace the spheres' radius */
    PetscCall(TestCplBuild(NULL, &t));
    PetscCall(TestCplMomentum(&t, P0, &pf0, &s0));
    PetscCall(TestCplRun(&t, 20, &st));
    PetscCall(CplGetSolidVolume(t.cpl, &g1, &p1));
    PetscCall(TestCplMomentum(&t, P1, &pf1, &s1));
    err = 0;
    for (int k = 0; k < 3; k++) err = PetscMax(err, PetscAbsReal(P1[k] - P0[k]) / s0);
    PetscCall(CheckClose("cubes: solid volume on the grid vs the particles'", g1, p1, 1e-12));
    PetscCall(CheckClose("cubes: the particles' volume vs 64 x 0.9^3", p1, 64 * 0.729, 1e-12));
    PetscCall(CheckBelow("cubes: particle + fluid + owed momentum over 20 steps: max change / sum|m v|", err, 1e-10));
    PetscCall(TestCplDestroy(&t));
  }
  PetscCall(PetscFinalize());
  return check_failures ? 1 : 0;
}
