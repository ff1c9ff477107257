/* DEM: the particle side of Sable (public interface). A Dem owns its particles (structure of
 * arrays), the shape table, the contact parameters, the walls and the neighbour lists, and
 * advances them with velocity Verlet. It reads its subdomain from the shared Domain and never
 * sees the fluid. Life cycle: DemCreate -> DemSetFromOptions -> DemSetUp -> DemStep... ->
 * DemDestroy. Options use the prefix -dem_ (see -help). */
#pragma once
#include "domain.h"
#include "io/io.h"

typedef struct _p_Dem *Dem;

/* Global diagnostics (collective reductions). Energies in J. */
typedef struct {
  PetscInt  n;             /* particles */
  PetscInt  contacts;      /* particle-particle contacts (overlap > 0) */
  PetscInt  wall_contacts; /* particle-wall contacts */
  PetscReal ke, ke_rot;    /* translational and rotational kinetic energy */
  PetscReal pe_grav;       /* gravitational potential energy, relative to the origin */
  PetscReal pe_spring;     /* elastic energy stored in normal and tangential springs */
  PetscReal max_overlap;   /* largest overlap / radius */
  PetscReal checksum;      /* sum of ids (exact in double up to 2^53) */
} DemStats;

/* One particle as tests and insertion see it. */
typedef struct {
  PetscInt  id, shape;
  PetscReal x[3], v[3], w[3], q[4];
  PetscReal r; /* a sphere's own radius (m) in a scene with sizes of their own; 0: its shape's */
} DemParticle;

PetscErrorCode DemCreate(Domain *dom, Dem *dem);
/* Reads every -dem_ option (material, contact law, walls, insertion, time step, run length). */
PetscErrorCode DemSetFromOptions(Dem dem);
/* Builds shapes and pair tables, inserts particles, checks the time step, builds the lists. */
PetscErrorCode DemSetUp(Dem dem);
/* Before DemSetUp: continue from the open checkpoint ck (read at the end of DemSetUp, kept open
 * by the caller until then) instead of inserting particles (the case's other options must be
 * those of the run that wrote it). NULL: insert. */
PetscErrorCode DemSetRestart(Dem dem, IoCkpt ck);
/* Collective. The DEM's part of an exact checkpoint (checkpoint.c, datasets dem/...): the whole
 * per-rank state a step reads, so that a run continued from it on the same rank count is bitwise
 * the uninterrupted run. */
PetscErrorCode DemCheckpointWrite(Dem dem, IoCkpt ck);
/* Collective. Replaces the state of a set-up Dem by a checkpoint's; one of another rank count is
 * redistributed by position (the run continues as the uninterrupted one to round-off, bitwise
 * with -dem_deterministic); refuses in one line a file missing a dataset or whose particles
 * cannot be mapped onto the domain. */
PetscErrorCode DemCheckpointRead(Dem dem, IoCkpt ck);
PetscErrorCode DemDestroy(Dem *dem);
/* Prints the modules, the contact pre-flight figures (Tc, dt/Tc, overlap estimate). */
PetscErrorCode DemView(Dem dem, PetscViewer viewer);

/* One time step. Collective. */
PetscErrorCode DemStep(Dem dem);
/* The signal the ranks agreed on at the last step's reduction (0: none), for the run loop. */
PetscErrorCode DemGetStopSignal(Dem dem, int *sig);
/* The largest particle radius (a convex shape's bounding radius, m), known after
 * DemSetFromOptions: the driver sizes the background grid with it. */
PetscErrorCode DemGetLargestRadius(Dem dem, PetscReal *r);
PetscErrorCode DemGetTime(Dem dem, PetscReal *t, PetscInt *step);
PetscErrorCode DemGetTimeStep(Dem dem, PetscReal *dt);
/* The option that set the time step: "-dem_dt", or "-dem_dt_tc" when that replaced it. */
PetscErrorCode DemGetTimeStepOption(Dem dem, const char **opt);
PetscErrorCode DemGetStats(Dem dem, DemStats *s);
/* The particles that entered (sources) and left (outlets) since the start, global totals. */
typedef struct {
  PetscInt  inserted, removed;
  PetscReal m_inserted, m_removed; /* kg */
} DemFlowStats;
PetscErrorCode DemGetFlow(Dem dem, DemFlowStats *f);
/* Outlets (sinks.c). DemAddOutletSide: not collective, before the first step; side s (0 lo,
 * 1 hi) of axis d removes the particles that leave the domain across it, name (the option that
 * asked for it) labels it in messages and the summary. DemGetOutletFlow: outlet k's global
 * totals. DemFlowView: collective; the balance initial + inserted - removed = present and each
 * outlet's totals, when the run has outlets or a particle entered or left. */
