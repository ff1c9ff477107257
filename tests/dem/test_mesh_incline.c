/* A sphere on a triangulated tilted plane (a mesh wall of 800 triangles, spacing about the
 * sphere's radius, cells split along alternating diagonals): it crosses shared edges and
 * vertices as it rolls, and the contact rule (walls_mesh.c) must make it feel one plane.
 * References:
 *   at rest on the level mesh, centred over a vertex shared by 4 triangles: overlap m g / kn
 *   (linear law), no sideways drift;
 *   rigid body with Coulomb friction mu: a sphere rolls without slip when tan(theta) <= 3.5 mu
 *   (the contact point does not slide: |v + w x (-r n)| stays ~0) with a = 5/7 g sin(theta),
 *   and slides above it with a = g (sin(theta) - mu cos(theta)) (bound 1%);
 *   the trajectory equals the run against the analytic plane -dem_plane_0 with the same normal
 *   to 1e-9 relative (positions against the distance travelled, velocities against the speed),
 *   on a path along grid lines (through vertices) and on a generic one. */
#include <unistd.h>
#include "dem_common.h"
#include "stl_write.h"

#define NSAMP 31
static const double R = 0.005, G = 9.81, KN = 1e5, MU = 0.3, H = 0.006; /* radius, gravity, stiffness, friction, grid spacing */

typedef struct {
  double x[NSAMP][3], v[NSAMP][3], slip; /* samples every 0.005 s; the largest slip speed after 0.05 s */
} Traj;

/* Runs 0.15 s from rest at in-plane coordinates (s0, y0) of the plane tilted by theta about y;
 * mesh: the triangulated plane in file, else the analytic one. */
static PetscErrorCode Run(double theta, double s0, double y0, const char *file, Traj *tr)
{
  const double m = 2500 * 4.0 / 3.0 * PETSC_PI * R * R * R, e1[3] = {cos(theta), 0, sin(theta)}, n[3] = {-sin(theta), 0, cos(theta)};
  const double d0 = m * G * cos(theta) / KN; /* static overlap */
  char         opts[1024], wall[256];
  Domain       dom;
  Dem          dem;

  PetscFunctionBeginUser;
  if (file) PetscCall(PetscSNPrintf(wall, sizeof wall, "-dem_mesh_0_file %s", file));
  else PetscCall(PetscSNPrintf(wall, sizeof wall, "-dem_plane_0 0,0,0,%.17g,0,%.17g", n[0], n[2]));
  PetscCall(PetscSNPrintf(opts, sizeof opts, "-domain_lo -0.15,-0.05,-0.15 -domain_hi 0.15,0.05,0.15 -dem_radius %g -dem_density 2500 -dem_kn %g -dem_restitution 0.5 -dem_friction %g -dem_dt 5e-6 -dem_impact_velocity 0.1 %s", R, KN, MU, wall));
  PetscCall(TestDemCreate(opts, &dom, &dem));
  DemParticle p = {.id = 3, .shape = 0, .q = {1, 0, 0, 0}};
  for (int k = 0; k < 3; k++) p.x[k] = s0 * e1[k] + (k == 1 ? y0 : 0) + (R - d0) * n[k];
  PetscCall(DemAddParticle(dem, &p));
  PetscCall(DemSetUp(dem));
  tr->slip = 0;
  for (PetscInt step = 0, smp = 0; smp < NSAMP; step++) {
    if (step % 1000 == 0) {
      const DemParticle q = TestGet(dem, 3);
      for (int k = 0; k < 3; k++) tr->x[smp][k] = q.x[k], tr->v[smp][k] = q.v[k];
      smp++;
    }
    if (step >= 10000) { /* slip velocity of the contact point x - r n: v + w x (-r n) */
      const DemParticle q    = TestGet(dem, 3);
      const double      c[3] = {q.w[1] * n[2] - q.w[2] * n[1], q.w[2] * n[0] - q.w[0] * n[2], q.w[0] * n[1] - q.w[1] * n[0]};
      const double      s[3] = {q.v[0] - R * c[0], q.v[1] - R * c[1], q.v[2] - R * c[2]};
      tr->slip               = PetscMax(tr->slip, sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]));
    }
    if (smp < NSAMP) PetscCall(DemStep(dem));
  }
  PetscCall(TestDemDestroy(&dom, &dem));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Writes the plane tilted by theta about y, triangulated, centred at the origin (a vertex). */
