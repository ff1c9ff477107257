/* Taylor-Green vortex, the exact decaying solution of the Navier-Stokes equations in the
 * periodic box [0, 2 pi]^2 (eps = 1, z periodic with two cells, w = 0):
 *   u = sin x cos y F(t),  v = -cos x sin y F(t),  F = exp(-2 nu t),
 * with rho = 1 kg/m^3, nu = mu = 0.1 Pa s (Re = 10 on the box), up to T = 1 s. The time step
 * scales as h^2 (dt = 0.5 h^2 s), so the first-order-in-time parts of the scheme (forward Euler
 * viscous term, pressure increment) also contribute O(h^2) and the whole error must fall at
 * second order over 16, 32, 64 cells. Checks: max and RMS velocity error relative to F(T), order
 * >= 1.9 for central advection; the TVD option is reported and must converge at order >= 1.5
 * (the van Leer limiter clips the smooth extrema). */
#include "fluid_common.h"

static void Exact(const PetscReal x[3], PetscReal v[3], void *ctx)
{
  const PetscReal F = *(const PetscReal *)ctx;
  v[0]              = PetscSinReal(x[0]) * PetscCosReal(x[1]) * F;
  v[1]              = -PetscCosReal(x[0]) * PetscSinReal(x[1]) * F;
  v[2]              = 0;
}

static PetscErrorCode RunVortex(PetscInt N, const char *adv, PetscReal *linf, PetscReal *l2)
{
  Domain          dom = {0};
  Fluid           fl;
  FluidStats      st;
  char            buf[32];
  PetscReal       h = 2 * PETSC_PI / N, F = 1, dt;
  const PetscReal T = 1, nu = 0.1;
  PetscInt        steps;

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(buf, sizeof buf, "%d", (int)N));
  PetscCall(PetscOptionsSetValue(NULL, "-da_grid_x", buf));
  PetscCall(PetscOptionsSetValue(NULL, "-da_grid_y", buf));
  PetscCall(PetscOptionsSetValue(NULL, "-fluid_advection", adv));
  PetscCall(TestFluidCreate(1.0, NULL, NULL, &dom, &fl));
  PetscCall(FluidSetVelocityFunction(fl, Exact, &F));
  steps = (PetscInt)PetscCeilReal(T / (0.5 * h * h));
  dt    = T / steps;
  for (PetscInt n = 0; n < steps; n++) PetscCall(FluidStep(fl, dt, &st));
  F = PetscExpReal(-2 * nu * T);
  PetscCall(FluidVelocityError(fl, Exact, &F, l2, linf));
  *l2 /= F;
  *linf /= F;
  PetscCall(FluidDestroy(&fl));
  PetscCall(DomainDestroy(&dom));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  PetscInt    Ns[3]  = {16, 32, 64};
  const char *adv[2] = {"central", "tvd"};
  PetscReal   linf[3], l2[3];
  char        hi[32];

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(PetscSNPrintf(hi, sizeof hi, "%.12g,%.12g,1", (double)(2 * PETSC_PI), (double)(2 * PETSC_PI)));
  PetscCall(PetscOptionsSetValue(NULL, "-domain_lo", "0,0,0"));
  PetscCall(PetscOptionsSetValue(NULL, "-domain_hi", hi));
  PetscCall(PetscOptionsSetValue(NULL, "-domain_periodic_x", "1"));
  PetscCall(PetscOptionsSetValue(NULL, "-domain_periodic_y", "1"));
  PetscCall(PetscOptionsSetValue(NULL, "-domain_periodic_z", "1"));
  PetscCall(PetscOptionsSetValue(NULL, "-da_grid_z", "2"));
  PetscCall(PetscOptionsSetValue(NULL, "-fluid_density", "1"));
  PetscCall(PetscOptionsSetValue(NULL, "-fluid_viscosity", "0.1"));
  PetscCall(PetscOptionsSetValue(NULL, "-fluid_poisson_ksp_rtol", "1e-10"));
  for (int a = 0; a < 2; a++) {
    const PetscReal bound = a ? 1.5 : 1.9;
    for (int i = 0; i < 3; i++) PetscCall(RunVortex(Ns[i], adv[a], &linf[i], &l2[i]));
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "# Taylor-Green %s, max error / F(T): %.3e %.3e %.3e, RMS: %.3e %.3e %.3e (N = 16, 32, 64)\n", adv[a], (double)linf[0], (double)linf[1], (double)linf[2], (double)l2[0], (double)l2[1], (double)l2[2]));
    for (int i = 0; i < 2; i++) {
      const PetscReal om = PetscLog2Real(linf[i] / linf[i + 1]), o2 = PetscLog2Real(l2[i] / l2[i + 1]);
      PetscCall(CheckAtLeast(CheckName("taylor_green_%s_max_order_%d_%d", adv[a], (int)Ns[i], (int)Ns[i + 1]), om, bound));
      PetscCall(CheckAtLeast(CheckName("taylor_green_%s_rms_order_%d_%d", adv[a], (int)Ns[i], (int)Ns[i + 1]), o2, bound));
    }
  }
  PetscCall(PetscFinalize());
  return check_failures ? 1 : 0;
}
