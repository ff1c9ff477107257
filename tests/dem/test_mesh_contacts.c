/* Edge, vertex and corner contacts of mesh walls (walls_mesh.c) against hand geometry. The
 * force on a sphere at rest (no gravity, restitution 1: no damping) is measured from one step
 * of 1e-7 s, F = m v / dt (the drift changes it by kn dt^2 / 2m ~ 4e-7 relative); the linear
 * law's reference is kn (r - d) along (x - q) / d, q the nearest point of the geometry, d = |x - q|.
 *   ridge: two faces sloping down at 30 deg from a ridge (each 12 triangles): a sphere above the
 *          ridge (on a vertex, and between vertices) feels the ridge once; one in the ridge's
 *          edge region feels it along (x - q); one over a face near the ridge feels the face
 *          only (the other face's ridge point lies on the accepted plane);
 *   apex:  a pyramid's 4 faces meet at an apex: a sphere in the apex region feels it once;
 *   corner: a floor and a wall as two meshes, and as one mesh: a sphere in the concave corner
 *          feels both faces, as from two planes (-dem_plane_0, -dem_plane_1); a sphere sliding
 *          along the floor into the wall follows the two-plane run to 1e-9 relative. */
#include <unistd.h>
#include "dem_common.h"
#include "stl_write.h"

static const double R = 0.005, KN = 1e5;
static char         fa[PETSC_MAX_PATH_LEN], fb[PETSC_MAX_PATH_LEN];

/* The wall force on a sphere at rest at x (walls: the wall options), from one step. */
static PetscErrorCode Force(const char *walls, const double x[3], double F[3])
{
  const double m = 2500 * 4.0 / 3.0 * PETSC_PI * R * R * R, dt = 1e-7;
  char         opts[1024];
  Domain       dom;
  Dem          dem;

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(opts, sizeof opts, "-domain_lo -0.05,-0.05,-0.05 -domain_hi 0.05,0.05,0.05 -dem_radius %g -dem_density 2500 -dem_kn %g -dem_restitution 1 -dem_friction 0.3 -dem_gravity 0,0,0 -dem_dt %g %s", R, KN, dt, walls));
  PetscCall(TestDemCreate(opts, &dom, &dem));
  DemParticle p = {.id = 1, .shape = 0, .x = {x[0], x[1], x[2]}, .q = {1, 0, 0, 0}};
  PetscCall(DemAddParticle(dem, &p));
  PetscCall(DemSetUp(dem));
  PetscCall(DemStep(dem));
  p = TestGet(dem, 1);
  for (int k = 0; k < 3; k++) F[k] = m * p.v[k] / dt;
  PetscCall(TestDemDestroy(&dom, &dem));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Checks F against kn (r - |x - q|) (x - q)/|x - q| (relative to its magnitude). */