static PetscErrorCode WritePlane(double theta, const char *file)
{
  const PetscInt nu = 40, nv = 10;
  const double   e1[3] = {H * cos(theta), 0, H * sin(theta)}, e2[3] = {0, H, 0};
  const double   o[3] = {-nu / 2 * e1[0], -nv / 2 * H, -nu / 2 * e1[2]};
  double        *v;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(18 * nu * nv, &v));
  TestGridTriangles(o, e1, e2, nu, nv, v);
  PetscCall(TestWriteStl(PETSC_COMM_WORLD, file, 2 * nu * nv, v));
  PetscCall(PetscFree(v));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The largest deviation of the mesh run from the plane run: positions relative to the distance
 * travelled, velocities relative to the final speed. */
static double TrajDiff(const Traj *a, const Traj *b)
{
  double dmax = 0, L = 0, V = 0;
  for (int k = 0; k < 3; k++) {
    L += PetscSqr(b->x[NSAMP - 1][k] - b->x[0][k]);
    V += PetscSqr(b->v[NSAMP - 1][k]);
  }
  L = sqrt(L);
  V = sqrt(V);
  for (int s = 0; s < NSAMP; s++)
    for (int k = 0; k < 3; k++) dmax = PetscMax(dmax, PetscMax(PetscAbsReal(a->x[s][k] - b->x[s][k]) / L, PetscAbsReal(a->v[s][k] - b->v[s][k]) / V));
  return dmax;
}

int main(int argc, char **argv)
{
  char   file[PETSC_MAX_PATH_LEN];
  Traj  *tm, *tp;
  double m;

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  m = 2500 * 4.0 / 3.0 * PETSC_PI * R * R * R;
  PetscCall(PetscSNPrintf(file, sizeof file, "/tmp/sable_test_mesh_incline_%d.stl", (int)getpid()));
  PetscCall(PetscMalloc2(1, &tm, 1, &tp));
  { /* level mesh, at rest over a vertex */
    PetscCall(WritePlane(0, file));
    PetscCall(Run(0, 0, 0, file, tm));
    PetscCall(CheckClose("at rest over a vertex of 4 triangles: overlap [m] vs analytic m g / kn", R - tm->x[NSAMP - 1][2], m * G / KN, 1e-9));
    PetscCall(CheckBelow("at rest over a vertex: sideways drift [m]", PetscMax(PetscAbsReal(tm->x[NSAMP - 1][0]), PetscAbsReal(tm->x[NSAMP - 1][1])), 1e-12));
  }
  const double f[2] = {0.5, 2.0}; /* tan(theta) / (3.5 mu): rolling, sliding */
  for (int c = 0; c < 2; c++) {
    const double th = atan(f[c] * 3.5 * MU), roll = f[c] < 1, ref = roll ? 5.0 / 7.0 * G * sin(th) : G * (sin(th) - MU * cos(th));
    PetscCall(WritePlane(th, file));
    for (int path = 0; path < 2; path++) {
      const double y0 = path ? 0.37 * H : 0; /* along a grid line (through vertices), or generic */
      PetscCall(Run(th, 0.1, y0, file, tm));
      PetscCall(Run(th, 0.1, y0, NULL, tp));
      const double a  = -((tm->v[30][0] - tm->v[10][0]) * cos(th) + (tm->v[30][2] - tm->v[10][2]) * sin(th)) / 0.1; /* downhill */
      const double sp = sqrt(PetscSqr(tm->v[30][0]) + PetscSqr(tm->v[30][2]));
      PetscCall(CheckClose(CheckName("tan(theta) = %.2f x 3.5 mu, y0 = %.2f h: %s a [m/s^2] vs analytic", f[c], y0 / H, roll ? "rolling" : "sliding"), a, ref, 0.01));
      if (roll) PetscCall(CheckBelow(CheckName("tan(theta) = %.2f x 3.5 mu, y0 = %.2f h: slip speed / speed (does not slide)", f[c], y0 / H), tm->slip / sp, 1e-3));
      else PetscCall(CheckAbove(CheckName("tan(theta) = %.2f x 3.5 mu, y0 = %.2f h: slip speed / speed (slides)", f[c], y0 / H), tm->slip / sp, 0.1));
      PetscCall(CheckBelow(CheckName("tan(theta) = %.2f x 3.5 mu, y0 = %.2f h: trajectory vs the analytic plane's (relative)", f[c], y0 / H), TrajDiff(tm, tp), 1e-9));
      PetscCall(CheckBelow(CheckName("tan(theta) = %.2f x 3.5 mu, y0 = %.2f h: sideways drift [m]", f[c], y0 / H), PetscAbsReal(tm->x[NSAMP - 1][1] - y0), 1e-12));
    }
  }
  PetscCall(PetscFree2(tm, tp));
  if (!unlink(file)) PetscCall(PetscInfo(NULL, "removed %s\n", file));
  PetscCall(PetscFinalize());
  return check_failures ? 1 : 0;
}
