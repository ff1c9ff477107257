/* Coupling private state. Work arrays are ghosted local Vecs of the fluid's cell DMDA (1 dof)
 * and face DMDA (3 dofs, component d on the lower d-face of the cell with the same index), both
 * with stencil width 2 and the domain's ownership, so a particle whose cube reaches one cell
 * beyond its rank's box spreads into the ghost region and DMLocalToGlobal(ADD_VALUES) sums it
 * into the owner's cell. Per-particle stencils are recomputed when needed (cheap, separable). */
#pragma once
#include "coupling/coupling.h"

typedef struct {         /* cube kernel of one particle: separable 1-D overlap fractions */
  PetscInt c0[3], f0[3]; /* first cell, first face control volume, per axis */
  int      nc[3], nf[3];
  double   wc[3][4], wf[3][4];
  double   zc, zf[3]; /* a vessel cutting the grid: 1 / the open share of the kernel's cells and of
                         each component's faces (vessel.c); 1 without */
} CplStencil;

/* The fluid's properties, as the fluid's options give them, and the particles' gravity. */
typedef struct {
  PetscReal rho, mu; /* kg/m^3, Pa s */
  PetscReal g[3];    /* m/s^2 */
} CplFluidProps;

/* The cube kernel (kernel.c): its scale, the per-shape figures, and the cached stencils of the
 * local particles. */
typedef struct {
  PetscReal   scale;                    /* -cpl_kernel_scale: side over the volume-equivalent side */
  PetscReal  *side, *vol, *diam, *mass; /* per shape: kernel side (m), volume (m^3), diameter, mass */
  PetscInt    nshape;
  PetscReal   cell_vol;                  /* fluid cell volume (m^3) */
  CplStencil *stc;                       /* cached kernel stencils of the local particles */
  PetscInt    stc_n, stc_cap, stc_state; /* stc_state: DemGetState when the stencils were computed */
  PetscBool   stc_valid;
} CplKernel;

/* The diffusion filter (filter.c). */
typedef struct {
  double    var;    /* the filter's added Gaussian variance per direction (m^2); 0: off */
  PetscReal width;  /* -cpl_filter_width: full width at half maximum in mean diameters */
  PetscReal d;      /* the mean diameter it uses (m) */
  PetscReal lam[3]; /* diffusion number of one sweep per axis, <= 1/6 */
  PetscInt  n;      /* sweeps per filtered field; 0: off */
} CplFilterState;

/* The drag's porosity on a length in diameters (smooth.c). */
typedef struct {
  PetscReal width;   /* -cpl_porosity_width: full width at half maximum in mean diameters; 0: off */
  PetscReal d;       /* the mean diameter it uses (m) */
  PetscReal sigma;   /* the smoothing's standard deviation per axis (m) */
  PetscInt  n[3];    /* auxiliary cells per fluid cell along each axis */
  PetscReal h[3];    /* auxiliary spacing (m) */
  int       half[3]; /* the 1-D kernels' half widths (nodes) */
  double   *k[3];    /* the 1-D kernels, 2 half + 1 weights summing to one */
  DM        da;      /* the auxiliary grid; NULL until used and after a redistribution */
  Vec       loc, glob;
} CplSmoothing;

/* The drag law and the coupling mode (couple.c options). */
typedef struct {
  CplDragLaw law;
  CplForm    form;
  CplMode    mode;
  PetscReal  eps_floor;   /* -cpl_porosity_floor */
  PetscReal  umf_eps;     /* -cpl_umf_porosity: the porosity of the bed: line's U_mf when the bed is loose */
  PetscBool  umf_eps_set; /* given: U_mf at it whatever the bed */
} CplDragSettings;

/* The drag sees the fluid without the particle's own disturbance (self.c). */
typedef struct {
  PetscBool             eps, u;       /* -cpl_self_porosity, -cpl_self_velocity */
  PetscReal             fade;         /* -cpl_self_fade */
  struct _CplSelfTable *tab;          /* the discrete self-response, built on first use */
  PetscInt              capped_total; /* particle-steps whose self correction hit its cap (not in checkpoints) */
} CplSelf;

