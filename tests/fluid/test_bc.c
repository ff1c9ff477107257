/* Boundary conditions and body forces against exact solutions.
 * 1. Free-slip channel: slip walls at y = 0, 1 m, periodic x and z, mean pressure gradient
 *    G = -1 Pa/m, rho = 1 kg/m^3, mu = 0.01 Pa s, from rest. With no shear at the walls the
 *    fluid accelerates as a plug, u = -G t / rho everywhere; after 50 steps of 0.01 s the max
 *    error relative to u(t) must be at roundoff (< 1e-12).
 * 2. Hydrostatics: a closed box (no-slip walls on all faces), gravity g = (0, 0, -9.81) m/s^2,
 *    rho = 1000 kg/m^3, eps = 0.6 uniform. The fluid stays at rest and the pressure balances
 *    the weight, dp/dz = rho eps g_z: after 20 steps max |u| < 1e-10 m/s and the pressure
 *    gradient between neighbouring cells matches rho eps g_z to 1e-10 relative. */
#include "fluid_common.h"

static void Plug(const PetscReal x[3], PetscReal v[3], void *ctx)
{
  (void)x;
  v[0] = *(const PetscReal *)ctx;
  v[1] = v[2] = 0;
}

static PetscErrorCode RunSlip(PetscReal *err)
{
  Domain     dom = {0};
  Fluid      fl;
  FluidStats st;
  PetscReal  l2, t = 0.5;

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsSetValue(NULL, "-fluid_bc_ylo", "slip"));
  PetscCall(PetscOptionsSetValue(NULL, "-fluid_bc_yhi", "slip"));
  PetscCall(TestFluidCreate(1.0, NULL, NULL, &dom, &fl));
  for (PetscInt n = 0; n < 50; n++) PetscCall(FluidStep(fl, 0.01, &st));
  PetscCall(FluidVelocityError(fl, Plug, &t, &l2, err));
  *err /= t;
  PetscCall(FluidDestroy(&fl));
  PetscCall(DomainDestroy(&dom));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscReal Porosity(const PetscReal x[3], void *ctx)
{
  (void)x;
  (void)ctx;
  return 0.6;
}

static PetscErrorCode RunHydrostatic(PetscReal *umax, PetscReal *gerr)
{
  Domain               dom = {0};
  Fluid                fl;
  FluidStats           st;
  DM                   cda;
  Vec                  u, p, ploc;
  const PetscScalar ***a;
  PetscInt             xs, ys, zs, xm, ym, zm;
  PetscReal            e = 0, target = 1000 * 0.6 * -9.81;

  PetscFunctionBeginUser;
  PetscCall(TestFluidCreate(1.0, NULL, NULL, &dom, &fl));
  PetscCall(FluidSetPorosityFunction(fl, Porosity, NULL));
  PetscCall(FluidInitPorosity(fl));
  for (PetscInt n = 0; n < 20; n++) PetscCall(FluidStep(fl, 0.01, &st));
  PetscCall(FluidGetVelocity(fl, &u));
  PetscCall(VecNorm(u, NORM_INFINITY, umax));
  PetscCall(FluidGetDMs(fl, &cda, NULL));
  PetscCall(FluidGetLocalFields(fl, NULL, &ploc));
  PetscCall(FluidGetPressure(fl, &p));
  PetscCall(DMDAGetCorners(cda, &xs, &ys, &zs, &xm, &ym, &zm));
  PetscCall(DMDAVecGetArrayRead(cda, ploc, (void *)&a));
  for (PetscInt k = PetscMax(zs, 1); k < zs + zm; k++)
    for (PetscInt j = ys; j < ys + ym; j++)
      for (PetscInt i = xs; i < xs + xm; i++) e = PetscMax(e, PetscAbsReal((a[k][j][i] - a[k - 1][j][i]) / dom.h[2] - target) / PetscAbsReal(target));
  PetscCall(DMDAVecRestoreArrayRead(cda, ploc, (void *)&a));
  PetscCall(MPIU_Allreduce(&e, gerr, 1, MPIU_REAL, MPIU_MAX, PETSC_COMM_WORLD));
  PetscCall(FluidDestroy(&fl));
  PetscCall(DomainDestroy(&dom));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  PetscReal slip = 1, umax = 1, gerr = 1;

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(PetscOptionsSetValue(NULL, "-domain_lo", "0,0,0"));
  PetscCall(PetscOptionsSetValue(NULL, "-domain_hi", "1,1,1"));
  PetscCall(PetscOptionsSetValue(NULL, "-da_grid_x", "4"));
  PetscCall(PetscOptionsSetValue(NULL, "-da_grid_y", "8"));
  PetscCall(PetscOptionsSetValue(NULL, "-da_grid_z", "8"));
  PetscCall(PetscOptionsSetValue(NULL, "-fluid_poisson_ksp_rtol", "1e-12"));
  PetscCall(PetscOptionsSetValue(NULL, "-fluid_poisson_ksp_norm_type", "unpreconditioned"));
  PetscCall(PetscOptionsSetValue(NULL, "-domain_periodic_x", "1"));
  PetscCall(PetscOptionsSetValue(NULL, "-domain_periodic_z", "1"));
  PetscCall(PetscOptionsSetValue(NULL, "-fluid_density", "1"));
  PetscCall(PetscOptionsSetValue(NULL, "-fluid_viscosity", "0.01"));
  PetscCall(PetscOptionsSetValue(NULL, "-fluid_pressure_gradient", "-1,0,0"));
  PetscCall(RunSlip(&slip));
  PetscCall(CheckBelow("slip_channel_plug_acceleration_rel_error", slip, 1e-12));
  PetscCall(PetscOptionsClear(NULL));
  PetscCall(PetscOptionsSetValue(NULL, "-domain_lo", "0,0,0"));
  PetscCall(PetscOptionsSetValue(NULL, "-domain_hi", "1,1,1"));
  PetscCall(PetscOptionsSetValue(NULL, "-da_grid_x", "4"));
  PetscCall(PetscOptionsSetValue(NULL, "-da_grid_y", "4"));
  PetscCall(PetscOptionsSetValue(NULL, "-da_grid_z", "8"));
  PetscCall(PetscOptionsSetValue(NULL, "-fluid_poisson_ksp_rtol", "1e-12"));
  PetscCall(PetscOptionsSetValue(NULL, "-fluid_poisson_ksp_norm_type", "unpreconditioned"));
  PetscCall(PetscOptionsSetValue(NULL, "-fluid_gravity", "0,0,-9.81"));
  PetscCall(RunHydrostatic(&umax, &gerr));
  PetscCall(CheckBelow("hydrostatic_box_max_velocity [m/s]", umax, 1e-10));
  PetscCall(CheckBelow("hydrostatic_box_dpdz_rel_error", gerr, 1e-10));
  PetscCall(PetscFinalize());
  return check_failures ? 1 : 0;
}
