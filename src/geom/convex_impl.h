/* Private header of the convex-shape module (polyhedron.c, hull.c, narrowphase.c). */
#pragma once
#include "sable.h" /* PETSC_SUCCESS on PETSc 3.18 */
#include "geom/convex.h"

/* Outcome of the hull construction; a degenerate input is reported, not raised, so that the
 * caller can name its source (a file and its line count, or an options value). */
typedef enum { CONVEX_HULL_OK, CONVEX_HULL_COINCIDENT, CONVEX_HULL_COLLINEAR, CONVEX_HULL_COPLANAR } ConvexHullStatus;

typedef struct {
  ConvexHullStatus status;
  PetscReal        measure; /* for a degenerate input: the largest distance found (coincident:
                               from the first point, collinear: from the line, coplanar: from
                               the plane) */
  PetscReal        tol;     /* the absolute tolerance it was compared with */
  PetscInt         nf;      /* number of triangles */
  PetscInt        *f;       /* 3*nf indices into the input points, outward orientation */
} ConvexHull;

/* Convex hull of n points (incremental, O(n^2)); hull->f is allocated when status is OK. */
PetscErrorCode ConvexHullBuild(PetscInt n, const PetscReal x[], ConvexHull *hull);

/* "all vertices are coplanar" and the like, for error messages. */
const char *ConvexHullStatusText(ConvexHullStatus s);

/* Contact point of two overlapping bodies given the contact normal n (unit, A to B) and the
 * depth: the centroid of the intersection of their contact features (feature.c).
 * Returns PETSC_FALSE, leaving point untouched, when n is not a supporting normal of A - B
 * (the support heights along n differ from depth) or the features do not intersect. support:
 * the features are the vertices on the support planes only (CONVEX_POINT_SUPPORT). */
PetscBool ConvexFeaturePoint(const ConvexBody *A, const ConvexBody *B, const PetscReal n[3], PetscReal depth, PetscBool support, PetscReal point[3]);
