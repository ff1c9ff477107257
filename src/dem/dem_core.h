/* DEM private state, the core: particles, the shape table, the contact model, the convex narrow
 * phase, neighbour lists, the ghost exchange and time, the object struct _p_Dem and the core's
 * internal functions. Particles are a structure of arrays, xyz interleaved per particle
 * (x[3*i+k]): local particles 0..n-1, then ghost copies of other ranks' (or periodic images of
 * our own) particles n..n+ng-1. Geometry and mass live once per
 * shape. The half Verlet list is CSR over local particles; for laws with history each list entry
 * carries its tangential spring, which follows the pair through list rebuilds and re-sorts.
 * Invariant: between rebuilds no particle has moved more than skin/2 from x0, and no wall more
 * than skin/2, so every pair that can touch is in the list.
 * The other concerns have their own private headers, which a file includes when it uses them:
 * dem_walls.h (walls and meshes), dem_sources.h (insertion, sources, outlets, the mass balance),
 * dem_checkpoint.h (checkpoint datasets, counters, remap). */
#pragma once
#include "dem/dem.h"
#include "dem/contact_laws.h"
#include "geom/convex.h"
#include "geom/sat.h"

#define DEM_MAX_SHAPES 32

typedef struct {
  double r, rho, m, inertia, invm, invi; /* sphere radius (m), density, mass, moment of inertia */
  /* convex shapes (shapes.c): r is the bounding radius; NULL cvx means a sphere */
  const ConvexShape *cvx;
  double             J[3], invJ[3]; /* principal moments of inertia (kg m^2), body axes */
  double             vol, req;      /* volume (m^3), equivalent radius for the contact laws (m) */
  ConvexAxes         ax;            /* a polyhedron's separating-axis candidates and box frame (geom/sat.h) */
  PetscBool          iso;           /* J1 = J2 = J3 (cube, regular polyhedra): rotation about w in one step */
} DemShape;

/* A position wrapped into the box along the periodic axes ([lo, hi)): between list builds a
 * particle may be up to skin/2 past a periodic side; frames hold it wrapped, and a frame read back
 * is wrapped again (a file written by another run). */
static inline void DemWrapPeriodic(const Domain *dom, double *x)
{
  for (int k = 0; k < 3; k++) {
    if (!dom->periodic[k]) continue;
    x[k] -= dom->len[k] * floor((x[k] - dom->lo[k]) / dom->len[k]);
    if (x[k] >= dom->hi[k]) x[k] = dom->lo[k]; /* round-off */
  }
}

/* splitmix64: a uniform double in [0,1) from (seed, site, stream), stateless, so a lattice site
 * or a source's candidate draws the same numbers on any rank count (insert.c, sources.c). */
static inline double dem_uniform(PetscInt seed, PetscInt site, int stream)
{
  uint64_t z = (uint64_t)seed * 0x9E3779B97F4A7C15ULL + (uint64_t)site * 0xBF58476D1CE4E5B9ULL + (uint64_t)stream * 0x94D049BB133111EBULL;
  z          = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z          = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  z ^= z >> 31;
  return (double)(z >> 11) * (1.0 / 9007199254740992.0);
}

/* Whether this rank owns a particle centred at x (the last rank along an axis also owns its
 * upper face). */
static inline PetscBool dem_in_box(const Domain *dom, const double *x)
{
  for (int k = 0; k < 3; k++) {
    const PetscBool last = dom->cstart[k] + dom->ccount[k] == dom->cells[k];
    if (x[k] < dom->sublo[k] || (last ? x[k] > dom->subhi[k] : x[k] >= dom->subhi[k])) return PETSC_FALSE;
  }
  return PETSC_TRUE;
}

typedef struct { /* material of one side of a contact */
  PetscReal kn, kt, e, mu, E, nu;
  PetscReal mur; /* rolling friction (-dem_rolling_friction, -dem_wall_rolling_friction) */
  PetscBool kn_set, kt_set, E_set;
} DemMaterial;

/* A tangential spring saved across a rebuild, keyed by ids (partner < 0: wall -1-partner). */
typedef struct {
  PetscInt owner, partner;
  double   xi[3];
} DemSpring;

/* Ghost exchange with the 26 neighbours (exchange.c). Direction d = (dx+1) + 3(dy+1) + 9(dz+1). */
typedef struct {
  PetscMPIInt rank[27];                         /* neighbour rank per direction, -1 if none */
  double      shift[27][3];                     /* periodic shift added to coordinates sent that way */
  PetscInt   *send[27], nsend[27], capsend[27]; /* local indices sent as ghosts per direction */
  PetscInt    nrecv[27], recvstart[27];         /* ghosts received per direction */
  double     *sbuf, *rbuf;
  size_t      capsbuf, caprbuf;
  PetscBool   active;   /* any neighbour at all (else exchange is a no-op) */
  PetscInt    migrated; /* particles sent away at the last rebuild (diagnostic) */
  PetscBool   remap;    /* the decomposition changed: the next build migrates to any rank */
} DemExchange;