/* The start: the fluid's initial state (start.c) and the pre-flight limit (preflight.c). */
typedef struct {
  CplInitFluid init;
  PetscReal    rtol;       /* -cpl_init_fluid_rtol */
  PetscInt     max_steps;  /* -cpl_init_fluid_max_steps */
  PetscInt     its;        /* pseudo steps the steady start took */
  PetscBool    restarting; /* CplSetRestarting: the fluid comes from a checkpoint, no initial state */
  PetscReal    relax_max;  /* -cpl_relaxation_ratio_max */
} CplStart;

/* Steps and time. */
typedef struct {
  PetscInt  substeps;
  PetscBool substeps_set;
  PetscBool frozen, correct;
  PetscBool adaptive; /* -fluid_adaptive_dt: nsub DEM steps of dtd per step (frozen: the fluid's step) */
  PetscInt  nsub;     /* DEM steps of the current step (substeps unless adaptive) */
  PetscReal dtd, dtf; /* the DEM step, -fluid_dt (s) */
  PetscReal dt, t;
  PetscInt  step;
} CplClock;

/* The exchange's fields: work locals and face globals (exchange.c, kernel.c). */
typedef struct {
  Vec cloc, floc[3];  /* work: cell local, face locals (one per field spread together) */
  Vec kv, jf, owed;   /* face globals: sum K W v, spread impulse, momentum owed */
  Vec gp, gploc, phi; /* -cpl_form A: the fluid's pressure gradient of the step's start (global, ghosted), the reaction of the particles' pressure-gradient forces (global); NULL otherwise */
} CplExchange;

/* Diagnostics and measured figures. */
typedef struct {
  PetscInt       clipped_total;
  PetscReal      solid_grid; /* last projection, before the floor */
  PetscReal      eps_min0;   /* the smallest porosity of the initial bed */
  PetscLogDouble t_fluid;    /* wall time in fluid steps (s): the measured cell weight */
} CplDiag;

/* The vessel (vessel.c): the fluid's open fractions when its vessel cuts the grid; the kernel then
 * deposits into the open volume only and reads the open cells and faces only. */
typedef struct {
  PetscBool on;               /* FluidVesselActive: some cell or face is not fully open */
  Vec       vol, area;        /* the fluid's open-volume (cells) and open-area (faces) fractions (borrowed) */
  Vec       vloc, aloc;       /* their ghosted local copies */
  PetscInt  lost, lost_total; /* kernels that met no open cell: at the last stencils, and once warned */
} CplVessel;

/* Log events. */
typedef struct {
  PetscLogEvent project, drag, exchange, dem, filter, smooth;
} CplEvents;

/* The coupling: the objects it couples, then its state grouped by concern (above). */
struct _p_Cpl {
  MPI_Comm        comm;
  Domain         *dom;
  Dem             dem;
  Fluid           fl;
  DM              cda, fda; /* the fluid's */
  CplFluidProps   prop;
  CplKernel       kern;
  CplFilterState  filt;
  CplSmoothing    pw;
  CplDragSettings drag;
  CplSelf         self;
  CplStart        start;
  CplClock        clock;
  CplExchange     ex;
  CplDiag         diag;
  CplVessel       ves;
  CplEvents       ev;
};

/* Whether face point idx, component d, is shared by two cells: not on the boundary of a
 * non-periodic axis (walls, inlets, outlets: the boundary takes the drag there), not an unused
 * extra point of the face grid. The exchange bookkeeping runs over these faces only. */
static inline PetscBool CplInteriorFace(const Domain *dom, int d, const PetscInt idx[3])
{
  for (int e = 0; e < 3; e++) {
    if (dom->periodic[e]) continue;
    if (idx[e] == dom->cells[e] || (e == d && idx[e] == 0)) return PETSC_FALSE;
  }
  return PETSC_TRUE;
}

/* Particle p's volume (m^3), drag diameter (m), kernel side (m) and mass (kg): a sphere of its
 * own size (pa->r, a scene of own sizes) 4/3 pi r^3, 2 r, kscale V^(1/3) and its shape's density
 * times V; otherwise its shape's figures (CplKernelSide, DemGetShape). */
