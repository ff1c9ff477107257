/* Plane Poiseuille flow: a channel of height H = 1 m between no-slip walls at y = 0 and y = H,
 * periodic in x and z, driven by the imposed mean pressure gradient G = -8 Pa/m with
 * rho = 1 kg/m^3, mu = 1 Pa s. The steady profile is u(y) = -G/(2 mu) y (H - y), u_max = 1 m/s.
 * Started from rest, the slowest mode decays as exp(-pi^2 nu t / H^2); at t = 1.6 s it is
 * 1.4e-7 of u_max, far below the discretisation error. Checks: the max error relative to u_max
 * is below 0.5% at 32 cells across, and the error falls at second order over 16, 32, 64 cells
 * (wall ghost values carry an O(h^2) error; interior differences of a parabola are exact).
 * The decomposition check (1, 2, 4 ranks) is tests/fluid/test_ranks.c. */
#include "fluid_common.h"

static void Exact(const PetscReal x[3], PetscReal v[3], void *ctx)
{
  (void)ctx;
  v[0] = 4.0 * x[1] * (1.0 - x[1]);
  v[1] = v[2] = 0;
}

static PetscErrorCode SetOpt(const char *name, const char *value)
{
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsSetValue(NULL, name, value));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode RunChannel(PetscInt N, PetscReal *err, PetscInt *steps)
{
  Domain          dom = {0};
  Fluid           fl;
  FluidStats      st;
  char            buf[32];
  PetscReal       h = 1.0 / N, dt, t = 0, l2;
  const PetscReal T = 1.6;

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(buf, sizeof buf, "%d", (int)N));
  PetscCall(SetOpt("-da_grid_y", buf));
  PetscCall(TestFluidCreate(0.5, NULL, NULL, &dom, &fl));
  /* explicit viscous limit 2 dt nu sum 1/h^2 <= 0.5: hx = hz = 0.5 */
  dt     = 0.45 / (2.0 * (1.0 / (h * h) + 8.0));
  *steps = (PetscInt)PetscCeilReal(T / dt);
  dt     = T / *steps;
  for (PetscInt n = 0; n < *steps; n++, t += dt) PetscCall(FluidStep(fl, dt, &st));
  PetscCall(FluidVelocityError(fl, Exact, NULL, &l2, err));
  PetscCall(FluidDestroy(&fl));
  PetscCall(DomainDestroy(&dom));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  PetscInt  Ns[3] = {16, 32, 64}, steps[3];
  PetscReal err[3], order[2];

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(SetOpt("-domain_lo", "0,0,0"));
  PetscCall(SetOpt("-domain_hi", "1,1,1"));
  PetscCall(SetOpt("-domain_periodic_x", "1"));
  PetscCall(SetOpt("-domain_periodic_z", "1"));
  PetscCall(SetOpt("-da_grid_x", "2"));
  PetscCall(SetOpt("-da_grid_z", "2"));
  PetscCall(SetOpt("-fluid_density", "1"));
  PetscCall(SetOpt("-fluid_viscosity", "1"));
  PetscCall(SetOpt("-fluid_pressure_gradient", "-8,0,0"));
  for (int i = 0; i < 3; i++) PetscCall(RunChannel(Ns[i], &err[i], &steps[i]));
  for (int i = 0; i < 2; i++) order[i] = PetscLog2Real(err[i] / err[i + 1]);
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "# Poiseuille max error / u_max: N=16 %.3e (%d steps), N=32 %.3e, N=64 %.3e\n", (double)err[0], (int)steps[0], (double)err[1], (double)err[2]));
  PetscCall(CheckBelow("poiseuille_32_cells_max_rel_error", err[1], 5e-3));
  PetscCall(CheckAtLeast("poiseuille_order_16_32", order[0], 1.9));
  PetscCall(CheckAtLeast("poiseuille_order_32_64", order[1], 1.9));
  PetscCall(PetscFinalize());
  return check_failures ? 1 : 0;
}
