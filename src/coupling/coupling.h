/* Coupling: two-way CFD-DEM exchange between the Dem and the Fluid of a run (Grains3D Part II
 * §4.3, eqs. 9-15; DESIGN §8). Only this module (and the drivers) sees both sides.
 *   - cube kernel (Bernard et al.): each particle's volume is a cube centred on it whose exact
 *     overlap with the cells gives the porosity, and with the face control volumes of the
 *     staggered grid the drag coefficient and the momentum exchange; the fluid velocity at a
 *     particle is the same weighted average (the transpose of the spreading);
 *   - drag F = K (u - U), K = 3 pi mu d F(eps, Re_p), Re_p = rho_f d eps |u - U| / mu, with F from
 *     Beetstra et al. (eq. 15, default), Di Felice, Gidaspow (Ergun / Wen-Yu) or Schiller-Naumann
 *     (single sphere), -cpl_drag;
 *   - particles: M dU/dt = M (1 - rho_f/rho_p) g + contacts + F (eq. 11); fluid: -F (eq. 10);
 *   - one fluid step per -cpl_substeps DEM steps; drag implicit on both sides; the momentum the
 *     particles receive equals the momentum the fluid loses (couple.c explains how).
 * Life cycle: CplCreate -> CplSetFromOptions -> CplSetUp (after DemSetUp and FluidSetUp) ->
 * CplStep ... -> CplDestroy. Options use the prefix -cpl_. */
#pragma once
#include "dem/dem.h"
#include "fluid/fluid.h"

typedef struct _p_Cpl *Cpl;

typedef enum {
  CPL_DRAG_BEETSTRA,
  CPL_DRAG_DIFELICE,
  CPL_DRAG_GIDASPOW,
  CPL_DRAG_SCHILLER
} CplDragLaw;

/* -cpl_mode: twoway (the fluid and the particles act on each other) or oneway (the fluid acts
 * on the particles only: porosity 1, no drag reaction, a single-phase fluid). */
typedef enum {
  CPL_MODE_TWOWAY,
  CPL_MODE_ONEWAY
} CplMode;

/* -cpl_form: the averaged momentum equations' form (Zhou, Kuang, Chu & Yu 2010, J. Fluid Mech.
 * 661:482). B (default): the fluid feels -grad p and the drag law carries the whole fluid-particle
 * force but buoyancy. A: the fluid feels -eps grad p, the particles the pressure-gradient force
 * -V grad p besides a drag eps times the law's (the same force in a steady uniform bed). */
typedef enum {
  CPL_FORM_B,
  CPL_FORM_A
} CplForm;

/* -cpl_init_fluid: the fluid velocity before the first coupling step. rest: zero (the inlet's
 * value on its faces); uniform: the inlet's superficial velocity over the porosity at every
 * face along the inlet's axis; steady: a steady solve through the initial bed, held fixed. */
typedef enum {
  CPL_INIT_REST,
  CPL_INIT_UNIFORM,
  CPL_INIT_STEADY
} CplInitFluid;

/* What one coupling step did. */
typedef struct {
  FluidStats fluid;     /* the fluid step */
  PetscReal  eps_min;   /* smallest cell porosity after the floor */
  PetscInt   clipped;   /* cells whose porosity was raised to -cpl_porosity_floor */
  PetscReal  owed_norm; /* |momentum carried to the next step| (N s), see couple.c */
  PetscReal  drag[3];   /* mean drag force on all particles over the step (N) */
} CplStats;

/* Collective. dom, dem and fluid must outlive the coupling. */
PetscErrorCode CplCreate(Domain *dom, Dem dem, Fluid fluid, Cpl *cpl);
/* Collective. Reads -cpl_drag, -cpl_form, -cpl_mode, -cpl_init_fluid (and its _rtol, _max_steps),
 * -cpl_substeps, -cpl_kernel_scale, -cpl_filter_width, -cpl_porosity_width, -cpl_porosity_floor, -cpl_relaxation_ratio_max,
 * -cpl_self_porosity, -cpl_self_velocity, -cpl_self_fade, -cpl_outlet_remove (the run's length and probes belong to the coupled driver); takes
 * the fluid's density and viscosity from the Fluid (call after FluidSetFromOptions), whose
 * -fluid_gravity must be 0,0,0 (gravity acts on the particles). */
