/* The wall options, read in one block: -dem_box xlo,ylo,zlo,xhi,yhi,zhi (m), six inward-facing
 * planes; -dem_plane_<k> px,py,pz,nx,ny,nz (m, -), -dem_plane_<k>_velocity vx,vy,vz (m/s) and
 * -dem_plane_<k>_remove_time t (s: the plane is gone from t on, a gate opened; 0: never), k = 0..9;
 * -dem_rect_<k> x0,y0,z0,x1,y1,z1,x2,y2,z2 (m), k = 0..9: a finite rectangle with
 * corners p0, p1, p2 (p1 - p0 perpendicular to p2 - p0), facing the side (p1 - p0) x (p2 - p0)
 * points to; -dem_quad_<k> (4 vertices), -dem_hopper (walls_polygon.c); -dem_cylinder,
 * -dem_cylinder_omega, -dem_cylinder_caps (walls_cylinder.c); triangle meshes -dem_mesh_<k>_*
 * (walls_mesh_options.c, not counted among the walls); -dem_<wall>_friction overrides
 * -dem_wall_friction for that wall. The block calls each surface kind's reader in the order of
 * the kinds (geom/surface.h); those of the plane (with the box) and the rectangle are here.
 * The walls are added to the store (walls.c) in this order. */
#include "dem/dem_walls.h"

static const char *const DemPlaneWordOptions[] = {"-dem_plane_%d_fluid"};

/* Adds the rectangle r (a patch region: p0 + s e1 + t e2, s, t in [0,1], e1 = p1 - p0 and
 * e2 = p2 - p0 perpendicular), facing the side e1 x e2 points to. */
