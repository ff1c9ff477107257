/* Private to src/fluid: the Fluid object and the index arithmetic of the staggered grid.
 * Layout: cell (i,j,k) holds p and eps at its centre; face point (i,j,k) of the face DMDA holds,
 * in component d, the velocity normal to the lower d-face of cell (i,j,k). Kernels work on raw
 * ghosted local arrays with linear offsets: a face point is an offset f into the face array
 * (component d at f + d), a cell an offset c into the cell array; stepping along axis e is
 * f +- fs[e], c +- cs[e]. Both DMDAs have stencil width 2 (the TVD limiter reaches two cells). */
#pragma once
#include "fluid/fluid.h"

typedef enum {
  FLUID_ADV_CENTRAL,
  FLUID_ADV_TVD,
  FLUID_ADV_NONE
} FluidAdvection;
typedef enum {
  FLUID_VISC_EXPLICIT,
  FLUID_VISC_IMPLICIT
} FluidViscous;

#define FLUID_INLET_TABLE_MAX 32

typedef struct {
  FluidBCType type;
  PetscReal   vel[3];  /* inlet velocity now (m/s) */
  PetscReal   vel0[3]; /* -fluid_bc_<face>_velocity: before the table's first time */
  PetscInt    ntab;    /* rows of -fluid_bc_<face>_velocity_table: t, u, v, w (s, m/s) */
  PetscInt    row;     /* the last row reached (-1: none yet) */
  PetscReal   tab[4 * FLUID_INLET_TABLE_MAX];
  /* patches on this face (patch.c; all NULL without one), per face point ia + N[a] ib of the
   * face's tangential axes a = (d + 1) % 3, b = (d + 2) % 3: */
  signed char *pkind; /* 0: the face's own condition; FLUID_BC_INLET or FLUID_BC_OUTLET: a patch's */
  PetscReal   *pvn;   /* patch inlet: superficial velocity along +axis d (m/s) */
  PetscReal   *pp;    /* patch outlet: pressure (Pa) */
} FluidBC;

/* How FluidFillCellGhosts mirrors a cell field at outlet faces: even (eps), odd about the outlet
 * pressure (p; a patch outlet's own pressure), odd about 0 at every outlet (the increment phi). */
#define FLUID_GHOST_EVEN      0
#define FLUID_GHOST_PRESSURE  1
#define FLUID_GHOST_INCREMENT 2

typedef struct _FluidPatches FluidPatches; /* patch.c */

/* -fluid_distributor (distributor.c): a perforated plate on the z-faces of layer k0. */
typedef struct {
  PetscBool        on;
  PetscInt         k0;         /* z-face layer of the plate */
  PetscReal        phi, cd;    /* open-area fraction, orifice discharge coefficient */
  Vec              beff;       /* beta + the vessel's film friction + the plate's linearised resistance (face Vec) */
  PetscObjectState beta_state; /* without a plate: beta's state when beff was made */
} FluidPlate;

/* Geometry of the ghosted local arrays of this rank, and the two DMDAs they come from. */
typedef struct {
  PetscInt  N[3];           /* global cells per axis */
  PetscInt  xs[3], xm[3];   /* owned cells (also the owned face points, plus the extra face) */
  PetscInt  fxm[3];         /* owned face points per axis */
  PetscInt  gcs[3], gcm[3]; /* ghosted cell box */
  PetscInt  gfs[3], gfm[3]; /* ghosted face box */
  PetscInt  cs[3], fs[3];   /* strides of the cell and face local arrays */
  PetscReal h[3], lo[3];
  DM        cda, fda; /* cell DMDA (1 dof), face DMDA (3 dofs) */
} FluidGrid;

/* Properties and body forces (fluid.c options). */
typedef struct {
  PetscReal rho, mu;    /* kg/m^3, Pa s */
  PetscReal gravity[3]; /* -fluid_gravity (m/s^2) */
  PetscReal dpdx[3];    /* -fluid_pressure_gradient: imposed mean pressure gradient (Pa/m) */
} FluidProps;

