/* Separating-axis test of two boxes in closed form (Gottschalk, Lin & Manocha 1996, OBBTree).
 *
 * A box shape is a polyhedron of 8 vertices whose 3 distinct face normals a_k (body frame) are
 * mutually orthogonal and whose vertices all lie at +-h_k along them (DemShapeBoxFrame, found
 * when the shape table is set up; a cube whose principal frame is arbitrary qualifies too). Its
 * extent along a direction u is then sum_k h_k |a_k . u|, so for the 15 candidate axes of two
 * boxes (3 + 3 face normals, 3 x 3 edge cross products, the set dem_sat of contacts_convex.c
 * scans by vertices) every extent comes from the 9 cosines C_ab = A_a . B_b of their world axes:
 *   face a of i:   r_i = h_a,                         r_j = sum_b g_b |C_ab|
 *   face b of j:   r_i = sum_a h_a |C_ab|,            r_j = g_b
 *   A_a x B_b:     r_i = h_a1 |C_a2b| + h_a2 |C_a1b|,  r_j = g_b1 |C_ab2| + g_b2 |C_ab1|  (/ |A_a x B_b|)
 * with (a, a1, a2) and (b, b1, b2) the three axes of each box. The overlap along an axis is
 * r_i + r_j - |d . axis|. The axes are tried in dem_sat's order (faces of i, faces of j, edge
 * pairs) with its rules: the first separating axis is returned in u, otherwise the least overlap
 * and its axis oriented from i to j (edge pairs with |A_a x B_b|^2 < 1e-12 are skipped: the face
 * axes cover them). About 200 flops against 15 x two 8-vertex scans. */
#include "dem/dem_impl.h"

/* The box frame of a polyhedron: PETSC_TRUE and sh->bh (half extents along sh->fn[0..2]) when it
 * is a box to 1e-12 of its bounding radius. */
PetscBool DemShapeBoxFrame(DemShape *sh)
{
  const ConvexShape *c   = sh->cvx;
  const double       tol = 1e-12 * sh->r;

  sh->box = PETSC_FALSE;
  if (!c || c->kind != CONVEX_POLYHEDRON || c->nv != 8 || sh->nfn != 3) return PETSC_FALSE;
  for (int a = 0; a < 3; a++)
    for (int b = a + 1; b < 3; b++)
      if (PetscAbsReal(dem_dot(sh->fn + 3 * a, sh->fn + 3 * b)) > 1e-12) return PETSC_FALSE;
  for (int k = 0; k < 3; k++) {
    sh->bh[k] = 0;
    for (PetscInt v = 0; v < 8; v++) sh->bh[k] = PetscMax(sh->bh[k], PetscAbsReal(dem_dot(c->v + 3 * v, sh->fn + 3 * k)));
    for (PetscInt v = 0; v < 8; v++)
      if (PetscAbsReal(PetscAbsReal(dem_dot(c->v + 3 * v, sh->fn + 3 * k)) - sh->bh[k]) > tol) return PETSC_FALSE;
  }
  sh->box = PETSC_TRUE;
  return PETSC_TRUE;
}

/* One axis (world, |axis|^2 = l2 > 0) with the extents ri + rj of its unit version times its
 * length: as dem_sat_axis, PETSC_TRUE when it separates (u = the unit axis). The square root is
 * taken only for a separating axis or a new least overlap. */
static inline PetscBool dem_box_axis(const double axis[3], double l2, double rij, const double d[3], DemSatMin *m, double u[3])
{
  const double du = dem_dot(d, axis), s = du >= 0 ? 1.0 : -1.0, ov = rij - s * du;
  if (ov < 0) { /* apart along it */
    const double il = 1 / sqrt(l2);
    for (int k = 0; k < 3; k++) u[k] = axis[k] * il;
    return PETSC_TRUE;
  }
  if (ov * ov < m->depth * m->depth * l2) { /* the overlap ov / |axis| is the least so far */
    const double il = 1 / sqrt(l2);
    m->depth        = ov * il;
    for (int k = 0; k < 3; k++) m->n[k] = s * axis[k] * il;
  }
  return PETSC_FALSE;
}

/* The separating-axis test of two boxes i (at the origin) and j (at d): PETSC_FALSE with the
 * first separating axis in u, or PETSC_TRUE with the least overlap and its axis in m (u = 0). */
PetscBool DemSatBox(const DemBody *bi, const DemBody *bj, const double d[3], DemSatMin *m, double u[3])
{
  const DemShape *si = bi->s, *sj = bj->s;
  const double   *Ri = bi->R, *Rj = bj->R, *h = si->bh, *g = sj->bh;
  double          A[3][3], B[3][3], C[3][3], aC[3][3];
  m->depth = 1e150; /* its square stays finite */

  for (int a = 0; a < 3; a++) { /* world axes: A_a = Ri fn_a, B_b = Rj fn_b */
    const double *fa = si->fn + 3 * a, *fb = sj->fn + 3 * a;
    for (int k = 0; k < 3; k++) {
      A[a][k] = Ri[3 * k] * fa[0] + Ri[3 * k + 1] * fa[1] + Ri[3 * k + 2] * fa[2];
      B[a][k] = Rj[3 * k] * fb[0] + Rj[3 * k + 1] * fb[1] + Rj[3 * k + 2] * fb[2];
    }
  }
  for (int a = 0; a < 3; a++)
    for (int b = 0; b < 3; b++) {
      C[a][b]  = dem_dot(A[a], B[b]);
      aC[a][b] = PetscAbsReal(C[a][b]);
    }
  for (int a = 0; a < 3; a++)
    if (dem_box_axis(A[a], 1, h[a] + g[0] * aC[a][0] + g[1] * aC[a][1] + g[2] * aC[a][2], d, m, u)) return PETSC_FALSE;
  for (int b = 0; b < 3; b++)
    if (dem_box_axis(B[b], 1, h[0] * aC[0][b] + h[1] * aC[1][b] + h[2] * aC[2][b] + g[b], d, m, u)) return PETSC_FALSE;
  for (int a = 0; a < 3; a++) {
    const int a1 = (a + 1) % 3, a2 = (a + 2) % 3;
    for (int b = 0; b < 3; b++) {
      const int    b1 = (b + 1) % 3, b2 = (b + 2) % 3;
      const double l2 = 1 - C[a][b] * C[a][b];
      double       L[3];
      if (l2 < 1e-12) continue; /* parallel edges: the face axes cover them */
      dem_cross(A[a], B[b], L);
      const double rij = h[a1] * aC[a2][b] + h[a2] * aC[a1][b] + g[b1] * aC[a][b2] + g[b2] * aC[a][b1];
      if (dem_box_axis(L, dem_dot(L, L), rij, d, m, u)) return PETSC_FALSE;
    }
  }
  u[0] = u[1] = u[2] = 0;
  return PETSC_TRUE;
}
