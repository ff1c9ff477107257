/* Grid study of the coupled drag on a single sphere (build: make build/tools/grid_settle).
 * Dimensionless: d = 1, rho_f = 1, rho_p = 2, g = 1; the viscosity is chosen so that the
 * Schiller-Naumann terminal Reynolds number is -gs_re, mu = (18 Re F_SN(Re))^(-1/2). The sphere
 * sits in a column periodic in x and y (-gs_width d wide, -gs_height d tall, -gs_below d above
 * the inlet) through which the fluid flows up from an inlet at -gs_inflow times the law's own
 * terminal velocity at eps = 1 (u_t, by bisection of 3 pi mu d F(1, Re) u_t = (rho_p - rho_f) V g),
 * the fluid started as -gs_init (uniform, or steady: solved through the particle held still).
 * With a grid-independent coupling the sphere hangs still at -gs_inflow 1. -gs_hold puts it
 * back at its place after every coupling step (its velocity evolves): the slip then converges
 * at a fixed position in the cell (-gs_offset, in cells from a cell's lower corner), without
 * the drift through the cell. Measured: the slip u_in - v_p (the particle's terminal velocity
 * relative to the undisturbed fluid) against u_t. The run lasts -gs_time_factor x
 * (20 tau + 10 min(l^2/nu, l/u_t)), l = 2 max(h, d) (tau = m/K: the particle's relaxation; the
 * disturbance's diffusion or advection over the kernel's reach); the slip is averaged over the
 * last fifth (drift: its change over that fifth). Runs on any number of ranks (the particle is
 * read and held on the rank that owns it). All -cpl_ options pass through (the law:
 * -cpl_drag). Prints one line "result: key=value ..." (self_capped: the particle-steps whose
 * -cpl_self_velocity correction hit its cap). The coupling step is min(-gs_step_tau x tau, h / 2u_t,
 * the run / 200) (-gs_step_tau up to 10, the -cpl_relaxation_ratio_max the tool sets: a longer
 * step reaches a slow steady state, e.g. Re 0.1 in a wide box, in fewer steps); -gs_print_every
 * N prints the slip's error every N steps ("step: n t err"). */
#include "coupling/coupling.h"
#include "dem/dem.h"

static PetscReal TerminalVelocity(CplDragLaw law, PetscReal mu)
{
  PetscReal lo = 0, hi = 100;
  for (int it = 0; it < 200; it++) {
    const PetscReal v = 0.5 * (lo + hi);
    if (3 * PETSC_PI * mu * CplDragFactor(law, 1, v / mu) * v > PETSC_PI / 6) hi = v;
    else lo = v;
  }
  return 0.5 * (lo + hi);
}

/* The particle's position and velocity on every rank (its owner broadcasts them); with hold,
 * its owner puts it back at x0 first. */