/* Boundary conditions (bc.c): one per face, the outlet pressure, whether some face is an inlet. */
typedef struct {
  FluidBC   face[3][2];
  PetscReal p_out;     /* outlet pressure (Pa) */
  PetscBool has_inlet; /* some face is an inlet: velocity ghosts read the porosity */
} FluidBCs;

/* Inlet tables in time (inlet.c); the faces' tables are in FluidBC. */
typedef struct {
  PetscBool linear; /* -fluid_inlet_interpolation linear (else step) */
  PetscBool told;   /* the inlet tables' rows at the run's start were announced */
} FluidInlet;

/* The time step and its limits (fluid.c options, step.c). */
typedef struct {
  PetscReal dt;
  PetscBool dt_set;      /* -fluid_dt given */
  char      dt_name[96]; /* FluidSetTimeStepName: how the caller sets dt, for the stability errors' advice */
  PetscReal cfl_max, visc_max;
  PetscBool adaptive; /* -fluid_adaptive_dt */
  PetscReal time;     /* sum of the steps taken (s): the inlet tables' clock */
  PetscInt  nsteps;
} FluidClock;

/* Fields (global) and their ghosted local copies. */
typedef struct {
  Vec              u, p, eps, eps_old, beta, us, src;
  Vec              uloc, ploc, epsloc, epsoldloc;
  PetscObjectState epsold_state; /* eps_old's state when epsoldloc was filled (-1: never) */
} FluidFields;

/* The momentum predictor (momentum.c, step.c): schemes, AB2 history of the advection term, work. */
typedef struct {
  FluidAdvection adv;
  FluidViscous   visc;
  Vec            uhat, advn, adv_old, vis;
  PetscReal      dt_old;
  PetscScalar   *advbuf; /* advection (momentum.c): per ghosted face point, a flux, then a mass flux */
  PetscInt       advbuf_n;
} FluidMomentum;

/* The pressure Poisson solve (poisson.c): matrix, KSP and the preconditioner's reuse. */
typedef struct {
  DM               pda; /* star-stencil copy of cda for the Poisson matrix (same ownership) */
  Vec              coef, coefloc;
  Vec              phi, rhs, philoc;
  Mat              A;
  PetscCount       ncoo;  /* entries of A in the order FluidPoissonAssemble writes them */
  PetscScalar     *coo_v; /* their values (MatSetValuesCOO) */
  KSP              ksp;
  MatNullSpace     nsp;
  PetscBool        singular;
  PetscObjectState eps_state, beta_state;
  PetscReal        dt_mat;
  PetscInt         pc_lag;                                              /* -fluid_poisson_pc_lag: matrix changes a preconditioner may serve */
  PetscReal        pc_growth;                                           /* -fluid_poisson_pc_lag_growth: rebuild when its > growth * its0 + 1 */
  PetscInt         pc_age, pc_its0, pc_its_last, pc_builds, pc_retries; /* changes served, its after the build, last its, builds, failed solves redone */
  PetscReal        dt_pc;
  Vec              eps_pc, beta_pc; /* with FluidSetCheckpointing: the eps and beta of the matrix the preconditioner was built from */
} FluidPoisson;

/* The implicit viscous solve (viscous.c; only with -fluid_viscous implicit). */
typedef struct {
  KSP              ksp;
  DM               da; /* star-stencil copy of fda for its matrix */
  Mat              V;
  Vec              bc, phiu; /* boundary part of its right-hand side; solution work vector */
  PetscObjectState eps_state, beta_state;
  PetscReal        dt_mat;
} FluidImplicitViscous;