/* Neighbour search (neighbours.c): its settings, the cells and the half (or full) Verlet list. */
typedef struct {
  PetscReal skin, reach; /* reach = 2 r_max + skin = halo width */
  PetscBool full_list;   /* -dem_deterministic: full rows summed in id order */
  PetscInt  sort_interval;
  /* cells over the local box (plus halo): counting sort */
  PetscInt  nc[3], ncell;
  double    lo[3], inv[3];
  PetscInt *cstart, *cof, *order;
  PetscInt *zrank; /* rank of each cell along a Morton (Z-order) curve: the re-sort order */
  /* half Verlet list */
  PetscInt *start, *nbr, cap;
  PetscInt *own;  /* row (local particle) of each entry: the pair loop screens entries flat */
  double   *hist; /* 3 per entry, NULL without history */
  PetscInt  builds, sorts;
} DemNeigh;

/* The particles (particles.c): local 0..n-1, then ghosts n..n+ng-1, room for cap. */
typedef struct {
  PetscInt  n, ng, cap;
  double   *x, *v, *w, *f, *tq, *q, *x0; /* x0: positions at the last list build */
  PetscInt *id, *shape;
  PetscInt  next_id;
  /* spheres of their own sizes (DemShapeTable.poly; NULL otherwise): radius (m), mass (kg),
     1/m and 1/I with I = 2/5 m r^2, of locals and ghosts; the shape names the material */
  double *rad, *m, *invm, *invi;
} DemParticles;

/* The shape table (shapes.c): spheres or convex shapes, which the table owns (cvx); convex =
 * the scene has any. */
typedef struct {
  DemShape    shp[DEM_MAX_SHAPES];
  PetscInt    nshape;
  PetscReal   shape_frac[DEM_MAX_SHAPES];
  ConvexShape cvx[DEM_MAX_SHAPES];
  PetscBool   convex;
  /* sizes of their own: a source draws each sphere's radius from a distribution (psd.h), which
     the particle keeps (DemParticle.r); r_source_max is the largest radius a source can add (m),
     set with the sources' options, so that reach and cells cover it from the start */
  PetscBool poly;
  PetscReal r_source_max;
  PetscReal r_source_min; /* the smallest radius a source can add (m): the time-step check covers it */
} DemShapeTable;

/* The radius (m) and mass (kg) of particle i (local or ghost): its own in a scene of own sizes,
 * else its shape's. For the paths outside the hot loops, which specialise on p->rad. */
static inline double DemRadius(const DemParticles *p, const DemShapeTable *st, PetscInt i)
{
  return p->rad ? p->rad[i] : st->shp[p->shape[i]].r;
}
static inline double DemMass(const DemParticles *p, const DemShapeTable *st, PetscInt i)
{
  return p->m ? p->m[i] : st->shp[p->shape[i]].m;
}
/* A sphere's mass from its density and radius: the one expression shapes and particles use. */
static inline double dem_sphere_mass(double rho, double r)
{
  return rho * 4.0 / 3.0 * PETSC_PI * r * r * r;
}

/* The contact model (contact_laws.c): the law, the materials and the parameters of every
 * (shape, shape) and (shape, wall) pair. */
typedef struct {
  DemMaterial   mat, wmat;
  DemLaw        law;
  PetscReal     tdamp_ratio, vimpact;
  DemPairParams pp[DEM_MAX_SHAPES * DEM_MAX_SHAPES], pw[DEM_MAX_SHAPES];
  PetscBool     rotation; /* any friction or rolling resistance: torques and spins are integrated */
  DemRoll       roll;     /* -dem_rolling_model (contact_laws.h) */
} DemContactModel;

/* The narrow phase of convex pairs (convex_contacts.c): its settings and its caches. */
typedef struct {
  PetscBool        convex_sat;                   /* -dem_convex_sat: separating-axis narrow phase for few-axis polyhedron pairs */
  PetscInt         convex_sat_axes;              /* -dem_convex_sat_axes: the most candidate axes a pair may have for it */
  ConvexPointModel convex_point;                 /* -dem_convex_contact_point patch|support */
  double          *sepax;                        /* per Verlet-list entry: a separating axis (world), 0 = none, and
                                       a flag: touching at the last step (4 each) */
  PetscInt         sepax_build;                  /* the list build it belongs to */
  double          *rot;                          /* rotation matrices of the particles (9 each) for the pair loop, */
  PetscInt        *rot_stamp;                    /* each valid where its stamp is the loop's pass number */
  PetscInt         rot_cap, rot_pass, rot_pairs; /* rot_pairs: pairs the last pass tested */
} DemConvexNarrow;

