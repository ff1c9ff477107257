/* The analytic walls of the DEM (walls.c, walls_options.c, walls_polygon.c, walls_cylinder.c):
 * a wall is a surface of geom/surface.h, where each kind's contact, gap, covering rule, surface
 * velocity, bounding box and face closing are written once, plus what the DEM keeps of it: the
 * option that made it, its friction, its removal time, the travel since the list build and the
 * list of particles within reach with their tangential springs. Triangle meshes are not walls
 * (walls_mesh.c). Invariant: between list builds no wall has moved more than skin/2. */
#pragma once
#include "dem/dem.h"
#include "geom/surface.h"

#define DEM_MAX_WALLS 24

typedef struct {
  Surface s;        /* the geometry and its motion (geom/surface.h) */
  char    name[32]; /* the option that made it, for messages: -dem_plane_0, -dem_box zlo */
  double  moved;    /* distance moved since the last list build (m) */
  double  mu;       /* friction override (-dem_box_friction, -dem_plane_<k>_friction), < 0: none */
  /* removal (-dem_plane_<k>_remove_time): from the first step whose forces act at t >= t_remove the
     wall is gone (no list, no contacts, no travel); removed says it went */
  double    t_remove;
  PetscBool removed;
  /* list of particles within reach, with their tangential springs */
  PetscInt *idx;
  double   *hist;
  PetscInt  cnt, cap;
} DemWall;

/* The walls (walls.c). */
typedef struct {
  DemWall  wall[DEM_MAX_WALLS];
  PetscInt nwall;
} DemWalls;

/* The option reader of each surface kind, DemWall<Kind>Options (walls_options.c: the box and the
 * planes, the rectangles; walls_polygon.c; walls_cylinder.c), called inside the walls' options
 * block in the order of SURFACE_KINDS: it adds its walls (DemWallAdd) and sets their kind and
 * parameters. A new kind is its geometry (geom/surface_<kind>.h), its line in SURFACE_KINDS and
 * this reader, in a file of its own. */
#define DEM_WALL_READER(K, k, C) PetscErrorCode DemWall##C##Options(PetscOptionItems *PetscOptionsObject, Dem dem);
SURFACE_KINDS(DEM_WALL_READER)
#undef DEM_WALL_READER

/* Whether a contact at point pt of a particle centred at xc is on the wall (the face rule of the
 * finite kinds; convex particles use it with the plane's contact). */
static inline PetscBool DemWallCovers(const DemWall *w, const double *pt, const double *xc)
{
  return surface_covers(&w->s, pt, xc);
}

/* Contact of a sphere (centre x, radius r) with wall w: the overlap (> 0 when touching) and the
 * unit normal from the centre towards the wall (geom/surface.h, the kind's sphere kernel). */
static inline double dem_wall_sphere(const DemWall *w, const double *x, double r, double nrm[3])
{
  return surface_sphere(&w->s, x, r, nrm);
}

/* Velocity of the wall's surface at point c (m/s). */
static inline void dem_wall_velocity(const DemWall *w, const double *c, double vw[3])
{
  surface_velocity(&w->s, c, vw);
}
