/* ranks: 1 2 */
/* The Poisson solver's options change the cost, never the answer: the lagged preconditioner
 * (-fluid_poisson_pc_lag, poisson.c) and geometric multigrid on the fluid's DMDA in place of
 * BoomerAMG (-fluid_poisson_pc_type mg, two levels, Galerkin, Chebyshev/Jacobi). A column 1 x 1 x 2 m
 * (8 x 4 x 17 cells), inlet 1 m/s at z = 0, outlet at z = 2, periodic x and y,
 * through which a porous bump eps = 1 - 0.5 exp(-((z - z0(t))^2 + (x - 0.5)^2) / 0.04) travels
 * with z0 = 0.3 + 2 t m/s, so the Poisson matrix changes at every one of the 60 steps of 0.01 s.
 * Run with the preconditioner rebuilt at every change (lag 0), with the default lag and with an
 * unbounded lag, and with multigrid; Poisson rtol 1e-11 (unpreconditioned norm). Checks:
 *   - velocity and pressure after 60 steps: max difference relative to the field's max
 *     < 1e-8 between lag 0 and each other run (the solutions agree to the solver tolerance);
 *   - continuity residual of every step relative to U/h < 1e-8 in every run;
 *   - builds: 60 with lag 0, 3 with the default lag 20 (at the 1st, 22nd and 43rd change: the
 *     iterations stay flat, so the growth rule does not fire), 1 unbounded; PETSc's own count of
 *     PCSetUp events agrees.
 * The scene: test_poisson_options.opts. */
#include "fluid_common.h"

typedef struct {
  PetscReal t;
} Bump;

static PetscReal BumpEps(const PetscReal x[3], void *ctx)
{
  const PetscReal z0 = 0.3 + 2 * ((Bump *)ctx)->t, r2 = (x[2] - z0) * (x[2] - z0) + (x[0] - 0.5) * (x[0] - 0.5);
  return 1 - 0.5 * PetscExpReal(-r2 / 0.04);
}

typedef struct {
  Vec       u, p;
  PetscReal div;
  PetscInt  builds, its, setups; /* builds as the fluid counts them; PCSetUp events as PETSc logs them */
} Result;