static inline PetscReal CplVolumeOf(Cpl cpl, const DemArrays *pa, PetscInt p)
{
  const PetscReal r = pa->r ? pa->r[p] : 0;
  return pa->r ? 4.0 / 3.0 * PETSC_PI * r * r * r : cpl->kern.vol[pa->shape[p]];
}
static inline PetscReal CplDiameterOf(Cpl cpl, const DemArrays *pa, PetscInt p)
{
  return pa->r ? 2 * pa->r[p] : cpl->kern.diam[pa->shape[p]];
}
static inline PetscReal CplSideOf(Cpl cpl, const DemArrays *pa, PetscInt p)
{
  return pa->r ? cpl->kern.scale * PetscCbrtReal(CplVolumeOf(cpl, pa, p)) : cpl->kern.side[pa->shape[p]];
}
static inline PetscReal CplMassOf(Cpl cpl, const DemArrays *pa, PetscInt p)
{
  const PetscInt s = pa->shape[p];
  return pa->r ? cpl->kern.mass[s] / cpl->kern.vol[s] * CplVolumeOf(cpl, pa, p) : cpl->kern.mass[s];
}

/* kernel.c */
PetscErrorCode CplStencilOf(Cpl cpl, const PetscReal x[3], PetscReal side, CplStencil *s);
PetscErrorCode CplKernelSide(Cpl cpl, PetscInt shape, PetscReal *side, PetscReal *vol, PetscReal *diam);
PetscErrorCode CplProjectPorosity(Cpl cpl, CplStats *st);
PetscErrorCode CplAdmitNewParticles(Cpl cpl);
void           CplInvalidateStencils(Cpl cpl);
PetscErrorCode CplInterpolateSelf(Cpl cpl, PetscReal *u, PetscReal *eps, PetscReal *self, PetscReal *usup);
PetscErrorCode CplFacePorosityScale(Cpl cpl, Vec beta);
PetscErrorCode CplInterpolateFaces(Cpl cpl, Vec floc, PetscReal *out);
typedef struct {
  const PetscReal *val; /* 3 per local particle, or 1 if scalar */
  PetscBool        scalar;
  Vec              out; /* global face Vec */
} CplSpread;
PetscErrorCode CplSpreadFaces(Cpl cpl, PetscInt n, const CplSpread sp[]);
/* smooth.c: the drag's porosity on a length in diameters (-cpl_porosity_width); CplSmoothProject,
 * CplSmoothAt and CplSmoothSeen are in coupling.h */
PetscErrorCode CplSmoothSetUp(Cpl cpl, PetscReal dmean);
PetscErrorCode CplSmoothDestroyGrid(Cpl cpl);
PetscErrorCode CplSmoothDestroy(Cpl cpl);
/* filter.c (CplFilter is in coupling.h) */
PetscErrorCode CplFilterSetUp(Cpl cpl, PetscReal dmean);
PetscErrorCode CplMeanDiameter(Cpl cpl, PetscReal *dmean);
/* exchange.c: the two halves of the drag set-up of a step, CplSetParticleDrag and
 * CplSetFluidDrag (the steady start uses them too), are in coupling.h */
/* self.c: the drag sees the fluid without the particle's own disturbance */
PetscErrorCode CplSeenPorosity(Cpl cpl, PetscInt n, PetscReal *u, PetscReal *eps, PetscReal *fade);
PetscErrorCode CplSelfTableDestroy(Cpl cpl);
PetscReal      CplUndisturbedK(Cpl cpl, PetscInt p, PetscReal d, PetscReal eps, const PetscReal u[3], const PetscReal v[3], PetscReal fade, PetscBool *capped);
/* vessel.c: the fluid's open fractions (after FluidSetUp and after each redistribution) */
PetscErrorCode CplVesselSetUp(Cpl cpl);
PetscErrorCode CplVesselDestroy(Cpl cpl);
PetscErrorCode CplVesselMask(Cpl cpl, Vec v, PetscBool face);
PetscErrorCode CplVesselLost(Cpl cpl);
/* start.c: the fluid's initial state (-cpl_init_fluid) */
PetscErrorCode CplInitFluidState(Cpl cpl);
/* preflight.c */
PetscErrorCode CplPreflight(Cpl cpl, PetscViewer viewer, PetscBool enforce);
