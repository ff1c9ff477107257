/* Analytic surfaces: the kinds of wall a particle meets (planes, rectangles, convex polygons,
 * cylinders), each written once. A kind is one header surface_<kind>.h of static inline
 * kernels ending in its entry, a SurfaceKindInfo (name, flags, kernels), and one line in each of
 * the enum SurfaceKind, the #includes and the table SurfaceKinds below; the dispatchers call
 * the kernels through the table.
 *
 * A Surface is placed in the world frame: a point p and a unit normal n pointing into the
 * granular side (a cylinder: a point of its axis and the unit axis), a translation velocity v and
 * a rotation omega about the axis through ax_p along ax_u (a drum and its caps). What each kind
 * gives (prefix surface_<kind>_):
 *   sphere(s, x, r, nrm)  the overlap of a sphere of centre x and radius r (> 0: touching) and the
 *                         unit normal from the centre towards the surface; a value <= 0 otherwise
 *                         (-1 where the surface does not cover the centre: its rim, its back)
 *   gap(s, x)             a signed distance of the point x from the surface, > 0 on the granular
 *                         side, never more than the true distance of a covered point: a sphere of
 *                         radius r can touch only where gap < r (the list pruning)
 *   covers(s, pt, xc)     whether a contact at pt of a body centred at xc is on the surface (the
 *                         face rule of finite kinds; convex bodies use it with the plane's contact)
 *   velocity(s, c, vw)    the surface velocity at the point c (m/s)
 *   bbox(s, lo, hi)       a box holding the surface (+-PETSC_MAX_REAL where it is unbounded)
 *   closes_face(s, d, side, c, tol)  whether it closes the domain face of axis d, side 0 lo / 1 hi,
 *                         corners c[4]: nothing crosses the face without crossing the surface
 *   example(s, lo, hi)    an instance in a box, and how many faces of the box it closes (the
 *                         unit test's case, tests/geom/test_surface.c)
 * and its SurfaceKindInfo: its name, whether it is planar (a convex body meets it through its
 * plane: ConvexCollidePlane with p and n, then covers) and one-sided (touched from the front
 * only: the pruning drops points more than the skin behind it).
 * Conventions of geom/convex.h: lengths in the caller's unit, the normal from the body to the
 * wall. Nothing allocates, nothing is collective. Checked by tests/geom/test_surface.c. */
#pragma once
#include <petscsys.h>
#include "geom/quat.h"

/* The kinds, in the order of the table SurfaceKinds below. A new kind: one line here, its
 * header's #include and its line in the table. */
typedef enum {
  SURFACE_PLANE,
  SURFACE_RECT,
  SURFACE_POLYGON,
  SURFACE_CYLINDER,
  SURFACE_NKINDS
} SurfaceKind;

#define SURFACE_POLY_MAX 8

typedef struct {
  SurfaceKind kind;
  double      p[3], n[3], v[3]; /* a point, the unit normal into the granular side (cylinder: the
                                   axis), the translation velocity (m/s) */
  double      e1[3], e2[3];     /* rectangle p + s e1 + t e2, s, t in [0,1] */
  /* convex polygon: vertices, unit in-plane edge normals pointing inside, and whether an edge is a
     free rim (edge contacts) or a joint with a neighbour wall (face only) */
  PetscInt  nv;
  double    vert[SURFACE_POLY_MAX][3], en[SURFACE_POLY_MAX][3];
  PetscBool rim[SURFACE_POLY_MAX];
  double    R;                       /* cylinder radius, the particles inside */
  double    omega, ax_p[3], ax_u[3]; /* rotation (rad/s) about the axis through ax_p along ax_u */
} Surface;

/* A kind: its name, whether it is planar (a convex body meets it through its plane, then the
 * face rule) and one-sided, and its kernels (surface_<kind>_*, above). */