PetscErrorCode CplSetFromOptions(Cpl cpl);
/* Not collective (after CplSetUp). The thinnest rank box, in fluid cells along each axis, that a
 * split or periodic axis may have: 2 (the kernel's ghost cells), more with -cpl_porosity_width
 * (its auxiliary grid's ghost layer). The load balancer keeps its cuts at least this wide. */
PetscErrorCode CplGetMinBoxWidth(Cpl cpl, PetscInt cells[3]);
/* Collective. After DemSetUp and FluidSetUp: attaches the drag arrays to the DEM, projects
 * the initial porosity (one-way: sets it to 1), runs the pre-flight checks (a hard violation
 * is an error), then sets the initial fluid state of -cpl_init_fluid. */
PetscErrorCode CplSetUp(Cpl cpl);
/* Collective. The coupling's part of an exact checkpoint (checkpoint.c, datasets cpl/...): the
 * momentum owed to the fluid, the clock and the counters. Read after CplSetUp (and after
 * FluidCheckpointRead); the per-particle drag arrays are the DEM's (dem/ext_...). */
PetscErrorCode CplCheckpointWrite(Cpl cpl, IoCkpt ck);
PetscErrorCode CplCheckpointRead(Cpl cpl, IoCkpt ck);
/* Prints the pre-flight figures: dt_dem / contact time, coupling step / particle relaxation
 * time, cell size / diameter, kernel side / cell size. */
PetscErrorCode CplView(Cpl cpl, PetscViewer viewer);
/* Collective. After DomainSetOwnership: the fluid, the coupling's own fields (the momentum owed
 * to the fluid) and the particles move onto the new layout (load balancing). Between steps. */
PetscErrorCode CplRedistribute(Cpl cpl);
PetscErrorCode CplDestroy(Cpl *cpl);

/* Collective. One fluid step of length substeps x dt_dem (frozen bed: -fluid_dt), with the DEM
 * sub-cycled inside it; with -fluid_adaptive_dt (a moving bed) the step is n x dt_dem, n the
 * largest whole number up to substeps within the fluid's stability limit (CplGetTimeStep gives
 * the step last taken). */
PetscErrorCode CplStep(Cpl cpl, CplStats *st);
PetscErrorCode CplGetTime(Cpl cpl, PetscReal *t, PetscInt *step);
PetscErrorCode CplGetTimeStep(Cpl cpl, PetscReal *dt);
/* The times the coupling steps end on are multiples of this (s): the coupling step itself, or
 * with adaptive steps (-fluid_adaptive_dt) the DEM step. Cadence tolerances use it. */
PetscErrorCode CplGetStepQuantum(Cpl cpl, PetscReal *dq);
/* Before CplSetUp: the fluid and the coupling will be read from a checkpoint, so set-up skips
 * the initial fluid state (-cpl_init_fluid). */
PetscErrorCode CplSetRestarting(Cpl cpl, PetscBool on);
PetscErrorCode CplGetMode(Cpl cpl, CplMode *mode);
/* DEM steps per coupling step (-cpl_substeps; with adaptive steps the most per step). */
PetscErrorCode CplGetSubsteps(Cpl cpl, PetscInt *substeps);
/* Cell-steps whose porosity was raised to -cpl_porosity_floor since set-up (same on every rank). */
PetscErrorCode CplGetClippedCount(Cpl cpl, PetscInt *count);
/* Particle-steps whose -cpl_self_velocity correction reached its cap (G K >= 0.9: the kernel is
 * hydrodynamically smaller than the particle) since set-up or restart (same on every rank). */
