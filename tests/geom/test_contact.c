/* Narrow phase of convex shapes against hand-computed contact geometry.
 *
 * Two cubes of edge a = 1 cm, A at the origin (axis-aligned), B above it overlapping by
 * delta = a/100 in three touching modes, with B's centre offset sideways:
 *   face-to-face   B axis-aligned: depth delta, normal +z, contact point at the centre of
 *                  the overlap patch, at z = a/2 - delta/2;
 *   edge-to-face   B turned 45 deg about x (an edge along x down): depth delta, normal +z,
 *                  point at z = a/2 - delta/2, y = y_B, x mid-way along the part of the
 *                  edge over A's face;
 *   vertex-to-face B's body diagonal turned to -z (a corner down): depth delta, normal +z,
 *                  point = (x_B, y_B, a/2 - delta/2) exactly.
 *   edge-to-edge   A turned 45 deg about y, B 45 deg about x: crossed edges, depth delta,
 *                  normal +z, point at the crossing (0, y_B) at mid-overlap height.
 * The vertex case is repeated with the whole scene rotated and translated (the answer must
 * rotate with it) and with A and B swapped (the normal must flip). Two cubes whose bounding
 * spheres overlap but which do not touch must give no contact. A cylinder standing on the cube
 * checks the analytic cylinder support.
 * Shape-plane: the cube on the floor z = 0 flat, on an edge, on a corner, each sunk by delta:
 * depth delta, normal -z (from the cube into the wall), point (x_c, y_c, -delta/2); a cylinder
 * on its end (point = disc centre), on its side (point under the axis midpoint), and tilted
 * (depth = h/2 cos t + r sin t - z_c).
 * Random near-contact pairs of cubes, icosahedra and cylinders (at 0.99 of the touching
 * distance along a random ray) check A-B / B-A symmetry and that the point is inside both.
 * Bound: 1e-9 a for MPR results on polyhedra (portal tolerance 1e-10 of the bounding radii);
 * 1e-12 a for the closed-form plane contacts. Cylinder pairs are reported, not checked: MPR's
 * normal converges slowly on the rims, so A-B and B-A stop on different portals (a limitation,
 * src/geom/README.md); their figures print on NOTE lines.
 */
#include "check.h"
#include "geom/convex.h"
#include "geom/quat.h"

