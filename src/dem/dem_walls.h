/* DEM private header of the walls: analytic walls (planes, rectangles, polygons, cylinders) and
 * triangle meshes, their contact with a sphere, their options, lists, contacts and checkpoint.
 * Their state (DemWall, DemWalls, DemMesh, DemMeshes) is in dem_walls_state.h, which the
 * object's layout needs. */
#pragma once
#include "dem/dem_core.h"

/* The option reader of each surface kind, DemWall<Kind>Options (walls_options.c: the box and the
 * planes, the rectangles; walls_polygon.c; walls_cylinder.c), called inside the walls' options
 * block in the order of the kinds (geom/surface.h): it adds its walls (DemWallAdd) and sets their
 * kind and parameters. A new kind is its geometry (geom/surface_<kind>.h and its lines in
 * surface.h) and this reader, in a file of its own, named in DemWallsSetFromOptions' table. */
PetscErrorCode DemWallPlaneOptions(PetscOptionItems *PetscOptionsObject, Dem dem);    /* walls_options.c: -dem_box, -dem_plane_<k> */
PetscErrorCode DemWallRectOptions(PetscOptionItems *PetscOptionsObject, Dem dem);     /* walls_options.c: -dem_rect_<k> */
PetscErrorCode DemWallPolygonOptions(PetscOptionItems *PetscOptionsObject, Dem dem);  /* walls_polygon.c: -dem_quad_<k>, -dem_hopper */
PetscErrorCode DemWallCylinderOptions(PetscOptionItems *PetscOptionsObject, Dem dem); /* walls_cylinder.c: -dem_cylinder */

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

/* Pair parameters of shape s with wall w from the contact model cm (a copy with the wall's own
 * friction, if it has one). */
#define DemWallParams(cm, w, s, tmp) ((w)->mu < 0 ? &(cm)->pw[s] : ((*(tmp) = (cm)->pw[s]), (tmp)->mu = (w)->mu, (tmp)))

/* The contact of sphere i (radius r, centre x) with a wall surface (an analytic wall or a mesh
 * triangle): overlap delta along the unit normal nrm from the centre to the wall, the surface's
 * velocity at the contact point vw and its angular velocity ww (rolling resistance takes
 * w_rel = w_i - ww). Adds the force and torques to i and advances its spring xi_t (NULL: none). */
static inline void dem_sphere_wall_force(DemParticles *pt, PetscInt i, double r, double delta, const double nrm[3], const double vw[3], const double ww[3], const DemPairParams *p, const DemContactModel *cm, double ieff, double *xi_t, double dt)
{
  const double l = r - 0.5 * delta, *vi = pt->v + 3 * i, *wi_ = pt->w + 3 * i;
  double       vr[3], c[3], kt, gt, F[3];
  dem_cross(wi_, nrm, c);
  for (int k = 0; k < 3; k++) vr[k] = vw[k] - vi[k] - l * c[k];
  const double vn = dem_dot(vr, nrm);
  const double fn = dem_normal_force(cm->law, p, delta, vn, &kt, &gt);
  for (int k = 0; k < 3; k++) F[k] = -fn * nrm[k];
  if (p->mu > 0) {
    double vt[3], ft[3];
    for (int k = 0; k < 3; k++) vt[k] = vr[k] - vn * nrm[k];
    dem_tangential_force(p, fn, kt, gt, nrm, vt, xi_t, dt, ft);
    if (cm->rotation) {
      dem_cross(nrm, ft, c);
      for (int k = 0; k < 3; k++) pt->tq[3 * i + k] -= l * c[k];
    }
    for (int k = 0; k < 3; k++) F[k] -= ft[k];
  }
  if (cm->roll) { /* V_w = r w_i x n */
    double wrel[3], vwr[3], mr[3];
    for (int k = 0; k < 3; k++) wrel[k] = wi_[k] - ww[k];
    dem_cross(wi_, nrm, vwr);
    for (int k = 0; k < 3; k++) vwr[k] *= r;
    dem_rolling_torque(cm->roll, p, fn, ieff, wrel, vwr, nrm, dt, mr);
    for (int k = 0; k < 3; k++) pt->tq[3 * i + k] += mr[k];
  }
  for (int k = 0; k < 3; k++) pt->f[3 * i + k] += F[k];
}