typedef struct {
  const char *name;
  PetscBool   planar, one_sided;
  double (*sphere)(const Surface *s, const double *x, double r, double nrm[3]);
  double (*gap)(const Surface *s, const double *x);
  PetscBool (*covers)(const Surface *s, const double *pt, const double *xc);
  void (*velocity)(const Surface *s, const double *c, double vw[3]);
  void (*bbox)(const Surface *s, double lo[3], double hi[3]);
  PetscBool (*closes_face)(const Surface *s, int d, int side, const double c[4][3], double tol);
  int (*example)(Surface *s, double lo[3], double hi[3]);
} SurfaceKindInfo;

/* The surface velocity of a rigid motion: v + omega u x (c - a). */
static inline void surface_rigid_velocity(const Surface *s, const double *c, double vw[3])
{
  for (int k = 0; k < 3; k++) vw[k] = s->v[k];
  if (s->omega != 0) {
    const double d[3] = {c[0] - s->ax_p[0], c[1] - s->ax_p[1], c[2] - s->ax_p[2]};
    double       t[3];
    convex_cross(s->ax_u, d, t);
    for (int k = 0; k < 3; k++) vw[k] += s->omega * t[k];
  }
}

/* A plane's signed distance (x - p).n, the gap of the planar kinds. */
static inline double surface_plane_distance(const Surface *s, const double *x)
{
  const double d[3] = {x[0] - s->p[0], x[1] - s->p[1], x[2] - s->p[2]};
  return convex_dot(d, s->n);
}

/* Whether the four corners c of a domain face lie behind or on the plane of s (within tol). */
static inline PetscBool surface_plane_behind(const Surface *s, const double c[4][3], double tol)
{
  PetscBool behind = PETSC_TRUE;
  for (int q = 0; q < 4; q++) {
    const double dq[3] = {c[q][0] - s->p[0], c[q][1] - s->p[1], c[q][2] - s->p[2]};
    behind             = (PetscBool)(behind && convex_dot(dq, s->n) <= tol);
  }
  return behind;
}

/* The kinds, one header each. */
#include "geom/surface_plane.h"
#include "geom/surface_rect.h"
#include "geom/surface_polygon.h"
#include "geom/surface_cylinder.h"

/* The table of kinds, indexed by SurfaceKind, and the dispatchers through it. */
static const SurfaceKindInfo *const SurfaceKinds[SURFACE_NKINDS] = {
  [SURFACE_PLANE]    = &surface_plane_kind,
  [SURFACE_RECT]     = &surface_rect_kind,
  [SURFACE_POLYGON]  = &surface_polygon_kind,
  [SURFACE_CYLINDER] = &surface_cylinder_kind,
};

static inline double surface_sphere(const Surface *s, const double *x, double r, double nrm[3])
{
  return SurfaceKinds[s->kind]->sphere(s, x, r, nrm);
}

static inline double surface_gap(const Surface *s, const double *x)
{
  return SurfaceKinds[s->kind]->gap(s, x);
}

static inline PetscBool surface_covers(const Surface *s, const double *pt, const double *xc)
{
  return SurfaceKinds[s->kind]->covers(s, pt, xc);
}

static inline void surface_velocity(const Surface *s, const double *c, double vw[3])
{
  SurfaceKinds[s->kind]->velocity(s, c, vw);
}

static inline void surface_bbox(const Surface *s, double lo[3], double hi[3])
{
  SurfaceKinds[s->kind]->bbox(s, lo, hi);
}

/* An instance of the kind in a box lo..hi (the unit test's): the number of the box's faces it closes. */
static inline int surface_example(SurfaceKind kind, Surface *s, double lo[3], double hi[3])
{
  return SurfaceKinds[kind]->example(s, lo, hi);
}

static inline PetscBool surface_closes_face(const Surface *s, int d, int side, const double c[4][3], double tol)
{
  return SurfaceKinds[s->kind]->closes_face(s, d, side, c, tol);
}

/* Whether a sphere of reach (radius + skin) centred at x may touch s before the next list build:
 * the gap is below the reach, and a one-sided surface has x at most skin behind it. */
static inline PetscBool surface_near(const Surface *s, const double *x, double reach, double skin)
{
  const double g = surface_gap(s, x);
  if (g >= reach) return PETSC_FALSE;
  return (PetscBool) !(SurfaceKinds[s->kind]->one_sided && g < -skin);
}
