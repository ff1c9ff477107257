/* ranks: 1 2 */
/* Convex particles against triangle meshes (walls_mesh.c DemMeshTouchConvex: the face rule of
 * the polygon walls, each plane counted once). References:
 *   a cube at rest on a triangulated floor (cells about half its side, split along alternating
 *   diagonals; placed over a vertex of the grid) sits where it sits on -dem_plane_0 (the same
 *   depth: the floor's plane is the same), at the static overlap m g / kn (linear law);
 *   a cube and an icosahedron sliding and tumbling across the grid's shared edges and vertices
 *   follow the -dem_plane_0 run to 1e-9 relative (positions against the distance travelled);
 *   a bed of 80 cubes settling in a closed mesh box (192 triangles) equals the -dem_box bed to
 *   1e-10 of the box after 1500 steps and its mean height within 1% after 4000;
 *   (the single particles on 1 rank; the bed on 1 and 2 ranks, the box cut along x, count and
 *   id checksum every step);
 *   the limit of the face rule: a cube lowered face-down onto a convex ridge (two faces at
 *   +-10 degrees) is not held: the ridge's edge pressing into its face is no face contact, and
 *   each face's plane, extended, cuts deepest into the cube's half over the other face, so no
 *   contact point lies on its own face; the cube passes through and rests on a plane below
 *   (the behaviour src/dem/README.md states). */
#include <unistd.h>
#include "dem_common.h"
#include "stl_write.h"

#define NSAMP 21
static const double A = 0.01, RHO = 2500, KN = 2e4, G = 9.81, HG = 0.006; /* cube side, density, stiffness, gravity, grid spacing */

typedef struct {
  double   x[NSAMP][3];
  PetscInt wc; /* DemGetStats' wall contacts at the end */
  double   pe; /* and elastic energy */
} Traj;

/* A particle of shape (options) from x0 with velocity v0 against walls for nstep steps; samples
 * the centre every nstep/(NSAMP-1) steps; *depth: m g / kn measured as the final wall force. */
static PetscErrorCode Run(const char *shape, const char *walls, const double x0[3], const double v0[3], PetscInt nstep, Traj *tr)
{
  char   opts[1024];
  Domain dom;
  Dem    dem;

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(opts, sizeof opts, "-domain_lo -0.1,-0.1,-0.03 -domain_hi 0.1,0.1,0.05 %s -dem_density %g -dem_contact_law linear -dem_kn %g -dem_restitution 0.3 -dem_friction 0.3 -dem_dt 1e-5 %s", shape, RHO, KN, walls));
  PetscCall(TestDemCreate(opts, &dom, &dem));
  DemParticle p = {.id = 1, .shape = 0, .q = {1, 0, 0, 0}};
  for (int k = 0; k < 3; k++) p.x[k] = x0[k], p.v[k] = v0[k];
  PetscCall(DemAddParticle(dem, &p));
  PetscCall(DemSetUp(dem));
  for (PetscInt s = 0, smp = 0; smp < NSAMP; s++) {
    if (s % (nstep / (NSAMP - 1)) == 0) {
      const DemParticle q = TestGet(dem, 1);
      for (int k = 0; k < 3; k++) tr->x[smp][k] = q.x[k];
      smp++;
    }
    if (smp < NSAMP) PetscCall(DemStep(dem));
  }
  {
    DemStats st;
    PetscCall(DemGetStats(dem, &st));
    tr->wc = st.wall_contacts;
    tr->pe = st.pe_spring;
  }
  PetscCall(TestDemDestroy(&dom, &dem));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Largest |x_mesh - x_plane| over the samples, relative to the largest distance travelled. */
static double TrajDiff(const Traj *a, const Traj *b)
{
  double d = 0, s = A;
  for (int i = 0; i < NSAMP; i++)
    for (int k = 0; k < 3; k++) {
      d = PetscMax(d, PetscAbsReal(a->x[i][k] - b->x[i][k]));
      s = PetscMax(s, PetscAbsReal(b->x[i][k] - b->x[0][k]));
    }
  return d / s;
}

/* 80 cubes from a jittered lattice settling in a closed box: positions by id after 1500 steps
 * (xa) and 4000 (xb). */
