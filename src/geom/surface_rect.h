/* Finite rectangle p + s e1 + t e2, s, t in [0,1], facing n = e1 x e2 / |..| (surface.h): a
 * contact counts where its point projects inside the rectangle and the body's centre is in
 * front of the plane (the face rule: a sphere overhanging an edge feels no force from this face,
 * its neighbour takes over, as in a box corner); one-sided. It closes a domain face when the
 * face's corners lie behind it and project onto it (within tol). */
#pragma once
static inline double surface_rect_gap(const Surface *s, const double *x)
{
  return surface_plane_distance(s, x);
}

static inline PetscBool surface_rect_covers(const Surface *s, const double *pt, const double *xc)
{
  const double d[3] = {pt[0] - s->p[0], pt[1] - s->p[1], pt[2] - s->p[2]};
  const double c[3] = {xc[0] - s->p[0], xc[1] - s->p[1], xc[2] - s->p[2]};
  if (convex_dot(c, s->n) <= 0) return PETSC_FALSE;
  const double u = convex_dot(d, s->e1) / convex_dot(s->e1, s->e1), t = convex_dot(d, s->e2) / convex_dot(s->e2, s->e2);
  return (PetscBool)(u >= 0 && u <= 1 && t >= 0 && t <= 1);
}

static inline double surface_rect_sphere(const Surface *s, const double *x, double r, double nrm[3])
{
  const double h = surface_plane_distance(s, x);
  for (int k = 0; k < 3; k++) nrm[k] = -s->n[k];
  if (!surface_rect_covers(s, x, x)) return -1;
  return r - h;
}

static inline void surface_rect_velocity(const Surface *s, const double *c, double vw[3])
{
  surface_rigid_velocity(s, c, vw);
}

static inline void surface_rect_bbox(const Surface *s, double lo[3], double hi[3])
{
  for (int k = 0; k < 3; k++) {
    lo[k] = s->p[k] + PetscMin(s->e1[k], 0.0) + PetscMin(s->e2[k], 0.0);
    hi[k] = s->p[k] + PetscMax(s->e1[k], 0.0) + PetscMax(s->e2[k], 0.0);
  }
}

static inline PetscBool surface_rect_closes_face(const Surface *s, int d, int side, const double c[4][3], double tol)
{
  const double l1 = sqrt(convex_dot(s->e1, s->e1)), l2 = sqrt(convex_dot(s->e2, s->e2));
  (void)d, (void)side;
  if (!surface_plane_behind(s, c, tol)) return PETSC_FALSE;
  for (int q = 0; q < 4; q++) {
    const double dq[3] = {c[q][0] - s->p[0], c[q][1] - s->p[1], c[q][2] - s->p[2]};
    const double u = convex_dot(dq, s->e1) / l1, t = convex_dot(dq, s->e2) / l2;
    if (!(u >= -tol && u <= l1 + tol && t >= -tol && t <= l2 + tol)) return PETSC_FALSE;
  }
  return PETSC_TRUE;
}

/* The unit test's instance: the floor z = 0 of the box [-1,1]^2 x [0,1]: it closes 1 face (zlo). */
static inline int surface_rect_example(Surface *s, double lo[3], double hi[3])
{
  *s = (Surface){.kind = SURFACE_RECT, .p = {-1, -1, 0}, .n = {0, 0, 1}, .e1 = {2, 0, 0}, .e2 = {0, 2, 0}};
  for (int k = 0; k < 3; k++) lo[k] = k < 2 ? -1 : 0, hi[k] = 1;
  return 1;
}

/* The kind's entry in the table of kinds (surface.h). */
static const SurfaceKindInfo surface_rect_kind = {"rectangle", PETSC_TRUE, PETSC_TRUE, surface_rect_sphere, surface_rect_gap, surface_rect_covers, surface_rect_velocity, surface_rect_bbox, surface_rect_closes_face, surface_rect_example};
