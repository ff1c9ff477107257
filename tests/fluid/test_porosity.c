/* Porosity-weighted continuity and momentum, three checks.
 * 1. Porosity step: a channel x in [0, 1] m (inlet u = 0.1 m/s at x = 0, pressure outlet at x = 1,
 *    no-slip walls in y, periodic z) with eps = 1 for x < 0.5 and 0.4 beyond. Continuity
 *    div(eps u) = 0 makes the volume flux Q(x) = sum over the plane of eps_f u A the same through
 *    every x-plane: max_i |Q_i - Q_in| / Q_in must be at the Poisson solver tolerance (rtol 1e-12).
 * 2. Moving porosity bump: eps = 1 - 0.4 exp(-|x - x0 - c t|^2 / w^2) travelling at c = 0.5 m/s
 *    through the same channel; every step max_cells |div(eps u) + deps/dt| relative to
 *    max |deps/dt| must be at solver tolerance.
 * 3. Uniform eps = 0.4 against eps = 1: Stokes flow (advection off) developing from an inlet, and
 *    a periodic channel with central advection. With U = eps u the equations for uniform eps are
 *    rho dU/dt = -grad p + mu lap U, those of eps = 1, so eps u at eps = 0.4 must equal u at
 *    eps = 1 and the pressures agree, to roundoff; the inlet takes the same superficial U in both
 *    (its face value is U/eps). */
#include "fluid_common.h"

typedef struct {
  PetscReal t, c;
} Bump;

static PetscReal Step(const PetscReal x[3], void *ctx)
{
  (void)ctx;
  return x[0] < 0.5 ? 1.0 : 0.4;
}
static PetscReal Uniform(const PetscReal x[3], void *ctx)
{
  (void)x;
  return *(const PetscReal *)ctx;
}
static PetscReal BumpEps(const PetscReal x[3], void *ctx)
{
  const Bump     *b  = (const Bump *)ctx;
  const PetscReal dx = x[0] - 0.3 - b->c * b->t, dy = x[1] - 0.5, w = 0.12;
  return 1.0 - 0.4 * PetscExpReal(-(dx * dx + dy * dy) / (w * w));
}

static PetscErrorCode ChannelOptions(const char *inlet)
{
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsSetValue(NULL, "-domain_lo", "0,0,0"));
  PetscCall(PetscOptionsSetValue(NULL, "-domain_hi", "1,0.5,0.0625"));
  PetscCall(PetscOptionsSetValue(NULL, "-domain_periodic_z", "1"));
  PetscCall(PetscOptionsSetValue(NULL, "-da_grid_x", "32"));
  PetscCall(PetscOptionsSetValue(NULL, "-da_grid_y", "16"));
  PetscCall(PetscOptionsSetValue(NULL, "-da_grid_z", "2"));
  PetscCall(PetscOptionsSetValue(NULL, "-fluid_bc_xlo", "inlet"));
  PetscCall(PetscOptionsSetValue(NULL, "-fluid_bc_xlo_velocity", inlet));
  PetscCall(PetscOptionsSetValue(NULL, "-fluid_bc_xhi", "outlet"));
  PetscCall(PetscOptionsSetValue(NULL, "-fluid_density", "1"));
  PetscCall(PetscOptionsSetValue(NULL, "-fluid_viscosity", "0.01"));
  PetscCall(PetscOptionsSetValue(NULL, "-fluid_poisson_ksp_rtol", "1e-12"));
  PetscCall(PetscOptionsSetValue(NULL, "-fluid_poisson_ksp_norm_type", "unpreconditioned"));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Volume flux through every x-plane of faces; max relative deviation from the inlet flux. */
