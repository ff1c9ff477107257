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
 * With support = PETSC_TRUE each feature is only the set of vertices on the body's own support
 * plane (within the length tolerance): the point of CONVEX_POINT_SUPPORT (convex.h).
 * A cylinder's candidate points are 2 x 32 rim samples, starting on each rim at the support
 * point, so a point contact is exact and an end face resting flat gives a 32-gon.
 * Stack-only (no allocation); a shape with more than CONVEX_FEATURE_MAX vertices -> PETSC_FALSE
 * (the caller keeps MPR's point).
 */
#include "geom/convex_impl.h"
#include "geom/quat.h"

#define CONVEX_FEATURE_MAX 256
#define CONVEX_CYL_SAMPLES 32
#define CLIP_MAX           (2 * CONVEX_FEATURE_MAX + 8)

/* cos and sin of 2 pi k / 32, k = 0..31 (rim samples of a cylinder) */
static const PetscReal cyl_cos[CONVEX_CYL_SAMPLES] = {1, 0.98078528040323043, 0.92387953251128674, 0.83146961230254524, 0.70710678118654757, 0.55557023301960229, 0.38268343236508984, 0.19509032201612833, 6.123233995736766e-17, -0.19509032201612819, -0.38268343236508973, -0.55557023301960196, -0.70710678118654746, -0.83146961230254535, -0.92387953251128674, -0.98078528040323043, -1, -0.98078528040323043, -0.92387953251128685, -0.83146961230254546, -0.70710678118654768, -0.55557023301960218, -0.38268343236509034, -0.19509032201612866, -1.8369701987210297e-16, 0.1950903220161283, 0.38268343236509, 0.55557023301960184, 0.70710678118654735, 0.83146961230254524, 0.92387953251128652, 0.98078528040323032};
static const PetscReal cyl_sin[CONVEX_CYL_SAMPLES] = {0, 0.19509032201612825, 0.38268343236508978, 0.55557023301960218, 0.70710678118654746, 0.83146961230254524, 0.92387953251128674, 0.98078528040323043, 1, 0.98078528040323043, 0.92387953251128674, 0.83146961230254546, 0.70710678118654757, 0.55557023301960218, 0.38268343236508989, 0.19509032201612861, 1.2246467991473532e-16, -0.19509032201612836, -0.38268343236508967, -0.55557023301960196, -0.70710678118654746, -0.83146961230254524, -0.92387953251128652, -0.98078528040323032, -1, -0.98078528040323043, -0.92387953251128663, -0.83146961230254546, -0.70710678118654768, -0.55557023301960218, -0.38268343236509039, -0.19509032201612872};

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

/* Where a body's feature faces: dir in world and, for a cylinder, the unit radial direction
 * (ux, uy) of its support point in the body frame. */
typedef struct {
  PetscReal ux, uy;
} Facing;

static inline Facing feature_facing(const ConvexBody *B, const PetscReal dir[3])
{
  Facing    f = {1, 0};
  PetscReal db[3], len;
  if (B->s->kind != CONVEX_CYLINDER) return f;
  convex_mat_tvec(B->R, dir, db);
  len = PetscSqrtReal(db[0] * db[0] + db[1] * db[1]);
  if (len > 0) f.ux = db[0] / len, f.uy = db[1] / len;
  return f;
}

/* i-th candidate point of B in the body frame. */
static inline void feature_point(const ConvexBody *B, Facing f, PetscInt i, PetscReal b[3])
{
  if (B->s->kind == CONVEX_CYLINDER) {
    const PetscInt  j = i % CONVEX_CYL_SAMPLES;
    const PetscReal r = B->s->radius;
    b[0]              = r * (cyl_cos[j] * f.ux - cyl_sin[j] * f.uy);
    b[1]              = r * (cyl_cos[j] * f.uy + cyl_sin[j] * f.ux);
    b[2]              = (i < CONVEX_CYL_SAMPLES ? 0.5 : -0.5) * B->s->height;
  } else {
    for (int k = 0; k < 3; k++) b[k] = B->s->v[3 * i + k];
  }
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
    out.k = 0;
    for (PetscInt i = 0; i < S->k; i++) {
      const PetscReal *p = S->p[i], *q = S->p[(i + 1) % S->k];
      const PetscReal  dp = cross2(a, b, p), dq = cross2(a, b, q);
      if (out.k + 2 > CLIP_MAX) return PETSC_FALSE;
      if (dp >= -eps2) out.p[out.k][0] = p[0], out.p[out.k][1] = p[1], out.k++;
      if ((dp >= -eps2) != (dq >= -eps2)) {
        const PetscReal t = dp / (dp - dq);
        out.p[out.k][0]   = p[0] + t * (q[0] - p[0]);
        out.p[out.k][1]   = p[1] + t * (q[1] - p[1]);
        out.k++;
      }
    }
    for (PetscInt i = 0; i < out.k; i++) S->p[i][0] = out.p[i][0], S->p[i][1] = out.p[i][1]; /* not the whole 8 kB */
    S->k = out.k;
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
    c[0]                = A->p[0][0] + t * d1[0] - 0.5 * off * d1[1];
    c[1]                = A->p[0][1] + t * d1[1] + 0.5 * off * d1[0];
  }
}

