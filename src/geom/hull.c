/* Three-dimensional convex hull of a small point set (up to a few hundred points).
 *
 * Incremental construction (Preparata & Hong 1977; O'Rourke, "Computational Geometry in C",
 * ch. 4): start from the tetrahedron spanned by four extreme points, then add the points one by
 * one; a point p at signed distance > tol from some faces ("visible" faces) replaces them by a
 * cone of triangles joining p to the horizon, the closed loop of edges between visible and
 * non-visible faces. Orientation is kept by building each new triangle (u,v,p) from the
 * horizon edge (u,v) in the order it has in the visible face it leaves.
 *
 * Robustness: tol = 1e-10 times the largest extent of the bounding box. Points within tol of
 * the current hull are treated as inside (so coplanar face points and duplicates are dropped).
 * Coplanar faces of the result are left triangulated. Cost O(n F) with F <= 2n - 4 faces.
 */
#include "geom/convex_impl.h"
#include "geom/quat.h"

typedef struct {
  PetscInt  v[3];
  PetscReal n[3], d; /* outward unit normal and offset: distance of y is n.y - d */
  PetscBool alive;
} HullFace;

typedef struct {
  const PetscReal *x;
  PetscReal        tol;
  HullFace        *face;
  PetscInt         nface, cap;
} HullWork;

/* Distance of point p from the line through a and b. */
static inline PetscReal hull_line_distance(const PetscReal a[3], const PetscReal b[3], const PetscReal p[3])
{
  PetscReal ab[3], ap[3], c[3];
  convex_sub(b, a, ab);
  convex_sub(p, a, ap);
  convex_cross(ab, ap, c);
  return convex_norm(c) / convex_norm(ab);
}

/* Signed distance of p from the plane through a, b, c (positive on the (b-a)x(c-a) side). */
static inline PetscReal hull_plane_distance(const PetscReal a[3], const PetscReal b[3], const PetscReal c[3], const PetscReal p[3])
{
  PetscReal ab[3], ac[3], ap[3], nrm[3];
  convex_sub(b, a, ab);
  convex_sub(c, a, ac);
  convex_sub(p, a, ap);
  convex_cross(ab, ac, nrm);
  return convex_dot(nrm, ap) / convex_norm(nrm);
}

