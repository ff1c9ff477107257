/* The implicit linear sink beta (u - u_s) and the implicit viscous option.
 * 1. Brinkman channel: walls at y = 0, H = 1 m, periodic x and z, mean pressure gradient
 *    G = -0.25 Pa/m, mu = 0.01 Pa s, rho = 1 kg/m^3, uniform beta = 0.16 kg m^-3 s^-1
 *    (lambda = sqrt(beta/mu) = 4 /m, boundary layers 0.25 m thick). Steady profile
 *       u(y) = (-G/beta) (1 - cosh(lambda (y - H/2)) / cosh(lambda H/2)).
 *    Run with -fluid_viscous implicit and dt = 0.1 s, about 65 times the explicit viscous limit
 *    at 128 cells, to t = 60 s (the slowest mode decays as exp(-(beta + mu pi^2/H^2) t / rho),
 *    to 1e-6 of the initial error). Checks: max error relative to -G/beta below
 *    0.5% at 32 cells, second order over 32, 64, 128 cells (16 cells, 4 across a boundary layer,
 *    are still pre-asymptotic: order 1.87 from 16 to 32).
 * 2. Stiff sink: periodic box, beta = 1e4, u_s = (0.3, 0, 0) m/s, G = -1 Pa/m, dt = 0.1 s
 *    (beta dt / rho = 1e3, far beyond any explicit limit). The backward-Euler sink relaxes to
 *    u = u_s - G/beta, the error shrinking 1000-fold per step; after 10 steps the error relative
 *    to it is set by the implicit viscous solve (rtol 1e-12) and must be below 1e-10.
 * 3. Continuity with a sink in the Poisson coefficients: inlet/outlet channel with
 *    beta = 1e3 (a cell field moved to the faces by FluidCellsToFaces) and eps = 0.4 beyond
 *    x = 0.5; max |div(eps u)| relative to U/h < 1e-9. */
#include "fluid_common.h"

static PetscReal Lambda = 4, Gmag = 0.25, Beta = 0.16;

static void Brinkman(const PetscReal x[3], PetscReal v[3], void *ctx)
{
  (void)ctx;
  v[0] = Gmag / Beta * (1 - PetscCoshReal(Lambda * (x[1] - 0.5)) / PetscCoshReal(Lambda * 0.5));
  v[1] = v[2] = 0;
}

static PetscErrorCode RunBrinkman(PetscInt N, PetscReal *err)
{
  Domain     dom = {0};
  Fluid      fl;
  FluidStats st;
  Vec        beta;
  char       buf[16];
  PetscReal  l2;

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(buf, sizeof buf, "%d", (int)N));
  PetscCall(PetscOptionsSetValue(NULL, "-da_grid_y", buf));
  PetscCall(TestFluidCreate(1.0, NULL, NULL, &dom, &fl));
  PetscCall(FluidGetDragCoefficient(fl, &beta));
  PetscCall(VecSet(beta, Beta));
  for (PetscInt n = 0; n < 600; n++) PetscCall(FluidStep(fl, 0.1, &st));
  PetscCall(FluidVelocityError(fl, Brinkman, NULL, &l2, err));
  *err /= Gmag / Beta;
  PetscCall(FluidDestroy(&fl));
  PetscCall(DomainDestroy(&dom));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode RunStiff(PetscReal *err)
{
  Domain     dom = {0};
  Fluid      fl;
  FluidStats st;
  Vec        beta, us, u;
  PetscReal  umax, umin;

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsSetValue(NULL, "-domain_periodic_y", "1"));
  PetscCall(PetscOptionsSetValue(NULL, "-da_grid_y", "4"));
  PetscCall(TestFluidCreate(1.0, NULL, NULL, &dom, &fl));
  PetscCall(FluidGetDragCoefficient(fl, &beta));
  PetscCall(FluidGetSolidVelocity(fl, &us));
  PetscCall(VecSet(beta, 1e4));
  PetscCall(VecStrideSet(us, 0, 0.3));
  for (PetscInt n = 0; n < 10; n++) PetscCall(FluidStep(fl, 0.1, &st));
  PetscCall(FluidGetVelocity(fl, &u));
  PetscCall(VecStrideMax(u, 0, NULL, &umax));
  PetscCall(VecStrideMin(u, 0, NULL, &umin));
  const PetscReal target = 0.3 + 1.0 / 1e4;
  *err                   = PetscMax(PetscAbsReal(umax - target), PetscAbsReal(umin - target)) / target;
  PetscCall(FluidDestroy(&fl));
  PetscCall(DomainDestroy(&dom));
  PetscCall(PetscOptionsClearValue(NULL, "-domain_periodic_y"));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscReal StepEps(const PetscReal x[3], void *ctx)
{
  (void)ctx;
  return x[0] < 0.5 ? 1.0 : 0.4;
}

static PetscReal PlugBeta(const PetscReal x[3], void *ctx)
{
  (void)ctx;
  return x[0] < 0.5 ? 0.0 : 1e3;
}

