/* ranks: 1 2 4 */
/* Parallel DEM against itself on one rank: the same scene run on PETSC_COMM_SELF (rank 0) and
 * on all ranks must give the same trajectories. Five scenes, each in the default mode (half
 * list; local-ghost pairs computed on both sides, so sums differ in order and results agree to
 * roundoff amplified by the dynamics; bound 1e-10 of the box after 2000 steps) and in
 * -dem_deterministic mode (full rows summed in id order: bitwise equal, bound 0):
 *   settle: spheres falling into a closed box with friction and springs (2000 steps);
 *   shear:  a fully periodic frictional box sheared by its initial velocity field (2000 steps);
 *   corner: a gas crossing the corner shared by 4 ranks and the periodic x and y sides at half
 *           the skin per step (planes close z);
 *   icosahedra: convex particles (libccd narrow phase) thrown into a box (gravity 60 m/s^2);
 *   rolling: the settle scene with constant rolling resistance on pairs and walls.
 * On 1 rank the serial half list is checked against the full rows (bound 1e-4 of the box: the
 * scene's chaotic amplification of roundoff, far below a lost pair's effect). Every run checks
 * the global count and id checksum every step (-dem_check_every 1). Also:
 * total momentum of the periodic shear box conserved to roundoff over 10^4 steps, and a single
 * particle crossing periodic boundaries keeps its velocity bitwise. On 4 ranks the process grid
 * is 2 x 2 x 1. The scenes: test_parallel_{settle,shear,corner,icosahedra,rolling}.opts. */
#include "dem_common.h"

/* Runs the scene file on comm with the options extra; positions by id, contacts at the end. */
static PetscErrorCode Run(MPI_Comm comm, const char *scene, const char *extra, PetscInt steps, PetscInt N, double *x, PetscInt *contacts)
{
  char        opts[512];
  Domain      dom;
  Dem         dem;
  DemStats    st;
  PetscMPIInt size;
  PetscInt    cnt;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(PetscSNPrintf(opts, sizeof opts, "%s -dem_check_every 1 %s", extra, size == 4 ? "-da_processors_x 2 -da_processors_y 2 -da_processors_z 1" : ""));
  PetscCall(TestDemCreateSceneOn(comm, scene, opts, &dom, &dem));
  PetscCall(DemSetUp(dem));
  for (PetscInt s = 0; s < steps; s++) PetscCall(DemStep(dem));
  PetscCall(DemGetStats(dem, &st));
  *contacts = st.contacts + st.wall_contacts;
  PetscCall(TestGatherById(dem, comm, N, x, NULL, &cnt));
  PetscCheck(cnt == N, comm, PETSC_ERR_PLIB, "%" PetscInt_FMT " particles, expected %" PetscInt_FMT, cnt, N);
  PetscCall(TestDemDestroy(&dom, &dem));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode Compare(const char *name, const char *scene, PetscInt N, double L, PetscInt steps)
{
  PetscMPIInt rank, size;
  double     *x[4], dq = 0, dp = 0, ds = 0; /* serial half, serial full, parallel half, parallel full */
  PetscInt    c[4] = {0, 0, 0, 0};

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
  PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));
  for (int k = 0; k < 4; k++) PetscCall(PetscMalloc1(3 * N, &x[k]));
  for (int det = 0; det < 2; det++) {
    const char *mode = det ? "-dem_deterministic" : "";
    if (!rank) PetscCall(Run(PETSC_COMM_SELF, scene, mode, steps, N, x[det], &c[det]));
    PetscCallMPI(MPI_Bcast(x[det], 3 * (int)N, MPI_DOUBLE, 0, PETSC_COMM_WORLD));
    PetscCallMPI(MPI_Bcast(&c[det], 1, MPIU_INT, 0, PETSC_COMM_WORLD));
    PetscCall(Run(PETSC_COMM_WORLD, scene, mode, steps, N, x[2 + det], &c[2 + det]));
  }
  for (PetscInt i = 0; i < 3 * N; i++) {
    dq = PetscMax(dq, PetscAbsReal(x[3][i] - x[1][i]) / L);
    dp = PetscMax(dp, PetscAbsReal(x[2][i] - x[0][i]) / L);
    ds = PetscMax(ds, PetscAbsReal(x[1][i] - x[0][i]) / L);
  }
  /* the serial half list against the serial full rows: the same forces summed in another order,
     apart only by roundoff amplified by the scene (chaotic ones reach ~1e-5 L over these steps);
     1e-4 L is far below what a missing or doubled pair does */
  if (size == 1) PetscCall(CheckBelow(CheckName("%s, 1 rank, half list vs -dem_deterministic full rows, %" PetscInt_FMT " steps: max |dx|/L", name, steps), ds, 1e-4));
  else {
    PetscCall(CheckEqualReal(CheckName("%s, %d ranks vs 1, -dem_deterministic, %" PetscInt_FMT " steps: max |dx|/L", name, size, steps), dq, 0));
    PetscCall(CheckEqual(CheckName("%s, %d ranks vs 1, -dem_deterministic: contacts", name, size), c[3], c[1]));
    /* default mode: sums differ in order, so agreement is to roundoff as amplified by the scene,
       whose own amplification is measured by the serial half-list vs full-list difference */
    CheckDetail("bound max(1e-10, 10 x the serial half/full-list difference %.3g), at most 1e-4", ds);
    PetscCall(CheckAtMost(CheckName("%s, %d ranks vs 1, default mode, %" PetscInt_FMT " steps: max |dx|/L", name, size, steps), dp, PetscMin(1e-4, PetscMax(1e-10, 10 * ds))));
  }
  for (int k = 0; k < 4; k++) PetscCall(PetscFree(x[k]));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Total momentum of the periodic shear box over 10^4 steps; roundoff bound relative to sum m|v|. */