/* The vessel (vessel.c): a level function phi (> 0 in the gas) bounding the fluid inside the box,
 * FAVOR open fractions (Hirt & Sicilian 1985). Everything below is NULL/false unless the vessel
 * cuts the grid (cut): the box path then runs unchanged. Local arrays are ghosted copies of the
 * cell and face DMDAs; aloc is the effective open-area fraction (0: closed, u fixed at 0), vloc
 * the open-volume fraction; full marks cells with vol 1 and six fully open faces; a face dof
 * with wall links (the neighbour along axis e, side s, closed by the vessel) has wl[o + d] >= 0,
 * the index of its six wall distances theta (in cells along that axis; 0: no link). */
typedef struct {
  FluidLevelFn level;
  void        *ctx;
  PetscBool    cut;       /* the vessel cuts the grid: the FAVOR path */
  PetscBool    slip;      /* -fluid_vessel_wall slip */
  PetscReal    theta_min; /* -fluid_vessel_theta_min */
  Vec          vol, area; /* global open fractions (FluidGetOpenFractions) */
  Vec          ind;       /* null space of the Poisson matrix without outlet: open cells */
  PetscReal   *aloc, *vloc, *full;
  PetscInt    *wl;    /* per owned face dof: first of its six thetas, or -1 */
  PetscReal   *theta; /* 6 per linked dof: (e, s) at 2 e + s */
  PetscInt     nlink;
  PetscInt     nopen; /* open cells (global) */
  Vec          film;  /* per face dof whose velocity point lies in the solid (no-slip): the wall
                         friction of its open sliver, 3 mu / w^2, w = a_f h (an implicit sink
                         added to beta, FluidBetaOfSolve); NULL when there is none */
} FluidVessel;

/* Log events of the step's phases. */
typedef struct {
  PetscLogEvent predict, poisson, correct;
} FluidEvents;

/* The Fluid: its state grouped by concern, one struct each (above). */
/* The drag's shift of the pressure on bounded faces (faceshift.c): per non-periodic side, one
 * value a face point (index along the face's axes a = (d + 1) % 3, b = (d + 2) % 3: i_a + N_a
 * i_b), the same on every rank; kept while u, beta, u_s and the source keep their states st. */
typedef struct {
  PetscBool        valid, any; /* any: beta is not 0 everywhere (else dp is not filled) */
  PetscObjectState st[4];
  PetscReal       *dp[3][2];
} FluidFaceShift;

struct _p_Fluid {
  MPI_Comm             comm;
  Domain              *dom;
  FluidGrid            g;
  FluidProps           prop;
  FluidBCs             bc;
  FluidInlet           inlet;
  FluidClock           clock;
  FluidFields          fld;
  FluidMomentum        mom;
  FluidPoisson         pois;
  FluidImplicitViscous vimp;
  FluidEvents          ev;
  FluidVessel          ves;
  PetscBool            setup;  /* FluidSetUp done */
  PetscBool            ckpt;   /* FluidSetCheckpointing */
  FluidPatches        *patch;  /* -fluid_patch_<k> (patch.c; NULL without) */
  FluidPlate           plate;  /* -fluid_distributor (distributor.c) */
  FluidFaceShift       fshift; /* faceshift.c */
};

PetscErrorCode FluidFaceShiftUpdate(Fluid, PetscBool *);
PetscReal      FluidFaceShiftAxisShare(const Fluid, int, int, PetscReal, PetscReal);
PetscReal      FluidFaceShiftAt(const Fluid, int, int, const PetscReal *, const PetscReal *);
PetscReal      FluidFaceShiftPoint(const Fluid, int, int, PetscInt);
PetscErrorCode FluidFaceShiftDestroy(Fluid);

static inline PetscInt FluidCellOff(const FluidGrid *g, PetscInt i, PetscInt j, PetscInt k)
{
  return ((k - g->gcs[2]) * g->gcm[1] + (j - g->gcs[1])) * g->gcm[0] + (i - g->gcs[0]);
}
static inline PetscInt FluidFaceOff(const FluidGrid *g, PetscInt i, PetscInt j, PetscInt k)
{
  return 3 * (((k - g->gfs[2]) * g->gfm[1] + (j - g->gfs[1])) * g->gfm[0] + (i - g->gfs[0]));
}
static inline PetscBool FluidPeriodic(Fluid fl, int d)
{
  return fl->bc.face[d][0].type == FLUID_BC_PERIODIC;
}