PetscErrorCode DemAddOutletSide(Dem dem, int d, int s, const char *name);
PetscErrorCode DemGetOutletCount(Dem dem, PetscInt *n);
PetscErrorCode DemGetOutletFlow(Dem dem, PetscInt k, const char **name, PetscInt *removed, PetscReal *mass);
PetscErrorCode DemFlowView(Dem dem, PetscViewer viewer);
/* Collective. One line per particle source (-dem_insert_<k>_*): particles and mass inserted,
 * batches, and the shortfall (particles due that found no room): how far behind it was and when
 * it caught up, or its region's solids fraction. Nothing without sources. */
PetscErrorCode DemViewSources(Dem dem, PetscViewer v);
/* Collective. Stops a diverging run with a message: kinetic energy not finite, or the largest
 * overlap above -dem_overlap_max radii (a time step too large for the stiffness lets particles
 * pass through each other while every number stays finite). s from DemGetStats. */
PetscErrorCode DemCheckHealth(Dem dem, const DemStats *s);
/* Packing fraction of the bed (particle volume over footprint x surface height, the surface
 * being the mean of the highest sphere top per column of one diameter) and mean coordination
 * number (particle-particle contacts per particle). Collective. */
PetscErrorCode DemGetBedFigures(Dem dem, PetscReal *phi, PetscReal *coord);
/* Collective (monitor.c). Along gravity: the centre coordinate below which the fraction frac of
 * the solids mass lies (exactly a particle's coordinate; 0.95 is the monitor's bed height), and
 * the centre of mass coordinate (m). 0, 0 without particles. */
PetscErrorCode DemGetBedHeights(Dem dem, PetscReal frac, PetscReal *h, PetscReal *mean);
/* Collective (monitor.c). Solids mass (kg) and particle count with centres in [lo, hi) (m). */
PetscErrorCode DemGetMassInBox(Dem dem, const PetscReal lo[3], const PetscReal hi[3], PetscReal *mass, PetscInt *count);
/* Collective (monitor.c). The coordinate along gravity of the top of the highest particle: centre
 * plus radius (a convex shape's bounding radius), 0 without particles. */
PetscErrorCode DemGetHighest(Dem dem, PetscReal *top);
/* Collective (monitor.c). The bed surface of the particles whose centres lie in the box [lo, hi)
 * (m): the coordinate along gravity where the solids volume profile in slabs of thickness dz
 * (m), read from the top, first reaches frac times its densest slab (0 without particles). */
PetscErrorCode DemGetBedSurface(Dem dem, const PetscReal lo[3], const PetscReal hi[3], PetscReal dz, PetscReal frac, PetscReal *surface);
/* Collective (monitor.c). Solids mass flow (kg/s) along +axis through the rectangle [lo, hi) of
 * the plane x[axis] = lo[axis]: sum(m v[axis]) / width over the particles whose centre lies
 * within width/2 (m) of the plane and inside the rectangle. */
PetscErrorCode DemGetMassFlow(Dem dem, const PetscReal lo[3], const PetscReal hi[3], int axis, PetscReal width, PetscReal *flow);
PetscErrorCode DemWriteOutput(Dem dem, Io io);
/* Whether the scene has non-spherical (convex) shapes, known after DemSetFromOptions. */
PetscErrorCode DemHasConvexShapes(Dem dem, PetscBool *convex);
/* True volume (m^3) and volume-equivalent diameter (m) of shape s, for the fluid coupling (the
 * cube kernel takes the volume, drag the equivalent diameter); a sphere gives 4/3 pi r^3, 2r.
 * Valid after DemSetUp. Not collective. */
PetscErrorCode DemGetShapeGeometry(Dem dem, PetscInt s, PetscReal *volume, PetscReal *d_eq);

