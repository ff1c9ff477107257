/* Convex shape geometry against exact references.
 *
 * 1. Volume and principal moments of inertia of each built-in (cube, regular tetrahedron,
 *    octahedron, icosahedron, cylinder) equal the textbook formulas to 1e-12 relative:
 *    the hull and the divergence-theorem integrals are exact up to roundoff.
 * 2. A 1 x 0.6 x 0.3 box, rotated by an arbitrary quaternion and shifted, with duplicate,
 *    face and interior points added, comes back as 8 vertices, its centre of mass at the
 *    shift, the box moments V(b^2+c^2)/12... as principal moments, and axis-aligned vertices.
 * 3. The hull of 300 random points (on and inside a sphere) contains every input point and is
 *    a closed triangulation (Euler: F = 2V - 4).
 * (Bad vertex lists and files are checked in test_errors.c.)
 * A reader should conclude that the mass properties handed to the DEM are exact and that a
 * vertex list in any orientation is brought to its principal frame.
 */
#include "check.h"
#include "geom/convex.h"
#include "geom/quat.h"

static double rel(double a, double b)
{
  return fabs(a - b) / fabs(b);
}

static PetscErrorCode CheckBuiltin(const char *name, const ConvexShape *s, double V, const double Iref[3], PetscInt nf)
{
  char   buf[128];
  double e = 0;

  PetscFunctionBeginUser;
  for (int k = 0; k < 3; k++) e = PetscMax(e, rel(s->inertia[k], Iref[k]));
  snprintf(buf, sizeof buf, "%s volume rel. error", name);
  PetscCall(CheckAtMost(buf, rel(s->volume, V), 1e-12));
  snprintf(buf, sizeof buf, "%s inertia rel. error", name);
  PetscCall(CheckAtMost(buf, e, 1e-12));
  if (nf) {
    snprintf(buf, sizeof buf, "%s hull triangles", name);
    PetscCall(CheckEqual(buf, s->nf, nf));
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode TestBuiltins(void)
{
  const double a = 0.013, phi = (1 + sqrt(5.0)) / 2, r = 0.004, h = 0.011;
  ConvexShape  s;
  double       V, Iref[3];

  PetscFunctionBeginUser;
  PetscCall(ConvexShapeCreateCube(a, &s));
  V       = a * a * a;
  Iref[0] = Iref[1] = Iref[2] = V * a * a / 6;
  PetscCall(CheckBuiltin("cube", &s, V, Iref, 12));
  PetscCall(CheckAtMost("cube bounding radius rel. error", rel(s.bounding_radius, sqrt(3.0) * a / 2), 1e-14));
  PetscCall(CheckAtMost("cube volume-equivalent diameter rel. error", rel(s.d_eq, a * cbrt(6 / PETSC_PI)), 1e-14));
  PetscCall(ConvexShapeDestroy(&s));
  PetscCall(ConvexShapeCreateTetrahedron(a, &s));
  V       = a * a * a / (6 * sqrt(2.0));
  Iref[0] = Iref[1] = Iref[2] = V * a * a / 20;
  PetscCall(CheckBuiltin("tetrahedron", &s, V, Iref, 4));
  PetscCall(ConvexShapeDestroy(&s));
  PetscCall(ConvexShapeCreateOctahedron(a, &s));
  V       = sqrt(2.0) * a * a * a / 3;
  Iref[0] = Iref[1] = Iref[2] = V * a * a / 10;
  PetscCall(CheckBuiltin("octahedron", &s, V, Iref, 8));
  PetscCall(ConvexShapeDestroy(&s));
  PetscCall(ConvexShapeCreateIcosahedron(a, &s));
  V       = 5 * (3 + sqrt(5.0)) * a * a * a / 12;
  Iref[0] = Iref[1] = Iref[2] = V * phi * phi * a * a / 10;
  PetscCall(CheckBuiltin("icosahedron", &s, V, Iref, 20));
  PetscCall(ConvexShapeDestroy(&s));
  PetscCall(ConvexShapeCreateCylinder(r, h, &s));
  V       = PETSC_PI * r * r * h;
  Iref[0] = Iref[1] = V * (3 * r * r + h * h) / 12;
  Iref[2]           = V * r * r / 2;
  PetscCall(CheckBuiltin("cylinder", &s, V, Iref, 0));
  PetscCall(ConvexShapeDestroy(&s));
  PetscFunctionReturn(0);
}

static PetscErrorCode TestRotatedBox(void)
{
  const double L[3] = {1.0, 0.6, 0.3}, shift[3] = {1.5, -2.0, 0.7}, axis0[3] = {0.3, -0.5, 0.8};
  double       axis[3], q[4], R[9], x[3 * 20], Iref[3], V = L[0] * L[1] * L[2], e = 0, ec = 0, ev = 0;
  PetscInt     n = 0;
  ConvexShape  s;

  PetscFunctionBeginUser;
  for (int k = 0; k < 3; k++) axis[k] = axis0[k] / convex_norm(axis0);
  convex_quat_from_axis_angle(axis, 1.234, q);
  convex_quat_to_matrix(q, R);
  for (int i = 0; i < 14; i++) { /* 8 corners, 2 duplicates, a face centre, a face point, 2 interior */
    double p[3], w[3];
    for (int d = 0; d < 3; d++) p[d] = ((i % 8) >> d & 1 ? 0.5 : -0.5) * L[d];
    if (i == 10) p[0] = 0, p[1] = 0;
    if (i == 11) p[0] = 0.1, p[1] = -0.2;
    if (i >= 12) p[0] *= 0.3, p[1] *= -0.2, p[2] *= 0.5;
    convex_mat_vec(R, p, w);
    for (int d = 0; d < 3; d++) x[3 * n + d] = w[d] + shift[d];
    n++;
  }
  PetscCall(ConvexShapeCreateFromVertices(n, x, &s));
  Iref[0] = V * (L[1] * L[1] + L[2] * L[2]) / 12; /* smallest moment: about the longest side */
  Iref[1] = V * (L[0] * L[0] + L[2] * L[2]) / 12;
  Iref[2] = V * (L[0] * L[0] + L[1] * L[1]) / 12;
  for (int k = 0; k < 3; k++) {
    double m = 0;
    e        = PetscMax(e, rel(s.inertia[k], Iref[k]));
    ec       = PetscMax(ec, fabs(s.com_input[k] - shift[k]));
    for (PetscInt i = 0; i < s.nv; i++) m = PetscMax(m, fabs(s.v[3 * i + k]));
    for (PetscInt i = 0; i < s.nv; i++) ev = PetscMax(ev, fabs(fabs(s.v[3 * i + k]) - m));
    ev = PetscMax(ev, fabs(m - L[k] / 2)); /* body axis k carries side k (moments ascending) */
  }
  PetscCall(CheckEqual("rotated box: hull vertices", s.nv, 8));
  PetscCall(CheckAtMost("rotated box: volume rel. error", rel(s.volume, V), 1e-12));
  PetscCall(CheckAtMost("rotated box: principal moments rel. error", e, 1e-12));
  PetscCall(CheckAtMost("rotated box: centre of mass error / side", ec / L[0], 1e-12));
  PetscCall(CheckAtMost("rotated box: body-frame vertices at +-L/2, error / side", ev / L[0], 1e-12));
  PetscCall(ConvexShapeDestroy(&s));
  PetscFunctionReturn(0);
}

static PetscErrorCode TestRandomHull(void)
{
  const PetscInt n = 300;
  double        *x, out = 0;
  ConvexShape    s;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(3 * n, &x));
  srand(12345);
  for (PetscInt i = 0; i < n; i++) {
    double p[3], r;
    do {
      for (int d = 0; d < 3; d++) p[d] = 2.0 * rand() / RAND_MAX - 1;
      r = convex_norm(p);
    } while (r > 1 || r < 1e-3);
    for (int d = 0; d < 3; d++) x[3 * i + d] = (i % 3 ? p[d] / r : p[d]); /* 2/3 on the sphere */
  }
  PetscCall(ConvexShapeCreateFromVertices(n, x, &s));
  for (PetscInt t = 0; t < s.nf; t++) { /* every input point below every face plane */
    double e1[3], e2[3], nrm[3], len;
    convex_sub(&s.v[3 * s.f[3 * t + 1]], &s.v[3 * s.f[3 * t]], e1);
    convex_sub(&s.v[3 * s.f[3 * t + 2]], &s.v[3 * s.f[3 * t]], e2);
    convex_cross(e1, e2, nrm);
    len = convex_norm(nrm);
    for (PetscInt i = 0; i < n; i++) {
      double d[3], b[3];
      convex_sub(&x[3 * i], s.com_input, d);
      convex_mat_tvec(s.rot_input, d, b);
      convex_sub(b, &s.v[3 * s.f[3 * t]], d);
      out = PetscMax(out, convex_dot(d, nrm) / len);
    }
  }
  PetscCall(CheckAtMost("random hull (300 points): max distance of a point outside", out, 1e-12));
  PetscCall(CheckEqual("random hull: Euler, triangles F = 2V - 4", s.nf, 2 * s.nv - 4));
  PetscCall(CheckAtMost("random hull: volume below the unit ball's", s.volume, 4 * PETSC_PI / 3));
  PetscCall(ConvexShapeDestroy(&s));
  PetscCall(PetscFree(x));
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  PetscCall(PetscInitialize(&argc, &argv, NULL, "convex shape geometry test"));
  PetscCall(TestBuiltins());
  PetscCall(TestRotatedBox());
  PetscCall(TestRandomHull());
  PetscCall(PetscFinalize());
  return check_failures ? 1 : 0;
}