PetscErrorCode CplGetSelfCappedCount(Cpl cpl, PetscInt *count);
/* Collective. The particles' weight less their buoyancy, sum of (m - rho_f V) g (N). */
PetscErrorCode CplGetBuoyantWeight(Cpl cpl, PetscReal w[3]);
/* The run's drag law's packed-bed pressure gradient (Pa/m) at porosity eps and superficial
 * velocity usup (m/s) for the first shape's diameter and the fluid's properties. */
PetscErrorCode CplGetPackedBedGradient(Cpl cpl, PetscReal eps, PetscReal usup, PetscReal *dpdl);
/* Collective. The bed's Sauter mean diameter d32 = sum d^3 / sum d^2 over the particles present
 * (volume-equivalent diameters for convex shapes; m) and its particle density sum m / sum V
 * (kg/m^3); the first shape's diameter and density without particles. */
PetscErrorCode CplGetBedDiameter(Cpl cpl, PetscReal *d32, PetscReal *rhop);
/* The porosity at which the bed: line takes U_mf (not collective): the bed's own eps_bed when
 * the bed is packed (at most CPL_LOOSE_PACKING), else -cpl_umf_porosity (CPL_UMF_POROSITY: a
 * lattice or a dilute start is not the bed that fluidizes); the option, when given, whatever the
 * bed. Returns which of the three it is. */
#define CPL_LOOSE_PACKING 0.445 /* porosity of the loosest random packing of spheres, solids fraction 0.555: Onoda & Liniger, Phys. Rev. Lett. 64 (1990) 2727 */
#define CPL_UMF_POROSITY  0.40  /* default: the voidage at minimum fluidization behind Wen & Yu's constants (AIChE Chem. Eng. Prog. Symp. Ser. 62 (1966) 100; Kunii & Levenspiel, Fluidization Engineering, 2nd ed., 1991, ch. 3) */
typedef enum {
  CPL_UMF_BED,   /* the bed's own porosity: it is packed */
  CPL_UMF_LOOSE, /* the bed is looser than CPL_LOOSE_PACKING: -cpl_umf_porosity's default */
  CPL_UMF_OPTION /* -cpl_umf_porosity given */
} CplUmfPorosity;
CplUmfPorosity CplGetUmfPorosity(Cpl cpl, PetscReal eps_bed, PetscReal *eps);
/* Minimum fluidization of a bed of spheres of diameter d (m; a bed's d32) and density rhop
 * (kg/m^3) at porosity eps (not collective): umf, the run's drag law's superficial velocity (m/s)
 * at which a packed bed of porosity eps carries its buoyant weight (0 when nothing is to carry);
 * Wen & Yu's ar (Archimedes number), re_wy and umf_wy (m/s) at d; eps and d as given. */
typedef struct {
  PetscReal umf, ar, re_wy, umf_wy;
  PetscReal eps, d;
} CplFluidization;
PetscErrorCode CplGetMinFluidization(Cpl cpl, PetscReal eps, PetscReal d, PetscReal rhop, CplFluidization *f);
/* Wall time spent in the fluid solver so far (s), for the measured load-balance weights. */
PetscErrorCode CplGetFluidTime(Cpl cpl, PetscLogDouble *t);

/* Diagnostics (collective). Momentum (N s) of the particles, of the fluid (sum over faces of
 * rho eps_f u V_cell) and the exchange still owed to the fluid. */
PetscErrorCode CplGetMomentum(Cpl cpl, PetscReal pp[3], PetscReal pf[3], PetscReal owed[3]);
/* Solid volume on the grid (sum over cells of (1 - eps) V_cell before the floor) and the sum of
 * the particle volumes (m^3). */
PetscErrorCode CplGetSolidVolume(Cpl cpl, PetscReal *grid, PetscReal *particles);
/* The cell layer containing height z along axis d: its centre zc (m), mean pressure (Pa) and
 * porosity, and the mean superficial velocity (m/s) through the face layer below it; in a vessel
 * that cuts the grid, the means over the open volume and the flux over the open area. */