static PetscErrorCode DemWallAddRect(Dem dem, const char *opt, const GeomRegion *r)
{
  double   n[3], z[3] = {0, 0, 0};
  DemWall *w;

  PetscFunctionBeginUser;
  dem_cross(r->g + 3, r->g + 6, n);
  PetscCall(DemWallAdd(dem, opt, r->g, n, z));
  w         = &dem->walls.wall[dem->walls.nwall - 1];
  w->s.kind = SURFACE_RECT;
  for (int k = 0; k < 3; k++) {
    w->s.e1[k] = r->g[3 + k];
    w->s.e2[k] = r->g[6 + k];
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Reads -dem_box and -dem_plane_<k> (+ _velocity, _remove_time, _friction) inside the walls'
 * options block: the plane kind's reader. */
PetscErrorCode DemWallPlaneOptions(PetscOptionItems *PetscOptionsObject, Dem dem)
{
  PetscReal box[6], pl[6], vel[3], trm;
  PetscBool set, vset, rset, help;
  char      opt[64], optv[80];

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsHasHelp(NULL, &help)); /* -help: every wall's options listed, given or not */
  PetscCall(SableOptionsRealN("-dem_box", "Closed box of six inward-facing walls: xlo,ylo,zlo,xhi,yhi,zhi", "m", box, 0, 6, &set));
  if (set) {
    for (int k = 0; k < 3; k++) {
      double p[3] = {0, 0, 0}, n[3] = {0, 0, 0}, z[3] = {0, 0, 0};
      PetscCheck(box[k + 3] > box[k], dem->comm, PETSC_ERR_ARG_OUTOFRANGE, "-dem_box: upper bound %g must exceed lower bound %g on axis %d", (double)box[k + 3], (double)box[k], k);
      PetscCheck(!dem->dom->periodic[k], dem->comm, PETSC_ERR_ARG_INCOMP, "-dem_box puts walls across the %c axis, which is periodic (-domain_periodic_%c): nothing could cross it; close the other axes with -dem_plane_k", "xyz"[k], "xyz"[k]);
      p[k] = box[k];
      n[k] = 1;
      PetscCall(PetscSNPrintf(opt, sizeof opt, "-dem_box %clo", "xyz"[k]));
      PetscCall(DemWallAdd(dem, opt, p, n, z));
      p[k] = box[k + 3];
      n[k] = -1;
      PetscCall(PetscSNPrintf(opt, sizeof opt, "-dem_box %chi", "xyz"[k]));
      PetscCall(DemWallAdd(dem, opt, p, n, z));
    }
    PetscCall(DemWallFrictionOption(PetscOptionsObject, dem, "-dem_box_friction", 6, dem->walls.nwall - 6));
  } else if (help) PetscCall(DemWallFrictionOption(PetscOptionsObject, dem, "-dem_box_friction", 6, -1));
  for (int k = 0; k < 10; k++) {
    PetscCall(PetscSNPrintf(opt, sizeof opt, "-dem_plane_%d", k));
    PetscCall(PetscSNPrintf(optv, sizeof optv, "-dem_plane_%d_velocity", k));
    PetscCall(SableOptionsRealN(opt, "Infinite plane wall: point px,py,pz and normal nx,ny,nz into the granular side", "m, -", pl, 0, 6, &set));
    vel[0] = vel[1] = vel[2] = 0;
    trm                      = 0; /* never */
    PetscCall(SableOptionsRealN(optv, "Translation velocity of the plane wall", "m/s", vel, 3, 3, &vset));
    PetscCheck(set || !vset || help, dem->comm, PETSC_ERR_ARG_WRONG, "%s given without %s", optv, opt);
    PetscCheck(!set || pl[3] != 0 || pl[4] != 0 || pl[5] != 0, dem->comm, PETSC_ERR_ARG_OUTOFRANGE, "%s %g,%g,%g,%g,%g,%g: the normal (the last 3 values) must be non-zero", opt, (double)pl[0], (double)pl[1], (double)pl[2], (double)pl[3], (double)pl[4], (double)pl[5]);
    if (set) PetscCall(DemWallAdd(dem, opt, pl, pl + 3, vel));
    PetscCall(PetscSNPrintf(optv, sizeof optv, "-dem_plane_%d_remove_time", k));
    PetscCall(SableOptionsReal(optv, "Time at which the plane wall is removed (a gate opening, as a silo's plate); 0: never", "s", "[0,inf)", 0, &trm, &rset));
    PetscCheck(set || !rset || help, dem->comm, PETSC_ERR_ARG_WRONG, "%s given without %s", optv, opt);
    if (rset && trm > 0) dem->walls.wall[dem->walls.nwall - 1].t_remove = trm;
    PetscCall(PetscSNPrintf(optv, sizeof optv, "-dem_plane_%d_friction", k));
    if (set || help) PetscCall(DemWallFrictionOption(PetscOptionsObject, dem, optv, 1, set ? dem->walls.nwall - 1 : -1));
    {
      static const char *const yesno[] = {"no", "yes"};
      PetscInt                 gas;
      PetscBool                gset;
      PetscCall(PetscSNPrintf(optv, sizeof optv, DemPlaneWordOptions[0], k));
      PetscCall(SableOptionsEnum(optv, "Whether the plane also bounds the gas in a coupled run (default no: a plane lets the gas through, as a distributor or a lid; a moving or removable plane cannot)", yesno, 2, 0, &gas, &gset));
      PetscCheck(set || !gset || help, dem->comm, PETSC_ERR_ARG_WRONG, "%s given without %s", optv, opt);
      if (set && gset) dem->walls.wall[dem->walls.nwall - 1].fluid = (int)gas;
    }
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Reads -dem_rect_<k> (+ _friction) inside the walls' options block: the rectangle kind's reader. */
PetscErrorCode DemWallRectOptions(PetscOptionItems *PetscOptionsObject, Dem dem)
{
  PetscBool set, help;
  char      opt[64], optv[80];

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsHasHelp(NULL, &help));
  for (int k = 0; k < 10; k++) {
    GeomRegion r; /* the region reader's patch: the one syntax and check of a rectangle */
    PetscCall(PetscSNPrintf(opt, sizeof opt, "-dem_rect_%d", k));
    PetscCall(GeomRegionOption(opt, GEOM_REGION_PATCH, "Finite rectangular wall: corners p0, p1, p2 (p1-p0 perpendicular to p2-p0); faces the side (p1-p0)x(p2-p0) points to", &r, &set));
    if (set) PetscCall(DemWallAddRect(dem, opt, &r));
    PetscCall(PetscSNPrintf(optv, sizeof optv, "-dem_rect_%d_friction", k));
    if (set || help) PetscCall(DemWallFrictionOption(PetscOptionsObject, dem, optv, 1, set ? dem->walls.nwall - 1 : -1));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The walls' options block: each surface kind's reader (dem_walls.h), in the order of the kinds
 * (geom/surface.h), then the meshes; the walls are numbered in this order. */
PetscErrorCode DemWallsSetFromOptions(Dem dem)
{
  /* one line a kind: -dem_box and -dem_plane_<k>; -dem_rect_<k>; -dem_quad_<k> and -dem_hopper; -dem_cylinder */
  PetscErrorCode (*const reader[SURFACE_NKINDS])(PetscOptionItems *, Dem) = {
    [SURFACE_PLANE]    = DemWallPlaneOptions,
    [SURFACE_RECT]     = DemWallRectOptions,
    [SURFACE_POLYGON]  = DemWallPolygonOptions,
    [SURFACE_CYLINDER] = DemWallCylinderOptions,
  };

  PetscFunctionBeginUser;
  PetscOptionsBegin(dem->comm, NULL, "DEM walls", NULL);
  for (int k = 0; k < SURFACE_NKINDS; k++) PetscCall(reader[k](PetscOptionsObject, dem));
  PetscCall(DemMeshesSetFromOptions(PetscOptionsObject, dem)); /* -dem_mesh_<k>_* (walls_mesh_options.c) */
  PetscOptionsEnd();
  for (PetscInt k = 0; k < dem->walls.nwall; k++) { /* convex particles meet a wall through its plane */
    const DemWall *w = &dem->walls.wall[k];
    PetscCheck(!dem->shapes.convex || SurfaceKinds[w->s.kind]->planar, dem->comm, PETSC_ERR_SUP, "%s: a %s wall takes spheres only, not the convex shapes of -dem_shape", w->name, SurfaceKinds[w->s.kind]->name);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}
