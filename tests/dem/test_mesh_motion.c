/* Moving mesh walls (walls_mesh.c): the pose x(t) = a + v t + Rot(u, theta(t)) (x_ref - a) and
 * the surface velocity v + omega u x (c - a(t)) at the contact point.
 *   belt: a sphere dropped at rest (no spin) onto a triangulated floor translating at V along x:
 *         friction spins it up until it rolls, at t* = 2 V / (7 mu g), with speed 2/7 V from then
 *         on (rigid body, Coulomb friction; bound 1%); and the whole run equals the one against
 *         -dem_plane_0 with -dem_plane_0_velocity V to 1e-9 relative;
 *   piston: the floor rising at 0.05 m/s along its normal lifts a resting sphere as the analytic
 *         moving plane does (1e-9 relative);
 *   paddle: a vertical mesh plate through the z axis turning after the table
 *         -dem_mesh_0_omega_table 0,0,0.1,2,0.3,2 (theta = 10 t^2 up to 0.1 s, then 0.1 + 2
 *         (t - 0.1)) reaches a free sphere at polar angle phi = 0.3 + asin(r / rho) when
 *         theta = 0.3, at t = 0.2 s exactly: the sphere starts moving within one step of it. */
#include <unistd.h>
#include "dem_common.h"
#include "stl_write.h"

static const double R = 0.005, KN = 1e5, MU = 0.3, G = 9.81;
static char         file[PETSC_MAX_PATH_LEN];

/* A sphere on the floor z = 0 moving with the given wall options for nstep steps of 5e-6 s;
 * its velocity at step tstar (if >= 0) and at the end, its final position. */
static PetscErrorCode Floor(const char *walls, PetscInt nstep, PetscInt tstar, double vstar[3], double x[3], double v[3])
{
  const double m = 2500 * 4.0 / 3.0 * PETSC_PI * R * R * R;
  char         opts[1024];
  Domain       dom;
  Dem          dem;

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(opts, sizeof opts, "-domain_lo -0.1,-0.1,-0.02 -domain_hi 0.1,0.1,0.1 -dem_radius %g -dem_density 2500 -dem_kn %g -dem_restitution 0.5 -dem_friction %g -dem_dt 5e-6 -dem_impact_velocity 0.1 %s", R, KN, MU, walls));
  PetscCall(TestDemCreate(opts, &dom, &dem));
  DemParticle p = {.id = 2, .shape = 0, .x = {0.0013, 0.0021, R - m * G / KN}, .q = {1, 0, 0, 0}};
  PetscCall(DemAddParticle(dem, &p));
  PetscCall(DemSetUp(dem));
  for (PetscInt s = 0; s < nstep; s++) {
    if (s == tstar) {
      p = TestGet(dem, 2);
      for (int k = 0; k < 3; k++) vstar[k] = p.v[k];
    }
    PetscCall(DemStep(dem));
  }
  p = TestGet(dem, 2);
  for (int k = 0; k < 3; k++) x[k] = p.x[k], v[k] = p.v[k];
  PetscCall(TestDemDestroy(&dom, &dem));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static double Diff(const double a[3], const double b[3], double scale)
{
  double d = 0;
  for (int k = 0; k < 3; k++) d = PetscMax(d, PetscAbsReal(a[k] - b[k]) / scale);
  return d;
}