/* Candidate points of a body in frame F: the height h along n of each; collect() forms the
 * plane coordinates (u, v) = (b . ub + u0, b . vb + v0) of a body-frame point b. */
typedef struct {
  PetscInt          k;
  PetscReal         h[CONVEX_FEATURE_MAX];
  PetscReal         ub[3], vb[3], u0, v0; /* the plane axes in the body frame, the centre's (u, v) */
  const ConvexBody *B;
  Facing            f;
} Cand;

static PetscBool candidates(const ConvexBody *B, const PetscReal dir[3], const Frame *F, Cand *C)
{
  PetscReal nb[3], off[3], h0;

  C->k = feature_count(B);
  if (C->k > CONVEX_FEATURE_MAX) return PETSC_FALSE;
  C->B = B;
  C->f = feature_facing(B, dir);
  convex_mat_tvec(B->R, F->n, nb); /* project in the body frame: h = b.(R^T n) + (x - o).n */
  convex_mat_tvec(B->R, F->t1, C->ub);
  convex_mat_tvec(B->R, F->t2, C->vb);
  convex_sub(B->x, F->o, off);
  h0 = convex_dot(off, F->n), C->u0 = convex_dot(off, F->t1), C->v0 = convex_dot(off, F->t2);
  if (B->s->kind == CONVEX_CYLINDER)
    for (PetscInt i = 0; i < C->k; i++) {
      PetscReal b[3];
      feature_point(B, C->f, i, b);
      C->h[i] = h0 + convex_dot(b, nb);
    }
  else
    for (PetscInt i = 0; i < C->k; i++) C->h[i] = h0 + convex_dot(B->s->v + 3 * i, nb);
  return PETSC_TRUE;
}

/* The projected candidates with height in [lo, hi]. Every candidate is projected and written
 * at the next free place, which advances only for those kept: no branch on the heights, whose
 * outcome is unpredictable (a few of a polyhedron's vertices or a cylinder's 64 rim samples
 * are kept). */
static void collect(const Cand *C, const Frame *F, PetscReal lo, PetscReal hi, Poly2 *P)
{
  const PetscReal l = lo - F->eps, h = hi + F->eps;
  PetscInt        k = 0;
  for (PetscInt i = 0; i < C->k; i++) {
    PetscReal b[3];
    feature_point(C->B, C->f, i, b);
    P->p[k][0] = C->u0 + convex_dot(b, C->ub), P->p[k][1] = C->v0 + convex_dot(b, C->vb);
    k += (C->h[i] >= l) & (C->h[i] <= h);
  }
  P->k = k;
}

/* Whether the 2-D point c lies on P (a hull: a point, a segment or a counter-clockwise polygon)
 * to the tolerances. */
static PetscBool inside2(const Poly2 *P, const PetscReal c[2], PetscReal eps, PetscReal eps2)
{
  if (P->k == 1) return (PetscBool)(PetscSqr(c[0] - P->p[0][0]) + PetscSqr(c[1] - P->p[0][1]) <= eps * eps);
  if (P->k == 2) {
    const PetscReal d[2] = {P->p[1][0] - P->p[0][0], P->p[1][1] - P->p[0][1]}, l2 = d[0] * d[0] + d[1] * d[1];
    PetscReal       t = l2 > 0 ? ((c[0] - P->p[0][0]) * d[0] + (c[1] - P->p[0][1]) * d[1]) / l2 : 0;
    t                 = PetscMax(0, PetscMin(1, t));
    return (PetscBool)(PetscSqr(c[0] - P->p[0][0] - t * d[0]) + PetscSqr(c[1] - P->p[0][1] - t * d[1]) <= eps * eps);
  }
  for (PetscInt i = 0; i < P->k; i++)
    if (cross2(P->p[i], P->p[(i + 1) % P->k], c) < -eps2) return PETSC_FALSE;
  return PETSC_TRUE;
}