static PetscErrorCode ParticleState(Dem dem, const PetscReal *x0, PetscReal x[3], PetscReal v[3])
{
  PetscInt    n;
  PetscReal   loc[6] = {0}, all[6];
  DemParticle p      = {0};

  PetscFunctionBeginUser;
  PetscCall(DemGetLocalCount(dem, &n));
  if (n == 1) {
    PetscCall(DemGetParticle(dem, 0, &p));
    if (x0) {
      for (int k = 0; k < 3; k++) p.x[k] = x0[k];
      PetscCall(DemSetParticle(dem, 0, &p));
    }
    for (int k = 0; k < 3; k++) loc[k] = p.x[k], loc[3 + k] = p.v[k];
  }
  PetscCall(MPIU_Allreduce(loc, all, 6, MPIU_REAL, MPIU_SUM, PETSC_COMM_WORLD));
  for (int k = 0; k < 3; k++) x[k] = all[k], v[k] = all[3 + k];
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  PetscReal  re = 10, tend, h = 2, width = 32, height = 48, below = -1, mu, ut, tau, dt, slip = 0, off[3] = {0.5, 0.5, 0.5}, x0[3], x[3] = {0}, v[3] = {0}, fac = 1, inflow = 1, steptau = 1;
  PetscInt   maxsteps = 4000, nsub = 10, noff = 3, every = 0;
  PetscBool  hold    = PETSC_TRUE;
  char       law[32] = "beetstra", init[32] = "uniform", opts[2048];
  CplDragLaw lw;
  Domain     dom;
  Dem        dem;
  Fluid      fl;
  Cpl        cpl;
  CplStats   st;
  PetscReal *hist, drift, zmin = 1e300, zmax = -1e300;
  PetscInt   n = 0, nx, nz, capped;

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscOptionsBegin(PETSC_COMM_WORLD, NULL, "grid settling study", NULL);
  PetscCall(PetscOptionsReal("-gs_re", "Schiller-Naumann terminal Reynolds number", NULL, re, &re, NULL));
  PetscCall(PetscOptionsReal("-gs_cell", "Cell size (diameters)", NULL, h, &h, NULL));
  PetscCall(PetscOptionsReal("-gs_width", "Column width (diameters)", NULL, width, &width, NULL));
  PetscCall(PetscOptionsReal("-gs_height", "Column height (diameters)", NULL, height, &height, NULL));
  PetscCall(PetscOptionsReal("-gs_below", "Particle height above the inlet (diameters; default a third of the column)", NULL, below, &below, NULL));
  PetscCall(PetscOptionsRealArray("-gs_offset", "Particle offset from a cell's lower corner along x, y, z (cells)", NULL, off, &noff, NULL));
  PetscCall(PetscOptionsBool("-gs_hold", "Put the particle back at its place after every coupling step", NULL, hold, &hold, NULL));
  PetscCall(PetscOptionsReal("-gs_inflow", "Inflow over the law's terminal velocity", NULL, inflow, &inflow, NULL));
  PetscCall(PetscOptionsReal("-gs_time_factor", "Run length over the default", NULL, fac, &fac, NULL));
  PetscCall(PetscOptionsInt("-gs_max_steps", "Most fluid steps", NULL, maxsteps, &maxsteps, NULL));
  PetscCall(PetscOptionsReal("-gs_step_tau", "Coupling step over the particle's relaxation time tau (at most; (0,10])", NULL, steptau, &steptau, NULL));
  PetscCall(PetscOptionsInt("-gs_print_every", "Print the slip's error every this many steps (0: never)", NULL, every, &every, NULL));
  PetscCall(PetscOptionsString("-gs_init", "Initial fluid: uniform or steady", NULL, init, init, sizeof init, NULL));
  PetscCall(PetscOptionsString("-cpl_drag", "Drag law", NULL, law, law, sizeof law, NULL));
  PetscOptionsEnd();
  PetscCheck(steptau > 0 && steptau <= 10, PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE, "-gs_step_tau %g: the coupling step over tau must be in (0,10] (the tool sets -cpl_relaxation_ratio_max 10)", (double)steptau);
  PetscCheck(every >= 0, PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE, "-gs_print_every %d: must be 0 (never) or a positive step count", (int)every);
  lw  = !strcmp(law, "schiller") ? CPL_DRAG_SCHILLER : CPL_DRAG_BEETSTRA;
  mu  = 1 / PetscSqrtReal(18 * re * CplDragFactor(CPL_DRAG_SCHILLER, 1, re));
  ut  = TerminalVelocity(lw, mu);
  tau = 2.0 / (18 * mu * CplDragFactor(lw, 1, ut / mu));
  {
    const PetscReal l = 2 * PetscMax(h, 1), tf = PetscMin(l * l / mu, l / ut);
    tend = fac * (20 * tau + 10 * tf);
    dt   = PetscMin(PetscMin(steptau * tau, 0.5 * h / ut), tend / (200 * fac));
  }
  nx = (PetscInt)(width / h + 0.5);
  nz = (PetscInt)(height / h + 0.5);
  if (below < 0) below = PetscFloorReal(nz / 3.0) * h;
  x0[0] = (nx / 2 + off[0]) * h;
  x0[1] = (nx / 2 + off[1]) * h;
  x0[2] = (PetscFloorReal(below / h) + off[2]) * h;
  PetscCall(PetscSNPrintf(opts, sizeof opts,
                          "-domain_lo 0,0,0 -domain_hi %g,%g,%g -domain_periodic_x -domain_periodic_y -da_grid_x %d -da_grid_y %d -da_grid_z %d -dem_radius 0.5 -dem_density 2 -dem_kn 1e-2 -dem_gravity 0,0,-1 -dem_lattice 1,1,1 -dem_lattice_spacing 1 -dem_lattice_origin %.17g,%.17g,%.17g -fluid_density 1 -fluid_viscosity %.17g -fluid_viscous implicit -fluid_bc_zlo inlet -fluid_bc_zlo_velocity 0,0,%.17g -fluid_bc_zhi outlet -cpl_init_fluid %s -cpl_relaxation_ratio_max 10 -dem_dt %.17g -cpl_substeps %d",
                          (double)(nx * h), (double)(nx * h), (double)(nz * h), (int)nx, (int)nx, (int)nz, (double)x0[0], (double)x0[1], (double)x0[2], (double)mu, (double)(inflow * ut), init, (double)(dt / nsub), (int)nsub));
  PetscCall(PetscOptionsInsertString(NULL, opts));
  PetscCall(DomainCreate(PETSC_COMM_WORLD, 1.0, 1, &dom));
  PetscCall(DemCreate(&dom, &dem));
  PetscCall(DemSetFromOptions(dem));
  PetscCall(DemExternalSetFromOptions(dem));
  PetscCall(FluidCreate(&dom, &fl));
  PetscCall(FluidSetFromOptions(fl));
  PetscCall(CplCreate(&dom, dem, fl, &cpl));
  PetscCall(CplSetFromOptions(cpl));
  PetscCall(DemSetUp(dem));
  PetscCall(FluidSetUp(fl));
  PetscCall(CplSetUp(cpl));
  maxsteps = PetscMin(maxsteps, (PetscInt)(tend / dt + 0.5));
  PetscCall(PetscMalloc1(maxsteps, &hist));
  for (n = 0; n < maxsteps; n++) {
    PetscCall(CplStep(cpl, &st));
    PetscCall(ParticleState(dem, hold ? x0 : NULL, x, v));
    hist[n] = inflow * ut - v[2];
    if (every > 0 && (n + 1) % every == 0) PetscCall(PetscPrintf(PETSC_COMM_WORLD, "step: %d %.6g %+.4f%%\n", (int)(n + 1), (double)((n + 1) * dt), (double)(100 * (hist[n] / ut - 1))));
    zmin = PetscMin(zmin, x[2]);
    zmax = PetscMax(zmax, x[2]);
  }
  for (PetscInt k = 4 * n / 5; k < n; k++) slip += hist[k] / (n - 4 * n / 5);
  drift = (hist[n - 1] - hist[4 * n / 5]) / ut;
  PetscCall(CplGetSelfCappedCount(cpl, &capped));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "result: law=%s re=%g cell=%g width=%g height=%g below=%g off=%g,%g,%g hold=%d init=%s mu=%.5g ut=%.6g slip=%.6g err=%+.3f%% steps=%d t=%.4g tau=%.4g drift=%+.2e z=%.3g..%.3g self_capped=%d\n", law, (double)re, (double)h, (double)(nx * h), (double)(nz * h), (double)below, (double)off[0], (double)off[1], (double)off[2], (int)hold, init, (double)mu, (double)ut, (double)slip, (double)(100 * (slip / ut - 1)), (int)n, (double)(n * dt), (double)tau, (double)drift, (double)zmin, (double)zmax, (int)capped));
  PetscCall(PetscFree(hist));
  PetscCall(CplDestroy(&cpl));
  PetscCall(FluidDestroy(&fl));
  PetscCall(DemDestroy(&dem));
  PetscCall(DomainDestroy(&dom));
  PetscCall(PetscFinalize());
  return 0;
}