static PetscErrorCode RunBed(const char *walls, double *xa, double *xb, PetscInt *count)
{
  char        opts[1024];
  Domain      dom;
  Dem         dem;
  PetscInt    cnt;
  PetscMPIInt size;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));
  PetscCall(PetscSNPrintf(opts, sizeof opts, "-domain_lo 0,0,0 -domain_hi 0.07,0.07,0.1 -dem_shape cube -dem_shape_size 0.009 -dem_density %g -dem_contact_law linear -dem_kn %g -dem_restitution 0.5 -dem_friction 0.3 -dem_lattice 4,4,5 -dem_lattice_spacing 0.017 -dem_lattice_jitter 0.3 -dem_lattice_speed 0.05 -dem_lattice_random_orientation -dem_dt 1e-5 -dem_check_every 1 %s %s", RHO, KN, walls, size == 2 ? "-da_grid_x 2 -da_processors_x 2 -da_processors_y 1 -da_processors_z 1" : ""));
  PetscCall(TestDemCreate(opts, &dom, &dem));
  PetscCall(DemSetUp(dem));
  for (PetscInt s = 0; s < 4000; s++) {
    if (s == 1500) PetscCall(TestGatherById(dem, PETSC_COMM_WORLD, 80, xa, NULL, &cnt));
    PetscCall(DemStep(dem));
  }
  PetscCall(TestGatherById(dem, PETSC_COMM_WORLD, 80, xb, NULL, count));
  PetscCall(TestDemDestroy(&dom, &dem));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  char         floor[PETSC_MAX_PATH_LEN], box[PETSC_MAX_PATH_LEN], ridge[PETSC_MAX_PATH_LEN], walls[PETSC_MAX_PATH_LEN + 64];
  const char  *cube = "-dem_shape cube -dem_shape_size 0.01", *ico = "-dem_shape icosahedron -dem_shape_size 0.006";
  const char  *plane = "-dem_plane_0 0,0,0,0,0,1";
  const double m = RHO * A * A * A, d0 = m * G / KN;
  double      *v;
  int          pid = (int)getpid();
  Traj         ta, tb;
  PetscMPIInt  size;

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));
  PetscCallMPI(MPI_Bcast(&pid, 1, MPI_INT, 0, PETSC_COMM_WORLD));
  PetscCall(PetscSNPrintf(floor, sizeof floor, "/tmp/sable_test_mesh_convex_floor_%d.stl", pid));
  PetscCall(PetscSNPrintf(box, sizeof box, "/tmp/sable_test_mesh_convex_box_%d.stl", pid));
  PetscCall(PetscSNPrintf(ridge, sizeof ridge, "/tmp/sable_test_mesh_convex_ridge_%d.stl", pid));
  PetscCall(PetscMalloc1(9 * 2 * 30 * 30, &v));
  { /* the floor z = 0 over [-0.09, 0.09]^2, a vertex at the origin */
    const double o[3] = {-0.09, -0.09, 0}, e1[3] = {HG, 0, 0}, e2[3] = {0, HG, 0};
    TestGridTriangles(o, e1, e2, 30, 30, v);
    PetscCall(TestWriteStl(PETSC_COMM_WORLD, floor, 2 * 30 * 30, v));
  }
  PetscCall(PetscSNPrintf(walls, sizeof walls, "-dem_mesh_0_file %s", floor));
  if (size == 1) { /* at rest over a vertex of the grid, from just above the floor */
    const double x0[3] = {0, 0, 0.5 * A + 1e-4}, v0[3] = {0, 0, 0};
    PetscCall(Run(cube, walls, x0, v0, 20000, &ta));
    PetscCall(Run(cube, plane, x0, v0, 20000, &tb));
    PetscCall(CheckBelow("cube at rest on a mesh floor (over a vertex of 8 triangles): |z - z_plane| / A", PetscAbsReal(ta.x[NSAMP - 1][2] - tb.x[NSAMP - 1][2]) / A, 1e-12));
    PetscCall(CheckClose("cube at rest on a mesh floor: overlap A/2 - z vs m g / kn", 0.5 * A - ta.x[NSAMP - 1][2], d0, 1e-9));
    PetscCall(CheckEqual("cube at rest on a mesh floor: DemGetStats' wall contacts (the -dem_plane_0 run's: 1)", ta.wc, tb.wc));
    PetscCall(CheckClose("cube at rest on a mesh floor: DemGetStats' elastic energy vs the -dem_plane_0 run's", ta.pe, tb.pe, 1e-12));
    PetscCall(CheckBelow("cube at rest on a mesh floor: sideways drift / A", PetscMax(PetscAbsReal(ta.x[NSAMP - 1][0]), PetscAbsReal(ta.x[NSAMP - 1][1])) / A, 1e-12));
  }
  if (size == 1) { /* sliding across the grid, on a generic path */
    const double x0[3] = {-0.05, -0.031, 0.5 * A - d0}, v0[3] = {0.5, 0.37, 0};
    PetscCall(Run(cube, walls, x0, v0, 10000, &ta));
    PetscCall(Run(cube, plane, x0, v0, 10000, &tb));
    PetscCall(CheckBelow("cube sliding 0.1 s across shared edges and vertices: trajectory vs -dem_plane_0 (relative)", TrajDiff(&ta, &tb), 1e-9));
    PetscCall(CheckAbove("cube sliding: distance travelled / grid spacing (edges crossed)", sqrt(PetscSqr(tb.x[NSAMP - 1][0] - x0[0]) + PetscSqr(tb.x[NSAMP - 1][1] - x0[1])) / HG, 3));
  }
  if (size == 1) { /* an icosahedron thrown onto the grid: it tumbles on vertices and edges */
    const double x0[3] = {-0.04, 0.013, 0.006}, v0[3] = {0.6, -0.2, -0.1};
    PetscCall(Run(ico, walls, x0, v0, 10000, &ta));
    PetscCall(Run(ico, plane, x0, v0, 10000, &tb));
    PetscCall(CheckBelow("icosahedron thrown onto the mesh floor, 0.1 s: trajectory vs -dem_plane_0 (relative)", TrajDiff(&ta, &tb), 1e-9));
  }
  if (size == 1) { /* the limit: a convex ridge along y, faces at -+10 degrees, the cube lowered face-down on it,
       a plane 2 cm below */
    const double t = tan(10 * PETSC_PI / 180), w = 0.03;
    const double rv[4 * 9] = {-w, -w, -t * w, 0, -w, 0, 0, w, 0, -w, -w, -t * w, 0, w, 0, -w, w, -t * w, 0, -w, 0, w, -w, -t * w, w, w, -t * w, 0, -w, 0, w, w, -t * w, 0, w, 0};
    const double x0[3] = {0, 0, 0.5 * A + 1e-4}, v0[3] = {0, 0, 0};
    PetscCall(TestWriteStl(PETSC_COMM_WORLD, ridge, 4, rv));
    PetscCall(PetscSNPrintf(walls, sizeof walls, "-dem_mesh_0_file %s -dem_plane_0 0,0,-0.02,0,0,1", ridge));
    PetscCall(Run(cube, walls, x0, v0, 20000, &ta));
    PetscCall(CheckClose("the face rule's limit: a cube face-down on a convex ridge (10 deg faces) is not held by the ridge and rests on the plane 2 cm below: height [m] vs -0.02 + A/2 - m g/kn", ta.x[NSAMP - 1][2], -0.02 + 0.5 * A - d0, 1e-6));
  }
  { /* a bed in a closed mesh box */
    const double len[3] = {0.07, 0.07, 0.1};
    double      *xm, *xb, *ym, *yb, dmax = 0, hm = 0, hb = 0, out = -1;
    PetscInt     cm, cb;
    const double zero[3] = {0, 0, 0};
    PetscCall(TestWriteStl(PETSC_COMM_WORLD, box, TestBoxTriangles(zero, len, 4, PETSC_FALSE, v), v));
    PetscCall(PetscMalloc4(240, &xm, 240, &xb, 240, &ym, 240, &yb));
    PetscCall(PetscSNPrintf(walls, sizeof walls, "-dem_mesh_0_file %s", box));
    PetscCall(RunBed(walls, xm, ym, &cm));
    PetscCall(RunBed("-dem_box 0,0,0,0.07,0.07,0.1", xb, yb, &cb));
    for (PetscInt i = 0; i < 240; i++) dmax = PetscMax(dmax, PetscAbsReal(xm[i] - xb[i]) / len[2]);
    for (PetscInt i = 0; i < 80; i++) {
      for (int k = 0; k < 3; k++) out = PetscMax(out, PetscMax(0.25 * A - ym[3 * i + k], ym[3 * i + k] - (len[k] - 0.25 * A)));
      hm += ym[3 * i + 2] / 80;
      hb += yb[3 * i + 2] / 80;
    }
    PetscCall(CheckEqual(CheckName("cube bed in a mesh box on %d ranks: particles at the end", size), cm, 80));
    PetscCall(CheckBelow(CheckName("cube bed in a mesh box on %d ranks: positions after 1500 steps vs -dem_box's (largest |dx| / box height)", size), dmax, 1e-10));
    PetscCall(CheckBelow(CheckName("cube bed in a mesh box on %d ranks: centres inside the box shrunk by A/4 at the end: largest excursion [m]", size), out, 0));
    PetscCall(CheckClose(CheckName("cube bed in a mesh box on %d ranks: mean centre height after 4000 steps vs -dem_box's", size), hm, hb, 0.01));
    PetscCall(PetscFree4(xm, xb, ym, yb));
  }
  PetscCall(PetscFree(v));
  {
    PetscMPIInt rank;
    PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
    if (!rank) (void)unlink(floor), (void)unlink(box), (void)unlink(ridge);
  }
  PetscCall(PetscFinalize());
  return check_failures ? 1 : 0;
}
