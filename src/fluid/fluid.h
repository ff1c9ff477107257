/* Fluid: porosity-averaged incompressible Navier-Stokes on a staggered (MAC) grid, Grains3D
 * Part II eqs. (9)-(10):
 *   d(eps)/dt + div(eps u) = 0
 *   rho (d(eps u)/dt + div(eps u u)) = -grad p - beta (u - u_s) + f + 2 mu div(eps D(u))
 * with porosity eps given as a cell field (set by tests or, later, by the coupling), a pointwise
 * implicit linear sink beta (u - u_s) for the drag and an explicit momentum source f, both per
 * unit volume. p and eps live at cell centres, velocity components on the cell faces, on the one
 * decomposition of the run (Domain, DESIGN §1). Units SI.
 *
 * Life cycle: FluidCreate -> FluidSetFromOptions -> FluidSetUp -> (set eps, beta, u_s, f) ->
 * FluidStep ... -> FluidDestroy. The caller sets eps^{n+1} in the porosity Vec before FluidStep;
 * the fluid keeps eps^n itself for the d(eps)/dt term. */
#pragma once
#include "domain.h"
#include "io/io.h"

typedef struct _p_Fluid *Fluid;

/* What one step did: Poisson iterations and final residual norm, max |div(eps u) + deps/dt| over
 * the cells after the projection (1/s), the advective CFL number and the viscous number of the
 * step, and the time step actually taken (s; smaller than asked when adaptive stepping cut it). */
typedef struct {
  PetscInt  poisson_its;
  PetscInt  poisson_pc_builds;  /* Poisson preconditioners built so far (see -fluid_poisson_pc_lag) */
  PetscInt  poisson_pc_retries; /* solves redone with a fresh preconditioner so far */
  PetscReal poisson_rnorm;
  PetscReal div_max;
  PetscReal cfl, visc_number;
  PetscReal dt;
} FluidStats;

/* Collective on the domain's communicator. The domain must outlive the fluid. */
PetscErrorCode FluidCreate(Domain *dom, Fluid *fluid);
/* Collective. Reads the -fluid_ options (-help lists them with units and defaults). */
PetscErrorCode FluidSetFromOptions(Fluid fluid);
/* Collective. Creates the grids, fields (u = 0, p = 0, eps = 1, beta = 0) and the Poisson KSP
 * (prefix -fluid_poisson_, hypre BoomerAMG by default). */
PetscErrorCode FluidSetUp(Fluid fluid);
PetscErrorCode FluidDestroy(Fluid *fluid);

/* Before FluidSetUp: the run writes exact checkpoints, so the fluid keeps what one needs beyond
 * its fields (the porosity and drag coefficient of the matrix the kept Poisson preconditioner
 * was built from: two more Vecs, copied at each rebuild). */
PetscErrorCode FluidSetCheckpointing(Fluid fluid, PetscBool on);
/* Collective. The fluid's part of an exact checkpoint (checkpoint.c, datasets fluid/...): every
 * field and counter a step reads from the previous one, fields in the natural ordering of the
 * grid, so that any rank count reads them back. Write needs FluidSetCheckpointing. Read after
 * FluidSetUp (and after CplSetUp in a coupled run, whose set-up sets the porosity): replaces the
 * state by the checkpoint's; refuses in one line naming the file and the dataset a checkpoint
 * of another grid. */
PetscErrorCode FluidCheckpointWrite(Fluid fluid, IoCkpt ck);
PetscErrorCode FluidCheckpointRead(Fluid fluid, IoCkpt ck);
/* Collective. One global Vec of the fluid's cell or face grid (a Vec of its DMs, or duplicated
 * from one) as dataset name in the grid's natural ordering, and back on any rank count (the
 * coupling's face fields use them too). */
PetscErrorCode FluidCheckpointWriteVec(IoCkpt ck, const char *name, Vec v);
PetscErrorCode FluidCheckpointReadVec(IoCkpt ck, const char *name, Vec v);

/* The vessel (vessel.c): FAVOR on the staggered grid (Hirt & Sicilian, J. Comput. Phys. 1985).
 * The fluid lives where the level function phi(x) > 0 (gas; < 0 solid; its zero set is the wall;
 * it need not be a distance, but with periodic axes it must be periodic). Each cell gets an
 * open-volume fraction vol_c, each face an open-area fraction a_f (both in [0,1]; below 1e-3, and
 * a face whose centre lies in the solid, closed: 0). Continuity becomes
 *   vol_c (eps^{n+1} - eps^n)/dt + sum_d [a_f eps_f u]^+_- / h_d = 0,
 * faces with a_f = 0 are fixed at u = 0, and the viscous term sees the wall at its distance along
 * each grid line (-fluid_vessel_wall noslip|slip, -fluid_vessel_theta_min). */