/* The point of a face map (FluidBC.pkind) of the normal face of axis d at tangential indices
 * q: ghost indices wrap along a periodic axis and clamp to the face along a bounded one. */
static inline PetscInt fluid_face_point(Fluid fl, int d, const PetscInt q[3])
{
  const int a = (d + 1) % 3, b = (d + 2) % 3;
  PetscInt  r[2] = {q[a], q[b]};
  for (int e = 0; e < 2; e++) {
    const int      ax = e ? b : a;
    const PetscInt n  = fl->g.N[ax];
    if (FluidPeriodic(fl, ax)) r[e] = ((r[e] % n) + n) % n;
    else r[e] = PetscMin(PetscMax(r[e], 0), n - 1);
  }
  return r[0] + fl->g.N[a] * r[1];
}

/* The condition at the boundary face point q of side s of axis d: a patch's, else the face's. */
static inline FluidBCType fluid_bc_at(Fluid fl, int d, int s, const PetscInt q[3])
{
  const FluidBC *bc = &fl->bc.face[d][s];
  if (bc->pkind) {
    const signed char k = bc->pkind[fluid_face_point(fl, d, q)];
    if (k) return (FluidBCType)k;
  }
  return bc->type;
}

/* Whether component d at face point idx is an unknown of the momentum equation by the box: not
 * a wall or inlet face (fixed), not the unused extra point of a tangential component. */
static inline PetscBool FluidFaceActiveBox(Fluid fl, int d, const PetscInt idx[3])
{
  for (int e = 0; e < 3; e++) {
    if (FluidPeriodic(fl, e)) continue;
    if (e != d && idx[e] == fl->g.N[e]) return PETSC_FALSE;
  }
  if (FluidPeriodic(fl, d)) return PETSC_TRUE;
  if (idx[d] == 0) return fluid_bc_at(fl, d, 0, idx) == FLUID_BC_OUTLET;
  if (idx[d] == fl->g.N[d]) return fluid_bc_at(fl, d, 1, idx) == FLUID_BC_OUTLET;
  return PETSC_TRUE;
}

/* ... and not closed by the vessel (idx within the ghosted face box). */
static inline PetscBool FluidFaceActive(Fluid fl, int d, const PetscInt idx[3])
{
  if (!FluidFaceActiveBox(fl, d, idx)) return PETSC_FALSE;
  return (PetscBool)(!fl->ves.aloc || fl->ves.aloc[FluidFaceOff(&fl->g, idx[0], idx[1], idx[2]) + d] > 0);
}

/* Loops over the owned face points: local face offset f, local cell offset c, global offset o. */
#define FLUID_FOR_OWNED_FACES(g, idx, f, c, o) \
  for (idx[2] = (g)->xs[2], o = 0; idx[2] < (g)->xs[2] + (g)->fxm[2]; idx[2]++) \
    for (idx[1] = (g)->xs[1]; idx[1] < (g)->xs[1] + (g)->fxm[1]; idx[1]++) \
      for (idx[0] = (g)->xs[0], f = FluidFaceOff(g, idx[0], idx[1], idx[2]), c = FluidCellOff(g, idx[0], idx[1], idx[2]); idx[0] < (g)->xs[0] + (g)->fxm[0]; idx[0]++, f += 3, c++, o += 3)

/* Loops over the owned cells: local cell offset c, global offset o. */
#define FLUID_FOR_OWNED_CELLS(g, idx, c, o) \
  for (idx[2] = (g)->xs[2], o = 0; idx[2] < (g)->xs[2] + (g)->xm[2]; idx[2]++) \
    for (idx[1] = (g)->xs[1]; idx[1] < (g)->xs[1] + (g)->xm[1]; idx[1]++) \
      for (idx[0] = (g)->xs[0], c = FluidCellOff(g, idx[0], idx[1], idx[2]); idx[0] < (g)->xs[0] + (g)->xm[0]; idx[0]++, c++, o++)