/* measured <= bound; bound < 0: a known limitation, reported on a NOTE line and not counted */
static PetscErrorCode CheckOrNote(const char *name, double measured, double bound)
{
  PetscFunctionBeginUser;
  if (bound < 0) PetscCall(PetscPrintf(PETSC_COMM_WORLD, "NOTE %s: %.3e (known limitation, not checked: src/geom/README.md)\n", name, measured));
  else PetscCall(CheckAtMost(name, measured, bound));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static double dist3(const double a[3], const double b[3])
{
  double d[3];
  convex_sub(a, b, d);
  return convex_norm(d);
}

static const double a = 0.01, delta = 0.0001, tol_mpr = 1e-9 * 0.01, tol_plane = 1e-12 * 0.01;
static const double ez[3] = {0, 0, 1};

/* Quaternion turning the body diagonal (1,1,1)/sqrt3 onto -z: a cube corner points down. */
static void corner_down(double q[4])
{
  const double u[3] = {1 / sqrt(3.0), 1 / sqrt(3.0), 1 / sqrt(3.0)}, m[3] = {0, 0, -1};
  double       ax[3];
  convex_cross(u, m, ax);
  const double s = convex_norm(ax);
  for (int k = 0; k < 3; k++) ax[k] /= s;
  convex_quat_from_axis_angle(ax, acos(convex_dot(u, m)), q);
}

static void edge_down(double q[4])
{
  const double ex[3] = {1, 0, 0};
  convex_quat_from_axis_angle(ex, PETSC_PI / 4, q);
}

static PetscErrorCode report(const char *mode, const ConvexContact *c, const double n_exp[3], double point_err)
{
  PetscFunctionBeginUser;
  PetscCall(CheckTrue(CheckName("%s: overlap found", mode), (PetscBool)(c->overlap != 0), NULL));
  PetscCall(CheckAtMost(CheckName("%s: |depth - delta| / a", mode), fabs(c->depth - delta) / a, tol_mpr / a));
  PetscCall(CheckAtMost(CheckName("%s: |normal - expected|", mode), dist3(c->normal, n_exp), tol_mpr / a));
  PetscCall(CheckAtMost(CheckName("%s: contact point error / a", mode), point_err / a, tol_mpr / a));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static double urand(void)
{
  return (double)rand() / RAND_MAX;
}

/* Uniform random unit quaternion (Shoemake 1992). */
static void random_quat(double q[4])
{
  const double u1 = urand(), u2 = 2 * PETSC_PI * urand(), u3 = 2 * PETSC_PI * urand();
  q[0] = sqrt(1 - u1) * sin(u2), q[1] = sqrt(1 - u1) * cos(u2), q[2] = sqrt(u1) * sin(u3), q[3] = sqrt(u1) * cos(u3);
}

/* How far world point p lies outside shape s at pose P (polyhedron: max signed face
 * distance; cylinder: max of the end and side distances). */
static double outside_distance(const ConvexShape *s, const ConvexPose *P, const double p[3])
{
  double R[9], d[3], b[3], best = -1e300;
  convex_quat_to_matrix(P->q, R);
  convex_sub(p, P->x, d);
  convex_mat_tvec(R, d, b);
  if (s->kind == CONVEX_CYLINDER) return PetscMax(fabs(b[2]) - s->height / 2, hypot(b[0], b[1]) - s->radius);
  for (PetscInt t = 0; t < s->nf; t++) {
    const double *v0 = &s->v[3 * s->f[3 * t]];
    double        e1[3], e2[3], nrm[3], r[3];
    convex_sub(&s->v[3 * s->f[3 * t + 1]], v0, e1);
    convex_sub(&s->v[3 * s->f[3 * t + 2]], v0, e2);
    convex_cross(e1, e2, nrm);
    convex_sub(b, v0, r);
    best = PetscMax(best, convex_dot(r, nrm) / convex_norm(nrm));
  }
  return best;
}

/* Random near-contact pairs: B on a random ray at 0.99 of the touching distance (bisection).
 * Swapping A and B must give the same depth and point and the opposite normal; the contact
 * point must lie inside both bodies (it is mid-overlap). Cylinders get looser bounds (main). */
static PetscErrorCode TestRandomPairs(const char *name, const ConvexShape *s, PetscInt npair, const double bound[4])
{
  double e_depth = 0, e_normal = 0, e_point = 0, e_out = -1e300, size = 2 * s->bounding_radius;

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < npair; i++) {
    ConvexPose    A = {{0, 0, 0}, {1, 0, 0, 0}}, B;
    ConvexContact c, c2;
    double        u[3], lo = 0, hi = size, nu;
    random_quat(A.q);
    random_quat(B.q);
    do {
      for (int k = 0; k < 3; k++) u[k] = 2 * urand() - 1;
      nu = convex_norm(u);
    } while (nu > 1 || nu < 1e-3);
    for (int it = 0; it < 50; it++) {
      const double mid = 0.5 * (lo + hi);
      for (int k = 0; k < 3; k++) B.x[k] = mid * u[k] / nu;
      PetscCall(ConvexCollide(s, &A, s, &B, &c));
      if (c.overlap) lo = mid;
      else hi = mid;
    }
    for (int k = 0; k < 3; k++) B.x[k] = 0.99 * lo * u[k] / nu;
    PetscCall(ConvexCollide(s, &A, s, &B, &c));
    PetscCall(ConvexCollide(s, &B, s, &A, &c2));
    if (!c.overlap || !c2.overlap) {
      e_depth = 1e300;
      continue;
    }
    e_depth  = PetscMax(e_depth, fabs(c.depth - c2.depth) / size);
    e_normal = PetscMax(e_normal, sqrt(PetscSqr(c.normal[0] + c2.normal[0]) + PetscSqr(c.normal[1] + c2.normal[1]) + PetscSqr(c.normal[2] + c2.normal[2])));
    e_point  = PetscMax(e_point, dist3(c.point, c2.point) / size);
    e_out    = PetscMax(e_out, PetscMax(outside_distance(s, &A, c.point), outside_distance(s, &B, c.point)) / c.depth);
  }
  PetscCall(CheckOrNote(CheckName("%s random pairs (%d): A-B swap |depth difference| / size", name, (int)npair), e_depth, bound[0]));
  PetscCall(CheckOrNote(CheckName("%s random pairs: A-B swap |n_AB + n_BA|", name), e_normal, bound[1]));
  PetscCall(CheckOrNote(CheckName("%s random pairs: A-B swap |point difference| / size", name), e_point, bound[2]));
  PetscCall(CheckOrNote(CheckName("%s random pairs: max signed distance of the contact point outside A or B / depth", name), e_out, bound[3]));
  PetscFunctionReturn(0);
}

static PetscErrorCode TestCubeCube(const ConvexShape *cube)
{
  ConvexPose    A = {{0, 0, 0}, {1, 0, 0, 0}}, B;
  ConvexContact c;

  PetscFunctionBeginUser;
  B = (ConvexPose){{0.3 * a, 0.2 * a, a - delta}, {1, 0, 0, 0}};
  PetscCall(ConvexCollide(cube, &A, cube, &B, &c));
  { /* overlap patch [-0.2, 0.5] x [-0.3, 0.5] a: its centre */
    const double p[3] = {0.15 * a, 0.10 * a, a / 2 - delta / 2};
    PetscCall(report("cube-cube face-to-face", &c, ez, dist3(c.point, p)));
  }

  B = (ConvexPose){{0.2 * a, 0.1 * a, a / 2 + a / sqrt(2.0) - delta}, {0}};
  edge_down(B.q);
  PetscCall(ConvexCollide(cube, &A, cube, &B, &c));
  { /* edge over x in [-0.3, 0.7] a, clipped by A's face to [-0.3, 0.5] a */
    const double p[3] = {0.1 * a, B.x[1], a / 2 - delta / 2};
    PetscCall(report("cube-cube edge-to-face", &c, ez, dist3(c.point, p)));
  }

  { /* A turned 45 deg about y (top edge along y), B 45 deg about x (bottom edge along x) */
    const double  ey[3] = {0, 1, 0}, p[3] = {0, 0.2 * a, a / sqrt(2.0) - delta / 2};
    ConvexPose    A2 = {{0, 0, 0}, {0}};
    ConvexContact c2;
    convex_quat_from_axis_angle(ey, PETSC_PI / 4, A2.q);
    B = (ConvexPose){{0.1 * a, 0.2 * a, sqrt(2.0) * a - delta}, {0}};
    edge_down(B.q);
    PetscCall(ConvexCollide(cube, &A2, cube, &B, &c2));
    PetscCall(report("cube-cube edge-to-edge (crossed)", &c2, ez, dist3(c2.point, p)));
  }
  B = (ConvexPose){{0.1 * a, -0.15 * a, a / 2 + a * sqrt(3.0) / 2 - delta}, {0}};
  corner_down(B.q);
  PetscCall(ConvexCollide(cube, &A, cube, &B, &c));
  {
    const double p[3] = {B.x[0], B.x[1], a / 2 - delta / 2};
    PetscCall(report("cube-cube vertex-to-face", &c, ez, dist3(c.point, p)));
  }
  {
    ConvexContact c2;
    const double  mz[3] = {0, 0, -1}, p[3] = {B.x[0], B.x[1], a / 2 - delta / 2};
    PetscCall(ConvexCollide(cube, &B, cube, &A, &c2));
    PetscCall(report("cube-cube vertex-to-face, A and B swapped", &c2, mz, dist3(c2.point, p)));
  }
  { /* the same scene rotated by Q and shifted by T */
    const double  ax0[3] = {-0.4, 0.7, 0.2}, T[3] = {0.31, -0.12, 2.5};
    double        ax[3], Q[4], M[9], n_exp[3], p[3], pr[3], qa[4], qb[4];
    ConvexPose    A2, B2;
    ConvexContact c3;
    for (int k = 0; k < 3; k++) ax[k] = ax0[k] / convex_norm(ax0);
    convex_quat_from_axis_angle(ax, 2.1, Q);
    convex_quat_to_matrix(Q, M);
    convex_quat_mul(Q, A.q, qa);
    convex_quat_mul(Q, B.q, qb);
    convex_mat_vec(M, A.x, A2.x);
    convex_mat_vec(M, B.x, B2.x);
    for (int k = 0; k < 3; k++) {
      A2.x[k] += T[k], B2.x[k] += T[k];
      A2.q[k] = qa[k], B2.q[k] = qb[k];
    }
    A2.q[3] = qa[3], B2.q[3] = qb[3];
    PetscCall(ConvexCollide(cube, &A2, cube, &B2, &c3));
    convex_mat_vec(M, ez, n_exp);
    p[0] = B.x[0], p[1] = B.x[1], p[2] = a / 2 - delta / 2;
    convex_mat_vec(M, p, pr);
    for (int k = 0; k < 3; k++) pr[k] += T[k];
    PetscCall(report("cube-cube vertex-to-face, scene rotated", &c3, n_exp, dist3(c3.point, pr)));
  }
  { /* B tilted by 0.004 rad about (1, -1, 0): its bottom corners differ in height by less than
       the overlap, so the patch point is inside the overlap patch, while the support point
       (CONVEX_POINT_SUPPORT) is the lowest corner, on A's top face at depth/2 */
    const double  u[3] = {1 / sqrt(2.0), -1 / sqrt(2.0), 0};
    double        M[9], low[3] = {0, 0, PETSC_MAX_REAL}, p[3];
    ConvexContact cs, cp;
    PetscBool     ok_s, ok_p;
    B = (ConvexPose){{0.3 * a, 0.2 * a, 0}, {0}};
    convex_quat_from_axis_angle(u, 0.004, B.q);
    convex_quat_to_matrix(B.q, M);
    for (int k = 0; k < 4; k++) {
      const double v[3] = {(k & 1 ? 0.5 : -0.5) * a, (k & 2 ? 0.5 : -0.5) * a, -0.5 * a};
      double       w[3];
      convex_mat_vec(M, v, w);
      if (w[2] < low[2]) low[0] = w[0], low[1] = w[1], low[2] = w[2];
    }
    B.x[2] = a / 2 - delta - low[2]; /* the lowest corner delta below A's top face */
    PetscCall(ConvexContactPoint(cube, &A, cube, &B, ez, delta, CONVEX_POINT_SUPPORT, &cs, &ok_s));
    PetscCall(ConvexContactPoint(cube, &A, cube, &B, ez, delta, CONVEX_POINT_PATCH, &cp, &ok_p));
    p[0] = B.x[0] + low[0], p[1] = B.x[1] + low[1], p[2] = a / 2 - delta / 2;
    PetscCall(CheckTrue("cube-cube tilted face-to-face, support point: found", ok_s, NULL));
    PetscCall(CheckAtMost("cube-cube tilted face-to-face, support point = the lowest corner at depth/2: error / a", dist3(cs.point, p) / a, tol_mpr / a));
    PetscCall(CheckTrue("cube-cube tilted face-to-face, patch point: found", ok_p, NULL));
    PetscCall(CheckAtMost("cube-cube tilted face-to-face, patch point is inside the patch, not at the corner: 0.1 a minus its distance to the corner, / a", (0.1 * a - dist3(cp.point, p)) / a, 0));
  }
  B = (ConvexPose){{1.02 * a, 1.02 * a, 0}, {0}}; /* bounding spheres overlap, cubes do not */
  edge_down(B.q);
  PetscCall(ConvexCollide(cube, &A, cube, &B, &c));
  PetscCall(CheckTrue("cube-cube near miss (corner gap 0.02 a): no overlap", (PetscBool)!c.overlap, NULL));
  PetscFunctionReturn(0);
}

static PetscErrorCode TestCylinderCube(const ConvexShape *cube)
{
  ConvexShape   cyl;
  ConvexPose    A = {{0, 0, 0}, {1, 0, 0, 0}}, B;
  ConvexContact c;
  const double  r = 0.3 * a, h = 0.8 * a;

  PetscFunctionBeginUser;
  PetscCall(ConvexShapeCreateCylinder(r, h, &cyl));
  B = (ConvexPose){{0.1 * a, 0.05 * a, a / 2 + h / 2 - delta}, {1, 0, 0, 0}};
  PetscCall(ConvexCollide(cube, &A, &cyl, &B, &c));
  {
    const double ez_[3] = {0, 0, 1};
    const double p[3]   = {B.x[0], B.x[1], a / 2 - delta / 2}; /* the disc lies inside the face */
    PetscCall(report("cube-cylinder end-to-face", &c, ez_, dist3(c.point, p)));
  }
  PetscCall(ConvexShapeDestroy(&cyl));
  PetscFunctionReturn(0);
}

static PetscErrorCode plane_check(const char *mode, const ConvexContact *c, double depth, const double p[3])
{
  const double mz[3] = {0, 0, -1};

  PetscFunctionBeginUser;
  PetscCall(CheckTrue(CheckName("%s: overlap found", mode), (PetscBool)(c->overlap != 0), NULL));
  PetscCall(CheckAtMost(CheckName("%s: |depth - expected| / a", mode), fabs(c->depth - depth) / a, tol_plane / a));
  PetscCall(CheckAtMost(CheckName("%s: |normal - (0,0,-1)|", mode), dist3(c->normal, mz), 1e-15));
  if (p) PetscCall(CheckAtMost(CheckName("%s: contact point error / a", mode), dist3(c->point, p) / a, tol_plane / a));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode TestPlane(const ConvexShape *cube)
{
  const double  p0[3] = {0, 0, 0}, x0 = 0.37 * a, y0 = -0.21 * a, r = 0.3 * a, h = 0.8 * a, t = 0.3;
  const double  p[3] = {x0, y0, -delta / 2};
  ConvexPose    B;
  ConvexContact c;
  ConvexShape   cyl;

  PetscFunctionBeginUser;
  B = (ConvexPose){{x0, y0, a / 2 - delta}, {1, 0, 0, 0}};
  PetscCall(ConvexCollidePlane(cube, &B, p0, ez, &c));
  PetscCall(plane_check("cube-plane flat", &c, delta, p));
  B.x[2] = a / sqrt(2.0) - delta;
  edge_down(B.q);
  PetscCall(ConvexCollidePlane(cube, &B, p0, ez, &c));
  PetscCall(plane_check("cube-plane edge", &c, delta, p));
  B.x[2] = a * sqrt(3.0) / 2 - delta;
  corner_down(B.q);
  PetscCall(ConvexCollidePlane(cube, &B, p0, ez, &c));
  PetscCall(plane_check("cube-plane corner", &c, delta, p));
  B.x[2] += 2 * delta;
  PetscCall(ConvexCollidePlane(cube, &B, p0, ez, &c));
  PetscCall(CheckTrue("cube-plane corner lifted by delta: no overlap", (PetscBool)!c.overlap, NULL));

  PetscCall(ConvexShapeCreateCylinder(r, h, &cyl));
  B = (ConvexPose){{x0, y0, h / 2 - delta}, {1, 0, 0, 0}};
  PetscCall(ConvexCollidePlane(&cyl, &B, p0, ez, &c));
  PetscCall(plane_check("cylinder-plane on its end", &c, delta, p));
  B.x[2] = r - delta;
  edge_down(B.q); /* 45 deg about x: the axis is not vertical; use 90 deg for the side */
  {
    const double ex[3] = {1, 0, 0};
    convex_quat_from_axis_angle(ex, PETSC_PI / 2, B.q);
  }
  PetscCall(ConvexCollidePlane(&cyl, &B, p0, ez, &c));
  PetscCall(plane_check("cylinder-plane on its side", &c, delta, p));
  {
    const double ex[3] = {1, 0, 0};
    convex_quat_from_axis_angle(ex, t, B.q);
  }
  B.x[2] = 0.5 * h * cos(t) + r * sin(t) - delta;
  PetscCall(ConvexCollidePlane(&cyl, &B, p0, ez, &c));
  PetscCall(plane_check("cylinder-plane tilted 0.3 rad", &c, delta, NULL));
  PetscCall(ConvexShapeDestroy(&cyl));
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  /* bounds: depth / size, normal, point / size, signed outside distance / depth. Polyhedra:
   * MPR converges on a flat face of A - B (to roundoff). Cylinder: MPR's normal converges
   * slowly on the rims (curved edges), so A-B and B-A stop on different portals: no bound we
   * could derive holds, so the figures are reported only (-1). */
  const double exact[4] = {1e-9, 1e-6, 1e-6, 0}, curved[4] = {-1, -1, -1, -1};
  ConvexShape  cube;

  PetscCall(PetscInitialize(&argc, &argv, NULL, "convex narrow phase test"));
  PetscCall(ConvexShapeCreateCube(a, &cube));
  PetscCall(TestCubeCube(&cube));
  PetscCall(TestCylinderCube(&cube));
  PetscCall(TestPlane(&cube));
  srand(2026);
  PetscCall(TestRandomPairs("cube", &cube, 500, exact));
  PetscCall(ConvexShapeDestroy(&cube));
  PetscCall(ConvexShapeCreateIcosahedron(a, &cube));
  PetscCall(TestRandomPairs("icosahedron", &cube, 500, exact));
  PetscCall(ConvexShapeDestroy(&cube));
  PetscCall(ConvexShapeCreateCylinder(0.4 * a, a, &cube));
  PetscCall(TestRandomPairs("cylinder", &cube, 500, curved));
  PetscCall(ConvexShapeDestroy(&cube));
  PetscCall(PetscFinalize());
  return check_failures ? 1 : 0;
}
