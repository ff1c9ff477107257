/* Cylinder of radius R about the axis through p along the unit n, the particles inside
 * (surface.h). A sphere of centre x has radial offset rho = (x - p) - ((x - p).n) n and overlap
 * r + |rho| - R, normal rho/|rho| from the centre to the wall; the gap is R - |rho|. Unbounded
 * along its axis; not planar (convex bodies do not meet it). It closes a domain face when its
 * axis is parallel to the face and it lies wholly on the domain's side of it. */
#pragma once
static inline double surface_cylinder_gap(const Surface *s, const double *x)
{
  const double d[3] = {x[0] - s->p[0], x[1] - s->p[1], x[2] - s->p[2]};
  const double a = convex_dot(d, s->n), rho2 = convex_dot(d, d) - a * a;
  return s->R - sqrt(PetscMax(rho2, 0.0));
}

static inline PetscBool surface_cylinder_covers(const Surface *s, const double *pt, const double *xc)
{
  (void)s, (void)pt, (void)xc;
  return PETSC_TRUE;
}

static inline double surface_cylinder_sphere(const Surface *s, const double *x, double r, double nrm[3])
{
  const double d[3] = {x[0] - s->p[0], x[1] - s->p[1], x[2] - s->p[2]};
  const double a = convex_dot(d, s->n), rho[3] = {d[0] - a * s->n[0], d[1] - a * s->n[1], d[2] - a * s->n[2]};
  const double l = sqrt(convex_dot(rho, rho));
  if (l <= 0) return -1;
  for (int k = 0; k < 3; k++) nrm[k] = rho[k] / l;
  return r + l - s->R;
}

static inline void surface_cylinder_velocity(const Surface *s, const double *c, double vw[3])
{
  surface_rigid_velocity(s, c, vw);
}

/* Bounded (p +- R) along the coordinate axes the cylinder's axis is perpendicular to. */
static inline void surface_cylinder_bbox(const Surface *s, double lo[3], double hi[3])
{
  for (int k = 0; k < 3; k++) {
    const PetscBool across = (PetscBool)(PetscAbsReal(s->n[k]) < 1e-12);
    lo[k]                  = across ? s->p[k] - s->R : -PETSC_MAX_REAL;
    hi[k]                  = across ? s->p[k] + s->R : PETSC_MAX_REAL;
  }
}

static inline PetscBool surface_cylinder_closes_face(const Surface *s, int d, int side, const double c[4][3], double tol)
{
  double lo[3], hi[3];
  surface_cylinder_bbox(s, lo, hi);
  if (PetscAbsReal(s->n[d]) >= 1e-12) return PETSC_FALSE;
  return (PetscBool)(side ? hi[d] <= c[0][d] + tol : lo[d] >= c[0][d] - tol);
}

/* The unit test's instance: radius 1 about the y axis in the box [-1,1] x [0,1] x [-1,1] (it
 * closes the 4 x and z faces). */
static inline int surface_cylinder_example(Surface *s, double lo[3], double hi[3])
{
  *s = (Surface){.kind = SURFACE_CYLINDER, .n = {0, 1, 0}, .R = 1};
  for (int k = 0; k < 3; k++) lo[k] = k == 1 ? 0 : -1, hi[k] = 1;
  return 4;
}

/* The kind's entry in the table of kinds (surface.h). */
static const SurfaceKindInfo surface_cylinder_kind = {"cylinder", PETSC_FALSE, PETSC_FALSE, surface_cylinder_sphere, surface_cylinder_gap, surface_cylinder_covers, surface_cylinder_velocity, surface_cylinder_bbox, surface_cylinder_closes_face, surface_cylinder_example};