/* PCSetUp events logged so far (the main stage). */
static PetscErrorCode SetUpCount(PetscInt *n)
{
  PetscLogEvent      ev;
  PetscEventPerfInfo info;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventGetId("PCSetUp", &ev));
  PetscCall(PetscLogEventGetPerfInfo(0, ev, &info));
  *n = info.count;
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode Run(const char *lag, PetscBool mg, Result *r)
{
  Domain     dom = {0};
  Fluid      fl;
  FluidStats st;
  Bump       b = {0};
  Vec        u, p;
  PetscInt   s0, s1;

  PetscFunctionBeginUser;
  PetscCall(SetUpCount(&s0));
  PetscCall(TestSceneLoad(PETSC_COMM_WORLD, "test_poisson_options.opts", NULL));
  if (lag) PetscCall(PetscOptionsSetValue(NULL, "-fluid_poisson_pc_lag", lag));
  if (mg)
    PetscCall(PetscOptionsInsertString(NULL, "-fluid_poisson_pc_type mg -fluid_poisson_pc_mg_levels 2 -fluid_poisson_pc_mg_galerkin pmat "
                                             "-fluid_poisson_mg_levels_ksp_type chebyshev -fluid_poisson_mg_levels_pc_type jacobi"));
  PetscCall(TestFluidCreate(1.0, BumpEps, &b, &dom, &fl));
  r->div = 0;
  for (PetscInt n = 1; n <= 60; n++) {
    b.t = 0.01 * n;
    PetscCall(FluidSetPorosityFunction(fl, BumpEps, &b));
    PetscCall(FluidStep(fl, 0.01, &st));
    r->div = PetscMax(r->div, st.div_max * dom.h[2] / 1.0);
    r->its += st.poisson_its;
  }
  r->builds = st.poisson_pc_builds;
  PetscCall(SetUpCount(&s1));
  r->setups = s1 - s0;
  PetscCall(FluidGetVelocity(fl, &u));
  PetscCall(FluidGetPressure(fl, &p));
  PetscCall(VecDuplicate(u, &r->u));
  PetscCall(VecDuplicate(p, &r->p));
  PetscCall(VecCopy(u, r->u));
  PetscCall(VecCopy(p, r->p));
  PetscCall(FluidDestroy(&fl));
  PetscCall(DomainDestroy(&dom));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* max |a - b| / max |b|, then a is freed. */
static PetscErrorCode RelDiff(Vec a, Vec b, PetscReal *d)
{
  PetscReal nb;

  PetscFunctionBeginUser;
  PetscCall(VecNorm(b, NORM_INFINITY, &nb));
  PetscCall(VecAXPY(a, -1.0, b));
  PetscCall(VecNorm(a, NORM_INFINITY, d));
  *d /= nb;
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  Result    r0 = {0}, rd = {0}, ri = {0}, rm = {0};
  PetscReal du[3], dp[3], dmax;

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(PetscLogDefaultBegin());
  PetscCall(Run("0", PETSC_FALSE, &r0));
  PetscCall(Run(NULL, PETSC_FALSE, &rd));
  PetscCall(Run("1000000", PETSC_FALSE, &ri));
  PetscCall(Run(NULL, PETSC_TRUE, &rm));
  PetscCall(RelDiff(rd.u, r0.u, &du[0]));
  PetscCall(RelDiff(rd.p, r0.p, &dp[0]));
  PetscCall(RelDiff(ri.u, r0.u, &du[1]));
  PetscCall(RelDiff(ri.p, r0.p, &dp[1]));
  PetscCall(RelDiff(rm.u, r0.u, &du[2]));
  PetscCall(RelDiff(rm.p, r0.p, &dp[2]));
  dmax = PetscMax(PetscMax(r0.div, rm.div), PetscMax(rd.div, ri.div));
  PetscCall(CheckBelow("pc_lag_default_vs_0_velocity_rel_diff", du[0], 1e-8));
  PetscCall(CheckBelow("pc_lag_default_vs_0_pressure_rel_diff", dp[0], 1e-8));
  PetscCall(CheckBelow("pc_lag_unbounded_vs_0_velocity_rel_diff", du[1], 1e-8));
  PetscCall(CheckBelow("pc_lag_unbounded_vs_0_pressure_rel_diff", dp[1], 1e-8));
  CheckDetail("CG its %d vs %d", (int)rm.its, (int)r0.its);
  PetscCall(CheckBelow("poisson_mg_vs_amg_velocity_rel_diff", du[2], 1e-8));
  PetscCall(CheckBelow("poisson_mg_vs_amg_pressure_rel_diff", dp[2], 1e-8));
  PetscCall(CheckBelow("poisson_continuity_rel_residual (all four runs)", dmax, 1e-8));
  PetscCall(CheckEqual("pc_lag_builds: lag 0", r0.builds, 60));
  PetscCall(CheckEqual("pc_lag_builds: default lag (builds at changes 1, 22, 43)", rd.builds, 3));
  PetscCall(CheckEqual("pc_lag_builds: unbounded lag", ri.builds, 1));
  CheckDetail("CG its %d, %d, %d", (int)r0.its, (int)rd.its, (int)ri.its);
  PetscCall(CheckEqual("pc_lag_builds: PCSetUp events that built, lag 0 (reference: our count)", r0.setups, r0.builds));
  PetscCall(CheckEqual("pc_lag_builds: PCSetUp events that built, default lag", rd.setups, rd.builds));
  PetscCall(CheckEqual("pc_lag_builds: PCSetUp events that built, unbounded lag", ri.setups, ri.builds));
  PetscCall(VecDestroy(&r0.u));
  PetscCall(VecDestroy(&r0.p));
  PetscCall(VecDestroy(&rd.u));
  PetscCall(VecDestroy(&rd.p));
  PetscCall(VecDestroy(&ri.u));
  PetscCall(VecDestroy(&ri.p));
  PetscCall(VecDestroy(&rm.u));
  PetscCall(VecDestroy(&rm.p));
  PetscCall(PetscFinalize());
  return check_failures ? 1 : 0;
}
