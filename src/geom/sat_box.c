/* Separating-axis test of two boxes in closed form (Gottschalk, Lin & Manocha 1996, OBBTree).
 *
 * A box shape is a polyhedron of 8 vertices whose 3 distinct face normals a_k (body frame) are
 * mutually orthogonal and whose vertices all lie at +-h_k along them (ConvexAxesBoxFrame, found
 * when the axes of a shape are built; a cube whose principal frame is arbitrary qualifies too).
 * Its extent along a direction u is then sum_k h_k |a_k . u|, so for the 15 candidate axes of
 * two boxes (3 + 3 face normals, 3 x 3 edge cross products, the set a general test scans by
 * vertices) every extent comes from the 9 cosines C_ab = A_a . B_b of their world axes:
 *   face a of i:   r_i = h_a,                         r_j = sum_b g_b |C_ab|
 *   face b of j:   r_i = sum_a h_a |C_ab|,            r_j = g_b
 *   A_a x B_b:     r_i = h_a1 |C_a2b| + h_a2 |C_a1b|,  r_j = g_b1 |C_ab2| + g_b2 |C_ab1|  (/ |A_a x B_b|)
 * with (a, a1, a2) and (b, b1, b2) the three axes of each box. The overlap along an axis is
 * r_i + r_j - |d . axis|. The axes are tried in the order faces of i, faces of j, edge pairs:
 * the first separating axis is returned in u, otherwise the least overlap and its axis oriented
 * from i to j (edge pairs with |A_a x B_b|^2 < 1e-12 are skipped: the face axes cover them).
 * About 200 flops against 15 x two 8-vertex scans; an edge axis is formed only for the answer
 * (ConvexSatBox). */
#include "geom/convex_impl.h"
#include "geom/quat.h"

/* The box frame of polyhedron c with face axes ax->fn: PETSC_TRUE and ax->bh (half extents along
 * ax->fn[0..2]) when it is a box to 1e-12 of its bounding radius; fn[2] is then turned to make
 * fn0 x fn1 = fn2. */
PetscBool ConvexAxesBoxFrame(const ConvexShape *c, ConvexAxes *ax)
{
  const double tol = 1e-12 * c->bounding_radius;

  ax->box = PETSC_FALSE;
  if (c->kind != CONVEX_POLYHEDRON || c->nv != 8 || ax->nfn != 3) return PETSC_FALSE;
  for (int a = 0; a < 3; a++)
    for (int b = a + 1; b < 3; b++)
      if (PetscAbsReal(convex_dot(ax->fn + 3 * a, ax->fn + 3 * b)) > 1e-12) return PETSC_FALSE;
  for (int k = 0; k < 3; k++) {
    ax->bh[k] = 0;
    for (PetscInt v = 0; v < 8; v++) ax->bh[k] = PetscMax(ax->bh[k], PetscAbsReal(convex_dot(c->v + 3 * v, ax->fn + 3 * k)));
    for (PetscInt v = 0; v < 8; v++)
      if (PetscAbsReal(PetscAbsReal(convex_dot(c->v + 3 * v, ax->fn + 3 * k)) - ax->bh[k]) > tol) return PETSC_FALSE;
  }
  double f01[3];
  convex_cross(ax->fn, ax->fn + 3, f01);
  if (convex_dot(f01, ax->fn + 6) < 0) /* a right-handed frame (ConvexSatBox): the sign of an axis is free */
    for (int k = 0; k < 3; k++) ax->fn[6 + k] = -ax->fn[6 + k];
  ax->box = PETSC_TRUE;
  return PETSC_TRUE;
}

/* The world unit axis number ax (0-2 faces of i, 3-5 faces of j, 6 + 3a + b the edge pair (a, b)
 * of squared length l2). */
static inline void convex_box_unit(double A[3][3], double B[3][3], int ax, double l2, double a[3])
{
  if (ax < 3)
    for (int k = 0; k < 3; k++) a[k] = A[ax][k];
  else if (ax < 6)
    for (int k = 0; k < 3; k++) a[k] = B[ax - 3][k];
  else {
    const double il = 1 / sqrt(l2);
    convex_cross(A[(ax - 6) / 3], B[(ax - 6) % 3], a);
    for (int k = 0; k < 3; k++) a[k] *= il;
  }
}