/* Access for tests and drivers: add particles (before DemSetUp or between steps), read them. */
PetscErrorCode DemAddParticle(Dem dem, const DemParticle *p);
PetscErrorCode DemGetLocalCount(Dem dem, PetscInt *n);
PetscErrorCode DemGetParticle(Dem dem, PetscInt i, DemParticle *p);
PetscErrorCode DemSetParticle(Dem dem, PetscInt i, const DemParticle *p);
/* Contact time and restitution the parameters give for a pair of shape s with shape t (t < 0:
 * the wall), at impact speed v (only the hertz law depends on v). */
PetscErrorCode DemGetContactFigures(Dem dem, PetscInt s, PetscInt t, PetscReal v, PetscReal *tc, PetscReal *e);
/* The same for spheres of their own radii ri, rj (m) of materials s, t (t < 0: the wall, rj
 * unused): m* and R* of the two sizes, the material's parameters (valid after DemSetUp). */
PetscErrorCode DemGetContactFiguresSized(Dem dem, PetscInt s, PetscInt t, PetscReal ri, PetscReal rj, PetscReal v, PetscReal *tc, PetscReal *e);
/* Before DemSetFromOptions' callers set up (i.e. before DemSetUp): the scene has spheres of their
 * own radii in [rmin, rmax] (m); widens the range a source or an init file declared
 * (DemShapeTable.r_source_min/max) so that reach, cells and the time-step check cover it. */
PetscErrorCode DemSetOwnSizes(Dem dem, PetscReal rmin, PetscReal rmax);
/* Whether the scene has spheres of their own sizes, and the range of radii it was set up for (m;
 * 0, 0 when not). Not collective. */
PetscErrorCode DemGetOwnSizes(Dem dem, PetscBool *poly, PetscReal *rmin, PetscReal *rmax);
/* Local particle-particle pairs in contact found by the Verlet list ([0]) and by an O(N^2)
 * search over the same positions ([1]), with an order-independent fingerprint of the id pairs
 * of each set; they must agree. Not collective. */
PetscErrorCode DemCountContactsBoth(Dem dem, PetscInt count[2], PetscReal key[2]);

/* Whether the walls keep the particles off the domain face side (0: lower, 1: upper) of axis d:
 * the whole face lies behind or on a plane (a -dem_box side, a -dem_plane_k at the face or
 * inside the domain, a cylinder cap), behind or on a rectangle or polygon spanning it, or
 * outside a cylinder parallel to it (walls.c). Not collective. */
PetscErrorCode DemWallsCloseFace(Dem dem, int d, int side, PetscBool *closed);

/* The vessel (vessel.c): the walls that bound the gas of a coupled run as one level function.
 * DemVesselSetUp (collective, after DemSetUp, in a coupled run only) decides which walls bound the
 * gas, prints one line per wall saying so, builds what the level needs (a mesh's bins) and
 * refuses a mesh asked to bound the gas that is not closed; *any: whether some wall does.
 * DemVesselLevel (not collective; the same on every rank): phi(x) > 0 in the gas, < 0 in the
 * solid, the minimum of the signed distances (m) of those walls (a mesh's clamped to +-2 fluid
 * cells); its ctx is the Dem. The fluid's FluidLevelFn. */
PetscErrorCode DemVesselSetUp(Dem dem, PetscBool *any);
/* Not collective. Whether DemVesselSetUp found walls that bound the gas (false before it). */
PetscErrorCode DemVesselGetActive(Dem dem, PetscBool *any);
PetscReal      DemVesselLevel(const PetscReal x[3], void *dem);

/* Coupling hooks (external.c). DemGetArrays: read-only views of the particle arrays, local
 * particles first, then ghosts (copies of other ranks' particles and periodic images); valid until the next
 * DemStep or DemAddParticle (a list rebuild may re-sort, a growth may move them). */
typedef struct {
  PetscInt         nlocal, nghost;
  const PetscReal *x, *v; /* position (m), velocity (m/s), xyz interleaved */
  const PetscInt  *id, *shape;
  const PetscReal *r; /* each sphere's own radius (m) in a scene of own sizes; NULL: its shape's (DemGetShapeGeometry) */
} DemArrays;
PetscErrorCode DemGetArrays(Dem dem, DemArrays *a);
/* Not collective. A number that changes whenever the local particles' positions or order may
 * have changed (DemSetUp, DemStep, DemAddParticle, DemSetParticle, list rebuilds, DemRedistribute):
 * a coupling keeps what it derived from positions while it is unchanged. */
