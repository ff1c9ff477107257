/* Contact point of two overlapping convex bodies from their contact features.
 *
 * Given the contact normal n (A to B), let h = (y - x_A).n be the height of a point y along n.
 * The overlap lies in the slab  h_B,min <= h <= h_A,max  between B's deepest point and A's.
 * The contact feature of A is the set of its vertices inside that slab (a vertex, an edge or a
 * face for a small overlap), likewise for B. Both are projected onto the plane normal to n;
 * the contact point is the centroid of the intersection of their 2-D convex hulls (polygon
 * clipping, Sutherland & Hodgman 1974), placed at mid-slab height (h_A,max + h_B,min)/2.
 * This gives the exact point for vertex-face, edge-face (middle of the clipped edge),
 * edge-edge (crossing point) and face-face (area centroid of the overlap patch) contacts, where
 * the barycentric point of MPR is biased towards the centres by O(depth).
 * A cylinder's candidate points are 2 x 32 rim samples, starting on each rim at the support
 * point, so a point contact is exact and an end face resting flat gives a 32-gon.
 * Stack-only (no allocation); more than CONVEX_FEATURE_MAX points in a slab -> PETSC_FALSE.
 */
#include "dem/convex_impl.h"
#include "dem/convex_quat.h"

#define CONVEX_FEATURE_MAX 256
#define CONVEX_CYL_SAMPLES 32
#define CLIP_MAX           (2 * CONVEX_FEATURE_MAX + 8)

typedef struct {
  PetscReal p[CLIP_MAX][2];
  PetscInt  k;
} Poly2;

typedef struct {
  PetscReal o[3], n[3], t1[3], t2[3]; /* origin and frame of the projection */
  PetscReal eps;                      /* length tolerance */
} Frame;

static inline PetscInt feature_count(const ConvexBody *B)
{
  return B->s->kind == CONVEX_CYLINDER ? 2 * CONVEX_CYL_SAMPLES : B->s->nv;
}

/* i-th candidate point of B in the world frame; dir is the direction B's feature faces. */
static inline void feature_point(const ConvexBody *B, const PetscReal dir[3], PetscInt i, PetscReal w[3])
{
  PetscReal b[3];
  if (B->s->kind == CONVEX_CYLINDER) {
    PetscReal       db[3], ux, uy, len, phi = 2 * PETSC_PI * (i % CONVEX_CYL_SAMPLES) / CONVEX_CYL_SAMPLES;
    const PetscReal r = B->s->radius;
    convex_mat_tvec(B->R, dir, db);
    len = PetscSqrtReal(db[0] * db[0] + db[1] * db[1]);
    ux  = len > 0 ? db[0] / len : 1;
    uy  = len > 0 ? db[1] / len : 0;
    b[0] = r * (PetscCosReal(phi) * ux - PetscSinReal(phi) * uy);
    b[1] = r * (PetscCosReal(phi) * uy + PetscSinReal(phi) * ux);
    b[2] = (i < CONVEX_CYL_SAMPLES ? 0.5 : -0.5) * B->s->height;
  } else {
    for (int k = 0; k < 3; k++) b[k] = B->s->v[3 * i + k];
  }
  convex_mat_vec(B->R, b, w);
  for (int k = 0; k < 3; k++) w[k] += B->x[k];
}

