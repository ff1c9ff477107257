/* Separating axes of convex polyhedra (public header of the geometry library).
 *
 * Two convex polyhedra are apart exactly when some axis separates their projections, and the
 * face normals of both together with the cross products of an edge direction of each are a
 * complete set of candidates (Gottschalk, Lin & Manocha 1996, OBBTree). A ConvexAxes holds the
 * distinct face normals and edge directions of one polyhedron in its body frame (n and -n count
 * once), built once per shape (sat_axes.c); when the polyhedron is a box it also holds its frame
 * and half extents, for the closed-form test of two boxes (sat_box.c). A cylinder has none.
 * A ConvexSatBody places the axes in the world by the body's rotation matrix (body -> world,
 * row-major, the matrix of its quaternion); the tests take the centre of the second body
 * relative to the first, d = x_j - x_i. Units: those of the shape. */
#pragma once
#include "geom/convex.h"

typedef struct {
  PetscReal *fn; /* distinct face normals, unit, body frame (3 each) */
  PetscInt   nfn;
  PetscReal *en; /* distinct edge directions, unit, body frame (3 each) */
  PetscInt   nen;
  PetscBool  box; /* a box: 8 vertices at +-bh[k] along fn[0..2], a right-handed frame */
  PetscReal  bh[3];
} ConvexAxes;

/* A polyhedron's axes placed in the world by its rotation matrix R (9). */
typedef struct {
  const ConvexAxes *ax;
  const PetscReal  *R;
} ConvexSatBody;

/* The least overlap of a pair found so far, and its axis oriented from body i to body j. */
typedef struct {
  PetscReal depth, n[3];
} ConvexSatMin;

/* Not collective. The axes of shape c (none for a cylinder); free them with ConvexAxesDestroy. */
PetscErrorCode ConvexAxesCreate(const ConvexShape *c, ConvexAxes *ax);
PetscErrorCode ConvexAxesDestroy(ConvexAxes *ax);

/* The separating-axis test of two boxes (ax->box) i and j, j at d from i: PETSC_FALSE with the
 * first separating axis in u, or PETSC_TRUE with the least overlap and its axis (i to j) in m
 * (u = 0). The axes are tried in the order faces of i, faces of j, edge pairs. */
PetscBool ConvexSatBox(const ConvexSatBody *bi, const ConvexSatBody *bj, const PetscReal d[3], ConvexSatMin *m, PetscReal u[3]);