PetscErrorCode DemGetState(Dem dem, PetscInt *state);
/* Radius (m) and mass (kg, known after DemSetUp) of shape s; number of shapes. */
PetscErrorCode DemGetShape(Dem dem, PetscInt s, PetscReal *radius, PetscReal *mass);
PetscErrorCode DemGetShapeCount(Dem dem, PetscInt *n);
PetscErrorCode DemGetGravity(Dem dem, PetscReal g[3]);
/* Per-local-particle arrays a coupling writes (they follow re-sorts; valid as DemGetArrays):
 * every translational half kick of length h becomes, with m the mass and F the contact and
 * gravity force,
 *   v <- (v + h ((F + fext)/m + k u/m)) / (1 + h k/m),   j <- j + h k (u - v),
 * i.e. a drag k (u - v) implicit in v, and j accumulates the drag impulse the particle actually
 * received (zero it when a coupling step starts). */
typedef struct {
  PetscReal *fext; /* constant external force (N), 3 per particle */
  PetscReal *k;    /* drag coefficient (kg/s), 1 per particle */
  PetscReal *u;    /* fluid velocity the drag pulls towards (m/s), 3 per particle */
  PetscReal *j;    /* drag impulse received (N s), 3 per particle */
} DemExternal;
/* Not collective. Allocates (zeroed) or frees the arrays above. A coupled run's restart switches
 * them on before DemSetUp, so that the checkpoint's arrays (dem/ext_...) are read back. */
PetscErrorCode DemSetExternal(Dem dem, PetscBool on);
PetscErrorCode DemGetExternal(Dem dem, DemExternal *e);
/* A frozen DEM integrates nothing (a packed bed). Option -dem_frozen, read by
 * DemExternalSetFromOptions (the driver calls it after DemSetFromOptions). */
PetscErrorCode DemExternalSetFromOptions(Dem dem);
PetscErrorCode DemSetFrozen(Dem dem, PetscBool frozen);
PetscErrorCode DemGetFrozen(Dem dem, PetscBool *frozen);

/* Load balancing hooks (redistribute.c, DemRedistribute in rebuild.c). DemRedistribute:
 * collective; after the Domain changed its ownership (DomainSetOwnership) every particle moves to
 * the rank that now owns its centre, with its full state, its tangential springs and its coupling
 * state; ghosts and lists are rebuilt. Call between steps. DemGetHaloWidth: the ghost halo
 * 2 r_max + skin (m), the thinnest a rank box may be along a split or periodic axis (valid after
 * DemSetUp). DemGetCellCounts: adds the number of local particles whose centre lies in each
 * owned cell of the Domain's grid to count[], indexed over the global grid, x fastest (not
 * collective). */
PetscErrorCode DemRedistribute(Dem dem);
PetscErrorCode DemGetHaloWidth(Dem dem, PetscReal *reach);
PetscErrorCode DemGetCellCounts(Dem dem, PetscInt *count);
/* Wall time this rank spent computing forces and integrating since DemSetUp (s; no waiting for
 * other ranks): the particle cost that -lb_weight measured divides by particle-steps. */
PetscErrorCode DemGetComputeTime(Dem dem, PetscLogDouble *t);
/* Mesh walls for the balancer (redistribute.c; not collective). DemGetMeshCount: the number of
 * mesh walls (the same on every rank). DemGetCellMeshCounts: adds to count[] (as DemGetCellCounts)
 * the candidate triangles, all meshes, of the local particles whose centre lies in each cell: the
 * triangles each one tests every step. DemGetMeshTime: the wall time this rank spent in the mesh
 * contacts (s, part of DemGetComputeTime's) and the candidate-steps it served, since DemSetUp. */
PetscErrorCode DemGetMeshCount(Dem dem, PetscInt *n);
PetscErrorCode DemGetCellMeshCounts(Dem dem, PetscInt *count);
PetscErrorCode DemGetMeshTime(Dem dem, PetscLogDouble *t, PetscReal *cand);
