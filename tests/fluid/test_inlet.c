/* ranks: 1 2 */
/* Inlet velocity tables (src/fluid/inlet.c) against mass conservation. A column 1 x 1 x 2 m,
 * periodic in x and y, inlet at z = 0, outlet at z = 2, with a porous band (eps = 0.5 for
 * 0.6 < z < 1.4, 1 elsewhere, fixed in time). For an incompressible fluid the volume flux
 * through the outlet, sum over the top faces of eps_f w h_x h_y, must equal the inlet's at the
 * end of every step: U(t_n) A with U the table's value at t_n = n dt. Checked, relative to
 * U(t_n), for 40 steps of 0.01 s:
 *   step:   U = 1 m/s, then 1.5 from t = 0.105 s (between two step ends: the step ending at 0.11
 *           takes it) and 0.5 from t = 0.25 s (Grains3D's switch);
 *   linear: U = 1 m/s up to 0.1 s, then linear to 2 m/s at 0.3 s and 2 after.
 * The Poisson tolerance is 1e-12, the bound 1e-9. On 2 ranks the column is split along z, so
 * inlet and outlet lie on different ranks. The scene: test_inlet.opts. */
#include "fluid_common.h"

static PetscReal Band(const PetscReal x[3], void *ctx)
{
  (void)ctx;
  return x[2] > 0.6 && x[2] < 1.4 ? 0.5 : 1.0;
}

/* The table's value, written out independently of inlet.c. */
static PetscReal Expected(PetscBool linear, PetscReal t)
{
  if (!linear) return t < 0.105 ? 1.0 : (t < 0.25 - 1e-12 ? 1.5 : 0.5);
  if (t <= 0.1) return 1.0;
  if (t >= 0.3) return 2.0;
  return 1.0 + (t - 0.1) / 0.2;
}

/* Volume flux through the outlet face z = L_z over its area. */
static PetscErrorCode OutletVelocity(Fluid fl, const Domain *dom, PetscReal *U)
{
  DM                    cda, fda;
  Vec                   u, eps;
  const PetscScalar ****a, ***e;
  PetscInt              xs, ys, zs, xm, ym, zm, N = dom->cells[2];
  PetscReal             q = 0;

  PetscFunctionBeginUser;
  PetscCall(FluidGetDMs(fl, &cda, &fda));
  PetscCall(FluidGetVelocity(fl, &u));
  PetscCall(FluidGetPorosity(fl, &eps));
  PetscCall(DMDAGetCorners(cda, &xs, &ys, &zs, &xm, &ym, &zm));
  PetscCall(DMDAVecGetArrayDOFRead(fda, u, (void *)&a));
  PetscCall(DMDAVecGetArrayRead(cda, eps, (void *)&e));
  if (zs + zm == N)
    for (PetscInt j = ys; j < ys + ym; j++)
      for (PetscInt i = xs; i < xs + xm; i++) q += e[N - 1][j][i] * a[N][j][i][2] * dom->h[0] * dom->h[1];
  PetscCall(DMDAVecRestoreArrayRead(cda, eps, (void *)&e));
  PetscCall(DMDAVecRestoreArrayDOFRead(fda, u, (void *)&a));
  PetscCall(MPIU_Allreduce(&q, U, 1, MPIU_REAL, MPIU_SUM, PETSC_COMM_WORLD));
  *U /= dom->len[0] * dom->len[1];
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode Run(PetscBool linear, PetscReal *err, PetscReal *Ulast)
{
  Domain      dom = {0};
  Fluid       fl;
  FluidStats  st;
  PetscMPIInt size;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));
  PetscCall(TestSceneLoad(PETSC_COMM_WORLD, "test_inlet.opts", NULL));
  if (size == 2) PetscCall(PetscOptionsInsertString(NULL, "-da_processors_x 1 -da_processors_y 1 -da_processors_z 2"));
  if (linear) PetscCall(PetscOptionsInsertString(NULL, "-fluid_bc_zlo_velocity_table 0.1,0,0,1,0.3,0,0,2 -fluid_inlet_interpolation linear"));
  else PetscCall(PetscOptionsInsertString(NULL, "-fluid_bc_zlo_velocity_table 0.105,0,0,1.5,0.25,0,0,0.5"));
  PetscCall(TestFluidCreate(1.0, Band, NULL, &dom, &fl));
  *err = 0;
  for (PetscInt n = 1; n <= 40; n++) {
    PetscReal U, Ue = Expected(linear, 0.01 * n);
    PetscCall(FluidStep(fl, 0.01, &st));
    PetscCall(OutletVelocity(fl, &dom, &U));
    *err   = PetscMax(*err, PetscAbsReal(U - Ue) / Ue);
    *Ulast = U;
  }
  PetscCall(FluidDestroy(&fl));
  PetscCall(DomainDestroy(&dom));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  PetscReal es = 1, el = 1, us = 0, ul = 0;

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(Run(PETSC_FALSE, &es, &us));
  PetscCall(Run(PETSC_TRUE, &el, &ul));
  CheckDetail("1 -> 1.5 -> 0.5 m/s, last %.6f", (double)us);
  PetscCall(CheckBelow("inlet_table_step_outlet_flux_rel_error", es, 1e-9));
  CheckDetail("ramp 1 -> 2 m/s, last %.6f", (double)ul);
  PetscCall(CheckBelow("inlet_table_linear_outlet_flux_rel_error", el, 1e-9));
  PetscCall(PetscFinalize());
  return check_failures ? 1 : 0;
}
