/* The walls' and meshes' state that struct _p_Dem embeds (walls.c, walls_polygon.c,
 * walls_cylinder.c, walls_mesh.c): struct definitions only (a wall is a surface of
 * geom/surface.h, where each kind's geometry is written once, plus what the DEM keeps of it),
 * included by dem_core.h where the
 * layout needs them (after DEM_MAX_SHAPES and DemMaterial); the functions and the contact
 * kernels of walls are in dem_walls.h. */
#pragma once
#include "dem/contact_laws.h"
#include "geom/surface.h"
#include "geom/trimesh.h"
#ifndef DEM_MAX_SHAPES
  #error "dem_walls_state.h is included by dem_core.h (it needs DEM_MAX_SHAPES and DemMaterial); include dem_walls.h"
#endif

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
  /* the vessel (vessel.c): -dem_plane_<k>_fluid, -dem_cylinder_fluid, -dem_cylinder_caps_fluid as
     asked (-1 not given, 0 no, 1 yes), and whether the wall bounds the gas (DemVesselSetUp) */
  int       fluid;
  PetscBool gas;
  /* list of particles within reach, with their tangential springs */
  PetscInt *idx;
  double   *hist;
  PetscInt  cnt, cap;
} DemWall;

/* The walls (walls.c). */
typedef struct {
  DemWall   wall[DEM_MAX_WALLS];
  PetscInt  nwall;
  PetscBool vessel; /* some wall or mesh bounds the gas (DemVesselSetUp, vessel.c) */
} DemWalls;

/* Triangle-mesh walls (walls_mesh.c, walls_mesh_options.c): -dem_mesh_<k>_file, k < 8. A mesh
 * is placed at t = 0 (ref) and moves rigidly: x(t) = a + v t + Rot(u, theta(t)) (x_ref - a),
 * theta the integral of omega (a constant or a table in time); the pose is a function of t only.
 * Per rank: the triangles near the rank's box (loc), their vertices at the pose of the forces
 * (cur: the reference's for a mesh at rest), per local particle the candidate triangles of the
 * last list build (CSR), and per particle a few tangential springs matched by normal (slot: n,
 * xi). A spring saved across a rebuild is two records, partner DEM_MESH_PARTNER(k, s, 0) (xi)
 * and (k, s, 1) (its normal). */
#define DEM_MAX_MESHES               8
#define DEM_MESH_SLOTS               4
#define DEM_MESH_MAXC                16
#define DEM_MESH_PARTNER(k, s, half) (-1 - DEM_MAX_WALLS - 2 * ((k)*DEM_MESH_SLOTS + (s)) - (half))
#define DEM_MESH_PARTNER_MIN         DEM_MESH_PARTNER(DEM_MAX_MESHES - 1, DEM_MESH_SLOTS - 1, 1)
typedef struct {
  char                   name[32];                        /* -dem_mesh_<k>, for messages */
  char                   file[PETSC_MAX_PATH_LEN];        /* the STL file */
  TriMesh                ref;                             /* the triangles at t = 0 (scaled, rotated, translated) */
  double                 vel[3], omega, ax_p[3], ax_u[3]; /* motion: translation (m/s), rotation (rad/s) about a + v t, u */
  double                *tab;                             /* -dem_mesh_<k>_omega_table t0,w0,t1,w1,... (s, rad/s); NULL: omega */
  PetscInt               ntab;                            /* points of the table */
  double                 raxis;                           /* largest distance of a vertex from the axis (m): the travel bound */
  PetscBool              moving;
  DemMaterial            mat;                           /* -dem_mesh_<k>_friction, ... (default the -dem_wall_* material) */
  DemPairParams          pw[DEM_MAX_SHAPES];            /* (shape, mesh) pair parameters */
  double                 theta, w_now, tpose;           /* the pose of cur: angle (rad), angular velocity (rad/s), time (s) */
  double                 moved;                         /* travel bound since the last list build (m) */
  int                    fluid;                         /* -dem_mesh_<k>_fluid: DEM_MESH_FLUID_* (-1 not given) */
  struct _DemVesselMesh *vm;                            /* the vessel's view of it (vessel.c), NULL unless it bounds the gas */
  PetscInt              *loc, nloc, caploc;             /* triangles near this rank's box */
  double                *cur;                           /* 9 per triangle (only loc's are current); ref.v at rest */
  PetscInt              *cstart, *ctri, capstart, capc; /* candidate triangles per local particle (CSR) */
  double                *slot;                          /* 6 DEM_MESH_SLOTS per local particle: normal, spring */
  PetscInt               capslot;
} DemMesh;
typedef struct {
  DemMesh  m[DEM_MAX_MESHES];
  PetscInt n;
} DemMeshes;
/* -dem_mesh_<k>_fluid: the gas inside the mesh (a vessel), outside it (an immersed obstacle), or
 * not bounded by it (vessel.c). */
enum {
  DEM_MESH_FLUID_NONE,
  DEM_MESH_FLUID_INSIDE,
  DEM_MESH_FLUID_OUTSIDE
};