PetscErrorCode CplGetLayer(Cpl cpl, int d, PetscReal z, PetscReal *zc, PetscReal *p, PetscReal *eps, PetscReal *usup);
/* Collective. The open area (m^2) of the plane of faces of axis d nearest z: the box's cross-section,
 * or, in a vessel that cuts the grid, the faces' open-area fractions times their areas. */
PetscErrorCode CplGetOpenArea(Cpl cpl, int d, PetscReal z, PetscReal *area);
/* Collective. Fluid velocity u (3 per local particle, m/s) and porosity eps (1 per particle) at
 * the particles, as the drag sees them: kernel-weighted averages of the face velocities and of
 * the cell porosity. */
PetscErrorCode CplInterpolate(Cpl cpl, PetscReal *u, PetscReal *eps);
/* Mean porosity of the cells whose centres lie in [z0, z1] along axis d (in a vessel that cuts the
 * grid, over their open volume). */
PetscErrorCode CplMeanPorosity(Cpl cpl, int d, PetscReal z0, PetscReal z1, PetscReal *eps);
/* The total drag coefficient per particle K = 3 pi mu d F (kg/s) of the law at porosity eps and
 * Re_p = rho_f d eps |u - U| / mu; not collective, pure. */
PetscReal CplDragFactor(CplDragLaw law, PetscReal eps, PetscReal re);
/* Pressure gradient magnitude (Pa/m) the law predicts for a uniform bed of spheres of diameter d
 * at porosity eps and superficial velocity U: n K U / eps, n = (1 - eps) / (pi d^3 / 6). */
PetscReal CplPackedBedGradient(CplDragLaw law, PetscReal eps, PetscReal usup, PetscReal d, PetscReal rho, PetscReal mu);

/* Pieces of a coupling step, public for the unit tests of the filter and the smoothing
 * (tests/coupling/test_filter.c, test_smooth.c); a run calls them inside CplStep. All collective.
 *   CplFilter: the diffusion filter (-cpl_filter_width) applied to a global cell (faces false) or
 *     face Vec of the fluid's DMDAs, in place; nothing when off.
 *   CplSmoothProject: the particles' solid fraction on the auxiliary grid of -cpl_porosity_width;
 *   CplSmoothAt: its smoothed value phi at the n local particles and each one's own share (own may
 *     be NULL); CplSmoothSeen: the porosity the drag sees there (fade may be NULL).
 *   CplSetParticleDrag, CplSetFluidDrag: the two halves of a step's drag set-up (the particles'
 *     coefficients and seen velocities; the fluid's face drag and the sum K W v). */
PetscErrorCode CplFilter(Cpl cpl, Vec g, PetscBool faces);
PetscErrorCode CplSmoothProject(Cpl cpl);
PetscErrorCode CplSmoothAt(Cpl cpl, PetscInt n, PetscReal *phi, PetscReal *own);
PetscErrorCode CplSmoothSeen(Cpl cpl, PetscInt n, PetscReal *eps, PetscReal *fade);
PetscErrorCode CplSetParticleDrag(Cpl cpl);
PetscErrorCode CplSetFluidDrag(Cpl cpl);
/* What those tests check (not collective; after CplSetUp): the filter's and the smoothing's own
 * figures and the fields they fill. The Vecs are the coupling's own: read them, do not destroy. */
typedef struct {
  PetscReal cell_vol;      /* fluid cell volume (m^3) */
  double    filter_var;    /* the filter's added Gaussian variance per direction (m^2); 0: off */
  PetscReal filter_lam[3]; /* diffusion number of one sweep per axis */
  PetscInt  filter_sweeps; /* sweeps per filtered field; 0: off */
  PetscReal smooth_sigma;  /* the smoothing's standard deviation per axis (m) */
  PetscReal smooth_h[3];   /* its auxiliary grid's spacing (m) */
  Vec       smooth_solid;  /* its auxiliary grid's solid fraction (global) after CplSmoothProject */
  Vec       kv;            /* face globals: sum K W v of the last CplSetFluidDrag */
} CplTestView;
PetscErrorCode CplGetTestView(Cpl cpl, CplTestView *v);
