/* The candidate separating axes of a convex polyhedron (sat.h): its distinct face normals, the
 * distinct directions of its true edges, and the box frame when it is a box (sat_box.c).
 * Face normals: one per hull triangle, normalised, n and -n counted once (|n.m| > 1 - 1e-9).
 * True edges: hull triangle edges whose two triangles lie on different faces (the triangulation
 * splits a face by edges that are no edges of the solid); their directions, normalised and
 * counted once the same way. Quadratic in the number of triangles, run once per shape.
 * A cylinder has neither (a test takes its centre line only). Units: those of the shape. */
#include "geom/convex_impl.h"
#include "geom/quat.h"

/* The face axis (index into ax->fn) parallel to the normal of hull triangle t. */
static PetscInt convex_face_axis(const ConvexAxes *ax, const ConvexShape *c, PetscInt t)
{
  const double *a = c->v + 3 * c->f[3 * t], *b = c->v + 3 * c->f[3 * t + 1], *d = c->v + 3 * c->f[3 * t + 2];
  double        e1[3], e2[3], n[3], len, best = -1;
  PetscInt      m = 0;
  for (int k = 0; k < 3; k++) e1[k] = b[k] - a[k], e2[k] = d[k] - a[k];
  convex_cross(e1, e2, n);
  len = sqrt(convex_dot(n, n));
  for (PetscInt k = 0; k < ax->nfn; k++) {
    const double t2 = PetscAbsReal(convex_dot(n, ax->fn + 3 * k)) / len;
    if (t2 > best) best = t2, m = k;
  }
  return m;
}

static PetscErrorCode ConvexAxesFaces(const ConvexShape *c, ConvexAxes *ax)
{
  PetscFunctionBegin;
  PetscCall(PetscMalloc1(3 * c->nf, &ax->fn));
  for (PetscInt t = 0; t < c->nf; t++) {
    const double *a = c->v + 3 * c->f[3 * t], *b = c->v + 3 * c->f[3 * t + 1], *d = c->v + 3 * c->f[3 * t + 2];
    double        e1[3], e2[3], n[3], len;
    PetscBool     dup = PETSC_FALSE;
    for (int k = 0; k < 3; k++) e1[k] = b[k] - a[k], e2[k] = d[k] - a[k];
    convex_cross(e1, e2, n);
    len = sqrt(convex_dot(n, n));
    for (int k = 0; k < 3; k++) n[k] /= len;
    for (PetscInt m = 0; m < ax->nfn && !dup; m++) dup = (PetscBool)(PetscAbsReal(convex_dot(n, ax->fn + 3 * m)) > 1 - 1e-9);
    if (dup) continue;
    for (int k = 0; k < 3; k++) ax->fn[3 * ax->nfn + k] = n[k];
    ax->nfn++;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode ConvexAxesEdges(const ConvexShape *c, ConvexAxes *ax)
{
  PetscFunctionBegin;
  PetscCall(PetscMalloc1(9 * c->nf, &ax->en));
  for (PetscInt t = 0; t < c->nf; t++)
    for (int e = 0; e < 3; e++) {
      const PetscInt a = c->f[3 * t + e], b = c->f[3 * t + (e + 1) % 3];
      PetscInt       o = -1;
      for (PetscInt u = 0; u < c->nf && o < 0; u++) /* the triangle across the edge (b, a) */
        for (int g = 0; g < 3; g++)
          if (c->f[3 * u + g] == b && c->f[3 * u + (g + 1) % 3] == a) o = u;
      if (o < 0 || PetscAbsReal(convex_dot(ax->fn + 3 * convex_face_axis(ax, c, t), ax->fn + 3 * convex_face_axis(ax, c, o))) > 1 - 1e-9) continue;
      double    d[3], len;
      PetscBool dup = PETSC_FALSE;
      for (int k = 0; k < 3; k++) d[k] = c->v[3 * b + k] - c->v[3 * a + k];
      len = sqrt(convex_dot(d, d));
      for (int k = 0; k < 3; k++) d[k] /= len;
      for (PetscInt m = 0; m < ax->nen && !dup; m++) dup = (PetscBool)(PetscAbsReal(convex_dot(d, ax->en + 3 * m)) > 1 - 1e-9);
      if (dup) continue;
      for (int k = 0; k < 3; k++) ax->en[3 * ax->nen + k] = d[k];
      ax->nen++;
    }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ConvexAxesCreate(const ConvexShape *c, ConvexAxes *ax)
{
  PetscFunctionBegin;
  PetscCall(PetscMemzero(ax, sizeof *ax));
  if (c->kind != CONVEX_POLYHEDRON) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(ConvexAxesFaces(c, ax));
  PetscCall(ConvexAxesEdges(c, ax));
  (void)ConvexAxesBoxFrame(c, ax);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ConvexAxesDestroy(ConvexAxes *ax)
{
  PetscFunctionBegin;
  PetscCall(PetscFree(ax->fn));
  PetscCall(PetscFree(ax->en));
  ax->nfn = ax->nen = 0;
  ax->box           = PETSC_FALSE;
  PetscFunctionReturn(PETSC_SUCCESS);
}
