/* ranks: 1 2 */
/* A particle source inside a mesh vessel: the candidates are tested against the mesh's triangles
 * (sources.c, walls_mesh.c DemMeshesBlock) as against the analytic walls. The vessel is an open
 * box of mesh triangles, x and y sides at 0.02 and 0.08 m, 4 x 4 cells a side; the source's
 * region (0.01..0.09 along x and y) crosses its sides, so candidates straddle triangles and must
 * be refused. Reference: no inserted sphere's centre is nearer than its radius to any triangle
 * (measured by the closest point of every triangle, here), and some are within two radii (the
 * region does reach the sides: the check could fail); the count is the batch's, on 1 and 2
 * ranks the same. Then DemGetStats counts the mesh's contacts: the batch, released without
 * gravity towards the sides, touches them (wall contacts > 0 where the vessel holds them), and
 * a sphere at rest on the mesh floor under gravity counts one wall contact. */
#include <unistd.h>
#include "dem_common.h"
#include "stl_write.h"
#include "geom/trimesh.h"

#define N 150
static const double R = 0.004;

int main(int argc, char **argv)
{
  char        file[PETSC_MAX_PATH_LEN], opts[1024];
  double      v[5 * 32 * 9], *x, dmin = PETSC_MAX_REAL, near = 0;
  PetscInt    cnt = 0;
  PetscMPIInt size;
  int         pid = (int)getpid();
  Domain      dom;
  Dem         dem;
  DemStats    st;

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));
  PetscCallMPI(MPI_Bcast(&pid, 1, MPI_INT, 0, PETSC_COMM_WORLD));
  PetscCall(PetscSNPrintf(file, sizeof file, "/tmp/sable_test_mesh_sources_%d.stl", pid));
  { /* the floor z = 0 and the four sides of the box 0.02..0.08 x 0.02..0.08 x 0..0.1 (open top) */
    const double lo[3] = {0.02, 0.02, 0}, hi[3] = {0.08, 0.08, 0.1};
    PetscCall(TestWriteStl(PETSC_COMM_WORLD, file, TestBoxTriangles(lo, hi, 4, PETSC_TRUE, v), v));
  }
  PetscCall(PetscSNPrintf(opts, sizeof opts, "-domain_lo 0,0,0 -domain_hi 0.1,0.1,0.1 -dem_radius %g -dem_kn 1e4 -dem_restitution 0.5 -dem_friction 0.3 -dem_dt 1e-5 -dem_gravity 0,0,0 -dem_mesh_0_file %s -dem_insert_0_region box -dem_insert_0_box 0.01,0.01,0.01,0.09,0.09,0.09 -dem_insert_0_count %d -dem_insert_0_period 1 -dem_insert_0_velocity_spread 0.5 -dem_check_every 1 %s", R, file, N, size == 2 ? "-da_processors_x 2 -da_processors_y 1 -da_processors_z 1" : ""));
  PetscCall(TestDemCreate(opts, &dom, &dem));
  PetscCall(DemSetUp(dem));
  PetscCall(DemStep(dem)); /* the batch is placed by the first step */
  PetscCall(PetscMalloc1(3 * N, &x));
  PetscCall(TestGatherById(dem, PETSC_COMM_WORLD, N, x, NULL, &cnt));
  for (PetscInt i = 0; i < cnt; i++) {
    double d = PETSC_MAX_REAL;
    for (int t = 0; t < 5 * 32; t++) {
      double q[3];
      TriClosestPoint(v + 9 * t, v + 9 * t + 3, v + 9 * t + 6, x + 3 * i, q);
      d = PetscMin(d, sqrt(PetscSqr(q[0] - x[3 * i]) + PetscSqr(q[1] - x[3 * i + 1]) + PetscSqr(q[2] - x[3 * i + 2])));
    }
    dmin = PetscMin(dmin, d / R);
    if (d < 2 * R) near++;
  }
  PetscCall(CheckEqual(CheckName("source in a mesh vessel on %d ranks: particles inserted (the batch)", size), cnt, N));
  PetscCall(CheckAtLeast(CheckName("source in a mesh vessel on %d ranks: nearest approach of an inserted centre to a triangle / r (1: touching)", size), dmin - 1, 0));
  PetscCall(CheckAbove(CheckName("source in a mesh vessel on %d ranks: inserted spheres within 2 r of a triangle (the region crosses the sides)", size), near, 0));
  for (PetscInt s = 0; s < 3000; s++) PetscCall(DemStep(dem));
  PetscCall(DemGetStats(dem, &st));
  PetscCall(CheckAbove(CheckName("source in a mesh vessel on %d ranks: DemGetStats' wall contacts after 0.03 s (spheres thrown at the sides)", size), (double)st.wall_contacts, 0));
  PetscCall(TestDemDestroy(&dom, &dem));
  PetscCall(PetscSNPrintf(opts, sizeof opts, "-domain_lo 0,0,0 -domain_hi 0.1,0.1,0.1 -dem_radius %g -dem_kn 1e4 -dem_restitution 0.3 -dem_dt 1e-5 -dem_mesh_0_file %s", R, file));
  PetscCall(TestDemCreate(opts, &dom, &dem));
  {
    DemParticle p = {.id = 0, .shape = 0, .q = {1, 0, 0, 0}, .x = {0.035, 0.05, R}};
    PetscMPIInt rank;
    PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
    if (!rank) PetscCall(DemAddParticle(dem, &p)); /* once: the set-up migrates it to its owner */
  }
  PetscCall(DemSetUp(dem));
  for (PetscInt s = 0; s < 2000; s++) PetscCall(DemStep(dem));
  PetscCall(DemGetStats(dem, &st));
  PetscCall(CheckEqual(CheckName("a sphere at rest on the mesh floor (over a vertex of 8 triangles) on %d ranks: DemGetStats' wall contacts", size), st.wall_contacts, 1));
  PetscCall(TestDemDestroy(&dom, &dem));
  PetscCall(PetscFree(x));
  {
    PetscMPIInt rank;
    PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
    if (!rank) (void)unlink(file);
  }
  PetscCall(PetscFinalize());
  return check_failures ? 1 : 0;
}