typedef PetscReal (*FluidLevelFn)(const PetscReal x[3], void *ctx);
/* Before FluidSetUp; collective (every rank passes the same function). NULL: the box. */
PetscErrorCode FluidSetVessel(Fluid fluid, FluidLevelFn level, void *ctx);
/* After FluidSetUp, not collective: whether the vessel cuts the grid (some cell or face not
 * fully open). When it does not, the fluid runs the box code unchanged, bit for bit. */
PetscErrorCode FluidVesselActive(Fluid fluid, PetscBool *cut);
/* Borrowed global Vecs after FluidSetUp (invalid after FluidRedistribute/FluidDestroy):
 * open-volume fraction per cell (cell DM, in [0,1]), open-area fraction per face component
 * (face DM, in [0,1]; the effective one: 0 on every closed face and on the unused extra points
 * of tangential components); both NULL when the vessel does not cut the grid. Closed cells have
 * volume 0 and keep eps = 1 (never read). */
PetscErrorCode FluidGetOpenFractions(Fluid fluid, Vec *vol, Vec *area);

/* Collective. Advances by dt (s): predictor with the implicit sink, projection so that
 * div(eps u) = -(eps^{n+1} - eps^n)/dt to solver tolerance, then eps^n <- eps^{n+1}.
 * Errors (naming dt, the limit and the cell) when dt exceeds the CFL or viscous limit, unless
 * -fluid_adaptive_dt is on, in which case it takes a smaller step reported in stats->dt. */
PetscErrorCode FluidStep(Fluid fluid, PetscReal dt, FluidStats *stats);

/* Collective. The largest step (s) the current velocity and porosity allow: the CFL limit
 * -fluid_cfl_max and, with the explicit viscous term, -fluid_viscous_number_max (PETSC_MAX_REAL
 * for a fluid at rest with the implicit viscous term). A caller that picks its own step from it
 * (the coupling's adaptive step) takes a margin below it. */
PetscErrorCode FluidGetStableTimeStep(Fluid fluid, PetscReal *dtmax);
/* Not collective. How the caller sets the step (an option text such as "-cpl_substeps 5 x
 * -dem_dt 0.001 s"): the stability errors then advise lowering it by name. */
PetscErrorCode FluidSetTimeStepName(Fluid fluid, const char *name);
/* Whether -fluid_adaptive_dt is on. Not collective. */
PetscErrorCode FluidGetAdaptive(Fluid fluid, PetscBool *on);
/* Initial states (init.c). Not collective: the inlets' velocity U (m/s, the superficial
 * velocity of -fluid_bc_<face>_velocity now) and how many inlet faces there are (U = 0 with
 * none); two inlets of different velocities are an error. Without an inlet face, the inlet
 * patches on one box face count as one inlet of their flow over the face's open area. */
PetscErrorCode FluidGetInletVelocity(Fluid fluid, PetscReal U[3], PetscInt *ninlet);
/* Collective. u_f = U_d / eps_f at every active face of component d (eps_f the mean of the two
 * cells' porosity eps^{n+1}), then the boundary values. With a vessel: the open faces (closed
 * ones 0); next to its wall the field is not solenoidal, the first projection corrects it. */
PetscErrorCode FluidSetSuperficialVelocity(Fluid fluid, const PetscReal U[3]);
/* Not collective. The fluid's clock (s, the inlet tables' time) and its step count (0: the next
 * step advects with forward Euler, not Adams-Bashforth); Set puts them back after pseudo steps. */
PetscErrorCode FluidGetClock(Fluid fluid, PetscReal *t, PetscInt *nsteps);
PetscErrorCode FluidSetClock(Fluid fluid, PetscReal t, PetscInt nsteps);

/* Grids: cell DMDA (one dof: p, eps) with the ownership of the domain, face DMDA (three dofs:
 * component d is the velocity normal to the lower d-face of the cell with the same index; along
 * a non-periodic axis it has one point more than the cells, owned by the last rank). */
PetscErrorCode FluidGetDMs(Fluid fluid, DM *cda, DM *fda);
/* Collective. After the Domain changed its ownership (DomainSetOwnership): rebuilds the DMDAs
 * on the new layout and moves every field bit for bit (redistribute.c). DMs and Vecs obtained
 * before are invalid afterwards. */
