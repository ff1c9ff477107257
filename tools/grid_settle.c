/* Grid study of the coupled drag on a single sphere (build: make build/tools/grid_settle).
 * Dimensionless: d = 1, rho_f = 1, rho_p = 2, g = 1; the viscosity is chosen so that the
 * Schiller-Naumann terminal Reynolds number is -gs_re, mu = (18 Re F_SN(Re))^(-1/2). The sphere
 * sits in a column periodic in x and y (-gs_width d wide, -gs_height d tall) through which the
 * fluid flows up from an inlet at the law's own terminal velocity at eps = 1 (u_t, by
 * bisection of 3 pi mu d F(1, Re) u_t = (rho_p - rho_f) V g), the fluid started uniform. With
 * a grid-independent coupling the sphere would hang still; it settles or rises by the error.
 * The slip u_t - v_p (fluid inflow minus particle velocity, the particle's terminal
 * velocity relative to the undisturbed fluid) is compared with u_t. Cells of -gs_cell d. The
 * run lasts 20 tau + 10 min(l^2/nu, l/u_t), l = 2 max(h, d) (tau = m/K: the particle's
 * relaxation; the fluid disturbance's diffusion or advection over the kernel's reach); the
 * slip is averaged over its last fifth (drift: its change over that fifth). All -cpl_ options pass through (the law: -cpl_drag).
 * Prints one line "result: key=value ...". */
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

int main(int argc, char **argv)
{
  PetscReal   re = 10, tend, h = 2, width = 32, height = 48, mu, ut, tau, dt, slip = 0, eps, u[3], off = 0.5;
  PetscInt    maxsteps = 4000, nsub = 10;
  char        law[32] = "beetstra", opts[2048];
  CplDragLaw  lw;
  Domain      dom;
  Dem         dem;
  Fluid       fl;
  Cpl         cpl;
  CplStats    st;
  DemParticle p = {0};
  PetscReal  *hist, drift;
  PetscInt    n = 0, nx, nz;

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscOptionsBegin(PETSC_COMM_WORLD, NULL, "grid settling study", NULL);
  PetscCall(PetscOptionsReal("-gs_re", "Schiller-Naumann terminal Reynolds number", NULL, re, &re, NULL));
  PetscCall(PetscOptionsReal("-gs_cell", "Cell size (diameters)", NULL, h, &h, NULL));
  PetscCall(PetscOptionsReal("-gs_width", "Column width (diameters)", NULL, width, &width, NULL));
  PetscCall(PetscOptionsReal("-gs_height", "Column height (diameters)", NULL, height, &height, NULL));
  PetscCall(PetscOptionsReal("-gs_offset", "Particle offset from a cell's lower face along x, y (cells)", NULL, off, &off, NULL));
  PetscCall(PetscOptionsInt("-gs_max_steps", "Most fluid steps", NULL, maxsteps, &maxsteps, NULL));
  PetscCall(PetscOptionsString("-cpl_drag", "Drag law", NULL, law, law, sizeof law, NULL));
  PetscOptionsEnd();
  lw  = !strcmp(law, "schiller") ? CPL_DRAG_SCHILLER : CPL_DRAG_BEETSTRA;
  mu  = 1 / PetscSqrtReal(18 * re * CplDragFactor(CPL_DRAG_SCHILLER, 1, re));
  ut  = TerminalVelocity(lw, mu);
  tau = 2.0 / (18 * mu * CplDragFactor(lw, 1, ut / mu));
  {
    const PetscReal l = 2 * PetscMax(h, 1), tf = PetscMin(l * l / mu, l / ut);
    tend = 20 * tau + 10 * tf;
    dt   = PetscMin(PetscMin(tau, 0.5 * h / ut), tend / 200);
  }
  nx = (PetscInt)(width / h + 0.5);
  nz = (PetscInt)(height / h + 0.5);
  PetscCall(PetscSNPrintf(opts, sizeof opts,
                          "-domain_lo 0,0,0 -domain_hi %g,%g,%g -domain_periodic_x -domain_periodic_y -da_grid_x %d -da_grid_y %d -da_grid_z %d -dem_radius 0.5 -dem_density 2 -dem_kn 1e-2 -dem_gravity 0,0,-1 -dem_lattice 1,1,1 -dem_lattice_spacing 1 -dem_lattice_origin %.17g,%.17g,%.17g -fluid_density 1 -fluid_viscosity %.17g -fluid_viscous implicit -fluid_bc_zlo inlet -fluid_bc_zlo_velocity 0,0,%.17g -fluid_bc_zhi outlet -cpl_init_fluid uniform -cpl_relaxation_ratio_max 10 -dem_dt %.17g -cpl_substeps %d",
                          (double)(nx * h), (double)(nx * h), (double)(nz * h), (int)nx, (int)nx, (int)nz, (double)((nx / 2 + off) * h), (double)((nx / 2 + off) * h), (double)((PetscFloorReal(nz / 3.0) + 0.5) * h), (double)mu, (double)ut, (double)(dt / nsub), (int)nsub));
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
    PetscCall(DemGetParticle(dem, 0, &p));
    hist[n] = ut - p.v[2];
  }
  for (PetscInt k = 4 * n / 5; k < n; k++) slip += hist[k] / (n - 4 * n / 5);
  drift = (hist[n - 1] - hist[4 * n / 5]) / ut;
  PetscCall(CplInterpolate(cpl, u, &eps));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "result: law=%s re=%g cell=%g width=%g mu=%.5g ut=%.6g slip=%.6g err=%+.3f%% eps_seen=%.5f u_seen=%.5g steps=%d t=%.4g tau=%.4g drift=%+.2e\n", law, (double)re, (double)h, (double)(nx * h), (double)mu, (double)ut, (double)slip, (double)(100 * (slip / ut - 1)), (double)eps, (double)u[2], (int)n, (double)(n * dt), (double)tau, (double)drift));
  PetscCall(PetscFree(hist));
  PetscCall(CplDestroy(&cpl));
  PetscCall(FluidDestroy(&fl));
  PetscCall(DemDestroy(&dem));
  PetscCall(DomainDestroy(&dom));
  PetscCall(PetscFinalize());
  return 0;
}
