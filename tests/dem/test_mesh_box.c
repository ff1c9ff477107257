/* ranks: 1 2 4 */
/* A closed box of mesh walls holding a settling bed: the scene of test_parallel_settle.opts (640
 * frictional spheres with springs falling from a jittered lattice) in a box made of one STL
 * file, each side 4 x 4 cells of 2 triangles (192 triangles: spheres cross their edges, and
 * touch two or three sides at the box's edges and corners, concave: both faces count), against
 * the same scene with -dem_box (the scene's options are written out here). On 1, 2 and 4 ranks (4: a 2 x 2 x 1 grid, each rank keeping the
 * triangles near its box): the particle count and id checksum are checked every step
 * (-dem_check_every 1, an error otherwise) and at the end. After 2000 steps (the bottom layer
 * on the floor, the outer columns against the sides) the packing equals the -dem_box one to
 * roundoff amplified by the collisions (bound 1e-10 of the box, as test_parallel's; the mesh's
 * overlap r - |q - x| and the plane's r - (x - p).n differ in the last bits, and the settling
 * bed amplifies that about 1e3-fold per 1000 steps); after 6000 steps (0.09 s) every centre is
 * inside the box and the bed's mean height is the -dem_box bed's within 1%. */
#include <unistd.h>
#include "dem_common.h"
#include "stl_write.h"

#define N 640
static const double L = 0.11592, H = 0.2;

/* Runs the scene with these walls: positions by id after 2000 steps (xa) and 6000 (xb), the count
 * at the end. */
static PetscErrorCode Run(const char *walls, double *xa, double *xb, PetscInt *count)
{
  char        opts[1024];
  Domain      dom;
  Dem         dem;
  DemStats    st;
  PetscMPIInt size;
  PetscInt    cnt;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));
  PetscCall(PetscSNPrintf(opts, sizeof opts, "-domain_lo 0,0,0 -domain_hi %g,%g,%g -dem_radius 0.0069 -dem_kn 7.2e5 -dem_restitution 0.75 -dem_friction 0.3 -dem_lattice 8,8,10 -dem_lattice_spacing 0.01449 -dem_lattice_jitter 0.5 -dem_lattice_speed 0.05 -dem_dt 1.5e-5 -dem_check_every 1 %s %s", L, L, H, walls, size == 4 ? "-da_processors_x 2 -da_processors_y 2 -da_processors_z 1" : ""));
  PetscCall(TestDemCreate(opts, &dom, &dem));
  PetscCall(DemSetUp(dem));
  for (PetscInt s = 0; s < 6000; s++) {
    if (s == 2000) PetscCall(TestGatherById(dem, PETSC_COMM_WORLD, N, xa, NULL, &cnt));
    PetscCall(DemStep(dem));
  }
  PetscCall(DemGetStats(dem, &st));
  PetscCheck(st.checksum == N * (N - 1) / 2.0 || st.checksum == N * (N + 1) / 2.0, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "id checksum %g", (double)st.checksum);
  PetscCall(TestGatherById(dem, PETSC_COMM_WORLD, N, xb, NULL, count));
  PetscCall(TestDemDestroy(&dom, &dem));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  char         file[PETSC_MAX_PATH_LEN], walls[PETSC_MAX_PATH_LEN + 64];
  double      *xm, *xb, *ym, *yb, v[6 * 32 * 9], dmax = 0, out = -1, hm = 0, hb = 0;
  const double r = 0.0069;
  PetscInt     cm, cb;
  PetscMPIInt  size;
  int          pid = (int)getpid();

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));
  PetscCallMPI(MPI_Bcast(&pid, 1, MPI_INT, 0, PETSC_COMM_WORLD));
  PetscCall(PetscSNPrintf(file, sizeof file, "/tmp/sable_test_mesh_box_%d.stl", pid));
  { /* the six sides: lo and hi of each axis */
    const double len[3]  = {L, L, H};
    const double zero[3] = {0, 0, 0};
    PetscCall(TestWriteStl(PETSC_COMM_WORLD, file, TestBoxTriangles(zero, len, 4, PETSC_FALSE, v), v));
  }
  PetscCall(PetscMalloc4(3 * N, &xm, 3 * N, &xb, 3 * N, &ym, 3 * N, &yb));
  PetscCall(PetscSNPrintf(walls, sizeof walls, "-dem_mesh_0_file %s", file));
  PetscCall(Run(walls, xm, ym, &cm));
  PetscCall(Run("-dem_box 0,0,0,0.11592,0.11592,0.2", xb, yb, &cb));
  for (PetscInt i = 0; i < 3 * N; i++) dmax = PetscMax(dmax, PetscAbsReal(xm[i] - xb[i]) / H);
  for (PetscInt i = 0; i < N; i++) {
    for (int k = 0; k < 3; k++) out = PetscMax(out, PetscMax(0.5 * r - ym[3 * i + k], ym[3 * i + k] - ((k < 2 ? L : H) - 0.5 * r)));
    hm += ym[3 * i + 2] / N;
    hb += yb[3 * i + 2] / N;
  }
  PetscCall(CheckEqual(CheckName("mesh box on %d ranks: particles at the end (0.09 s)", size), cm, N));
  PetscCall(CheckBelow(CheckName("mesh box on %d ranks: packing after 2000 steps (bottom layer on the floor, sides touched) vs -dem_box's (largest |dx| / box height)", size), dmax, 1e-10));
  PetscCall(CheckBelow(CheckName("mesh box on %d ranks: centres held inside the box shrunk by r/2 at the end: largest excursion [m]", size), out, 0));
  PetscCall(CheckClose(CheckName("mesh box on %d ranks: mean centre height at the end [m] vs -dem_box's (the bed settling, chaotic by then)", size), hm, hb, 0.01));
  PetscCall(PetscFree4(xm, xb, ym, yb));
  {
    PetscMPIInt rank;
    PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
    if (!rank) (void)unlink(file);
  }
  PetscCall(PetscFinalize());
  return check_failures ? 1 : 0;
}