static PetscErrorCode Momentum(void)
{
  char        opts[2048];
  Domain      dom;
  Dem         dem;
  double      p0[3] = {0, 0, 0}, scale = 0, worst = 0;
  PetscMPIInt size;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));
  PetscCall(PetscSNPrintf(opts, sizeof opts, "-dem_check_every 1 %s", size == 4 ? "-da_processors_x 2 -da_processors_y 2 -da_processors_z 1" : ""));
  PetscCall(TestDemCreateScene("test_parallel_shear.opts", opts, &dom, &dem));
  PetscCall(DemSetUp(dem));
  for (PetscInt s = 0; s <= 10000; s++) {
    PetscInt n;
    double   p[3] = {0, 0, 0}, pg[3], a = 0, ag;
    PetscCall(DemGetLocalCount(dem, &n));
    for (PetscInt i = 0; i < n; i++) { /* one shape: momentum per unit mass */
      DemParticle q = {0};
      PetscCall(DemGetParticle(dem, i, &q));
      for (int k = 0; k < 3; k++) p[k] += q.v[k];
      a += sqrt(q.v[0] * q.v[0] + q.v[1] * q.v[1] + q.v[2] * q.v[2]);
    }
    PetscCallMPI(MPI_Allreduce(p, pg, 3, MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD));
    PetscCallMPI(MPI_Allreduce(&a, &ag, 1, MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD));
    if (s == 0) {
      for (int k = 0; k < 3; k++) p0[k] = pg[k];
      scale = ag;
    }
    for (int k = 0; k < 3; k++) worst = PetscMax(worst, PetscAbsReal(pg[k] - p0[k]) / scale);
    if (s < 10000) PetscCall(DemStep(dem));
  }
  PetscCall(CheckBelow(CheckName("periodic shear box, %d ranks, 10^4 steps: total momentum change / sum m|v|", size), worst, 1e-12));
  PetscCall(TestDemDestroy(&dom, &dem));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* One particle crossing periodic boundaries (and rank boundaries) diagonally. */
static PetscErrorCode Crossing(void)
{
  char         opts[2048];
  Domain       dom;
  Dem          dem;
  double       x[3] = {NAN, NAN, NAN}, v[3] = {NAN, NAN, NAN}; /* NaN: fails the checks if not found */
  PetscInt     cnt;
  PetscMPIInt  size;
  const double v0[3] = {3.0, -2.0, 1.0};

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));
  PetscCall(PetscSNPrintf(opts, sizeof opts, "-domain_lo 0,0,0 -domain_hi 0.1,0.1,0.1 -domain_periodic_x -domain_periodic_y -domain_periodic_z -dem_radius 0.005 -dem_kn 1e4 -dem_gravity 0,0,0 -dem_check_every 1 %s", size == 4 ? "-da_processors_x 2 -da_processors_y 2 -da_processors_z 1" : ""));
  PetscCall(TestDemCreateOn(PETSC_COMM_WORLD, opts, &dom, &dem));
  PetscMPIInt rank;
  PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
  if (!rank) {
    DemParticle p = {.id = 0, .shape = 0, .x = {0.01, 0.01, 0.01}, .v = {v0[0], v0[1], v0[2]}, .q = {1, 0, 0, 0}};
    PetscCall(DemAddParticle(dem, &p));
  }
  PetscCall(DemSetUp(dem));
  for (PetscInt s = 0; s < 2000; s++) PetscCall(DemStep(dem)); /* 0.02 s: 0.6 box lengths in x */
  PetscCall(TestGatherById(dem, PETSC_COMM_WORLD, 1, x, v, &cnt));
  double err = 0;
  for (int k = 0; k < 3; k++) {
    double e = PetscFmodReal(0.01 + v0[k] * 0.02 - x[k] + 10.0, 0.1); /* wrapped distance */
    err      = PetscMax(err, PetscMin(e, 0.1 - e));
  }
  PetscCall(CheckEqual(CheckName("particle across periodic and rank boundaries, %d ranks: particles found", size), cnt, 1));
  for (int k = 0; k < 3; k++) PetscCall(CheckEqualReal(CheckName("particle across periodic and rank boundaries, %d ranks: velocity component %d unchanged", size, k), v[k], v0[k]));
  PetscCall(CheckBelow(CheckName("particle across periodic and rank boundaries, %d ranks: position error [m]", size), err, 1e-12));
  PetscCall(TestDemDestroy(&dom, &dem));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(Compare("settle", "test_parallel_settle.opts", 640, 0.2, 2000));
  PetscCall(Compare("periodic shear box", "test_parallel_shear.opts", 216, 0.0828, 2000));
  PetscCall(Compare("corner crossing at skin/2 per step", "test_parallel_corner.opts", 576, 0.1, 1000));
  PetscCall(Compare("bed of icosahedra (libccd)", "test_parallel_icosahedra.opts", 150, 0.12, 3000));
  PetscCall(Compare("settle with rolling resistance", "test_parallel_rolling.opts", 640, 0.2, 4000));
  PetscCall(Momentum());
  PetscCall(Crossing());
  PetscCall(PetscFinalize());
  return check_failures ? 1 : 0;
}
