/* Private header of the geometry library (polyhedron.c, hull.c, narrowphase.c, feature.c,
 * shapes.c, sat_axes.c, sat_box.c). */
#pragma once
#include "sable.h" /* PETSC_SUCCESS on PETSc 3.18 */
#include "geom/convex.h"
#include "geom/sat.h"

/* Outcome of the hull construction; a degenerate input is reported, not raised, so that the
 * caller can name its source (a file and its line count, or an options value). */
typedef enum {
  CONVEX_HULL_OK,
  CONVEX_HULL_COINCIDENT,
  CONVEX_HULL_COLLINEAR,
  CONVEX_HULL_COPLANAR
} ConvexHullStatus;

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

/* The box frame of a polyhedron whose face axes ax->fn are built (sat_box.c, for sat_axes.c):
 * PETSC_TRUE and ax->box, ax->bh when it is a box; ax->fn[6..8] turned to a right-handed frame. */
PetscBool ConvexAxesBoxFrame(const ConvexShape *c, ConvexAxes *ax);