/* div(eps u) in the cell at local offsets (f, c), eps on a face the mean of its two cells. */
static inline PetscScalar fluid_mass_divergence(const FluidGrid *g, const PetscScalar *u, const PetscScalar *eps, PetscInt f, PetscInt c)
{
  PetscScalar s = 0;
  for (int d = 0; d < 3; d++) s += (0.5 * (eps[c] + eps[c + g->cs[d]]) * u[f + g->fs[d] + d] - 0.5 * (eps[c] + eps[c - g->cs[d]]) * u[f + d]) / g->h[d];
  return s;
}

/* inlet.c's tables (also the patches'): the velocity of one face at time t and the last row reached (-1: none); rows within 1e-9
 * (relative) of t count as reached, so a clock that accumulated rounding still switches on the
 * step that ends at a row's time. */
static inline PetscInt fluid_inlet_at(const FluidBC *bc, PetscBool linear, PetscReal t, PetscReal v[3])
{
  const PetscReal tr = t + 1e-9 * PetscMax(1.0, PetscAbsReal(t));
  PetscInt        r  = -1;

  for (int k = 0; k < 3; k++) v[k] = bc->vel0[k];
  while (r + 1 < bc->ntab && bc->tab[4 * (r + 1)] <= tr) r++;
  if (r < 0) return r;
  for (int k = 0; k < 3; k++) v[k] = bc->tab[4 * r + 1 + k];
  if (linear && r + 1 < bc->ntab) {
    const PetscReal *a = &bc->tab[4 * r], *b = a + 4, w = PetscMax(0.0, (t - a[0]) / (b[0] - a[0]));
    for (int k = 0; k < 3; k++) v[k] = (1 - w) * a[1 + k] + w * b[1 + k];
  }
  return r;
}

/* FAVOR: sum_d [a_f eps_f u]^+_- / h_d in the cell at local offsets (f, c), a the ghosted
 * open-area fractions. */
static inline PetscScalar fluid_mass_divergence_favor(const FluidGrid *g, const PetscScalar *u, const PetscScalar *eps, const PetscReal *a, PetscInt f, PetscInt c)
{
  PetscScalar s = 0;
  for (int d = 0; d < 3; d++) s += (a[f + g->fs[d] + d] * 0.5 * (eps[c] + eps[c + g->cs[d]]) * u[f + g->fs[d] + d] - a[f + d] * 0.5 * (eps[c] + eps[c - g->cs[d]]) * u[f + d]) / g->h[d];
  return s;
}
/* A cell of the vessel with no active face: its Poisson row is the identity, it has no residual. */
static inline PetscBool FluidCellClosed(Fluid fl, const PetscInt idx[3])
{
  const PetscInt f = FluidFaceOff(&fl->g, idx[0], idx[1], idx[2]);
  for (int d = 0; d < 3; d++) {
    PetscInt up[3] = {idx[0], idx[1], idx[2]};
    up[d]++;
    if (FluidFaceActiveBox(fl, d, idx) && fl->ves.aloc[f + d] > 0) return PETSC_FALSE;
    if (FluidFaceActiveBox(fl, d, up) && fl->ves.aloc[f + fl->g.fs[d] + d] > 0) return PETSC_FALSE;
  }
  return PETSC_TRUE;
}

