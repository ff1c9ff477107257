/* Convex particle shapes and their narrow-phase contact (public header).
 *
 * A ConvexShape is a "reference particle" in the sense of Grains3D (Rakotonirina & Wachs 2018,
 * Part II §2-3): geometry and mass properties per unit density, stored once per shape type;
 * particles carry only a position (centre of mass) and a unit quaternion q = (w,x,y,z) that
 * rotates body-frame vectors into the world frame. In the body frame the centre of mass is the
 * origin and the axes are the principal axes of inertia, so the inertia tensor is diagonal.
 *
 * Kinds: a convex polyhedron (vertex list + triangulated hull) or a right circular cylinder
 * (axis along body z, analytic support function). Mass properties are exact (divergence
 * theorem on the hull, see polyhedron.c); the narrow phase wraps libccd (narrowphase.c).
 *
 * Conventions for every contact returned here: A is the first body, B the second (a plane
 * wall is always B); normal is the unit vector from A towards B; depth > 0 is the overlap
 * (translating B by depth*normal separates the bodies); point is in the world frame, midway
 * between the two surfaces inside the overlap. Force on A = -F_n normal, on B = +F_n normal.
 * Units: whatever length unit the caller uses (SI in Sable); volume and inertia are per unit
 * density, so mass = rho*volume and J = rho*inertia.
 */
#pragma once
#include <petscsys.h>

typedef enum {
  CONVEX_POLYHEDRON,
  CONVEX_CYLINDER
} ConvexKind;

typedef struct {
  ConvexKind kind;
  PetscInt   nv;              /* number of hull vertices (0 for a cylinder) */
  PetscReal *v;               /* 3*nv body-frame vertex coordinates, principal frame */
  PetscInt   nf;              /* number of hull triangles (0 for a cylinder) */
  PetscInt  *f;               /* 3*nf vertex indices, counter-clockwise seen from outside */
  PetscReal  radius, height;  /* cylinder only; axis along body z */
  PetscReal  volume;          /* V */
  PetscReal  inertia[3];      /* principal moments per unit density, about body x, y, z */
  PetscReal  com_input[3];    /* centre of mass in the frame of the input vertices */
  PetscReal  rot_input[9];    /* row-major R, input-frame vector = R * body-frame vector */
  PetscReal  bounding_radius; /* max distance of the surface from the centre of mass */
  PetscReal  d_eq;            /* volume-equivalent sphere diameter (6V/pi)^(1/3) */
} ConvexShape;

typedef struct {
  PetscReal x[3]; /* world position of the centre of mass */
  PetscReal q[4]; /* unit quaternion (w,x,y,z), body -> world */
} ConvexPose;

/* A shape placed in the world: centre of mass x and rotation matrix R (body -> world, row-major,
 * the matrix of the pose's quaternion). */
typedef struct {
  const ConvexShape *s;
  PetscReal          x[3];
  PetscReal          R[9];
} ConvexBody;

typedef struct {
  PetscBool overlap;   /* PETSC_FALSE: the other fields are zero */
  PetscReal depth;     /* overlap distance along normal, > 0 */
  PetscReal normal[3]; /* unit, from A towards B */
  PetscReal point[3];  /* world contact point, midway inside the overlap */
} ConvexContact;

/* Constructors. Not collective. They fill *shape (which the caller owns) and allocate its
 * arrays; free them with ConvexShapeDestroy. Errors: fewer than 4 vertices, all vertices
 * coincident / collinear / coplanar (relative tolerance 1e-10 of the extent), size <= 0. */