/* The separating-axis test of two boxes i (at the origin) and j (at d): PETSC_FALSE with the
 * first separating axis in u, or PETSC_TRUE with the least overlap and its axis in m (u = 0).
 * The products with d of the edge axes come from those of i's axes, t_a = A_a . d:
 *   A_a x B_b = sum_k C_kb A_a x A_k = C_a1b A_a2 - C_a2b A_a1
 * (the box frame is right-handed, ConvexAxesBoxFrame). All 15 overlaps (times the axis length) are
 * formed first, without branches; the first negative one separates, else the least of
 * ov^2 / l2; the world axis, and the square root of its length, are formed once, for the
 * answer. */
PetscBool ConvexSatBox(const ConvexSatBody *bi, const ConvexSatBody *bj, const PetscReal d[3], ConvexSatMin *m, PetscReal u[3])
{
  static const int  nx1[3] = {1, 2, 0}, nx2[3] = {2, 0, 1};
  const ConvexAxes *si = bi->ax, *sj = bj->ax;
  const double     *Ri = bi->R, *Rj = bj->R, *h = si->bh, *g = sj->bh;
  double            A[3][3], B[3][3], C[3][3], aC[3][3], t[3], w[3], ov[15], l2[15], du[15], key[15];
  int               best = 0;

  for (int a = 0; a < 3; a++) { /* world axes: A_a = Ri fn_a, B_b = Rj fn_b */
    const double *fa = si->fn + 3 * a, *fb = sj->fn + 3 * a;
    for (int k = 0; k < 3; k++) {
      A[a][k] = Ri[3 * k] * fa[0] + Ri[3 * k + 1] * fa[1] + Ri[3 * k + 2] * fa[2];
      B[a][k] = Rj[3 * k] * fb[0] + Rj[3 * k + 1] * fb[1] + Rj[3 * k + 2] * fb[2];
    }
  }
  for (int a = 0; a < 3; a++) {
    t[a] = convex_dot(A[a], d);
    w[a] = convex_dot(B[a], d);
    for (int c = 0; c < 3; c++) {
      C[a][c]  = convex_dot(A[a], B[c]);
      aC[a][c] = PetscAbsReal(C[a][c]);
    }
  }
  for (int a = 0; a < 3; a++) {
    du[a]     = t[a];
    du[3 + a] = w[a];
    l2[a] = l2[3 + a] = 1;
    ov[a]             = h[a] + g[0] * aC[a][0] + g[1] * aC[a][1] + g[2] * aC[a][2] - PetscAbsReal(t[a]);
    ov[3 + a]         = h[0] * aC[0][a] + h[1] * aC[1][a] + h[2] * aC[2][a] + g[a] - PetscAbsReal(w[a]);
  }
  for (int a = 0; a < 3; a++) {
    const int a1 = nx1[a], a2 = nx2[a];
    for (int c = 0; c < 3; c++) {
      const int    c1 = nx1[c], c2 = nx2[c], k = 6 + 3 * a + c;
      const double q   = C[a1][c] * C[a1][c] + C[a2][c] * C[a2][c]; /* |A_a x B_c|^2, not 1 - C_ac^2: no cancellation */
      const double rij = h[a1] * aC[a2][c] + h[a2] * aC[a1][c] + g[c1] * aC[a][c2] + g[c2] * aC[a][c1];
      du[k]            = C[a1][c] * t[a2] - C[a2][c] * t[a1];
      l2[k]            = q < 1e-12 ? 1 : q; /* parallel edges: the face axes cover them (never chosen) */
      ov[k]            = q < 1e-12 ? 1e150 : rij - PetscAbsReal(du[k]);
    }
  }
  for (int k = 0; k < 15; k++)
    if (ov[k] < 0) { /* apart along it */
      convex_box_unit(A, B, k, l2[k], u);
      return PETSC_FALSE;
    }
  for (int k = 0; k < 15; k++) key[k] = ov[k] * ov[k] / l2[k];
  for (int k = 1; k < 15; k++) best = key[k] < key[best] ? k : best;
  convex_box_unit(A, B, best, l2[best], m->n);
  m->depth = ov[best] / sqrt(l2[best]);
  if (du[best] < 0)
    for (int k = 0; k < 3; k++) m->n[k] = -m->n[k];
  u[0] = u[1] = u[2] = 0;
  return PETSC_TRUE;
}
