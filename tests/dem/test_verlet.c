/* Neighbour lists. (1) The half Verlet list finds exactly the contacts of a brute-force O(N^2)
 * search (same count, same id pairs by an order-independent fingerprint), checked every 20 steps
 * over 6,000 steps of a polydisperse, frictional, moving configuration with periodic re-sorts.
 * (2) The tangential springs survive rebuilds and re-sorts: a run that rebuilds and re-sorts
 * often (small skin) and one that rebuilds rarely and never sorts (large skin) follow the same
 * trajectories, to roundoff amplified by the granular dynamics (bound 1e-9 of the box).
 * The scene: test_verlet.opts. */
#include "dem_common.h"

static PetscErrorCode Positions(const char *extra, PetscInt steps, PetscReal *x)
{
  Domain   dom;
  Dem      dem;
  PetscInt n;

  PetscFunctionBeginUser;
  PetscCall(TestDemCreateScene("test_verlet.opts", extra, &dom, &dem));
  PetscCall(DemSetUp(dem));
  for (PetscInt s = 0; s < steps; s++) PetscCall(DemStep(dem));
  PetscCall(DemGetLocalCount(dem, &n));
  for (PetscInt i = 0; i < n; i++) {
    DemParticle p = {0};
    PetscCall(DemGetParticle(dem, i, &p));
    for (int k = 0; k < 3; k++) x[3 * p.id + k] = p.x[k];
  }
  PetscCall(TestDemDestroy(&dom, &dem));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  Domain    dom;
  Dem       dem;
  PetscInt  mism = 0, checks = 0, maxc = 0, cnt[2];
  PetscReal key[2], *xa, *xb, dmax = 0;

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(TestDemCreateScene("test_verlet.opts", NULL, &dom, &dem));
  PetscCall(DemSetUp(dem));
  for (PetscInt s = 0; s <= 6000; s++) {
    if (s % 20 == 0) {
      PetscCall(DemCountContactsBoth(dem, cnt, key));
      if (cnt[0] != cnt[1] || key[0] != key[1]) mism++;
      maxc = PetscMax(maxc, cnt[1]);
      checks++;
    }
    PetscCall(DemStep(dem));
  }
  PetscCall(CheckEqual(CheckName("Verlet list = brute force over %" PetscInt_FMT " checks (360 polydisperse spheres): mismatches", checks), mism, 0));
  PetscCall(CheckAbove("Verlet list = brute force: most contacts at a check", maxc, 0));
  PetscCall(TestDemDestroy(&dom, &dem));

  PetscCall(PetscMalloc2(3 * 360, &xa, 3 * 360, &xb));
  PetscCall(Positions("-dem_skin 0.0004 -dem_sort_interval 1", 3000, xa));
  PetscCall(Positions("-dem_skin 0.006 -dem_sort_interval 0", 3000, xb));
  for (int i = 0; i < 3 * 360; i++) dmax = PetscMax(dmax, PetscAbsReal(xa[i] - xb[i]));
  PetscCall(CheckBelow("springs carried across rebuilds and re-sorts: skin 0.1 r with sorting vs 1.5 r without, 3000 steps: max position difference [m]", dmax, 1e-9 * 0.16));
  PetscCall(PetscFree2(xa, xb));
  PetscCall(PetscFinalize());
  return check_failures ? 1 : 0;
}
