/* Convex shape geometry: hull, exact mass properties, principal frame, built-in shapes.
 *
 * Mass properties per unit density by the divergence theorem: the solid is the union of the
 * signed tetrahedra (r, a, b, c) over the outward hull triangles (a,b,c), r a reference point.
 * With the vertices taken relative to r and J = det[a b c] (six times the signed volume),
 *   V       = sum J/6,
 *   int x_i = sum J/24 (a_i + b_i + c_i),
 *   int x_i x_j = sum J/120 [ sum_k p_k,i p_k,j + (sum_k p_k,i)(sum_k p_k,j) ],  p in {a,b,c}
 * (Tonon, J. Math. Stat. 1 (2005) 8-11; Eberly, "Polyhedral mass properties", 2002). A first
 * pass about the vertex mean gives the centre of mass c; a second pass about c gives the
 * covariance C without cancellation, and the inertia tensor is I = tr(C) E - C.
 * I is diagonalised by cyclic Jacobi rotations (Golub & Van Loan §8.5); eigenvalues are
 * sorted ascending and the eigenvector matrix Q is made proper (det +1). Body-frame vertices
 * are Q^T (x - c). Cylinder (radius r, height h, axis z): V = pi r^2 h,
 * I_xx = I_yy = V (3 r^2 + h^2)/12, I_zz = V r^2/2.
 */
#include "geom/convex_impl.h"
#include "geom/quat.h"

/* Volume, first moment and covariance of the hull about ref (see header comment). */
static void poly_moments(const PetscReal x[], PetscInt nf, const PetscInt f[], const PetscReal ref[3], PetscReal *vol, PetscReal m1[3], PetscReal C[9])
{
  *vol = 0;
  for (int i = 0; i < 3; i++) m1[i] = 0;
  for (int i = 0; i < 9; i++) C[i] = 0;
  for (PetscInt t = 0; t < nf; t++) {
    PetscReal p[3][3], s[3], bc[3], J;
    for (int k = 0; k < 3; k++) convex_sub(&x[3 * f[3 * t + k]], ref, p[k]);
    convex_cross(p[1], p[2], bc);
    J = convex_dot(p[0], bc);
    *vol += J / 6;
    for (int i = 0; i < 3; i++) {
      s[i] = p[0][i] + p[1][i] + p[2][i];
      m1[i] += J / 24 * s[i];
    }
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) C[3 * i + j] += J / 120 * (p[0][i] * p[0][j] + p[1][i] * p[1][j] + p[2][i] * p[2][j] + s[i] * s[j]);
  }
}

/* Jacobi eigen-decomposition of a symmetric 3x3 A (destroyed): A = Q diag(lam) Q^T, lam
 * ascending, det Q = +1. Off-diagonal terms below 1e-14 of the trace count as zero, so a
 * (nearly) isotropic tensor keeps the input axes instead of rotating by roundoff noise. */
static void convex_jacobi3(PetscReal A[9], PetscReal lam[3], PetscReal Q[9])
{
  const PetscReal tiny = 1e-14 * (PetscAbsReal(A[0]) + PetscAbsReal(A[4]) + PetscAbsReal(A[8]));
  const int       P[3] = {0, 0, 1}, R[3] = {1, 2, 2};

  for (int i = 0; i < 9; i++) Q[i] = (i % 4 == 0) ? 1 : 0;
  for (int sweep = 0; sweep < 50; sweep++) {
    PetscBool rotated = PETSC_FALSE;
    for (int r = 0; r < 3; r++) {
      const int p = P[r], q = R[r];
      PetscReal apq = A[3 * p + q], theta, t, c, s;
      if (PetscAbsReal(apq) <= tiny) continue;
      rotated = PETSC_TRUE;
      theta   = (A[3 * q + q] - A[3 * p + p]) / (2 * apq);
      t       = (theta >= 0 ? 1 : -1) / (PetscAbsReal(theta) + PetscSqrtReal(theta * theta + 1));
      c       = 1 / PetscSqrtReal(t * t + 1);
      s       = t * c;
      for (int k = 0; k < 3; k++) { /* A <- A G (columns p, q) */
        PetscReal akp = A[3 * k + p], akq = A[3 * k + q];
        A[3 * k + p] = c * akp - s * akq;
        A[3 * k + q] = s * akp + c * akq;
      }
      for (int k = 0; k < 3; k++) { /* A <- G^T A (rows p, q) */
        PetscReal apk = A[3 * p + k], aqk = A[3 * q + k];
        A[3 * p + k] = c * apk - s * aqk;
        A[3 * q + k] = s * apk + c * aqk;
      }
      for (int k = 0; k < 3; k++) { /* Q <- Q G */
        PetscReal qkp = Q[3 * k + p], qkq = Q[3 * k + q];
        Q[3 * k + p] = c * qkp - s * qkq;
        Q[3 * k + q] = s * qkp + c * qkq;
      }
    }
    if (!rotated) break;
  }
  for (int i = 0; i < 3; i++) lam[i] = A[4 * i];
  for (int i = 0; i < 2; i++) /* selection sort of the three pairs, ascending */
    for (int j = i + 1; j < 3; j++)
      if (lam[j] < lam[i]) {
        PetscReal t = lam[i];
        lam[i]      = lam[j];
        lam[j]      = t;
        for (int k = 0; k < 3; k++) {
          t            = Q[3 * k + i];
          Q[3 * k + i] = Q[3 * k + j];
          Q[3 * k + j] = t;
        }
      }
  {
    PetscReal c0[3] = {Q[0], Q[3], Q[6]}, c1[3] = {Q[1], Q[4], Q[7]}, c2[3] = {Q[2], Q[5], Q[8]}, x[3];
    convex_cross(c0, c1, x);
    if (convex_dot(x, c2) < 0)
      for (int k = 0; k < 3; k++) Q[3 * k + 2] = -Q[3 * k + 2];
  }
}