static PetscErrorCode Paddle(void)
{
  const double rho = 0.05, phi = 0.3 + asin(R / rho), t_hit = 0.2, dt = 1e-5;
  const double o[3] = {0, 0, -0.02}, e1[3] = {0.02, 0, 0}, e2[3] = {0, 0, 0.01};
  double       v[2 * 5 * 4 * 9], t = 0, t_move = -1;
  char         opts[1024];
  Domain       dom;
  Dem          dem;

  PetscFunctionBeginUser;
  TestGridTriangles(o, e1, e2, 5, 4, v); /* x in [0, 0.1], z in [-0.02, 0.02], y = 0 */
  PetscCall(TestWriteStl(PETSC_COMM_WORLD, file, 40, v));
  PetscCall(PetscSNPrintf(opts, sizeof opts, "-domain_lo -0.1,-0.1,-0.05 -domain_hi 0.1,0.1,0.05 -dem_radius %g -dem_density 2500 -dem_kn %g -dem_restitution 0.5 -dem_friction %g -dem_gravity 0,0,0 -dem_dt %g -dem_mesh_0_file %s -dem_mesh_0_omega_table 0,0,0.1,2,0.3,2 -dem_mesh_0_axis 0,0,1", R, KN, MU, dt, file));
  PetscCall(TestDemCreate(opts, &dom, &dem));
  DemParticle p = {.id = 5, .shape = 0, .x = {rho * cos(phi), rho * sin(phi), 0}, .q = {1, 0, 0, 0}};
  PetscCall(DemAddParticle(dem, &p));
  PetscCall(DemSetUp(dem));
  while (t < 0.25 && t_move < 0) {
    PetscCall(DemStep(dem));
    PetscCall(DemGetTime(dem, &t, NULL));
    p = TestGet(dem, 5);
    if (p.v[0] != 0 || p.v[1] != 0) t_move = t;
  }
  PetscCall(TestDemDestroy(&dom, &dem));
  PetscCall(CheckCloseAbs("paddle turning after a table: time the sphere starts moving [s] vs the table's exact angle integral", t_move, t_hit, 1.5 * dt));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  const double V = 0.3, ts = 2 * V / (7 * MU * G), dt = 5e-6;
  const double o[3] = {-0.05, -0.05, 0}, e1[3] = {0.007, 0, 0}, e2[3] = {0, 0.007, 0};
  double       v[2 * 15 * 15 * 9], xm[3], vm[3], xp[3], vp[3], sm[3], sp[3];
  char         walls[PETSC_MAX_PATH_LEN + 128];

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(PetscSNPrintf(file, sizeof file, "/tmp/sable_test_mesh_motion_%d.stl", (int)getpid()));
  TestGridTriangles(o, e1, e2, 15, 15, v); /* the floor z = 0, x, y in [-0.05, 0.055] */
  PetscCall(TestWriteStl(PETSC_COMM_WORLD, file, 450, v));
  const PetscInt nstar = (PetscInt)(ts / dt + 0.5), nend = 2 * nstar;
  PetscCall(PetscSNPrintf(walls, sizeof walls, "-dem_mesh_0_file %s -dem_mesh_0_velocity %g,0,0", file, V));
  PetscCall(Floor(walls, nend, nstar, sm, xm, vm));
  PetscCall(PetscSNPrintf(walls, sizeof walls, "-dem_plane_0 0,0,0,0,0,1 -dem_plane_0_velocity %g,0,0", V));
  PetscCall(Floor(walls, nend, nstar, sp, xp, vp));
  PetscCall(CheckClose("belt: speed at t* = 2 V / (7 mu g) [m/s] vs analytic 2/7 V", sm[0], 2.0 / 7.0 * V, 0.01));
  PetscCall(CheckClose("belt: then rolls: speed at 2 t* [m/s] vs analytic 2/7 V", vm[0], 2.0 / 7.0 * V, 0.01));
  PetscCall(CheckBelow("belt: state at 2 t* vs the moving plane's (relative)", PetscMax(Diff(xm, xp, PetscAbsReal(xp[0])), Diff(vm, vp, V)), 1e-9));
  PetscCall(PetscSNPrintf(walls, sizeof walls, "-dem_mesh_0_file %s -dem_mesh_0_velocity 0,0,0.05", file));
  PetscCall(Floor(walls, 20000, -1, sm, xm, vm));
  PetscCall(PetscSNPrintf(walls, sizeof walls, "-dem_plane_0 0,0,0,0,0,1 -dem_plane_0_velocity 0,0,0.05"));
  PetscCall(Floor(walls, 20000, -1, sp, xp, vp));
  PetscCall(CheckClose("piston: height after 0.1 s [m] vs the analytic moving plane's", xm[2], xp[2], 1e-9));
  PetscCall(CheckClose("piston: rising at the floor's speed [m/s]", vm[2], 0.05, 1e-3));
  PetscCall(Paddle());
  (void)unlink(file);
  PetscCall(PetscFinalize());
  return check_failures ? 1 : 0;
}