static inline PetscReal cross2(const PetscReal a[2], const PetscReal b[2], const PetscReal c[2])
{
  return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

/* Convex hull of P in place (Andrew's monotone chain), counter-clockwise, collinear dropped. */
static void hull2(Poly2 *P, PetscReal eps, PetscReal eps2)
{
  PetscReal h[CLIP_MAX][2];
  PetscInt  m = 0, k = P->k;

  for (PetscInt i = 1; i < k; i++) { /* insertion sort by (x, y) */
    PetscReal x = P->p[i][0], y = P->p[i][1];
    PetscInt  j = i - 1;
    for (; j >= 0 && (P->p[j][0] > x || (P->p[j][0] == x && P->p[j][1] > y)); j--) P->p[j + 1][0] = P->p[j][0], P->p[j + 1][1] = P->p[j][1];
    P->p[j + 1][0] = x, P->p[j + 1][1] = y;
  }
  if (k < 3) goto done;
  for (PetscInt pass = 0; pass < 2; pass++) {
    const PetscInt start = m;
    for (PetscInt i = 0; i < k; i++) {
      const PetscReal *q = P->p[pass ? k - 1 - i : i];
      while (m >= start + 2 && cross2(h[m - 2], h[m - 1], q) <= eps2) m--;
      h[m][0] = q[0], h[m][1] = q[1], m++;
    }
    m--; /* the last point of each chain starts the other */
  }
  if (m < 2) m = 2; /* all points (nearly) equal or collinear: keep the two chain ends */
  for (PetscInt i = 0; i < m; i++) P->p[i][0] = h[i][0], P->p[i][1] = h[i][1];
  P->k = m;
done: /* a segment shorter than the tolerance is a point */
  if (P->k == 2 && PetscSqr(P->p[1][0] - P->p[0][0]) + PetscSqr(P->p[1][1] - P->p[0][1]) <= eps * eps) P->k = 1;
}

/* Clip subject S (k >= 1, a segment if k = 2) by convex counter-clockwise C (m >= 3). */
static PetscBool clip2(Poly2 *S, const Poly2 *C, PetscReal eps2)
{
  Poly2 out;
  for (PetscInt e = 0; e < C->k && S->k > 0; e++) {
    const PetscReal *a = C->p[e], *b = C->p[(e + 1) % C->k];
    out.k              = 0;
    for (PetscInt i = 0; i < S->k; i++) {
      const PetscReal *p = S->p[i], *q = S->p[(i + 1) % S->k];
      const PetscReal  dp = cross2(a, b, p), dq = cross2(a, b, q);
      if (out.k + 2 > CLIP_MAX) return PETSC_FALSE;
      if (dp >= -eps2) out.p[out.k][0] = p[0], out.p[out.k][1] = p[1], out.k++;
      if ((dp >= -eps2) != (dq >= -eps2)) {
        const PetscReal t = dp / (dp - dq);
        out.p[out.k][0] = p[0] + t * (q[0] - p[0]);
        out.p[out.k][1] = p[1] + t * (q[1] - p[1]);
        out.k++;
      }
    }
    *S = out;
  }
  return S->k > 0 ? PETSC_TRUE : PETSC_FALSE;
}

/* Area centroid of polygon P, or the middle of its two farthest points if it is degenerate. */
static void centroid2(const Poly2 *P, PetscReal eps2, PetscReal c[2])
{
  PetscReal A = 0, cx = 0, cy = 0, best = -1;
  for (PetscInt i = 1; i + 1 < P->k; i++) {
    const PetscReal t = cross2(P->p[0], P->p[i], P->p[i + 1]);
    A += t;
    cx += t * (P->p[0][0] + P->p[i][0] + P->p[i + 1][0]) / 3;
    cy += t * (P->p[0][1] + P->p[i][1] + P->p[i + 1][1]) / 3;
  }
  if (PetscAbsReal(A) > eps2) {
    c[0] = cx / A, c[1] = cy / A;
    return;
  }
  for (PetscInt i = 0; i < P->k; i++)
    for (PetscInt j = i; j < P->k; j++) {
      const PetscReal d = PetscSqr(P->p[i][0] - P->p[j][0]) + PetscSqr(P->p[i][1] - P->p[j][1]);
      if (d > best) best = d, c[0] = 0.5 * (P->p[i][0] + P->p[j][0]), c[1] = 0.5 * (P->p[i][1] + P->p[j][1]);
    }
}

/* Two segments: their crossing, or the middle of their common part if parallel. */
static void segments2(const Poly2 *A, const Poly2 *B, PetscReal eps, PetscReal c[2])
{
  const PetscReal d1[2] = {A->p[1][0] - A->p[0][0], A->p[1][1] - A->p[0][1]}, d2[2] = {B->p[1][0] - B->p[0][0], B->p[1][1] - B->p[0][1]};
  const PetscReal l1 = PetscSqrtReal(d1[0] * d1[0] + d1[1] * d1[1]), l2 = PetscSqrtReal(d2[0] * d2[0] + d2[1] * d2[1]);
  const PetscReal den = d1[0] * d2[1] - d1[1] * d2[0], w[2] = {B->p[0][0] - A->p[0][0], B->p[0][1] - A->p[0][1]};

  if (PetscAbsReal(den) > eps * (l1 + l2)) {
    PetscReal t = (w[0] * d2[1] - w[1] * d2[0]) / den;
    t           = PetscMax(0, PetscMin(1, t));
    c[0] = A->p[0][0] + t * d1[0], c[1] = A->p[0][1] + t * d1[1];
  } else { /* parallel: overlap interval along d1, halfway between the two lines */
    const PetscReal u0 = (w[0] * d1[0] + w[1] * d1[1]) / (l1 * l1), u1 = u0 + (d2[0] * d1[0] + d2[1] * d1[1]) / (l1 * l1);
    const PetscReal lo = PetscMax(0, PetscMin(u0, u1)), hi = PetscMin(1, PetscMax(u0, u1)), t = 0.5 * (lo + hi);
    const PetscReal off = (w[1] * d1[0] - w[0] * d1[1]) / (l1 * l1); /* B's line offset along the normal of d1 */
    c[0] = A->p[0][0] + t * d1[0] - 0.5 * off * d1[1];
    c[1] = A->p[0][1] + t * d1[1] + 0.5 * off * d1[0];
  }
}

/* Height range of B's candidates along n and the projected points within [lo, hi]. */
static PetscBool collect(const ConvexBody *B, const PetscReal dir[3], const Frame *F, PetscReal lo, PetscReal hi, Poly2 *P)
{
  const PetscInt n = feature_count(B);
  P->k             = 0;
  for (PetscInt i = 0; i < n; i++) {
    PetscReal w[3], r[3], h;
    feature_point(B, dir, i, w);
    convex_sub(w, F->o, r);
    h = convex_dot(r, F->n);
    if (h < lo - F->eps || h > hi + F->eps) continue;
    if (P->k == CONVEX_FEATURE_MAX) return PETSC_FALSE;
    P->p[P->k][0] = convex_dot(r, F->t1), P->p[P->k][1] = convex_dot(r, F->t2), P->k++;
  }
  return P->k > 0 ? PETSC_TRUE : PETSC_FALSE;
}

static PetscReal extreme_height(const ConvexBody *B, const PetscReal dir[3], const Frame *F, PetscReal sign)
{
  PetscReal best = -PETSC_MAX_REAL;
  for (PetscInt i = 0; i < feature_count(B); i++) {
    PetscReal w[3], r[3];
    feature_point(B, dir, i, w);
    convex_sub(w, F->o, r);
    best = PetscMax(best, sign * convex_dot(r, F->n));
  }
  return sign * best;
}

PetscBool ConvexFeaturePoint(const ConvexBody *A, const ConvexBody *B, const PetscReal n[3], PetscReal point[3])
{
  Poly2           PA, PB;
  Frame           F;
  const PetscReal mn[3] = {-n[0], -n[1], -n[2]}, e[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  PetscReal       hA, hB, c[2] = {0, 0}, eps2, len;
  int             ax = 0;

  for (int k = 1; k < 3; k++) ax = PetscAbsReal(n[k]) < PetscAbsReal(n[ax]) ? k : ax;
  for (int k = 0; k < 3; k++) F.o[k] = A->x[k], F.n[k] = n[k];
  convex_cross(n, e[ax], F.t1);
  len = convex_norm(F.t1);
  for (int k = 0; k < 3; k++) F.t1[k] /= len;
  convex_cross(n, F.t1, F.t2);
  F.eps = 1e-10 * (A->s->bounding_radius + B->s->bounding_radius);
  eps2  = F.eps * (A->s->bounding_radius + B->s->bounding_radius);
  hA    = extreme_height(A, n, &F, 1);
  hB    = extreme_height(B, mn, &F, -1);
  if (!collect(A, n, &F, hB, hA, &PA) || !collect(B, mn, &F, hB, hA, &PB)) return PETSC_FALSE;
  hull2(&PA, F.eps, eps2);
  hull2(&PB, F.eps, eps2);
  if (PA.k == 1) c[0] = PA.p[0][0], c[1] = PA.p[0][1];
  else if (PB.k == 1) c[0] = PB.p[0][0], c[1] = PB.p[0][1];
  else if (PA.k == 2 && PB.k == 2) segments2(&PA, &PB, F.eps, c);
  else {
    Poly2 *S = PA.k >= PB.k ? &PB : &PA, *C = PA.k >= PB.k ? &PA : &PB;
    if (!clip2(S, C, eps2)) return PETSC_FALSE;
    centroid2(S, eps2, c);
  }
  for (int k = 0; k < 3; k++) point[k] = F.o[k] + c[0] * F.t1[k] + c[1] * F.t2[k] + 0.5 * (hA + hB) * F.n[k];
  return PETSC_TRUE;
}