/* fluid.c: the cell and face DMDAs from the Domain's ownership, and the grid geometry */
PetscErrorCode FluidCreateDMs(Fluid fl);
PetscErrorCode FluidCreateLocals(Fluid fl);
PetscErrorCode FluidSolversDestroy(Fluid fl);
/* bc.c */
PetscErrorCode FluidSetFromOptionsBC(Fluid fl);
PetscErrorCode FluidFillVelocityGhosts(Fluid fl, PetscScalar *u, const PetscScalar *eps);
PetscErrorCode FluidLocalPorosityOld(Fluid fl, PetscBool force);
PetscErrorCode FluidInletsEndStep(Fluid fl);
PetscErrorCode FluidInletFaceValues(Fluid fl, Vec u);
PetscErrorCode FluidFillCellGhosts(Fluid fl, PetscScalar *a, PetscInt ghost, PetscReal outlet_value);
PetscErrorCode FluidBoundaryFaceValues(Fluid fl, Vec u);
PetscErrorCode FluidLocalVelocity(Fluid fl, Vec u, Vec uloc, Vec epsloc);
PetscErrorCode FluidLocalCell(Fluid fl, Vec a, Vec aloc, PetscInt ghost, PetscReal outlet_value);
/* inlet.c: time tables of inlet velocities */
PetscErrorCode FluidSetFromOptionsInlet(Fluid fl);
PetscErrorCode FluidUpdateInlets(Fluid fl, PetscReal t, PetscBool *changed);
/* patch.c: inlet and outlet patches, volume sources */
PetscErrorCode FluidSetFromOptionsPatch(Fluid fl);
PetscErrorCode FluidSetUpPatches(Fluid fl);
PetscErrorCode FluidUpdatePatches(Fluid fl, PetscReal t, PetscBool *changed);
PetscErrorCode FluidPatchesAtClock(Fluid fl);
PetscErrorCode FluidPatchSource(Fluid fl, Vec *src);
PetscErrorCode FluidDestroyPatches(Fluid fl);
PetscErrorCode FluidPatchesRelayout(Fluid fl);
PetscErrorCode FluidPatchInletVelocity(Fluid fl, PetscReal U[3], PetscInt *n);
/* distributor.c: the perforated plate */
PetscErrorCode    FluidSetFromOptionsDistributor(Fluid fl);
PetscErrorCode    FluidResistanceUpdate(Fluid fl);
static inline Vec FluidBetaOfSolve(Fluid fl)
{
  return fl->plate.on || fl->ves.film ? fl->plate.beff : fl->fld.beta;
}
/* momentum.c: explicit terms per unit volume at the active faces of the owned points */
PetscErrorCode FluidAdvectionTerm(Fluid fl, const PetscScalar *u, const PetscScalar *eps, PetscScalar *out);
PetscErrorCode FluidViscousTerm(Fluid fl, const PetscScalar *u, const PetscScalar *eps, PetscBool transpose_only, PetscScalar *out);
/* viscous.c: implicit viscous predictor */
PetscErrorCode FluidViscousCreateKSP(Fluid fl);
PetscErrorCode FluidViscousSetUp(Fluid fl);
PetscErrorCode FluidViscousSolve(Fluid fl, PetscReal dt, Vec rhs, Vec uhat);
/* vessel.c */
PetscErrorCode FluidSetFromOptionsVessel(Fluid fl);
PetscErrorCode FluidVesselSetUp(Fluid fl);
PetscErrorCode FluidVesselDestroy(Fluid fl);
PetscErrorCode FluidVesselZeroClosed(Fluid fl, PetscScalar *uloc);
PetscReal      FluidVesselViscousNumber(Fluid fl, PetscReal dt, const PetscScalar *eps, PetscInt cell[3]);
/* poisson.c */
PetscErrorCode FluidCheckMGLevelsOption(Fluid fl, const char *name);
PetscErrorCode FluidPoissonCreateKSP(Fluid fl);
PetscErrorCode FluidPoissonSetUp(Fluid fl);
PetscErrorCode FluidProject(Fluid fl, PetscReal dt, FluidStats *st);
PetscErrorCode FluidDivergenceMax(Fluid fl, PetscReal dt, PetscReal *dmax);
PetscErrorCode FluidPoissonRestore(Fluid fl, PetscBool current);
