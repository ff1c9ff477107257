/* Narrow phase for convex shapes: shape-shape through libccd, shape-plane in closed form.
 *
 * Shape-shape: the Minkowski Portal Refinement of libccd (Snethen, "XenoCollide", Game
 * Programming Gems 7, 2008) on the support functions
 *   s_K(d) = x + R s_body(R^T d),  s_body = argmax_{v in vertices} v.d  (polyhedron),
 *   s_body = (r d_xy/|d_xy|, sign(d_z) h/2)                              (cylinder, axis z).
 * MPR searches the Minkowski difference A - B along the ray from x_A - x_B to the origin: the
 * depth and normal it returns are those of the portal face it converges to (exact for a
 * face-face, edge-face or vertex-face contact hit by that ray), not the minimum translation in
 * general. The portal tolerance is 1e-10 of the sum of the bounding radii (libccd's default,
 * 1e-4, is absolute). libccd's direction points from A to B. Its position (a barycentric mix
 * of support points that is biased towards the centres by O(depth)) is replaced by the
 * centroid of the contact features (feature.c) and kept only if that fails.
 *
 * Shape-plane, plane through p0 with unit normal n (wall below, domain above): the depth of
 * a body point y is (p0 - y).n. A polyhedron's depth is the maximum over its vertices; its
 * contact point lies under the depth-weighted mean of the penetrating vertices (a face resting
 * flat gives the face centre, an edge its midpoint; the point moves continuously as the body
 * tilts), at mid-overlap height, depth/2 below the plane. A cylinder uses the same rule on its
 * two rim circles in closed form (see cylinder_rim_weight).
 */
#include <ccd/ccd.h>
#include "geom/convex_impl.h"
#include "geom/quat.h"

const char *const ConvexPointModels[] = {"patch", "support", "ConvexPointModel", "CONVEX_POINT_", NULL};

/* Body-frame support point of a shape in direction d (body frame). */
static inline void convex_support_body(const ConvexShape *s, const PetscReal d[3], PetscReal out[3])
{
  if (s->kind == CONVEX_CYLINDER) {
    const PetscReal rxy = PetscSqrtReal(d[0] * d[0] + d[1] * d[1]);
    out[0]              = rxy > 0 ? s->radius * d[0] / rxy : 0;
    out[1]              = rxy > 0 ? s->radius * d[1] / rxy : 0;
    out[2]              = d[2] >= 0 ? 0.5 * s->height : -0.5 * s->height;
  } else {
    const PetscReal *v    = s->v;
    PetscInt         best = 0;
    PetscReal        bd   = v[0] * d[0] + v[1] * d[1] + v[2] * d[2];
    for (PetscInt i = 1; i < s->nv; i++) {
      const PetscReal t = v[3 * i] * d[0] + v[3 * i + 1] * d[1] + v[3 * i + 2] * d[2];
      if (t > bd) {
        bd   = t;
        best = i;
      }
    }
    out[0] = v[3 * best];
    out[1] = v[3 * best + 1];
    out[2] = v[3 * best + 2];
  }
}

static void convex_ccd_support(const void *obj, const ccd_vec3_t *dir, ccd_vec3_t *out)
{
  const ConvexBody *b    = (const ConvexBody *)obj;
  PetscReal         d[3] = {dir->v[0], dir->v[1], dir->v[2]}, db[3], sb[3], sw[3];

  convex_mat_tvec(b->R, d, db);
  convex_support_body(b->s, db, sb);
  convex_mat_vec(b->R, sb, sw);
  for (int k = 0; k < 3; k++) out->v[k] = sw[k] + b->x[k];
}

static void convex_ccd_center(const void *obj, ccd_vec3_t *c)
{
  const ConvexBody *b = (const ConvexBody *)obj;
  for (int k = 0; k < 3; k++) c->v[k] = b->x[k];
}

static void convex_body_set(const ConvexShape *s, const ConvexPose *p, ConvexBody *b)
{
  b->s = s;
  for (int k = 0; k < 3; k++) b->x[k] = p->x[k];
  convex_quat_to_matrix(p->q, b->R);
}