PetscErrorCode FluidRedistribute(Fluid fluid);
/* The time step of -fluid_dt (s), and whether the option was given (NULL: not asked). */
PetscErrorCode FluidGetTimeStep(Fluid fluid, PetscReal *dt, PetscBool *given);
/* Not collective. The fluid's properties as its options set them (FluidSetFromOptions):
 * -fluid_density rho (kg/m^3), -fluid_viscosity mu (Pa s), -fluid_gravity g (m/s^2). */
PetscErrorCode FluidGetDensity(Fluid fluid, PetscReal *rho);
PetscErrorCode FluidGetViscosity(Fluid fluid, PetscReal *mu);
PetscErrorCode FluidGetGravity(Fluid fluid, PetscReal g[3]);
/* Boundary condition of the face side (0: lower, 1: upper) of axis d (-fluid_bc_{x,y,z}{lo,hi};
 * periodic from -domain_periodic_*); FluidBCNames gives its option value (bc.c). Not collective. */
typedef enum {
  FLUID_BC_PERIODIC,
  FLUID_BC_WALL,
  FLUID_BC_SLIP,
  FLUID_BC_INLET,
  FLUID_BC_OUTLET
} FluidBCType;
extern const char *const FluidBCNames[];
PetscErrorCode           FluidGetBC(Fluid fluid, int d, int side, FluidBCType *type);
/* Borrowed global Vecs, valid until FluidDestroy. eps: porosity eps^{n+1} (cell, set it before
 * FluidStep); eps_old: eps^n (cell, read only); beta: drag coefficient per face component
 * (kg m^-3 s^-1, face; on a wall or inlet face point, which has no momentum equation, beta (u -
 * u_s) V_f is the force the half cell next to the face holds, as a kernel deposits it, V_f the
 * face's momentum volume, V_cell or a_f V_cell in a vessel: a uniform medium has half its
 * density there; the face's pressure reads it, faceshift.c); u_s: solid velocity per face component (m/s); source: explicit momentum
 * source per face component (N/m^3; on a wall or inlet face point, as beta, the half cell's); u: face velocity (m/s); p: pressure (Pa). */
PetscErrorCode FluidGetPorosity(Fluid fluid, Vec *eps);
PetscErrorCode FluidGetPorosityOld(Fluid fluid, Vec *eps_old);
PetscErrorCode FluidGetDragCoefficient(Fluid fluid, Vec *beta);
PetscErrorCode FluidGetSolidVelocity(Fluid fluid, Vec *us);
PetscErrorCode FluidGetMomentumSource(Fluid fluid, Vec *source);
PetscErrorCode FluidGetVelocity(Fluid fluid, Vec *u);
PetscErrorCode FluidGetPressure(Fluid fluid, Vec *p);
/* Collective. The pressure gradient the momentum equation uses, (p_c - p_{c-1})/h + the imposed
 * mean gradient (-fluid_pressure_gradient), into the global face Vec g (Pa/m): at every active
 * face; a face point on a wall or inlet takes its first interior neighbour's (it has no momentum
 * equation); unused and closed face points 0. For the pressure-gradient force on particles. */
PetscErrorCode FluidGetPressureGradient(Fluid fluid, Vec g);
/* Collective. Ghosted local copies for interpolation: the face velocity with boundary ghosts
 * filled from the boundary conditions (two layers), and the pressure with its ghosts. Borrowed,
 * valid until the next FluidStep. */
PetscErrorCode FluidGetLocalFields(Fluid fluid, Vec *uloc, Vec *ploc);
/* Collective (probe.c). The pressure at point x (m), trilinear between the cell centres around
 * it; within half a cell of a non-periodic boundary extrapolated along its normal from the two
 * nearest centre rows (on the face 1.5 p1 - 0.5 p2, exact for a linear pressure), plus at a
 * wall or inlet the drag's shift (faceshift.c: on the face the whole of it, 0 at the first
 * centre) (Pa). */
PetscErrorCode FluidProbePressure(Fluid fluid, const PetscReal x[3], PetscReal *p);
/* Collective. The mean pressure over the open part of the boundary face of axis d (not periodic),
 * side s (0 low, 1 high), weighted by open area (Pa): the set pressure at outlet points, elsewhere
 * the face pressure, the centres' extrapolation plus the drag the particles leave on the face
 * (faceshift.c). */