/* Time (dem.c). */
typedef struct {
  PetscReal dt, t, dt_frac, dt_tc;
  PetscReal dt_given; /* -dem_dt as given, for the log when -dem_dt_tc replaces it */
  PetscBool dt_set;   /* -dem_dt given */
  PetscInt  step;
} DemClock;

/* External forces from a coupling (external.c): per-particle arrays, NULL unless DemSetExternal
 * switched them on; frozen: nothing is integrated. */
typedef struct {
  double   *fext, *kdrag, *udrag, *jdrag;
  PetscBool on, frozen;
} DemExternalState;

/* The state of the other concerns that struct _p_Dem embeds by value: their struct definitions
 * only, which the layout needs (their functions: dem_walls.h, dem_sources.h). They use
 * DEM_MAX_SHAPES and DemMaterial above. */
#include "dem/dem_walls_state.h"
#include "dem/dem_sources_state.h"

struct _p_Dem {
  MPI_Comm         comm;
  Domain          *dom;
  DemParticles     p;
  DemShapeTable    shapes;
  DemContactModel  contact;
  DemConvexNarrow  narrow;
  DemWalls         walls;
  DemMeshes        meshes; /* triangle-mesh walls (walls_mesh.c) */
  DemNeigh         nl;
  DemExchange      ex;
  DemClock         clock;
  DemInsertion     insert;
  DemExternalState ext;
  DemFlow          flow;
  DemSinks         sinks;
  /* run control */
  PetscReal      g[3];        /* gravity (m/s^2) */
  PetscReal      overlap_max; /* -dem_overlap_max: a larger overlap stops the run (DemCheckHealth) */
  PetscInt       check_every;
  DemStats       initial; /* count and checksum at set-up, for -dem_check_every */
  PetscBool      need_build;
  int            stop_sig;  /* a signal any rank had caught at the last step's reduction (0: none) */
  PetscLogDouble t_compute; /* wall time in force computation and integration (s) */
  PetscLogDouble t_mesh;    /* of which in the mesh contacts of DemStep (s) */
  PetscReal      mesh_cand; /* candidate triangles summed over the steps of t_mesh */
  PetscInt       state;     /* changes whenever positions or the local order may have (DemGetState) */
  IoCkpt         restart;   /* DemSetRestart: a checkpoint replaces the insertion */
  DemSources     src;       /* particle sources (sources.c) */
};

/* Internal functions of the core, by file, from the leaves up (the DEM's .c files form no circle
 * of calls: tools/check-layout); the walls', the sources' and the checkpoints' are declared in
 * their own headers. */
PetscErrorCode       DemEventsRegister(void); /* events.c */
extern PetscLogEvent DEM_Exchange, DEM_Neighbours, DEM_Contacts, DEM_Walls, DEM_Integrate, DEM_Output, DEM_Placement;
PetscErrorCode       DemSpringsSort(DemSpring *r, PetscInt n);                                        /* springs.c */
const DemSpring     *DemSpringFind(const DemSpring *r, PetscInt n, PetscInt owner, PetscInt partner); /* springs.c */
PetscErrorCode       DemSpringsSave(Dem dem, DemSpring **recs, PetscInt *nrec, PetscInt *cap);        /* springs.c */
PetscErrorCode       DemSpringsRestore(Dem dem, const DemSpring *recs, PetscInt nrec);                /* springs.c */
PetscErrorCode       DemParticlesReserve(Dem dem, PetscInt n);                                        /* particles.c */
PetscErrorCode       DemParticlesPermute(Dem dem, const PetscInt *perm);                              /* particles.c */
void                 DemParticleSetSize(Dem dem, PetscInt i, double r);                               /* fields.c: radius, mass, 1/m, 1/I of a poly scene's particle i */
PetscErrorCode       DemMaterialsSetUp(Dem dem);                                                      /* contact_laws.c */
PetscErrorCode       DemHertzRestitutionMap(double e, double *ch, double *tau);                       /* contact_laws.c */
PetscErrorCode       DemCheckTimeStepSizes(Dem dem);                                                  /* contact_laws.c: spheres of their own sizes */
PetscErrorCode       DemShapesSetFromOptions(Dem dem);                                                /* shapes.c */
PetscErrorCode       DemShapesSetUp(Dem dem);                                                         /* shapes.c */
PetscErrorCode       DemShapesDestroy(Dem dem);                                                       /* shapes.c */
PetscErrorCode       DemExchangeSetUp(Dem dem);                                                       /* exchange.c */
PetscErrorCode       DemExchangeDestroy(Dem dem);                                                     /* exchange.c */
PetscErrorCode       DemMigrate(Dem dem, DemSpring **recs, PetscInt *nrec, PetscInt *caprec);         /* exchange.c */
PetscErrorCode       DemBufReserve(double **buf, size_t *cap, size_t n);                              /* exchange.c */
/* exchange.c: the migration record of local particle i (position + shift, state, coupling
 * state, springs): doubles written; unpack appends the particle and its springs */