static PetscErrorCode HullAddFace(HullWork *w, PetscInt a, PetscInt b, PetscInt c)
{
  HullFace *F;
  PetscReal ab[3], ac[3], len;

  PetscFunctionBegin;
  if (w->nface == w->cap) {
    w->cap = 2 * w->cap + 16;
    PetscCall(PetscRealloc(sizeof(HullFace) * (size_t)w->cap, &w->face));
  }
  F       = &w->face[w->nface++];
  F->v[0] = a;
  F->v[1] = b;
  F->v[2] = c;
  convex_sub(&w->x[3 * b], &w->x[3 * a], ab);
  convex_sub(&w->x[3 * c], &w->x[3 * a], ac);
  convex_cross(ab, ac, F->n);
  len = convex_norm(F->n);
  for (int k = 0; k < 3; k++) F->n[k] /= len;
  F->d     = convex_dot(F->n, &w->x[3 * a]);
  F->alive = PETSC_TRUE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Four affinely independent extreme points, or the reason why there are none. */
static void HullSeed(PetscInt n, const PetscReal x[], PetscReal tol, PetscInt s[4], ConvexHull *hull)
{
  PetscReal best;

  s[0] = 0;
  for (PetscInt i = 1; i < n; i++)
    if (x[3 * i] < x[3 * s[0]]) s[0] = i;
  best = -1;
  for (PetscInt i = 0; i < n; i++) {
    PetscReal d[3], r;
    convex_sub(&x[3 * i], &x[3 * s[0]], d);
    r = convex_norm(d);
    if (r > best) {
      best = r;
      s[1] = i;
    }
  }
  hull->measure = best;
  if (best <= tol) {
    hull->status = CONVEX_HULL_COINCIDENT;
    return;
  }
  best = -1;
  for (PetscInt i = 0; i < n; i++) {
    PetscReal r = hull_line_distance(&x[3 * s[0]], &x[3 * s[1]], &x[3 * i]);
    if (r > best) {
      best = r;
      s[2] = i;
    }
  }
  hull->measure = best;
  if (best <= tol) {
    hull->status = CONVEX_HULL_COLLINEAR;
    return;
  }
  best = -1;
  for (PetscInt i = 0; i < n; i++) {
    PetscReal r = PetscAbsReal(hull_plane_distance(&x[3 * s[0]], &x[3 * s[1]], &x[3 * s[2]], &x[3 * i]));
    if (r > best) {
      best = r;
      s[3] = i;
    }
  }
  hull->measure = best;
  hull->status  = best <= tol ? CONVEX_HULL_COPLANAR : CONVEX_HULL_OK;
}

/* Is the directed edge (a,b) an edge of face F (in either direction given by dir)? */
static inline PetscBool hull_face_has_edge(const HullFace *F, PetscInt a, PetscInt b)
{
  for (int k = 0; k < 3; k++)
    if (F->v[k] == a && F->v[(k + 1) % 3] == b) return PETSC_TRUE;
  return PETSC_FALSE;
}

/* Add point p: replace the faces it sees by the cone from p to their horizon. */
static PetscErrorCode HullAddPoint(HullWork *w, PetscInt p, PetscInt **vis, PetscInt *viscap)
{
  const PetscReal *y    = &w->x[3 * p];
  PetscInt         nvis = 0, nface0;

  PetscFunctionBegin;
  for (PetscInt i = 0; i < w->nface; i++) {
    HullFace *F = &w->face[i];
    if (!F->alive || convex_dot(F->n, y) - F->d <= w->tol) continue;
    if (nvis == *viscap) {
      *viscap = 2 * *viscap + 16;
      PetscCall(PetscRealloc(sizeof(PetscInt) * (size_t)*viscap, vis));
    }
    (*vis)[nvis++] = i;
  }
  if (!nvis) PetscFunctionReturn(PETSC_SUCCESS);
  nface0 = w->nface;
  for (PetscInt i = 0; i < nvis; i++) {
    for (int k = 0; k < 3; k++) {
      PetscInt  a = w->face[(*vis)[i]].v[k], b = w->face[(*vis)[i]].v[(k + 1) % 3];
      PetscBool inner = PETSC_FALSE;
      for (PetscInt j = 0; j < nvis && !inner; j++) inner = hull_face_has_edge(&w->face[(*vis)[j]], b, a);
      if (!inner) PetscCall(HullAddFace(w, a, b, p));
    }
  }
  for (PetscInt i = 0; i < nvis; i++) w->face[(*vis)[i]].alive = PETSC_FALSE;
  PetscAssert(w->nface > nface0, PETSC_COMM_SELF, PETSC_ERR_PLIB, "hull: a visible region without horizon");
  PetscFunctionReturn(PETSC_SUCCESS);
}

const char *ConvexHullStatusText(ConvexHullStatus s)
{
  switch (s) {
  case CONVEX_HULL_COINCIDENT:
    return "all vertices coincide";
  case CONVEX_HULL_COLLINEAR:
    return "all vertices are collinear";
  case CONVEX_HULL_COPLANAR:
    return "all vertices are coplanar";
  default:
    return "ok";
  }
}

PetscErrorCode ConvexHullBuild(PetscInt n, const PetscReal x[], ConvexHull *hull)
{
  HullWork  w    = {x, 0, NULL, 0, 0};
  PetscInt  s[4] = {0, 0, 0, 0}, *vis = NULL, viscap = 0, k = 0;
  PetscReal lo[3], hi[3], ext = 0;

  PetscFunctionBegin;
  PetscCall(PetscMemzero(hull, sizeof(*hull)));
  PetscCheck(n >= 4, PETSC_COMM_SELF, PETSC_ERR_ARG_SIZ, "a convex hull needs at least 4 points, got %" PetscInt_FMT, n);
  for (int d = 0; d < 3; d++) lo[d] = hi[d] = x[d];
  for (PetscInt i = 1; i < n; i++)
    for (int d = 0; d < 3; d++) {
      lo[d] = PetscMin(lo[d], x[3 * i + d]);
      hi[d] = PetscMax(hi[d], x[3 * i + d]);
    }
  for (int d = 0; d < 3; d++) ext = PetscMax(ext, hi[d] - lo[d]);
  w.tol = hull->tol = 1e-10 * ext;
  HullSeed(n, x, w.tol, s, hull);
  if (hull->status != CONVEX_HULL_OK) PetscFunctionReturn(PETSC_SUCCESS);
  /* orient the seed tetrahedron outwards: s[3] must lie below face (s0,s1,s2) */
  if (hull_plane_distance(&x[3 * s[0]], &x[3 * s[1]], &x[3 * s[2]], &x[3 * s[3]]) > 0) {
    PetscInt t = s[1];
    s[1]       = s[2];
    s[2]       = t;
  }
  PetscCall(HullAddFace(&w, s[0], s[1], s[2]));
  PetscCall(HullAddFace(&w, s[0], s[3], s[1]));
  PetscCall(HullAddFace(&w, s[1], s[3], s[2]));
  PetscCall(HullAddFace(&w, s[2], s[3], s[0]));
  for (PetscInt i = 0; i < n; i++)
    if (i != s[0] && i != s[1] && i != s[2] && i != s[3]) PetscCall(HullAddPoint(&w, i, &vis, &viscap));
  for (PetscInt i = 0; i < w.nface; i++) hull->nf += w.face[i].alive ? 1 : 0;
  PetscCall(PetscMalloc1(3 * hull->nf, &hull->f));
  for (PetscInt i = 0; i < w.nface; i++)
    if (w.face[i].alive)
      for (int d = 0; d < 3; d++) hull->f[k++] = w.face[i].v[d];
  PetscCall(PetscFree(vis));
  PetscCall(PetscFree(w.face));
  PetscFunctionReturn(PETSC_SUCCESS);
}
