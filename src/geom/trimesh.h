/* Triangle meshes (public header): a wall surface a user brings as an STL file.
 *
 * A TriMesh is a soup of triangles, three vertices each (v[9 t + 3 j + k]: triangle t, vertex
 * j, coordinate k), with a unit normal per triangle from the vertex order (right hand:
 * (b - a) x (c - a)). Triangles are two-sided: a sphere is pushed away from the side its centre
 * is on, so the orientation a CAD tool wrote does not matter. STL files (ASCII or binary,
 * detected from the content, not the name) are read on rank 0 and broadcast (stl.c); a
 * truncated file, a count that disagrees with the size, a non-finite coordinate or text that
 * is not STL stops with one line naming the file and the triangle; zero-area triangles
 * (area below 1e-12 of the squared longest edge) and exact duplicates are skipped and counted.
 * TriMeshTransform places a read mesh: scale about the origin, then rotate, then translate.
 *
 * TriClosestPoint is the geometric kernel of sphere-triangle contacts: the point of the
 * triangle nearest to p and the feature it lies on (face, edge or vertex), from which the DEM
 * resolves contacts without counting a shared edge or vertex twice (dem/walls_mesh.c).
 * Units: whatever length unit the caller uses (SI in Sable). */
#pragma once
#include <petscsys.h>

typedef struct {
  PetscInt ntri;       /* triangles kept */
  double  *v;          /* 9 per triangle */
  double  *n;          /* 3 per triangle: unit normal (b - a) x (c - a) / |..| */
  PetscInt ndegen;     /* zero-area triangles skipped by the reader */
  PetscInt nduplicate; /* exact duplicates skipped by the reader */
} TriMesh;

/* Reads an ASCII or binary STL on rank 0 of comm and gives every rank the same mesh. */
PetscErrorCode TriMeshReadSTL(MPI_Comm comm, const char *path, TriMesh *m);
/* x -> R(rot) (scale x) + shift; rot: angles in degrees about x, then y, then z (fixed axes). */
PetscErrorCode TriMeshTransform(TriMesh *m, double scale, const double rot[3], const double shift[3]);
/* An empty mesh with room for ntri triangles (their vertices to be filled, then TriMeshFinish). */
PetscErrorCode TriMeshCreate(PetscInt ntri, TriMesh *m);
/* Computes the normals of m (after vertices were filled or moved). */
PetscErrorCode TriMeshFinish(TriMesh *m);
PetscErrorCode TriMeshDestroy(TriMesh *m);

typedef enum {
  TRI_FACE = 0,
  TRI_EDGE_AB,
  TRI_EDGE_BC,
  TRI_EDGE_CA,
  TRI_VERT_A,
  TRI_VERT_B,
  TRI_VERT_C
} TriFeature;

/* The point q of triangle (a, b, c) nearest to p, and the feature q lies on (Ericson,
 * Real-Time Collision Detection, 5.1.5: Voronoi regions of the vertices, then of the edges,
 * else the face). Returns the feature. */
static inline TriFeature TriClosestPoint(const double *a, const double *b, const double *c, const double *p, double q[3])
{
  double ab[3], ac[3], ap[3], bp[3], cp[3];
  for (int k = 0; k < 3; k++) {
    ab[k] = b[k] - a[k];
    ac[k] = c[k] - a[k];
    ap[k] = p[k] - a[k];
    bp[k] = p[k] - b[k];
    cp[k] = p[k] - c[k];
  }
#define TRI_DOT(u, w) ((u)[0] * (w)[0] + (u)[1] * (w)[1] + (u)[2] * (w)[2])
  const double d1 = TRI_DOT(ab, ap), d2 = TRI_DOT(ac, ap);
  if (d1 <= 0 && d2 <= 0) {
    for (int k = 0; k < 3; k++) q[k] = a[k];
    return TRI_VERT_A;
  }
  const double d3 = TRI_DOT(ab, bp), d4 = TRI_DOT(ac, bp);
  if (d3 >= 0 && d4 <= d3) {
    for (int k = 0; k < 3; k++) q[k] = b[k];
    return TRI_VERT_B;
  }
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double t = d1 / (d1 - d3);
    for (int k = 0; k < 3; k++) q[k] = a[k] + t * ab[k];
    return TRI_EDGE_AB;
  }
  const double d5 = TRI_DOT(ab, cp), d6 = TRI_DOT(ac, cp);
  if (d6 >= 0 && d5 <= d6) {
    for (int k = 0; k < 3; k++) q[k] = c[k];
    return TRI_VERT_C;
  }
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double t = d2 / (d2 - d6);
    for (int k = 0; k < 3; k++) q[k] = a[k] + t * ac[k];
    return TRI_EDGE_CA;
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    for (int k = 0; k < 3; k++) q[k] = b[k] + t * (c[k] - b[k]);
    return TRI_EDGE_BC;
  }
  const double den = 1.0 / (va + vb + vc), s = vb * den, t = vc * den;
  for (int k = 0; k < 3; k++) q[k] = a[k] + s * ab[k] + t * ac[k];
  return TRI_FACE;
#undef TRI_DOT
}