/* The 2-D contact point c of the features PA and PB (hulled here). check: only a point that lies
 * on both features is accepted (a single vertex or a segment crossing can miss the other feature
 * when the normal is not the exact minimum-penetration one). */
static PetscBool features_point(Poly2 *PA, Poly2 *PB, PetscReal eps, PetscReal eps2, PetscBool check, PetscReal c[2])
{
  if (check || (PA->k > 1 && PB->k > 1)) { /* else a single vertex on one side is the point (vertex-face) */
    hull2(PA, eps, eps2);
    hull2(PB, eps, eps2);
  }
  if (PA->k == 1) {
    c[0] = PA->p[0][0], c[1] = PA->p[0][1];
    return (PetscBool)(!check || inside2(PB, c, eps, eps2));
  }
  if (PB->k == 1) {
    c[0] = PB->p[0][0], c[1] = PB->p[0][1];
    return (PetscBool)(!check || inside2(PA, c, eps, eps2));
  }
  if (PA->k == 2 && PB->k == 2) {
    segments2(PA, PB, eps, c);
    return (PetscBool)(!check || (inside2(PA, c, eps, eps2) && inside2(PB, c, eps, eps2)));
  }
  Poly2 *S = PA->k >= PB->k ? PB : PA, *C = PA->k >= PB->k ? PA : PB;
  if (!clip2(S, C, eps2)) return PETSC_FALSE;
  centroid2(S, eps2, c);
  return PETSC_TRUE;
}

PetscBool ConvexFeaturePoint(const ConvexBody *A, const ConvexBody *B, const PetscReal n[3], PetscReal depth, PetscBool support, PetscReal point[3])
{
  Poly2           PA, PB;
  Cand            CA, CB;
  Frame           F;
  const PetscReal mn[3] = {-n[0], -n[1], -n[2]}, e[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  PetscReal       hA, hB, c[2] = {0, 0}, eps2, il;
  int             ax = 0;

  for (int k = 1; k < 3; k++) ax = PetscAbsReal(n[k]) < PetscAbsReal(n[ax]) ? k : ax;
  for (int k = 0; k < 3; k++) F.o[k] = A->x[k], F.n[k] = n[k];
  convex_cross(n, e[ax], F.t1);
  il = 1 / convex_norm(F.t1);
  for (int k = 0; k < 3; k++) F.t1[k] *= il;
  convex_cross(n, F.t1, F.t2);
  F.eps = 1e-10 * (A->s->bounding_radius + B->s->bounding_radius);
  eps2  = F.eps * (A->s->bounding_radius + B->s->bounding_radius);
  if (!candidates(A, n, &F, &CA) || !candidates(B, mn, &F, &CB)) return PETSC_FALSE;
  hA = -PETSC_MAX_REAL, hB = PETSC_MAX_REAL;
  for (PetscInt i = 0; i < CA.k; i++) hA = PetscMax(hA, CA.h[i]);
  for (PetscInt i = 0; i < CB.k; i++) hB = PetscMin(hB, CB.h[i]);
  /* n is a supporting normal of A - B only if the slab is as thick as the overlap; else MPR
   * stopped on a portal edge (its direction is then not a face normal) and the slab features
   * are meaningless. 1% leaves room for the slower convergence of the normal on curved
   * surfaces (cylinder). */
  if (hA - hB > 1.01 * depth + F.eps) return PETSC_FALSE;
  PetscBool found = PETSC_FALSE;
  if (support) { /* the vertices on each body's own support plane; the patch if they miss */
    collect(&CA, &F, hA, hA, &PA);
    collect(&CB, &F, hB, hB, &PB);
    found = (PetscBool)(PA.k && PB.k && features_point(&PA, &PB, F.eps, eps2, PETSC_TRUE, c));
  }
  if (!found) {
    collect(&CA, &F, hB, hA, &PA);
    collect(&CB, &F, hB, hA, &PB);
    if (!PA.k || !PB.k || !features_point(&PA, &PB, F.eps, eps2, PETSC_FALSE, c)) return PETSC_FALSE;
  }
  for (int k = 0; k < 3; k++) point[k] = F.o[k] + c[0] * F.t1[k] + c[1] * F.t2[k] + 0.5 * (hA + hB) * F.n[k];
  return PETSC_TRUE;
}
