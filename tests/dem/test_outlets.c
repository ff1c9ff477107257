/* ranks: 1 2 4 */
/* Outlets and the mass balance. 384 spheres of two sizes fall from a lattice in a box open
 * below; three outlets take them: a box across z = 0.123, a patch lying on z = 0.123 over
 * x < 0.05, and the domain side zlo. On 2 and 4 ranks the process grids are 1 x 1 x 2 and
 * 1 x 1 x 4 (PETSc's default for this domain): z = 0.123 is a rank boundary, so the patch lies on
 * it and the box straddles it, and particles cross the other cuts on their way down. Every step
 * the test gathers which ids are present (every rank's local
 * particles, by id) and compares with the DEM's counters (DemGetFlow, DemGetOutletFlow):
 *   - a particle absent from a step that was present at the step before is counted exactly
 *     once: the removed count grows by the number of ids that vanished, and no id comes back;
 *   - the removed mass grows by the mass of the ids that vanished (their shapes' masses);
 *   - initial - removed = present, and the DEM's own balance check (-dem_check_every 1: count
 *     and id checksum) passes at every step;
 *   - the outlets' totals add up to the run's, and each outlet took particles.
 * That the balance check trips when a removal goes uncounted: test_outlets_restart.sh. */
#include "dem_common.h"

#define SCENE \
  "-domain_lo 0,0,0 -domain_hi 0.1449,0.1449,0.24633 -dem_plane_0 0,0,0,1,0,0 -dem_plane_1 0.1449,0,0,-1,0,0 -dem_plane_2 0,0,0,0,1,0 " \
  "-dem_plane_3 0,0.1449,0,0,-1,0 -dem_radius 0.0069,0.006 -dem_density 2500 -dem_kn 7.2e5 -dem_friction 0.3 -dem_dt 1e-5 -dem_gravity 0,0,-40 -dem_lattice 8,8,6 " \
  "-dem_lattice_spacing 0.01449 -dem_lattice_origin 0,0,0.14 -dem_lattice_speed 0.1 -dem_check_every 1 " \
  "-dem_outlet_0_box 0.06,0,0.11,0.09,0.1449,0.135 -dem_outlet_1_patch 0,0,0.123,0.05,0,0.123,0,0.1449,0.123 -dem_outlet_2_side zlo"

/* present[id] over all ranks (1: some rank owns it). */
static PetscErrorCode Present(Dem dem, PetscInt N, int *loc, int *present)
{
  PetscInt n;

  PetscFunctionBeginUser;
  PetscCall(PetscArrayzero(loc, N));
  PetscCall(DemGetLocalCount(dem, &n));
  for (PetscInt i = 0; i < n; i++) {
    DemParticle p;
    PetscCall(DemGetParticle(dem, i, &p));
    PetscCheck(p.id >= 0 && p.id < N, PETSC_COMM_SELF, PETSC_ERR_PLIB, "id %" PetscInt_FMT " not in [0, %" PetscInt_FMT ")", p.id, N);
    loc[p.id]++;
  }
  PetscCallMPI(MPI_Allreduce(loc, present, (int)N, MPI_INT, MPI_SUM, PETSC_COMM_WORLD));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  Domain       dom;
  Dem          dem;
  DemFlowStats f, f0;
  PetscInt     N, n, nout, steps = 0, bad_once = 0, bad_count = 0, back = 0, vanished = 0, sum_out = 0, min_out = PETSC_MAX_INT;
  int         *loc, *prev, *now, *shape;
  PetscReal    mass[2], m_vanished = 0, m_out = 0, t;
  DemStats     st;

  PetscFunctionBeginUser;
  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(TestDemCreate(SCENE, &dom, &dem));
  PetscCall(DemSetUp(dem));
  PetscCall(DemGetStats(dem, &st));
  N = st.n;
  for (PetscInt s = 0; s < 2; s++) PetscCall(DemGetShape(dem, s, NULL, &mass[s]));
  PetscCall(PetscCalloc4(N, &loc, N, &prev, N, &now, N, &shape));
  PetscCall(DemGetLocalCount(dem, &n));
  for (PetscInt i = 0; i < n; i++) {
    DemParticle p;
    PetscCall(DemGetParticle(dem, i, &p));
    loc[p.id] = (int)p.shape;
  }
  PetscCallMPI(MPI_Allreduce(loc, shape, (int)N, MPI_INT, MPI_SUM, PETSC_COMM_WORLD));
  PetscCall(Present(dem, N, loc, prev));
  do {
    PetscInt  gone = 0;
    PetscReal mg   = 0;
    PetscCall(DemGetFlow(dem, &f0));
    PetscCall(DemStep(dem)); /* -dem_check_every 1: the DEM's own balance, every step */
    PetscCall(DemGetFlow(dem, &f));
    PetscCall(Present(dem, N, loc, now));
    for (PetscInt id = 0; id < N; id++) {
      if (now[id] > 1) bad_once++;
      if (prev[id] && !now[id]) {
        gone++;
        mg += mass[shape[id]];
      }
      if (!prev[id] && now[id]) back++;
    }
    if (f.removed - f0.removed != gone) bad_count++;
    if (PetscAbsReal(f.m_removed - f0.m_removed - mg) > 1e-12 * (mg + 1e-30)) bad_count++;
    vanished += gone;
    m_vanished += mg;
    PetscCall(PetscArraycpy(prev, now, N));
    PetscCall(DemGetTime(dem, &t, NULL));
    steps++;
  } while (t < 0.4 && f.removed < N);
  PetscCall(DemGetStats(dem, &st));
  PetscCall(DemGetOutletCount(dem, &nout));
  for (PetscInt k = 0; k < nout; k++) {
    PetscInt  r;
    PetscReal m;
    PetscCall(DemGetOutletFlow(dem, k, NULL, &r, &m));
    sum_out += r;
    m_out += m;
    min_out = PetscMin(min_out, r);
  }
  PetscCall(CheckEqual(CheckName("steps where the removed count or mass differs from the ids that vanished (of %d steps)", (int)steps), bad_count, 0));
  PetscCall(CheckEqual("ids owned by two ranks at once, summed over steps", bad_once, 0));
  PetscCall(CheckEqual("ids that came back after they vanished", back, 0));
  PetscCall(CheckEqual("particles removed against ids vanished", f.removed, vanished));
  PetscCall(CheckClose("removed mass against the vanished particles' masses [kg]", f.m_removed, m_vanished, 1e-12));
  PetscCall(CheckEqual("initial - removed against present", N - f.removed, st.n));
  PetscCall(CheckEqual("outlets' removed counts summed against the run's", sum_out, f.removed));
  PetscCall(CheckClose("outlets' removed masses summed against the run's [kg]", m_out, f.m_removed, 1e-12));
  PetscCall(CheckEqual("outlets (box, patch, side)", nout, 3));
  PetscCall(CheckAtLeast("fewest particles an outlet took", (PetscReal)min_out, 10));
  PetscCall(PetscFree4(loc, prev, now, shape));
  PetscCall(DemDestroy(&dem));
  PetscCall(DomainDestroy(&dom));
  PetscCall(PetscFinalize());
  return check_failures ? 1 : 0;
}