PetscErrorCode ConvexShapeCreateFromVertices(PetscInt n, const PetscReal xyz[], ConvexShape *shape);
PetscErrorCode ConvexShapeCreateFromFile(const char path[], ConvexShape *shape);
PetscErrorCode ConvexShapeCreateCube(PetscReal edge, ConvexShape *shape);
PetscErrorCode ConvexShapeCreateTetrahedron(PetscReal edge, ConvexShape *shape);
PetscErrorCode ConvexShapeCreateOctahedron(PetscReal edge, ConvexShape *shape);
PetscErrorCode ConvexShapeCreateIcosahedron(PetscReal edge, ConvexShape *shape);
PetscErrorCode ConvexShapeCreateCylinder(PetscReal radius, PetscReal height, ConvexShape *shape);
PetscErrorCode ConvexShapeDestroy(ConvexShape *shape);
PetscErrorCode ConvexShapeView(const ConvexShape *shape, PetscViewer viewer);

/* Narrow phase between two shapes (libccd MPR for depth and normal; contact point from the
 * contact features, see feature.c). Not collective; no allocation; re-entrant. Bodies
 * whose bounding spheres do not overlap are rejected before libccd is called. */
PetscErrorCode ConvexCollide(const ConvexShape *a, const ConvexPose *pa, const ConvexShape *b, const ConvexPose *pb, ConvexContact *c);

/* Contact of a shape (A) with a plane wall (B) through point p0 with unit normal n pointing
 * out of the wall into the domain. depth = max over the body of (p0 - x).n; the contact point
 * lies under the depth-weighted centroid of the penetrating vertices (a flat face gives its
 * centre, an edge its midpoint; continuous as the body tilts), depth/2 below the plane;
 * normal = -n (from A to B, as for pairs). Cylinder: same rule on its rims, closed form. */
PetscErrorCode ConvexCollidePlane(const ConvexShape *a, const ConvexPose *pa, const PetscReal p0[3], const PetscReal n[3], ConvexContact *c);
/* Where the contact point of a pair sits (ConvexContactPoint):
 *  PATCH:   the centroid of the intersection of the two contact features, each taken as the
 *           body's vertices in the slab between the two support planes (thickness = depth): a
 *           face-face contact acts at its patch centre and the point moves smoothly while a
 *           face tilts, but it is not the gradient of the elastic energy, so a frictionless
 *           elastic collision does not conserve energy exactly.
 *  SUPPORT: the support features only (the vertices on each support plane): the deepest
 *           vertex of a vertex-face contact, the crossing of an edge-edge contact. With the
 *           exact minimum penetration this is the gradient of 1/2 k depth^2 (the torque the
 *           energy gives), so the energy is conserved up to the time-step error; the point
 *           jumps when the deepest vertex changes (a face nearly parallel to the other). */
typedef enum {
  CONVEX_POINT_PATCH,
  CONVEX_POINT_SUPPORT
} ConvexPointModel;
extern const char *const ConvexPointModels[]; /* the names of -dem_convex_contact_point, in enum order */

/* ConvexCollide with the contact point of the given model (ConvexCollide itself: PATCH). */
PetscErrorCode ConvexCollideWith(const ConvexShape *a, const ConvexPose *pa, const ConvexShape *b, const ConvexPose *pb, ConvexPointModel model, ConvexContact *c);

/* Not collective. The contact of A and B when the caller already knows the exact minimum
 * penetration: unit normal n (A to B) and depth > 0 (a separating-axis test over face normals
 * and edge-edge axes gives them for polyhedra). Fills c with them and the feature point; returns
 * *ok = PETSC_FALSE (c->overlap false) when n is not a supporting normal of the pair, and the
 * caller should then use ConvexCollideWith. */
PetscErrorCode ConvexContactPoint(const ConvexShape *a, const ConvexPose *pa, const ConvexShape *b, const ConvexPose *pb, const PetscReal n[3], PetscReal depth, ConvexPointModel model, ConvexContact *c, PetscBool *ok);

/* ConvexContactPoint for bodies whose rotation matrices the caller holds: PETSC_TRUE with c
 * filled, or PETSC_FALSE (c->overlap false). */
PetscBool ConvexBodiesContactPoint(const ConvexBody *A, const ConvexBody *B, const PetscReal n[3], PetscReal depth, ConvexPointModel model, ConvexContact *c);