/* Keep only hull vertices, compute mass properties, move to the principal frame. */
static PetscErrorCode ShapeFromHull(PetscInt n, const PetscReal xyz[], const ConvexHull *hull, ConvexShape *s)
{
  PetscInt *map;
  PetscReal ref[3] = {0, 0, 0}, m1[3], C[9], inert[9], vol, tr, Q[9];

  PetscFunctionBegin;
  PetscCall(PetscMalloc1(n, &map));
  for (PetscInt i = 0; i < n; i++) map[i] = -1;
  for (PetscInt t = 0; t < 3 * hull->nf; t++) map[hull->f[t]] = 0;
  s->nv = 0;
  for (PetscInt i = 0; i < n; i++)
    if (map[i] == 0) map[i] = s->nv++;
  s->nf = hull->nf;
  PetscCall(PetscMalloc1(3 * s->nv, &s->v));
  PetscCall(PetscMalloc1(3 * s->nf, &s->f));
  for (PetscInt i = 0; i < n; i++)
    if (map[i] >= 0)
      for (int d = 0; d < 3; d++) s->v[3 * map[i] + d] = xyz[3 * i + d];
  for (PetscInt t = 0; t < 3 * s->nf; t++) s->f[t] = map[hull->f[t]];
  PetscCall(PetscFree(map));

  for (PetscInt i = 0; i < s->nv; i++)
    for (int d = 0; d < 3; d++) ref[d] += s->v[3 * i + d] / s->nv;
  poly_moments(s->v, s->nf, s->f, ref, &vol, m1, C);
  for (int d = 0; d < 3; d++) s->com_input[d] = ref[d] + m1[d] / vol;
  poly_moments(s->v, s->nf, s->f, s->com_input, &s->volume, m1, C);
  tr = C[0] + C[4] + C[8];
  for (int i = 0; i < 9; i++) inert[i] = (i % 4 == 0 ? tr : 0) - C[i];
  convex_jacobi3(inert, s->inertia, Q);
  for (int i = 0; i < 9; i++) s->rot_input[i] = Q[i];
  s->bounding_radius = 0;
  for (PetscInt i = 0; i < s->nv; i++) {
    PetscReal d[3];
    convex_sub(&s->v[3 * i], s->com_input, d);
    convex_mat_tvec(Q, d, &s->v[3 * i]);
    s->bounding_radius = PetscMax(s->bounding_radius, convex_norm(&s->v[3 * i]));
  }
  s->d_eq = PetscCbrtReal(6 * s->volume / PETSC_PI);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ConvexShapeCreateFromVertices(PetscInt n, const PetscReal xyz[], ConvexShape *shape)
{
  ConvexHull hull;

  PetscFunctionBegin;
  PetscCall(PetscMemzero(shape, sizeof(*shape)));
  PetscCheck(n >= 4, PETSC_COMM_SELF, PETSC_ERR_ARG_SIZ, "convex polyhedron: %" PetscInt_FMT " vertices given, at least 4 needed", n);
  for (PetscInt i = 0; i < 3 * n; i++) PetscCheck(!PetscIsInfOrNanReal(xyz[i]), PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "convex polyhedron: vertex %" PetscInt_FMT " has a non-finite coordinate %g", i / 3, (double)xyz[i]);
  PetscCall(ConvexHullBuild(n, xyz, &hull));
  PetscCheck(hull.status == CONVEX_HULL_OK, PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG, "convex polyhedron: %s (%" PetscInt_FMT " vertices, largest spread %g <= tolerance %g); a solid needs 4 vertices not in one plane", ConvexHullStatusText(hull.status), n, (double)hull.measure, (double)hull.tol);
  shape->kind = CONVEX_POLYHEDRON;
  PetscCall(ShapeFromHull(n, xyz, &hull, shape));
  PetscCall(PetscFree(hull.f));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ConvexShapeDestroy(ConvexShape *shape)
{
  PetscFunctionBegin;
  if (!shape) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscFree(shape->v));
  PetscCall(PetscFree(shape->f));
  PetscCall(PetscMemzero(shape, sizeof(*shape)));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ConvexShapeView(const ConvexShape *s, PetscViewer viewer)
{
  PetscFunctionBegin;
  if (!viewer) viewer = PETSC_VIEWER_STDOUT_SELF;
  if (s->kind == CONVEX_CYLINDER) PetscCall(PetscViewerASCIIPrintf(viewer, "convex shape: cylinder, radius %g, height %g\n", (double)s->radius, (double)s->height));
  else PetscCall(PetscViewerASCIIPrintf(viewer, "convex shape: polyhedron, %" PetscInt_FMT " vertices, %" PetscInt_FMT " triangles\n", s->nv, s->nf));
  PetscCall(PetscViewerASCIIPrintf(viewer, "  volume %.10g, principal inertia per unit density %.10g %.10g %.10g\n", (double)s->volume, (double)s->inertia[0], (double)s->inertia[1], (double)s->inertia[2]));
  PetscCall(PetscViewerASCIIPrintf(viewer, "  bounding radius %.10g, volume-equivalent diameter %.10g\n", (double)s->bounding_radius, (double)s->d_eq));
  PetscFunctionReturn(PETSC_SUCCESS);
}