/* Internal functions of the walls and meshes, by file. */
PetscErrorCode DemWallAdd(Dem dem, const char *name, const double p[3], const double n[3], const double v[3]);                                          /* walls.c */
PetscErrorCode DemWallFrictionOption(PetscOptionItems *PetscOptionsObject, Dem dem, const char *opt, PetscInt n, PetscInt first);                       /* walls.c; first < 0: -help, no wall */
PetscErrorCode DemWallsBuildLists(DemWalls *walls, const DemParticles *pt, const DemShapeTable *st, double skin, const DemSpring *recs, PetscInt nrec); /* walls.c */
PetscErrorCode DemContactsWalls(DemParticles *pt, const DemShapeTable *st, const DemContactModel *cm, DemWalls *walls, double dt);                      /* walls.c */
PetscErrorCode DemWallsSetFromOptions(Dem dem);                                                                                                         /* walls_options.c */
PetscErrorCode DemWallPairsFill(Dem dem, const DemMaterial *wm, DemPairParams *pw, PetscReal *tc);                                                      /* contact_laws.c: (shape, wall) pairs of material wm */
PetscErrorCode DemMeshesSetFromOptions(PetscOptionItems *PetscOptionsObject, Dem dem);                                                                  /* walls_mesh_options.c */
PetscErrorCode DemMeshesSetUp(Dem dem);                                                                                                                 /* walls_mesh_options.c: materials, after DemMaterialsSetUp */
PetscErrorCode DemMeshesDestroy(Dem dem);
PetscErrorCode DemVesselMeshDestroy(DemMesh *m);                                                       /* vessel.c: the vessel's view of a mesh */
PetscErrorCode DemMeshesMove(Dem dem, double t, double *moved);                                        /* walls_mesh.c: the pose at t; the largest travel since the build */
PetscErrorCode DemMeshesBuildLists(Dem dem, const DemSpring *recs, PetscInt nrec);                     /* walls_mesh.c */
PetscErrorCode DemContactsMeshes(Dem dem);                                                             /* walls_mesh.c */
PetscErrorCode DemMeshesSaveSprings(Dem dem, DemSpring **recs, PetscInt *nrec, PetscInt *cap);         /* walls_mesh.c: appends the slots' records, sorted */
PetscErrorCode DemMeshesCheckpoint(Dem dem, IoCkpt ck, PetscBool write);                               /* walls_mesh.c: same rank count */
PetscErrorCode DemMeshTouchConvex(Dem dem, const DemMesh *m, PetscInt i, ConvexContact cc[], int *nc); /* walls_mesh.c: the face rule */
void           DemMeshMatchSlots(double *sl, int na, const double an[][3], int match[]);               /* walls_mesh.c: springs matched by normal */
PetscErrorCode DemContactsMeshesConvex(Dem dem);                                                       /* convex_contacts.c */
PetscErrorCode DemMeshesStatsLocal(Dem dem, double r[5], PetscInt c[3], double *rmax);                 /* walls_mesh.c: contacts, normal elastic energy */
PetscErrorCode DemMeshesCloseFace(Dem dem, int d, int side, double tol, PetscBool *closed);            /* walls_mesh.c: triangles tiling the face */
PetscErrorCode DemMeshDepth(Dem dem, PetscInt k, PetscInt i, double *depth);                           /* walls_mesh.c: placement check, radii */
PetscBool      DemMeshesBlock(Dem dem, const double x[3], double r);                                   /* walls_mesh.c: a source's candidate meets a triangle */
PetscErrorCode DemContactsWallsConvex(Dem dem);                                                        /* convex_contacts.c */
