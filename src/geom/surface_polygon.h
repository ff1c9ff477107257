/* Convex planar polygon vert[0..nv-1], counter-clockwise seen from the granular side, plane
 * (p = vert[0], n), unit in-plane edge normals en pointing inside (surface.h). A point y projects
 * inside when (y - vert[e]).en[e] >= 0 for every edge e (exact by convexity). The face rule of
 * the rectangle; where a sphere's centre projects outside across an edge, the edge is a joint
 * with a neighbour wall (no contact) or a free rim (rim[e]: the nearest point of the edge segment
 * is touched, a hopper's orifice). One-sided; it closes a domain face as a rectangle does. */
#pragma once
static inline double surface_polygon_gap(const Surface *s, const double *x)
{
  return surface_plane_distance(s, x);
}

static inline PetscBool surface_polygon_covers(const Surface *s, const double *pt, const double *xc)
{
  const double c[3] = {xc[0] - s->p[0], xc[1] - s->p[1], xc[2] - s->p[2]};
  if (convex_dot(c, s->n) <= 0) return PETSC_FALSE;
  for (PetscInt e = 0; e < s->nv; e++) {
    const double de[3] = {pt[0] - s->vert[e][0], pt[1] - s->vert[e][1], pt[2] - s->vert[e][2]};
    if (convex_dot(de, s->en[e]) < 0) return PETSC_FALSE;
  }
  return PETSC_TRUE;
}

/* A sphere centred at x against the free rim: the nearest point of the rim edges the centre lies
 * outside of; none (1e300) if it lies outside a joint edge. The distance and in nrm the unit
 * direction to that point. */
static inline double surface_polygon_rim(const Surface *s, const double *x, double nrm[3])
{
  double best = 1e300;
  for (PetscInt e = 0; e < s->nv; e++) {
    const double *a = s->vert[e], *b = s->vert[(e + 1) % s->nv];
    const double  d[3] = {x[0] - a[0], x[1] - a[1], x[2] - a[2]}, ab[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    if (convex_dot(d, s->en[e]) >= 0) continue;
    if (!s->rim[e]) return 1e300;
    const double t    = PetscMin(1.0, PetscMax(0.0, convex_dot(d, ab) / convex_dot(ab, ab)));
    const double q[3] = {a[0] + t * ab[0] - x[0], a[1] + t * ab[1] - x[1], a[2] + t * ab[2] - x[2]};
    const double l    = sqrt(convex_dot(q, q));
    if (l < best && l > 0) {
      best = l;
      for (int k = 0; k < 3; k++) nrm[k] = q[k] / l;
    }
  }
  return best;
}

static inline double surface_polygon_sphere(const Surface *s, const double *x, double r, double nrm[3])
{
  const double h = surface_plane_distance(s, x);
  for (int k = 0; k < 3; k++) nrm[k] = -s->n[k];
  if (h <= 0) return -1;
  if (surface_polygon_covers(s, x, x)) return r - h;
  return r - surface_polygon_rim(s, x, nrm);
}

static inline void surface_polygon_velocity(const Surface *s, const double *c, double vw[3])
{
  surface_rigid_velocity(s, c, vw);
}

static inline void surface_polygon_bbox(const Surface *s, double lo[3], double hi[3])
{
  for (int k = 0; k < 3; k++) lo[k] = hi[k] = s->vert[0][k];
  for (PetscInt e = 1; e < s->nv; e++)
    for (int k = 0; k < 3; k++) lo[k] = PetscMin(lo[k], s->vert[e][k]), hi[k] = PetscMax(hi[k], s->vert[e][k]);
}

static inline PetscBool surface_polygon_closes_face(const Surface *s, int d, int side, const double c[4][3], double tol)
{
  (void)d, (void)side;
  if (!surface_plane_behind(s, c, tol)) return PETSC_FALSE;
  for (int q = 0; q < 4; q++)
    for (PetscInt e = 0; e < s->nv; e++) {
      const double de[3] = {c[q][0] - s->vert[e][0], c[q][1] - s->vert[e][1], c[q][2] - s->vert[e][2]};
      if (convex_dot(de, s->en[e]) < -tol) return PETSC_FALSE;
    }
  return PETSC_TRUE;
}

/* The unit test's instance: a pentagon at z = 0 holding the floor of the box [-1,1]^2 x [0,1]
 * closing 1 face (zlo), two of its edges free rims. */
static inline int surface_polygon_example(Surface *s, double lo[3], double hi[3])
{
  const double v[5][3] = {{-1, -1, 0}, {1, -1, 0}, {1.4, 0, 0}, {1, 1, 0}, {-1, 1, 0}};
  *s                   = (Surface){.kind = SURFACE_POLYGON, .n = {0, 0, 1}, .nv = 5};
  for (PetscInt e = 0; e < 5; e++) {
    const double *a = v[e], *b = v[(e + 1) % 5], d[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    double        m[3];
    convex_cross(s->n, d, m);
    const double lm = sqrt(convex_dot(m, m));
    for (int k = 0; k < 3; k++) s->vert[e][k] = a[k], s->en[e][k] = m[k] / lm;
    s->rim[e] = (PetscBool)(e == 0 || e == 2);
  }
  for (int k = 0; k < 3; k++) s->p[k] = v[0][k], lo[k] = k < 2 ? -1 : 0, hi[k] = 1;
  return 1;
}

/* The kind's entry in the table of kinds (surface.h). */
static const SurfaceKindInfo surface_polygon_kind = {"polygon", PETSC_TRUE, PETSC_TRUE, surface_polygon_sphere, surface_polygon_gap, surface_polygon_covers, surface_polygon_velocity, surface_polygon_bbox, surface_polygon_closes_face, surface_polygon_example};