static PetscErrorCode RunPorousPlug(PetscReal *res)
{
  Domain     dom = {0};
  Fluid      fl;
  FluidStats st;
  Vec        beta, eps, bcell, cells[3];
  PetscReal  worst = 0;

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsClearValue(NULL, "-domain_periodic_x"));
  PetscCall(PetscOptionsClearValue(NULL, "-fluid_pressure_gradient"));
  PetscCall(PetscOptionsSetValue(NULL, "-fluid_bc_xlo", "inlet"));
  PetscCall(PetscOptionsSetValue(NULL, "-fluid_bc_xlo_velocity", "0.1,0,0"));
  PetscCall(PetscOptionsSetValue(NULL, "-fluid_bc_xhi", "outlet"));
  PetscCall(PetscOptionsSetValue(NULL, "-da_grid_x", "32"));
  PetscCall(PetscOptionsSetValue(NULL, "-da_grid_y", "16"));
  PetscCall(TestFluidCreate(1.0, NULL, NULL, &dom, &fl));
  /* beta as a cell field, as the coupling will compute it, moved to the faces */
  PetscCall(FluidGetPorosity(fl, &eps));
  PetscCall(VecDuplicate(eps, &bcell));
  PetscCall(FluidSetPorosityFunction(fl, PlugBeta, NULL));
  PetscCall(VecCopy(eps, bcell));
  PetscCall(FluidSetPorosityFunction(fl, StepEps, NULL));
  PetscCall(FluidInitPorosity(fl));
  PetscCall(FluidGetDragCoefficient(fl, &beta));
  cells[0] = cells[1] = cells[2] = bcell;
  PetscCall(FluidCellsToFaces(fl, cells, beta));
  for (PetscInt n = 0; n < 50; n++) {
    PetscCall(FluidStep(fl, 0.05, &st));
    worst = PetscMax(worst, st.div_max * dom.h[0] / 0.1);
  }
  *res = worst;
  PetscCall(VecDestroy(&bcell));
  PetscCall(FluidDestroy(&fl));
  PetscCall(DomainDestroy(&dom));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  PetscInt  Ns[3] = {32, 64, 128};
  PetscReal err[3], o[2], stiff = 1, plug = 1;

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(PetscOptionsSetValue(NULL, "-domain_lo", "0,0,0"));
  PetscCall(PetscOptionsSetValue(NULL, "-domain_hi", "1,1,1"));
  PetscCall(PetscOptionsSetValue(NULL, "-domain_periodic_x", "1"));
  PetscCall(PetscOptionsSetValue(NULL, "-domain_periodic_z", "1"));
  PetscCall(PetscOptionsSetValue(NULL, "-da_grid_x", "2"));
  PetscCall(PetscOptionsSetValue(NULL, "-da_grid_z", "2"));
  PetscCall(PetscOptionsSetValue(NULL, "-fluid_density", "1"));
  PetscCall(PetscOptionsSetValue(NULL, "-fluid_viscosity", "0.01"));
  PetscCall(PetscOptionsSetValue(NULL, "-fluid_pressure_gradient", "-0.25,0,0"));
  PetscCall(PetscOptionsSetValue(NULL, "-fluid_viscous", "implicit"));
  PetscCall(PetscOptionsSetValue(NULL, "-fluid_poisson_ksp_rtol", "1e-12"));
  PetscCall(PetscOptionsSetValue(NULL, "-fluid_poisson_ksp_norm_type", "unpreconditioned"));
  PetscCall(PetscOptionsSetValue(NULL, "-fluid_viscous_ksp_rtol", "1e-12"));
  for (int i = 0; i < 3; i++) PetscCall(RunBrinkman(Ns[i], &err[i]));
  for (int i = 0; i < 2; i++) o[i] = PetscLog2Real(err[i] / err[i + 1]);
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "# Brinkman max error / (-G/beta): %.3e %.3e %.3e (N = 32, 64, 128)\n", (double)err[0], (double)err[1], (double)err[2]));
  PetscCall(CheckBelow("brinkman_implicit_32_cells_max_rel_error", err[0], 5e-3));
  PetscCall(CheckAtLeast("brinkman_implicit_order_32_64", o[0], 1.9));
  PetscCall(CheckAtLeast("brinkman_implicit_order_64_128", o[1], 1.9));
  PetscCall(PetscOptionsSetValue(NULL, "-fluid_pressure_gradient", "-1,0,0"));
  PetscCall(RunStiff(&stiff));
  CheckDetail("beta dt/rho = 1e3");
  PetscCall(CheckBelow("stiff_sink_relaxes_to_us_minus_G_over_beta", stiff, 1e-10));
  PetscCall(RunPorousPlug(&plug));
  PetscCall(CheckBelow("porous_plug_with_sink_continuity_rel_residual", plug, 1e-9));
  PetscCall(PetscFinalize());
  return check_failures ? 1 : 0;
}
