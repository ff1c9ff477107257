/* DEM private state. Particles are a structure of arrays, xyz interleaved per particle
 * (x[3*i+k]): local particles 0..n-1, then ghost copies of other ranks' (or periodic images of
 * our own) particles n..n+ng-1. Geometry and mass live once per
 * shape. The half Verlet list is CSR over local particles; for laws with history each list entry
 * carries its tangential spring, which follows the pair through list rebuilds and re-sorts.
 * Invariant: between rebuilds no particle has moved more than skin/2 from x0, and no wall more
 * than skin/2, so every pair that can touch is in the list. */
#pragma once
#include "dem/dem.h"
#include "dem/contact_laws.h"
#include "geom/convex.h"
#include "geom/sat.h"
#include "geom/trimesh.h"
#include "dem/psd.h"

#define DEM_MAX_SHAPES 32
#define DEM_MAX_WALLS  24

typedef struct {
  double r, rho, m, inertia, invm, invi; /* sphere radius (m), density, mass, moment of inertia */
  /* convex shapes (shapes.c): r is the bounding radius; NULL cvx means a sphere */
  const ConvexShape *cvx;
  double             J[3], invJ[3]; /* principal moments of inertia (kg m^2), body axes */
  double             vol, req;      /* volume (m^3), equivalent radius for the contact laws (m) */
  ConvexAxes         ax;            /* a polyhedron's separating-axis candidates and box frame (geom/sat.h) */
  PetscBool          iso;           /* J1 = J2 = J3 (cube, regular polyhedra): rotation about w in one step */
} DemShape;

typedef enum {
  DEM_WALL_PLANE,
  DEM_WALL_RECT,
  DEM_WALL_POLYGON,
  DEM_WALL_CYLINDER
} DemWallKind;
#define DEM_POLY_MAX 8

typedef struct {
  DemWallKind kind;
  char        name[32];         /* the option that made it, for messages: -dem_plane_0, -dem_box zlo */
  double      p[3], n[3], v[3]; /* a point, the unit normal pointing into the granular side, velocity;
                              a cylinder: a point of its axis, the unit axis, v = 0 */
  double      moved;            /* distance moved since the last list build (m) */
  /* finite rectangle p + s e1 + t e2, s,t in [0,1], touched from the front only (-dem_rect_k) */
  PetscBool finite; /* a rectangle or a polygon: touched from the front only */
  double    e1[3], e2[3];
  /* convex polygon (walls_polygon.c): vertices, unit in-plane edge normals pointing inside, and
     whether an edge is a free rim (edge contacts) or a joint with a neighbour wall (face only) */
  PetscInt  nv;
  double    vert[DEM_POLY_MAX][3], en[DEM_POLY_MAX][3];
  PetscBool rim[DEM_POLY_MAX];
  double    R; /* cylinder radius (m), particles inside (walls_cylinder.c) */
  /* rotation about an axis (drum and its end caps): surface velocity v + omega u x (x - a) */
  double omega, ax_p[3], ax_u[3];
  double mu; /* friction override (-dem_box_friction, -dem_plane_<k>_friction), < 0: none */
  /* removal (-dem_plane_<k>_remove_time): from the first step whose forces act at t >= t_remove the
     wall is gone (no list, no contacts, no travel); removed says it went */
  double    t_remove;
  PetscBool removed;
  /* list of particles within reach, with their tangential springs */
  PetscInt *idx;
  double   *hist;
  PetscInt  cnt, cap;
} DemWall;

/* Whether a contact at point pt of a particle centred at xc is on the wall: always for an
 * infinite plane; for a rectangle or a polygon, pt projects inside it and xc is on its front
 * side (the face rule; convex particles use it for polygons, spheres see rim edges too). */
static inline PetscBool DemWallCovers(const DemWall *w, const double *pt, const double *xc)
{
  if (!w->finite) return PETSC_TRUE;
  const double d[3] = {pt[0] - w->p[0], pt[1] - w->p[1], pt[2] - w->p[2]};
  const double c[3] = {xc[0] - w->p[0], xc[1] - w->p[1], xc[2] - w->p[2]};
  if (dem_dot(c, w->n) <= 0) return PETSC_FALSE;
  if (w->kind == DEM_WALL_POLYGON) {
    for (PetscInt e = 0; e < w->nv; e++) {
      const double de[3] = {pt[0] - w->vert[e][0], pt[1] - w->vert[e][1], pt[2] - w->vert[e][2]};
      if (dem_dot(de, w->en[e]) < 0) return PETSC_FALSE;
    }
    return PETSC_TRUE;
  }
  const double s = dem_dot(d, w->e1) / dem_dot(w->e1, w->e1), t = dem_dot(d, w->e2) / dem_dot(w->e2, w->e2);
  return (PetscBool)(s >= 0 && s <= 1 && t >= 0 && t <= 1);
}