static PetscErrorCode CheckContact(const char *name, const char *walls, const double x[3], const double q[3])
{
  double F[3], d[3] = {x[0] - q[0], x[1] - q[1], x[2] - q[2]}, err = 0;

  PetscFunctionBeginUser;
  PetscCall(Force(walls, x, F));
  const double l = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]), f = KN * (R - l);
  for (int k = 0; k < 3; k++) err = PetscMax(err, PetscAbsReal(F[k] - f * d[k] / l) / f);
  PetscCall(CheckBelow(CheckName("%s: force vs kn (r - d) (x - q)/d (relative, per component)", name), err, 1e-5));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode Ridge(void)
{
  const double a = PETSC_PI / 6, h = 0.004, dA[3] = {-cos(a), 0, -sin(a)}, dB[3] = {cos(a), 0, -sin(a)}, nB[3] = {sin(a), 0, cos(a)};
  double       v[2 * 36 * 9], o[3] = {0, -3 * h, 0}, e1[3], e2[3] = {0, h, 0}, x[3], q[3] = {0, 0, 0};
  char         walls[PETSC_MAX_PATH_LEN + 32];

  PetscFunctionBeginUser;
  for (int k = 0; k < 3; k++) e1[k] = h * dA[k];
  TestGridTriangles(o, e1, e2, 2, 6, v);
  for (int k = 0; k < 3; k++) e1[k] = h * dB[k];
  TestGridTriangles(o, e1, e2, 2, 6, v + 9 * 24);
  PetscCall(TestWriteStl(PETSC_COMM_WORLD, fa, 48, v));
  PetscCall(PetscSNPrintf(walls, sizeof walls, "-dem_mesh_0_file %s", fa));
  for (int s = 0; s < 2; s++) { /* above the ridge: on a vertex (y = 0), between vertices */
    x[0] = 0, x[1] = q[1] = s * 0.37 * h, x[2] = 0.99 * R;
    PetscCall(CheckContact(s ? "ridge, above its edge" : "ridge, above a vertex on the ridge", walls, x, q));
  }
  x[0] = 0.2 * R, x[1] = q[1] = 0.37 * h, x[2] = 0.95 * R; /* the edge region, off the top */
  PetscCall(CheckContact("ridge, edge region off the top", walls, x, q));
  for (int k = 0; k < 3; k++) { /* over face B near the ridge: the ridge point of A is dropped */
    x[k] = 0.95 * R * nB[k] + 0.3 * R * dB[k] + (k == 1 ? 0.37 * h : 0);
    q[k] = 0.3 * R * dB[k] + (k == 1 ? 0.37 * h : 0);
  }
  PetscCall(CheckContact("ridge, over a face near the ridge", walls, x, q));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode Apex(void)
{
  const double b = 2 * R, c[4][3] = {{b, b, -b}, {-b, b, -b}, {-b, -b, -b}, {b, -b, -b}}, x[3] = {0.1 * R, 0.05 * R, 0.97 * R}, q[3] = {0, 0, 0};
  double       v[36];
  char         walls[PETSC_MAX_PATH_LEN + 32];

  PetscFunctionBeginUser;
  for (int t = 0; t < 4; t++)
    for (int k = 0; k < 3; k++) {
      v[9 * t + k]     = 0;
      v[9 * t + 3 + k] = c[t][k];
      v[9 * t + 6 + k] = c[(t + 1) % 4][k];
    }
  PetscCall(TestWriteStl(PETSC_COMM_WORLD, fa, 4, v));
  PetscCall(PetscSNPrintf(walls, sizeof walls, "-dem_mesh_0_file %s", fa));
  PetscCall(CheckContact("pyramid apex of 4 triangles", walls, x, q));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* A sphere sliding along the floor into the wall, 0.02 s; final position and velocity. */
static PetscErrorCode Slide(const char *walls, double x[3], double v[3])
{
  char   opts[1024];
  Domain dom;
  Dem    dem;

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(opts, sizeof opts, "-domain_lo -0.05,-0.05,-0.05 -domain_hi 0.05,0.05,0.05 -dem_radius %g -dem_density 2500 -dem_kn %g -dem_restitution 0.5 -dem_friction 0.3 -dem_dt 5e-6 -dem_impact_velocity 0.5 %s", R, KN, walls));
  PetscCall(TestDemCreate(opts, &dom, &dem));
  DemParticle p = {.id = 1, .shape = 0, .x = {0.012, 0.001, R - 1.3e-7}, .v = {-0.6, 0.05, 0}, .q = {1, 0, 0, 0}};
  PetscCall(DemAddParticle(dem, &p));
  PetscCall(DemSetUp(dem));
  for (int s = 0; s < 4000; s++) PetscCall(DemStep(dem));
  p = TestGet(dem, 1);
  for (int k = 0; k < 3; k++) x[k] = p.x[k], v[k] = p.v[k];
  PetscCall(TestDemDestroy(&dom, &dem));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode Corner(void)
{
  const double h = 0.005, o[3] = {0, -0.02, 0}, ef[3] = {h, 0, 0}, ew[3] = {0, 0, h}, ey[3] = {0, h, 0};
  double       v[2 * 2 * 64 * 9], x[3] = {0.98 * R, 0.37 * h, 0.97 * R}, F[3], P[3];
  char         walls[3][2 * PETSC_MAX_PATH_LEN + 64];
  const char  *label[2] = {"two meshes", "one mesh"};

  PetscFunctionBeginUser;
  TestGridTriangles(o, ef, ey, 8, 8, v);           /* floor z = 0, x in [0, 0.04] */
  TestGridTriangles(o, ey, ew, 8, 8, v + 9 * 128); /* wall x = 0, z in [0, 0.04] */
  PetscCall(TestWriteStl(PETSC_COMM_WORLD, fa, 128, v));
  PetscCall(TestWriteStl(PETSC_COMM_WORLD, fb, 128, v + 9 * 128));
  PetscCall(PetscSNPrintf(walls[0], sizeof walls[0], "-dem_mesh_0_file %s -dem_mesh_1_file %s", fa, fb));
  PetscCall(PetscSNPrintf(walls[2], sizeof walls[2], "-dem_plane_0 0,0,0,0,0,1 -dem_plane_1 0,0,0,1,0,0"));
  PetscCall(Force(walls[2], x, P));
  PetscCall(CheckClose("corner, two planes: force on x vs kn (r - x)", P[0], KN * (R - x[0]), 1e-5));
  double xm[3], vm[3], xp[3], vp[3], e = 0;
  PetscCall(Slide(walls[2], xp, vp));
  PetscCall(Slide(walls[0], xm, vm));
  for (int k = 0; k < 3; k++) e = PetscMax(e, PetscMax(PetscAbsReal(xm[k] - xp[k]) / 0.012, PetscAbsReal(vm[k] - vp[k]) / 0.6));
  PetscCall(CheckAbove("sliding into the corner: rebound speed off the wall [m/s] (it reached the wall)", vp[0], 0.05));
  PetscCall(CheckBelow("sliding into the corner of two meshes: state vs two planes' after 0.02 s (relative)", e, 1e-9));
  for (int c = 0; c < 2; c++) {
    if (c) { /* both faces in one file */
      PetscCall(TestWriteStl(PETSC_COMM_WORLD, fa, 256, v));
      PetscCall(PetscSNPrintf(walls[1], sizeof walls[1], "-dem_mesh_0_file %s", fa));
    }
    PetscCall(Force(walls[c], x, F));
    PetscCall(CheckClose(CheckName("concave corner, %s: force on x vs kn (r - x)", label[c]), F[0], KN * (R - x[0]), 1e-5));
    PetscCall(CheckClose(CheckName("concave corner, %s: force on z vs kn (r - z)", label[c]), F[2], KN * (R - x[2]), 1e-5));
    PetscCall(CheckBelow(CheckName("concave corner, %s: force vs two planes' (relative)", label[c]), sqrt(PetscSqr(F[0] - P[0]) + PetscSqr(F[1] - P[1]) + PetscSqr(F[2] - P[2])) / sqrt(PetscSqr(P[0]) + PetscSqr(P[2])), 1e-12));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(PetscSNPrintf(fa, sizeof fa, "/tmp/sable_test_mesh_contacts_a_%d.stl", (int)getpid()));
  PetscCall(PetscSNPrintf(fb, sizeof fb, "/tmp/sable_test_mesh_contacts_b_%d.stl", (int)getpid()));
  PetscCall(Ridge());
  PetscCall(Apex());
  PetscCall(Corner());
  (void)unlink(fa);
  (void)unlink(fb);
  PetscCall(PetscFinalize());
  return check_failures ? 1 : 0;
}