PetscErrorCode ConvexCollide(const ConvexShape *a, const ConvexPose *pa, const ConvexShape *b, const ConvexPose *pb, ConvexContact *c)
{
  PetscFunctionBegin;
  PetscCall(ConvexCollideWith(a, pa, b, pb, CONVEX_POINT_PATCH, c));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ConvexCollideWith(const ConvexShape *a, const ConvexPose *pa, const ConvexShape *b, const ConvexPose *pb, ConvexPointModel model, ConvexContact *c)
{
  ConvexBody A, B;
  ccd_t      ccd;
  ccd_real_t depth;
  ccd_vec3_t dir, pos;
  PetscReal  dx[3], reach = a->bounding_radius + b->bounding_radius;

  PetscFunctionBegin;
  PetscCall(PetscMemzero(c, sizeof(*c)));
  convex_sub(pb->x, pa->x, dx);
  if (convex_dot(dx, dx) >= reach * reach) PetscFunctionReturn(PETSC_SUCCESS);
  convex_body_set(a, pa, &A);
  convex_body_set(b, pb, &B);
  CCD_INIT(&ccd);
  ccd.support1       = convex_ccd_support;
  ccd.support2       = convex_ccd_support;
  ccd.center1        = convex_ccd_center;
  ccd.center2        = convex_ccd_center;
  ccd.max_iterations = 1000;
  ccd.mpr_tolerance  = 1e-10 * reach;
  if (ccdMPRPenetration(&A, &B, &ccd, &depth, &dir, &pos) != 0 || !(depth > 0)) PetscFunctionReturn(PETSC_SUCCESS);
  c->overlap = PETSC_TRUE;
  c->depth   = depth;
  for (int k = 0; k < 3; k++) {
    c->normal[k] = dir.v[k];
    c->point[k]  = pos.v[k];
  }
  (void)ConvexFeaturePoint(&A, &B, c->normal, c->depth, (PetscBool)(model == CONVEX_POINT_SUPPORT), c->point); /* keeps MPR's point if it fails */
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ConvexContactPoint(const ConvexShape *a, const ConvexPose *pa, const ConvexShape *b, const ConvexPose *pb, const PetscReal n[3], PetscReal depth, ConvexPointModel model, ConvexContact *c, PetscBool *ok)
{
  ConvexBody A, B;

  PetscFunctionBegin;
  convex_body_set(a, pa, &A);
  convex_body_set(b, pb, &B);
  *ok = ConvexBodiesContactPoint(&A, &B, n, depth, model, c);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscBool ConvexBodiesContactPoint(const ConvexBody *A, const ConvexBody *B, const PetscReal n[3], PetscReal depth, ConvexPointModel model, ConvexContact *c)
{
  c->overlap = PETSC_FALSE;
  c->depth   = 0;
  for (int k = 0; k < 3; k++) c->normal[k] = c->point[k] = 0;
  if (!ConvexFeaturePoint(A, B, n, depth, (PetscBool)(model == CONVEX_POINT_SUPPORT), c->point)) return PETSC_FALSE;
  c->overlap = PETSC_TRUE;
  c->depth   = depth;
  for (int k = 0; k < 3; k++) c->normal[k] = n[k];
  return PETSC_TRUE;
}

/* Depth-weighted rim of one end circle: centre e (depth de), radius r, in-plane unit u towards
 * the deepest rim point whose depth is de + r s. With phi the angle from u, the weight is
 * w = max(0, de + r s cos phi); returns W = int w dphi and adds int w y dphi to *acc. */
static inline PetscReal cylinder_rim_weight(const PetscReal e[3], PetscReal de, PetscReal r, PetscReal s, const PetscReal u[3], PetscReal acc[3])
{
  PetscReal cmin, phi0, W, Wc;

  if (r * s <= 1e-14 * r) { /* axis along n: the rim is level */
    W = de > 0 ? 2 * PETSC_PI * de : 0;
    for (int k = 0; k < 3; k++) acc[k] += W * e[k];
    return W;
  }
  cmin = -de / (r * s);
  if (cmin >= 1) return 0;
  phi0 = cmin <= -1 ? PETSC_PI : PetscAcosReal(cmin);
  W    = 2 * (de * phi0 + r * s * PetscSinReal(phi0));
  Wc   = 2 * (de * PetscSinReal(phi0) + r * s * (phi0 / 2 + PetscSinReal(2 * phi0) / 4));
  for (int k = 0; k < 3; k++) acc[k] += W * e[k] + r * Wc * u[k];
  return W;
}

/* Cylinder against the plane: deepest rim depth and the depth-weighted rim centroid. */
static void CylinderPlane(const ConvexShape *s, const ConvexBody *B, const PetscReal p0[3], const PetscReal n[3], PetscReal *depth, PetscReal y[3])
{
  const PetscReal a[3] = {B->R[2], B->R[5], B->R[8]}, an = convex_dot(a, n);
  PetscReal       u[3], sn, acc[3] = {0, 0, 0}, W = 0;

  for (int k = 0; k < 3; k++) u[k] = -(n[k] - an * a[k]);
  sn = convex_norm(u);
  for (int k = 0; k < 3; k++) u[k] = sn > 0 ? u[k] / sn : 0;
  *depth = -PETSC_MAX_REAL;
  for (int end = -1; end <= 1; end += 2) {
    PetscReal e[3], d[3], de;
    for (int k = 0; k < 3; k++) e[k] = B->x[k] + end * 0.5 * s->height * a[k];
    convex_sub(p0, e, d);
    de     = convex_dot(d, n);
    *depth = PetscMax(*depth, de + s->radius * sn);
    W += cylinder_rim_weight(e, de, s->radius, sn, u, acc);
  }
  for (int k = 0; k < 3; k++) y[k] = W > 0 ? acc[k] / W : 0;
}

/* Polyhedron against the plane: deepest vertex depth and depth-weighted vertex centroid. */
static void PolyhedronPlane(const ConvexShape *s, const ConvexBody *B, const PetscReal p0[3], const PetscReal n[3], PetscReal *depth, PetscReal y[3])
{
  PetscReal W = 0;

  *depth = -PETSC_MAX_REAL;
  for (int k = 0; k < 3; k++) y[k] = 0;
  for (PetscInt i = 0; i < s->nv; i++) {
    PetscReal w[3], d[3], di;
    convex_mat_vec(B->R, &s->v[3 * i], w);
    for (int k = 0; k < 3; k++) w[k] += B->x[k];
    convex_sub(p0, w, d);
    di     = convex_dot(d, n);
    *depth = PetscMax(*depth, di);
    if (di <= 0) continue;
    W += di;
    for (int k = 0; k < 3; k++) y[k] += di * w[k];
  }
  for (int k = 0; k < 3; k++) y[k] = W > 0 ? y[k] / W : 0;
}

PetscErrorCode ConvexCollidePlane(const ConvexShape *a, const ConvexPose *pa, const PetscReal p0[3], const PetscReal n[3], ConvexContact *c)
{
  ConvexBody B;
  PetscReal  d[3], depth, y[3], h;

  PetscFunctionBegin;
  PetscCall(PetscMemzero(c, sizeof(*c)));
  PetscAssert(PetscAbsReal(convex_norm(n) - 1) < 1e-10, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "plane normal must be a unit vector, |n| = %g", (double)convex_norm(n));
  convex_sub(p0, pa->x, d);
  if (convex_dot(d, n) <= -a->bounding_radius) PetscFunctionReturn(PETSC_SUCCESS);
  convex_body_set(a, pa, &B);
  if (a->kind == CONVEX_CYLINDER) CylinderPlane(a, &B, p0, n, &depth, y);
  else PolyhedronPlane(a, &B, p0, n, &depth, y);
  if (!(depth > 0)) PetscFunctionReturn(PETSC_SUCCESS);
  c->overlap = PETSC_TRUE;
  c->depth   = depth;
  convex_sub(y, p0, d);
  h = convex_dot(d, n) + 0.5 * depth; /* y's height above the mid-overlap plane */
  for (int k = 0; k < 3; k++) {
    c->normal[k] = -n[k];
    c->point[k]  = y[k] - h * n[k];
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}