PetscErrorCode FluidFacePressure(Fluid fluid, int d, int s, PetscReal *pmean);
/* A segment a -> b (line), or an axis-aligned box [a, b] flat along some axes (a rectangle: flat
 * along its normal), in m; name (the option that gave it) labels the error of one that leaves
 * the domain. */
typedef struct {
  PetscReal   a[3], b[3];
  PetscBool   line;
  const char *name;
} FluidSpan;
/* Collective (probe.c). For each of the n spans, the average over it of the interpolant of
 * FluidProbePressure applied to the cell-centred pressure (Pa), porosity (-) and interstitial
 * velocity (3 components, m/s; 0 unless velocity; these two take the nearest centre row near a
 * bounded side, not the extrapolation): avg[5 s + 0..4]. Exact (no sampling), the same bits on
 * any rank count. */
PetscErrorCode FluidAverageFields(Fluid fluid, PetscInt n, const FluidSpan *spans, PetscBool velocity, PetscReal *avg);
/* Collective. Call after changing the velocity Vec by hand (initial conditions): applies the
 * boundary values to the boundary faces. */
PetscErrorCode FluidApplyBoundaryValues(Fluid fluid);
/* Collective. Writes eps, p and the cell-centred velocity into the open frame of io (the fluid
 * mesh is declared on first use), and, when a vessel cuts the grid, its open-volume fraction
 * as the cell field "vessel" (clip at 0.5 to see the vessel). */
PetscErrorCode FluidWriteOutput(Fluid fluid, Io io);
/* Collective. The cell-centred velocity of the owned cells (m/s; per component the mean of the
 * cell's two face values), 3 per cell, x fastest, as FluidWriteOutput writes it; vel has room
 * for 3 x the owned cell count. */
PetscErrorCode FluidGetCellVelocity(Fluid fluid, PetscReal *vel);

/* Analytic fields (fields.c): x is a point (m); a scalar function returns the value, a vector
 * function fills v[3] (m/s). */
typedef PetscReal (*FluidScalarFn)(const PetscReal x[3], void *ctx);
typedef void (*FluidVectorFn)(const PetscReal x[3], PetscReal v[3], void *ctx);
/* Not collective. Sets eps^{n+1} at the owned cell centres. */
PetscErrorCode FluidSetPorosityFunction(Fluid fluid, FluidScalarFn fn, void *ctx);
/* Not collective. Sets each velocity component at its owned face centres, then the boundary
 * values on fixed faces. */
PetscErrorCode FluidSetVelocityFunction(Fluid fluid, FluidVectorFn fn, void *ctx);
/* Collective. RMS and max over all face values (unused extra points excluded) of |u - fn|. */
PetscErrorCode FluidVelocityError(Fluid fluid, FluidVectorFn fn, void *ctx, PetscReal *l2, PetscReal *linf);
/* Collective. Declares the current porosity eps^{n+1} also the previous one (no d(eps)/dt in the
 * next step) and the level of the velocity (its inlet faces U_n / eps_f): call once after setting
 * the initial porosity. */
PetscErrorCode FluidInitPorosity(Fluid fluid);
/* Collective. Face values from cell-centred fields: component d of the face Vec (beta, u_s or
 * source) is the mean of cell[d] over the two cells of the face (the boundary cell's own value
 * on domain faces). For a scalar such as beta pass the same Vec three times. Cell Vecs are
 * global Vecs of the cell DMDA (or of the domain's DMDA: same layout). */
PetscErrorCode FluidCellsToFaces(Fluid fluid, Vec cell[3], Vec face);

/* Inlet and outlet patches -fluid_patch_<k>_* (patch.c; src/fluid/README.md, "Patches"). Not
 * collective: how many. Collective: patch i's option index k, its mean pressure (Pa; on a box
 * face the face pressure, extrapolated to the face, the set pressure on outlet faces) and its
 * mass flow (kg/s) measured from the face fluxes rho eps_f u A: into the domain at an inlet, out
 * of it at an outlet; a source inside the domain: rho sum S_c V_c. */
PetscErrorCode FluidGetPatchCount(Fluid fluid, PetscInt *n);
/* Not collective; from the options alone (before the fluid exists): the indices k of the options
 * -fluid_patch_<k>_... given, sorted, without repeats, the order of the fluid's patches; *idx is
 * freed by the caller (PetscFree). */
PetscErrorCode FluidPatchIndices(PetscInt *n, PetscInt **idx);
PetscErrorCode FluidPatchMeasure(Fluid fluid, PetscInt i, PetscInt *k, PetscReal *p, PetscReal *mdot);