size_t         DemMigSize(Dem dem, PetscInt i, const DemSpring *recs, PetscInt nrec);
size_t         DemMigPack(Dem dem, PetscInt i, const DemSpring *recs, PetscInt nrec, const double shift[3], double *b);
PetscErrorCode DemMigUnpack(Dem dem, const double *b, DemSpring **recs, PetscInt *nrec, PetscInt *caprec, size_t *used);
/* Errors when a local particle is wholly outside the domain across a non-periodic side. */
PetscErrorCode DemCheckInDomain(Dem dem);                                                                                      /* exchange.c */
PetscErrorCode DemGhostsCreate(Dem dem);                                                                                       /* exchange.c */
PetscErrorCode DemGhostsUpdate(Dem dem);                                                                                       /* exchange.c */
PetscErrorCode DemMigrateGlobal(Dem dem, DemSpring **recs, PetscInt *nrec, PetscInt *caprec);                                  /* redistribute.c */
PetscErrorCode DemNeighSetCells(Dem dem, const PetscInt nc[3]);                                                                /* neighbours.c */
PetscErrorCode DemNeighSort(Dem dem);                                                                                          /* neighbours.c */
PetscErrorCode DemNeighBuildList(Dem dem);                                                                                     /* neighbours.c */
PetscErrorCode DemNeighResetCells(Dem dem);                                                                                    /* neighbours.c */
PetscErrorCode DemNeighDestroy(Dem dem);                                                                                       /* neighbours.c */
PetscErrorCode DemContactsPairs(DemParticles *p, const DemShapeTable *st, const DemContactModel *cm, DemNeigh *nl, double dt); /* contacts.c */
PetscErrorCode DemContactsPairsConvex(Dem dem);                                                                                /* convex_contacts.c */
/* A body in a pair test (convex_contacts.c): shape, centre, quaternion and its
 * rotation matrix (body -> world), pointing into the particle arrays. */
typedef struct {
  const DemShape *s;
  const double   *x, *q, *R;
} DemBody;
/* The pose of a particle for the convex module: its centre x (3) and quaternion q (4). */
static inline ConvexPose DemPose(const double *x, const double *q)
{
  ConvexPose p = {{x[0], x[1], x[2]}, {q[0], q[1], q[2], q[3]}};
  return p;
}
PetscErrorCode DemConvexPairContact(Dem dem, PetscInt i, PetscInt j, ConvexContact *c);                                                               /* convex_contacts.c: the forces' narrow phase */
PetscErrorCode DemConvexStatsLocal(Dem dem, double r[5], PetscInt c[3], double *rmax);                                                                /* convex_diag.c */
PetscErrorCode DemConvexWriteSurface(Dem dem, const double *x, Io io);                                                                                /* convex_diag.c */
PetscErrorCode DemRotateFirstHalf(DemParticles *p, const DemShapeTable *st, double dt);                                                               /* rotation.c */
PetscErrorCode DemRotateSecondHalf(DemParticles *p, const DemShapeTable *st, double dt);                                                              /* rotation.c */
                                                                                                                                                      /* external.c */
PetscErrorCode DemExternalCheckpointCheck(Dem dem, IoCkpt ck);                                                                                        /* external.c: a coupled checkpoint for a coupled case, a dry one for a dry case */
void           DemExternalKick(DemParticles *p, const DemShapeTable *st, DemExternalState *e, double h);                                              /* external.c */
PetscErrorCode DemIntegrateFirstHalf(DemParticles *p, const DemShapeTable *st, DemExternalState *e, PetscBool rotation, double dt, double *maxdisp2); /* integrate.c */
PetscErrorCode DemIntegrateSecondHalf(DemParticles *p, const DemShapeTable *st, DemExternalState *e, PetscBool rotation, double dt);                  /* integrate.c */
double         DemImpactOverlap(Dem dem, const DemPairParams *p);                                                                                     /* diag.c */
PetscErrorCode DemRebuild(Dem dem);                                                                                                                   /* rebuild.c */
PetscErrorCode DemRebuildFrom(Dem dem, DemSpring *recs, PetscInt nrec, PetscInt caprec);                                                              /* rebuild.c */
