/* Cost of one convex narrow-phase call (not a test; figures go to doc/performance.md).
 *
 * For each shape (cube, icosahedron, cylinder; size 1) it draws N random near-contact pairs:
 * uniformly random orientations (Shoemake 1992) and direction u, B placed at distance
 * t* (1 + s) along u, where t* is the touching distance (bisection) and s is uniform in
 * [-2%, +2%], so that about half of the pairs overlap by up to ~1% of the size. Each
 * ConvexCollide call is timed alone (clock_gettime, monotonic) and the median is reported
 * for overlapping and separated pairs, with the mean over all, and the same for
 * ConvexCollidePlane on random poses near the plane.
 * Usage: make build/tools/bench_convex && build/tools/bench_convex [-n 20000]
 */
#include <time.h>
#include "geom/convex.h"
#include "geom/quat.h"

static double urand(void)
{
  return (double)rand() / RAND_MAX;
}

static void random_quat(double q[4])
{
  const double u1 = urand(), u2 = 2 * PETSC_PI * urand(), u3 = 2 * PETSC_PI * urand();
  q[0] = sqrt(1 - u1) * sin(u2), q[1] = sqrt(1 - u1) * cos(u2), q[2] = sqrt(u1) * sin(u3), q[3] = sqrt(u1) * cos(u3);
}

static double now_ns(void)
{
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return 1e9 * t.tv_sec + t.tv_nsec;
}

static int cmp(const void *a, const void *b)
{
  const double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

static double median(double *v, PetscInt n)
{
  if (!n) return NAN;
  qsort(v, (size_t)n, sizeof *v, cmp);
  return v[n / 2];
}

static PetscErrorCode BenchShape(const char *name, const ConvexShape *s, PetscInt n)
{
  double       *tin, *tout, *tpl, sum = 0, dmax = 0;
  PetscInt      nin = 0, nout = 0;
  ConvexContact c;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc3(n, &tin, n, &tout, n, &tpl));
  for (PetscInt i = 0; i < n; i++) {
    ConvexPose A = {{0, 0, 0}, {1, 0, 0, 0}}, B;
    double     u[3], lo = 0, hi = 2 * s->bounding_radius, t0, t1, f;
    random_quat(A.q);
    random_quat(B.q);
    do {
      for (int k = 0; k < 3; k++) u[k] = 2 * urand() - 1;
    } while (convex_norm(u) > 1 || convex_norm(u) < 1e-3);
    f = convex_norm(u);
    for (int k = 0; k < 3; k++) u[k] /= f;
    for (int it = 0; it < 50; it++) { /* touching distance along u */
      const double mid = 0.5 * (lo + hi);
      for (int k = 0; k < 3; k++) B.x[k] = mid * u[k];
      PetscCall(ConvexCollide(s, &A, s, &B, &c));
      if (c.overlap) lo = mid;
      else hi = mid;
    }
    f = 1 + 0.04 * (urand() - 0.5);
    for (int k = 0; k < 3; k++) B.x[k] = lo * f * u[k];
    t0 = now_ns();
    PetscCall(ConvexCollide(s, &A, s, &B, &c));
    t1 = now_ns();
    sum += t1 - t0;
    if (c.overlap) tin[nin++] = t1 - t0, dmax = PetscMax(dmax, c.depth);
    else tout[nout++] = t1 - t0;
    { /* plane z = 0, body centred near the touching height */
      const double p0[3] = {0, 0, 0}, nz[3] = {0, 0, 1};
      B.x[0] = B.x[1] = 0;
      B.x[2]          = s->bounding_radius * (0.5 + 0.5 * urand());
      t0              = now_ns();
      PetscCall(ConvexCollidePlane(s, &B, p0, nz, &c));
      tpl[i] = now_ns() - t0;
    }
  }
  printf("%-12s pairs %6d: median %6.0f ns overlapping (%d, max depth %.3f), %6.0f ns separated (%d); mean %6.0f ns; plane median %4.0f ns\n", name, (int)n, median(tin, nin), (int)nin, dmax, median(tout, nout), (int)nout, sum / n, median(tpl, n));
  PetscCall(PetscFree3(tin, tout, tpl));
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  ConvexShape s;
  PetscInt    n = 20000;

  PetscCall(PetscInitialize(&argc, &argv, NULL, "convex narrow-phase benchmark"));
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-n", &n, NULL));
  srand(2026);
  PetscCall(ConvexShapeCreateCube(1.0, &s));
  PetscCall(BenchShape("cube", &s, n));
  PetscCall(ConvexShapeDestroy(&s));
  PetscCall(ConvexShapeCreateIcosahedron(1.0, &s));
  PetscCall(BenchShape("icosahedron", &s, n));
  PetscCall(ConvexShapeDestroy(&s));
  PetscCall(ConvexShapeCreateCylinder(0.5, 1.0, &s));
  PetscCall(BenchShape("cylinder", &s, n));
  PetscCall(ConvexShapeDestroy(&s));
  PetscCall(PetscFinalize());
  return 0;
}