/* Sphere (centre x, radius r) against a polygon's free rim: the nearest point of the rim edges
 * the centre lies outside of; no contact if it lies outside a joint edge (the neighbour wall
 * takes over) or behind the plane. Returns the distance and the unit direction to that point. */
static inline double dem_wall_rim(const DemWall *w, const double *x, double nrm[3])
{
  double best = 1e300;
  for (PetscInt e = 0; e < w->nv; e++) {
    const double *a = w->vert[e], *b = w->vert[(e + 1) % w->nv];
    const double  d[3] = {x[0] - a[0], x[1] - a[1], x[2] - a[2]}, ab[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    if (dem_dot(d, w->en[e]) >= 0) continue;
    if (!w->rim[e]) return 1e300;
    const double t    = PetscMin(1.0, PetscMax(0.0, dem_dot(d, ab) / dem_dot(ab, ab)));
    const double q[3] = {a[0] + t * ab[0] - x[0], a[1] + t * ab[1] - x[1], a[2] + t * ab[2] - x[2]};
    const double l    = sqrt(dem_dot(q, q));
    if (l < best && l > 0) {
      best = l;
      for (int k = 0; k < 3; k++) nrm[k] = q[k] / l;
    }
  }
  return best;
}

/* Contact of a sphere (centre x, radius r) with wall w: the overlap (> 0 when touching) and the
 * unit normal from the centre towards the wall. Plane and rectangle: the face rule above;
 * polygon: face, or its free rim; cylinder (particles inside): radial. */
static inline double dem_wall_sphere(const DemWall *w, const double *x, double r, double nrm[3])
{
  const double d[3] = {x[0] - w->p[0], x[1] - w->p[1], x[2] - w->p[2]};
  if (w->kind == DEM_WALL_CYLINDER) {
    const double a = dem_dot(d, w->n), rho[3] = {d[0] - a * w->n[0], d[1] - a * w->n[1], d[2] - a * w->n[2]};
    const double l = sqrt(dem_dot(rho, rho));
    if (l <= 0) return -1;
    for (int k = 0; k < 3; k++) nrm[k] = rho[k] / l;
    return r + l - w->R;
  }
  const double h = dem_dot(d, w->n);
  for (int k = 0; k < 3; k++) nrm[k] = -w->n[k];
  if (w->kind == DEM_WALL_POLYGON) {
    if (h <= 0) return -1;
    if (DemWallCovers(w, x, x)) return r - h;
    return r - dem_wall_rim(w, x, nrm);
  }
  if (!DemWallCovers(w, x, x)) return -1;
  return r - h;
}

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

/* Velocity of the wall's surface at point c (m/s). */
static inline void dem_wall_velocity(const DemWall *w, const double *c, double vw[3])
{
  for (int k = 0; k < 3; k++) vw[k] = w->v[k];
  if (w->omega != 0) {
    const double d[3] = {c[0] - w->ax_p[0], c[1] - w->ax_p[1], c[2] - w->ax_p[2]};
    double       t[3];
    dem_cross(w->ax_u, d, t);
    for (int k = 0; k < 3; k++) vw[k] += w->omega * t[k];
  }
}

/* Pair parameters of shape s with wall w from the contact model cm (a copy with the wall's own
 * friction, if it has one). */
#define DemWallParams(cm, w, s, tmp) ((w)->mu < 0 ? &(cm)->pw[s] : ((*(tmp) = (cm)->pw[s]), (tmp)->mu = (w)->mu, (tmp)))

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

/* The walls (walls.c). */
typedef struct {
  DemWall  wall[DEM_MAX_WALLS];
  PetscInt nwall;
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
  char          name[32];                        /* -dem_mesh_<k>, for messages */
  char          file[PETSC_MAX_PATH_LEN];        /* the STL file */
  TriMesh       ref;                             /* the triangles at t = 0 (scaled, rotated, translated) */
  double        vel[3], omega, ax_p[3], ax_u[3]; /* motion: translation (m/s), rotation (rad/s) about a + v t, u */
  double       *tab;                             /* -dem_mesh_<k>_omega_table t0,w0,t1,w1,... (s, rad/s); NULL: omega */
  PetscInt      ntab;                            /* points of the table */
  double        raxis;                           /* largest distance of a vertex from the axis (m): the travel bound */
  PetscBool     moving;
  DemMaterial   mat;                           /* -dem_mesh_<k>_friction, ... (default the -dem_wall_* material) */
  DemPairParams pw[DEM_MAX_SHAPES];            /* (shape, mesh) pair parameters */
  double        theta, w_now, tpose;           /* the pose of cur: angle (rad), angular velocity (rad/s), time (s) */
  double        moved;                         /* travel bound since the last list build (m) */
  PetscInt     *loc, nloc, caploc;             /* triangles near this rank's box */
  double       *cur;                           /* 9 per triangle (only loc's are current); ref.v at rest */
  PetscInt     *cstart, *ctri, capstart, capc; /* candidate triangles per local particle (CSR) */
  double       *slot;                          /* 6 DEM_MESH_SLOTS per local particle: normal, spring */
  PetscInt      capslot;
} DemMesh;
typedef struct {
  DemMesh  m[DEM_MAX_MESHES];
  PetscInt n;
} DemMeshes;

/* Time (dem.c). */
typedef struct {
  PetscReal dt, t, dt_frac, dt_tc;
  PetscReal dt_given; /* -dem_dt as given, for the log when -dem_dt_tc replaces it */
  PetscBool dt_set;   /* -dem_dt given */
  PetscInt  step;
} DemClock;

/* Insertion (insert.c). */
typedef struct {
  PetscInt  lat[3], lat_count; /* lattice sites, and how many of them are filled (-1: all) */
  PetscReal lat_a, lat_origin[3], lat_jitter, lat_speed;
  PetscBool lat_origin_set, random_orient;
  PetscInt  seed;
  char      init_file[PETSC_MAX_PATH_LEN];
  /* where the inserted particles came from, by id (placement.c): the file's are below file_end
     (0: no file), the lattice's follow, [file_end, file_end + lat_count) */
  PetscInt  file_end;
  PetscReal init_overlap_max; /* -dem_init_file_overlap_max (radii); 0: from the contact design */
  /* -dem_init_file_radii auto|shapes|own: whether the file's spheres keep their own radii (a
     scene of own sizes) or become shapes by radius; the file's radius range (m) */
  PetscInt  file_radii;
  PetscBool file_own;
  PetscReal file_rmin, file_rmax;
} DemInsertion;

/* The particles that entered and left the run (sources.c, sinks.c): global totals, the same on
 * every rank; the mass balance is initial + inserted - removed = present, in count and in the
 * id checksum (DemStep's -dem_check_every). */
typedef struct {
  PetscInt  inserted, removed;       /* particles */
  PetscReal m_inserted, m_removed;   /* their mass (kg) */
  PetscReal id_inserted, id_removed; /* sums of their ids */
} DemFlow;

/* Outlets (sinks.c): a box, a plane patch or a domain side that removes particles in the
 * window t_start <= t <= t_stop, with its global totals; the particles marked at this step
 * (local indices, increasing, and the outlet of each) wait for the rebuild that removes them. */
#define DEM_MAX_OUTLETS 10 /* -dem_outlet_<k>, k = 0..9; a coupled run may add the 6 sides */
typedef enum {
  DEM_OUTLET_BOX,
  DEM_OUTLET_PATCH,
  DEM_OUTLET_SIDE
} DemOutletKind;
typedef struct {
  DemOutletKind kind;
  char          name[48];                 /* the option that made it, for messages and the summary */
  double        lo[3], hi[3];             /* box */
  double        p[3], e1[3], e2[3], n[3]; /* patch: corner, edges, unit normal */
  int           axis, side;               /* side: axis 0..2, 0 lo / 1 hi */
  double        t_start, t_stop;          /* s */
  PetscInt      removed;                  /* global totals */
  double        m_removed, id_removed;
} DemOutlet;
typedef struct {
  DemOutlet out[DEM_MAX_OUTLETS + 6];
  PetscInt  nout;
  PetscInt *gone, *gone_out, ngone, capgone;
} DemSinks;
/* Particle sources (sources.c): -dem_insert_<k>_*. Geometry and rates as set; the state (counts,
 * mass, candidate counter, batch number, shortfall) is the same on every rank and checkpointed. */
#define DEM_MAX_SOURCES 10
typedef enum {
  DEM_SRC_BOX,
  DEM_SRC_CYLINDER,
  DEM_SRC_PATCH
} DemSourceRegion;
typedef struct {
  PetscInt        k; /* its option index: -dem_insert_<k>_* */
  DemSourceRegion region;
  PetscReal       g[12];               /* box lo,hi; cylinder centre, unit axis, R, L; patch p0, e1, e2 */
  PetscReal       n[3], depth;         /* patch: unit normal (the stream's side) and the slab depth (m) */
  PetscReal       lo[3], hi[3];        /* the region's bounding box (m) */
  PetscReal       rate, mass_rate;     /* 1/s, kg/s; 0: none */
  PetscInt        count;               /* total; < 0: none */
  PetscReal       mass;                /* total (kg); < 0: none */
  PetscReal       start, stop, period; /* s */
  PetscReal       v[3], vspread;       /* m/s */
  PetscBool       random_orient;
  PetscInt        shape, seed, attempts;
  DemPsd          psd;
  PetscReal       m_mean; /* mean particle mass (kg) */
  PetscReal       vol;    /* the region's volume (m^3) */
  /* state */
  PetscInt  inserted, cand, batch, shortfall;
  PetscInt  said, sh_max; /* the log's note (1) and warning (2) printed; the largest shortfall */
  PetscReal m_inserted;
  PetscReal t_caught; /* when the shortfall last returned to 0 (s; < 0: never or not now) */
  PetscReal fill;     /* the region's solids volume fraction after the last batch that left a shortfall */
} DemSource;
typedef struct {
  DemSource    s[DEM_MAX_SOURCES];
  PetscInt     n;
  DemParticle *pend; /* accepted at this step, added by the owner at the rebuild */
  PetscInt     npend, cappend;
} DemSources;

/* External forces from a coupling (external.c): per-particle arrays, NULL unless DemSetExternal
 * switched them on; frozen: nothing is integrated. */
typedef struct {
  double   *fext, *kdrag, *udrag, *jdrag;
  PetscBool on, frozen;
} DemExternalState;

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

/* Internal functions, by file, from the leaves up: a file calls only files listed above it
 * (the DEM's .c files form no circle of calls). */
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
PetscErrorCode DemCheckInDomain(Dem dem);                                                                                                               /* exchange.c */
PetscErrorCode DemGhostsCreate(Dem dem);                                                                                                                /* exchange.c */
PetscErrorCode DemGhostsUpdate(Dem dem);                                                                                                                /* exchange.c */
PetscErrorCode DemMigrateGlobal(Dem dem, DemSpring **recs, PetscInt *nrec, PetscInt *caprec);                                                           /* redistribute.c */
PetscErrorCode DemNeighSetCells(Dem dem, const PetscInt nc[3]);                                                                                         /* neighbours.c */
PetscErrorCode DemNeighSetCells(Dem dem, const PetscInt nc[3]);                                                                                         /* neighbours.c */
PetscErrorCode DemNeighSort(Dem dem);                                                                                                                   /* neighbours.c */
PetscErrorCode DemNeighBuildList(Dem dem);                                                                                                              /* neighbours.c */
PetscErrorCode DemNeighResetCells(Dem dem);                                                                                                             /* neighbours.c */
PetscErrorCode DemNeighDestroy(Dem dem);                                                                                                                /* neighbours.c */
PetscErrorCode DemWallAdd(Dem dem, const char *name, const double p[3], const double n[3], const double v[3]);                                          /* walls.c */
PetscErrorCode DemWallFrictionOption(PetscOptionItems *PetscOptionsObject, Dem dem, const char *opt, PetscInt n, PetscInt first);                       /* walls.c; first < 0: -help, no wall */
PetscErrorCode DemWallsBuildLists(DemWalls *walls, const DemParticles *pt, const DemShapeTable *st, double skin, const DemSpring *recs, PetscInt nrec); /* walls.c */
PetscErrorCode DemContactsWalls(DemParticles *pt, const DemShapeTable *st, const DemContactModel *cm, DemWalls *walls, double dt);                      /* walls.c */
PetscErrorCode DemWallPolygonOptions(PetscOptionItems *PetscOptionsObject, Dem dem);                                                                    /* walls_polygon.c */
PetscErrorCode DemWallCylinderOptions(PetscOptionItems *PetscOptionsObject, Dem dem);                                                                   /* walls_cylinder.c */
PetscErrorCode DemWallsSetFromOptions(Dem dem);                                                                                                         /* walls_options.c */
PetscErrorCode DemWallPairsFill(Dem dem, const DemMaterial *wm, DemPairParams *pw, PetscReal *tc);                                                      /* contact_laws.c: (shape, wall) pairs of material wm */
PetscErrorCode DemMeshesSetFromOptions(PetscOptionItems *PetscOptionsObject, Dem dem);                                                                  /* walls_mesh_options.c */
PetscErrorCode DemMeshesSetUp(Dem dem);                                                                                                                 /* walls_mesh_options.c: materials, after DemMaterialsSetUp */
PetscErrorCode DemMeshesDestroy(Dem dem);                                                                                                               /* walls_mesh_options.c */
PetscErrorCode DemMeshesMove(Dem dem, double t, double *moved);                                                                                         /* walls_mesh.c: the pose at t; the largest travel since the build */
PetscErrorCode DemMeshesBuildLists(Dem dem, const DemSpring *recs, PetscInt nrec);                                                                      /* walls_mesh.c */
PetscErrorCode DemContactsMeshes(Dem dem);                                                                                                              /* walls_mesh.c */
PetscErrorCode DemMeshesSaveSprings(Dem dem, DemSpring **recs, PetscInt *nrec, PetscInt *cap);                                                          /* walls_mesh.c: appends the slots' records, sorted */
PetscErrorCode DemMeshesCheckpoint(Dem dem, IoCkpt ck, PetscBool write);                                                                                /* walls_mesh.c: same rank count */
PetscErrorCode DemMeshTouchConvex(Dem dem, const DemMesh *m, PetscInt i, ConvexContact cc[], int *nc);                                                  /* walls_mesh.c: the face rule */
void           DemMeshMatchSlots(double *sl, int na, const double an[][3], int match[]);                                                                /* walls_mesh.c: springs matched by normal */
PetscErrorCode DemContactsMeshesConvex(Dem dem);                                                                                                        /* convex_contacts.c */
PetscErrorCode DemMeshesStatsLocal(Dem dem, double r[5], PetscInt c[3], double *rmax);                                                                  /* walls_mesh.c: contacts, normal elastic energy */
PetscErrorCode DemMeshesCloseFace(Dem dem, int d, int side, double tol, PetscBool *closed);                                                             /* walls_mesh.c: triangles tiling the face */
PetscErrorCode DemMeshDepth(Dem dem, PetscInt k, PetscInt i, double *depth);                                                                            /* walls_mesh.c: placement check, radii */
PetscBool      DemMeshesBlock(Dem dem, const double x[3], double r);                                                                                    /* walls_mesh.c: a source's candidate meets a triangle */
PetscErrorCode DemContactsPairs(DemParticles *p, const DemShapeTable *st, const DemContactModel *cm, DemNeigh *nl, double dt);                          /* contacts.c */
PetscErrorCode DemContactsPairsConvex(Dem dem);                                                                                                         /* convex_contacts.c */
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
PetscErrorCode DemConvexPairContact(Dem dem, PetscInt i, PetscInt j, ConvexContact *c);                                                                         /* convex_contacts.c: the forces' narrow phase */
PetscErrorCode DemContactsWallsConvex(Dem dem);                                                                                                                 /* convex_contacts.c */
PetscErrorCode DemConvexStatsLocal(Dem dem, double r[5], PetscInt c[3], double *rmax);                                                                          /* convex_diag.c */
PetscErrorCode DemConvexWriteSurface(Dem dem, const double *x, Io io);                                                                                          /* convex_diag.c */
PetscErrorCode DemRotateFirstHalf(DemParticles *p, const DemShapeTable *st, double dt);                                                                         /* rotation.c */
PetscErrorCode DemRotateSecondHalf(DemParticles *p, const DemShapeTable *st, double dt);                                                                        /* rotation.c */
                                                                                                                                                                /* external.c */
PetscErrorCode           DemExternalCheckpointCheck(Dem dem, IoCkpt ck);                                                                                        /* external.c: a coupled checkpoint for a coupled case, a dry one for a dry case */
void                     DemExternalKick(DemParticles *p, const DemShapeTable *st, DemExternalState *e, double h);                                              /* external.c */
PetscErrorCode           DemIntegrateFirstHalf(DemParticles *p, const DemShapeTable *st, DemExternalState *e, PetscBool rotation, double dt, double *maxdisp2); /* integrate.c */
PetscErrorCode           DemIntegrateSecondHalf(DemParticles *p, const DemShapeTable *st, DemExternalState *e, PetscBool rotation, double dt);                  /* integrate.c */
PetscErrorCode           DemInsertSetFromOptions(Dem dem);                                                                                                      /* insert.c */
PetscErrorCode           DemInsert(Dem dem);                                                                                                                    /* insert.c */
PetscErrorCode           DemInsertRestartSizes(Dem dem);                                                                                                        /* insert.c */
double                   DemLatticeSpacing(Dem dem);                                                                                                            /* insert.c */
PetscErrorCode           DemSourcesSetFromOptions(Dem dem);                                                                                                     /* sources_options.c */
PetscErrorCode           DemSourcesSetUp(Dem dem);                                                                                                              /* sources_options.c: after the time step is known */
double                   DemSourceMass(Dem dem, const DemSource *s, double d);                                                                                  /* sources_options.c: a particle of diameter d (kg) */
extern const char *const DemSourceRegionNames[];                                                                                                                /* sources_options.c: box, cylinder, patch */
PetscBool                DemSourcesDue(Dem dem);                                                                                                                /* sources.c: a batch is placed at this step (same on every rank) */
PetscErrorCode           DemSourcesPlace(Dem dem);                                                                                                              /* sources.c: collective; the batch, pending until the rebuild */
PetscErrorCode           DemSourcesAddPending(Dem dem);                                                                                                         /* sources.c: in DemRebuild, ghosts dropped */
PetscErrorCode           DemSourcesCheckpoint(Dem dem, IoCkpt ck, PetscBool write);                                                                             /* sources.c */
PetscErrorCode           DemSourcesDestroy(Dem dem);                                                                                                            /* sources.c */
double                   DemImpactOverlap(Dem dem, const DemPairParams *p);                                                                                     /* diag.c */
PetscErrorCode           DemCheckPlacement(Dem dem);                                                                                                            /* placement.c */
PetscErrorCode           DemRebuild(Dem dem);                                                                                                                   /* rebuild.c */
PetscErrorCode           DemRebuildFrom(Dem dem, DemSpring *recs, PetscInt nrec, PetscInt caprec);                                                              /* rebuild.c */
PetscErrorCode           DemCheckpointNeedsRemap(Dem dem, IoCkpt ck, PetscBool *remap);                                                                         /* checkpoint_remap.c: another rank count or other boxes */
PetscErrorCode           DemCheckpointReadRemap(Dem dem, IoCkpt ck);                                                                                            /* checkpoint_remap.c */

/* Outlets and the mass balance (sinks.c): called by dem.c (DemStep), rebuild.c and the
 * checkpoints; sinks.c calls particles.c and diag.c only. */
PetscErrorCode DemSinksSetFromOptions(Dem dem);
PetscErrorCode DemSinksMark(Dem dem);                                   /* not collective: the particles the outlets take at this step */
PetscErrorCode DemSinksRemove(Dem dem);                                 /* collective: removes the marked ones; global totals */
PetscErrorCode DemCheckBalance(Dem dem);                                /* collective: initial + inserted - removed = present */
PetscErrorCode DemSinksCheckpoint(Dem dem, IoCkpt ck, PetscBool write); /* collective: dem->flow and the outlets' totals */
PetscErrorCode DemSinksDestroy(Dem dem);

/* Checkpoints (checkpoint.c, checkpoint_remap.c). The per-rank counters of dem/counters, in
 * their stored order (DemCkptCounters). */
enum {
  CK_N,
  CK_NG,
  CK_NEXT_ID,
  CK_BUILDS,
  CK_SORTS,
  CK_STEP,
  CK_STATE,
  CK_INITIAL_N,
  CK_NWALL,
  CK_MIGRATED,
  CK_NC0,
  CK_NC1,
  CK_NC2,
  CK_NEED_BUILD,
  DEM_CKPT_NCOUNT
};