static PetscErrorCode PlaneFluxDeviation(Fluid fl, Domain *dom, PetscReal *dev)
{
  DM                    cda, fda;
  Vec                   uloc, eloc, eps;
  const PetscScalar ****u, ***e;
  PetscInt              xs, ys, zs, xm, ym, zm, N = dom->cells[0];
  PetscReal            *q, *Q, m = 0;

  PetscFunctionBeginUser;
  PetscCall(FluidGetDMs(fl, &cda, &fda));
  PetscCall(FluidGetLocalFields(fl, &uloc, NULL));
  PetscCall(FluidGetPorosity(fl, &eps));
  PetscCall(DMGetLocalVector(cda, &eloc));
  PetscCall(DMGlobalToLocal(cda, eps, INSERT_VALUES, eloc));
  PetscCall(PetscCalloc2(N + 1, &q, N + 1, &Q));
  PetscCall(DMDAGetCorners(cda, &xs, &ys, &zs, &xm, &ym, &zm));
  PetscCall(DMDAVecGetArrayDOFRead(fda, uloc, (void *)&u));
  PetscCall(DMDAVecGetArrayRead(cda, eloc, (void *)&e));
  for (PetscInt k = zs; k < zs + zm; k++)
    for (PetscInt j = ys; j < ys + ym; j++)
      for (PetscInt i = xs; i < xs + xm + (xs + xm == N ? 1 : 0); i++) {
        /* eps on the face: mean of the cells, the boundary cell itself on the domain faces */
        const PetscReal ef = (i == 0) ? e[k][j][0] : (i == N ? e[k][j][N - 1] : 0.5 * (e[k][j][i] + e[k][j][i - 1]));
        q[i] += ef * u[k][j][i][0] * dom->h[1] * dom->h[2];
      }
  PetscCall(DMDAVecRestoreArrayRead(cda, eloc, (void *)&e));
  PetscCall(DMDAVecRestoreArrayDOFRead(fda, uloc, (void *)&u));
  PetscCall(DMRestoreLocalVector(cda, &eloc));
  PetscCall(MPIU_Allreduce(q, Q, (PetscMPIInt)(N + 1), MPIU_REAL, MPIU_SUM, PETSC_COMM_WORLD));
  for (PetscInt i = 0; i <= N; i++) m = PetscMax(m, PetscAbsReal(Q[i] - Q[0]) / PetscAbsReal(Q[0]));
  *dev = m;
  PetscCall(PetscFree2(q, Q));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode RunStep(void)
{
  Domain     dom = {0};
  Fluid      fl;
  FluidStats st;
  PetscReal  dev = 0, worst = 0;

  PetscFunctionBeginUser;
  PetscCall(ChannelOptions("0.1,0,0"));
  PetscCall(TestFluidCreate(1.0, Step, NULL, &dom, &fl));
  for (PetscInt n = 0; n < 100; n++) {
    PetscCall(FluidStep(fl, 2e-3, &st));
    PetscCall(PlaneFluxDeviation(fl, &dom, &dev));
    worst = PetscMax(worst, dev);
  }
  CheckDetail("Poisson rtol 1e-12; 100 steps");
  PetscCall(CheckBelow("porosity_step_plane_flux_max_rel_deviation", worst, 1e-9));
  PetscCall(FluidDestroy(&fl));
  PetscCall(DomainDestroy(&dom));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode RunBump(void)
{
  Domain     dom = {0};
  Fluid      fl;
  FluidStats st;
  Bump       b     = {0, 0.5};
  PetscReal  worst = 0, dt = 2e-3, rate;
  Vec        eps, eps0, de;

  PetscFunctionBeginUser;
  PetscCall(ChannelOptions("0.1,0,0"));
  PetscCall(TestFluidCreate(1.0, BumpEps, &b, &dom, &fl));
  PetscCall(FluidGetPorosity(fl, &eps));
  PetscCall(FluidGetPorosityOld(fl, &eps0));
  PetscCall(VecDuplicate(eps, &de));
  for (PetscInt n = 0; n < 100; n++) {
    b.t += dt;
    PetscCall(FluidSetPorosityFunction(fl, BumpEps, &b));
    PetscCall(VecWAXPY(de, -1.0, eps0, eps));
    PetscCall(VecNorm(de, NORM_INFINITY, &rate));
    PetscCall(FluidStep(fl, dt, &st));
    worst = PetscMax(worst, st.div_max / (rate / dt));
  }
  CheckDetail("Poisson rtol 1e-12; 100 steps, residual / max|deps/dt|");
  PetscCall(CheckBelow("moving_bump_continuity_max_rel_residual", worst, 1e-9));
  PetscCall(VecDestroy(&de));
  PetscCall(FluidDestroy(&fl));
  PetscCall(DomainDestroy(&dom));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Runs nsteps with uniform porosity e; returns eps u (face Vec) and p, to be destroyed. */
static PetscErrorCode RunUniform(PetscReal e, PetscInt nsteps, PetscReal dt, Vec *U, Vec *P)
{
  Domain     dom = {0};
  Fluid      fl;
  FluidStats st;
  Vec        u, p;

  PetscFunctionBeginUser;
  PetscCall(TestFluidCreate(1.0, NULL, NULL, &dom, &fl));
  if (e != 1.0) PetscCall(FluidSetPorosityFunction(fl, Uniform, &e));
  PetscCall(FluidInitPorosity(fl));
  for (PetscInt n = 0; n < nsteps; n++) PetscCall(FluidStep(fl, dt, &st));
  PetscCall(FluidGetVelocity(fl, &u));
  PetscCall(FluidGetPressure(fl, &p));
  PetscCall(VecDuplicate(u, U));
  PetscCall(VecAXPY(*U, e, u));
  PetscCall(VecDuplicate(p, P));
  PetscCall(VecCopy(p, *P));
  PetscCall(FluidDestroy(&fl));
  PetscCall(DomainDestroy(&dom));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode CompareUniform(const char *name, const char *inlet_half, const char *inlet_one, PetscReal dt)
{
  Vec       U1, P1, U2, P2;
  PetscReal du, dp, nu, np;

  PetscFunctionBeginUser;
  if (inlet_half) PetscCall(PetscOptionsSetValue(NULL, "-fluid_bc_xlo_velocity", inlet_half));
  PetscCall(RunUniform(0.4, 50, dt, &U2, &P2));
  if (inlet_one) PetscCall(PetscOptionsSetValue(NULL, "-fluid_bc_xlo_velocity", inlet_one));
  PetscCall(RunUniform(1.0, 50, dt, &U1, &P1));
  PetscCall(VecNorm(U1, NORM_INFINITY, &nu));
  PetscCall(VecNorm(P1, NORM_INFINITY, &np));
  PetscCall(VecAXPY(U2, -1.0, U1));
  PetscCall(VecAXPY(P2, -1.0, P1));
  PetscCall(VecNorm(U2, NORM_INFINITY, &du));
  PetscCall(VecNorm(P2, NORM_INFINITY, &dp));
  du /= nu;
  dp = np > 0 ? dp / np : dp; /* a periodic channel has p = 0: compare absolutely (Pa) */
  PetscCall(CheckBelow(CheckName("uniform_eps_%s_superficial_velocity_rel_diff", name), du, 1e-10));
  PetscCall(CheckBelow(CheckName("uniform_eps_%s_pressure_rel_diff", name), dp, 1e-10));
  PetscCall(VecDestroy(&U1));
  PetscCall(VecDestroy(&P1));
  PetscCall(VecDestroy(&U2));
  PetscCall(VecDestroy(&P2));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(RunStep());
  PetscCall(RunBump());
  /* Stokes through-flow from an inlet: superficial inlet velocity 0.1 m/s */
  PetscCall(ChannelOptions("0.1,0,0"));
  PetscCall(PetscOptionsSetValue(NULL, "-fluid_advection", "none"));
  PetscCall(CompareUniform("stokes_inlet", NULL, NULL, 2e-3));
  /* periodic channel with advection, driven by a mean pressure gradient */
  PetscCall(PetscOptionsClear(NULL));
  PetscCall(PetscOptionsSetValue(NULL, "-domain_lo", "0,0,0"));
  PetscCall(PetscOptionsSetValue(NULL, "-domain_hi", "1,0.5,0.0625"));
  PetscCall(PetscOptionsSetValue(NULL, "-domain_periodic_x", "1"));
  PetscCall(PetscOptionsSetValue(NULL, "-domain_periodic_z", "1"));
  PetscCall(PetscOptionsSetValue(NULL, "-da_grid_x", "8"));
  PetscCall(PetscOptionsSetValue(NULL, "-da_grid_y", "16"));
  PetscCall(PetscOptionsSetValue(NULL, "-da_grid_z", "2"));
  PetscCall(PetscOptionsSetValue(NULL, "-fluid_density", "1"));
  PetscCall(PetscOptionsSetValue(NULL, "-fluid_viscosity", "0.01"));
  PetscCall(PetscOptionsSetValue(NULL, "-fluid_pressure_gradient", "-1,0,0"));
  PetscCall(PetscOptionsSetValue(NULL, "-fluid_poisson_ksp_rtol", "1e-12"));
  PetscCall(CompareUniform("periodic_channel", NULL, NULL, 2e-3));
  PetscCall(PetscFinalize());
  return check_failures ? 1 : 0;
}
