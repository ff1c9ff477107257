/* Infinite plane through p with unit normal n into the granular side (surface.h): touched from
 * both sides by the face rule, overlap r - (x - p).n; unbounded; it closes a domain face when
 * the face's four corners lie behind it or on it. */
#pragma once
static inline double surface_plane_gap(const Surface *s, const double *x)
{
  return surface_plane_distance(s, x);
}

static inline PetscBool surface_plane_covers(const Surface *s, const double *pt, const double *xc)
{
  (void)s, (void)pt, (void)xc;
  return PETSC_TRUE;
}

static inline double surface_plane_sphere(const Surface *s, const double *x, double r, double nrm[3])
{
  const double h = surface_plane_distance(s, x);
  for (int k = 0; k < 3; k++) nrm[k] = -s->n[k];
  return r - h;
}

static inline void surface_plane_velocity(const Surface *s, const double *c, double vw[3])
{
  surface_rigid_velocity(s, c, vw);
}

static inline void surface_plane_bbox(const Surface *s, double lo[3], double hi[3])
{
  (void)s;
  for (int k = 0; k < 3; k++) lo[k] = -PETSC_MAX_REAL, hi[k] = PETSC_MAX_REAL;
}

static inline PetscBool surface_plane_closes_face(const Surface *s, int d, int side, const double c[4][3], double tol)
{
  (void)d, (void)side;
  return surface_plane_behind(s, c, tol);
}

/* The unit test's instance: the floor z = 0 of the box [-1,1]^2 x [0,1]: it closes 1 face (zlo). */
static inline int surface_plane_example(Surface *s, double lo[3], double hi[3])
{
  *s = (Surface){.kind = SURFACE_PLANE, .n = {0, 0, 1}};
  for (int k = 0; k < 3; k++) lo[k] = k < 2 ? -1 : 0, hi[k] = 1;
  return 1;
}

/* The kind's entry in the table of kinds (surface.h). */
static const SurfaceKindInfo surface_plane_kind = {"plane", PETSC_TRUE, PETSC_FALSE, surface_plane_sphere, surface_plane_gap, surface_plane_covers, surface_plane_velocity, surface_plane_bbox, surface_plane_closes_face, surface_plane_example};
