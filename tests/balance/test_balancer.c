/* ranks: 2 4 */
/* Load balancing moves the shared DMDA cuts; nothing physical may change.
 * Dry column: 720 frictional spheres (linear law with tangential springs) settling in the bottom
 * third of a tall box split along z over all ranks (1 x 1 x P), so the upper ranks own nothing:
 *   - one forced rebalance moves every particle with its state bit for bit (positions and
 *     velocities gathered by id before and after: max difference 0), keeps the count, the id
 *     checksum and the elastic energy of the tangential springs (the springs travel with their
 *     particles; the sum changes order, bound 1e-12 relative), and ends with L_max/L_avg < 1.15
 *     (the required bound) measured on the particles after the move;
 *   - runs with a rebalance every 50 steps give the trajectories of a run without: bitwise in
 *     -dem_deterministic mode (bound 0, as the parallel equivalence tests), within 1e-10 of the
 *     box in the default mode (the default-mode bound of tests/dem/test_parallel.c).
 * Coupled bed (the fluidized-bed case, small): after a few coupled steps one forced rebalance
 * leaves velocity, pressure and porosity equal cell by cell, bit for bit (gathered in natural
 * order; bound 0), and the particles too; then the run continues and matches the run without
 * balancing to the Poisson tolerance. The column's scene: test_balancer_column.opts. */
#include "cpl_common.h"

#define NCOL 720 /* particles in the column */

static PetscErrorCode Gather(Dem dem, PetscInt N, double *x, double *v, PetscInt *cnt)
{
  PetscFunctionBeginUser;
  PetscCall(TestGatherById(dem, PETSC_COMM_WORLD, N, x, v, cnt));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static double MaxDiff(const double *a, const double *b, PetscInt n)
{
  double d = 0;
  for (PetscInt i = 0; i < n; i++) d = PetscMax(d, PetscAbsReal(a[i] - b[i]));
  return d;
}

/* The column run for `steps` steps, rebalancing every `every` steps (0: never); positions out. */
static PetscErrorCode RunColumn(const char *mode, PetscInt steps, PetscInt every, double *x)
{
  char     opts[256];
  Domain   dom;
  Dem      dem;
  Balance  lb;
  PetscInt cnt;

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(opts, sizeof opts, "%s %s", mode, every ? "-lb_scheme frequent" : ""));
  PetscCall(TestDemCreateScene("test_balancer_column.opts", opts, &dom, &dem));
  PetscCall(BalanceCreate(&dom, dem, NULL, &lb));
  PetscCall(PetscOptionsSetValue(NULL, "-lb_interval", every ? "50" : "1"));
  PetscCall(BalanceSetFromOptions(lb));
  PetscCall(DemSetUp(dem));
  PetscCall(BalanceSetUp(lb));
  for (PetscInt s = 0; s < steps; s++) {
    PetscCall(DemStep(dem));
    PetscCall(BalanceCheck(lb, PETSC_FALSE, NULL));
  }
  PetscCall(Gather(dem, NCOL, x, NULL, &cnt));
  PetscCheck(cnt == NCOL, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "%" PetscInt_FMT " particles, expected %d", cnt, NCOL);
  PetscCall(BalanceDestroy(&lb));
  PetscCall(TestDemDestroy(&dom, &dem));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode TestColumnMove(void)
{
  Domain      dom;
  Dem         dem;
  Balance     lb;
  DemStats    s0, s1;
  PetscReal   lmin, lmax, lavg, lmax0;
  double     *x0, *v0, *x1, *v1;
  PetscInt    c0, c1;
  PetscBool   moved;
  PetscMPIInt size;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));
  PetscCall(TestDemCreateScene("test_balancer_column.opts", NULL, &dom, &dem));
  PetscCall(BalanceCreate(&dom, dem, NULL, &lb));
  PetscCall(BalanceSetFromOptions(lb));
  PetscCall(DemSetUp(dem));
  PetscCall(BalanceSetUp(lb));
  for (PetscInt s = 0; s < 3000; s++) PetscCall(DemStep(dem)); /* falls and packs: springs loaded */
  PetscCall(PetscMalloc4(3 * NCOL, &x0, 3 * NCOL, &v0, 3 * NCOL, &x1, 3 * NCOL, &v1));
  PetscCall(Gather(dem, NCOL, x0, v0, &c0));
  PetscCall(DemGetStats(dem, &s0));
  PetscCall(BalanceGetLoads(lb, &lmin, &lmax0, &lavg));
  PetscCall(BalanceCheck(lb, PETSC_TRUE, &moved));
  PetscCall(Gather(dem, NCOL, x1, v1, &c1));
  PetscCall(DemGetStats(dem, &s1));
  PetscCall(BalanceGetLoads(lb, &lmin, &lmax, &lavg));
  const double dx = MaxDiff(x0, x1, 3 * NCOL), dv = MaxDiff(v0, v1, 3 * NCOL);
  const double de = PetscAbsReal(s1.pe_spring - s0.pe_spring) / PetscMax(s0.pe_spring, 1e-300);
  PetscCall(CheckTrue(CheckName("column, %d ranks: a forced rebalance moves the cuts", size), moved, NULL));
  PetscCall(CheckEqual(CheckName("column, %d ranks: particles before the move", size), c0, NCOL));
  PetscCall(CheckEqual(CheckName("column, %d ranks: particles after the move", size), c1, NCOL));
  PetscCall(CheckEqualReal(CheckName("column, %d ranks: id checksum after the move", size), s1.checksum, s0.checksum));
  PetscCall(CheckEqualReal(CheckName("column, %d ranks: max |dx| of the particles moved [m]", size), dx, 0));
  PetscCall(CheckEqualReal(CheckName("column, %d ranks: max |dv| of the particles moved [m/s]", size), dv, 0));
  PetscCall(CheckAbove(CheckName("column, %d ranks: tangential/normal spring energy before the move [J]", size), s0.pe_spring, 0));
  PetscCall(CheckBelow(CheckName("column, %d ranks: spring energy, relative change over the move (same springs, other summation order)", size), de, 1e-12));
  CheckDetail("%.3f before", (double)(lmax0 / lavg));
  PetscCall(CheckBelow(CheckName("column, %d ranks: L_max/L_avg after one rebalance", size), lmax / lavg, 1.15));
  PetscCall(PetscFree4(x0, v0, x1, v1));
  PetscCall(BalanceDestroy(&lb));
  PetscCall(TestDemDestroy(&dom, &dem));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode TestColumnTrajectories(void)
{
  double     *a, *b;
  PetscMPIInt size;
  const char *mode[2] = {"-dem_deterministic", ""};

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));
  PetscCall(PetscMalloc2(3 * NCOL, &a, 3 * NCOL, &b));
  for (int m = 0; m < 2; m++) {
    PetscCall(RunColumn(mode[m], 1500, 0, a));
    PetscCall(RunColumn(mode[m], 1500, 50, b));
    const double d = MaxDiff(a, b, 3 * NCOL) / 0.45, bound = m ? 1e-10 : 0;
    PetscCall(CheckAtMost(CheckName("column, %d ranks, %s mode: 1500 steps rebalanced every 50 vs never: max |dx|/L", size, m ? "default" : "deterministic"), d, bound));
  }
  PetscCall(PetscFree2(a, b));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Every value of a field of DMDA da gathered in natural order on every rank. */
static PetscErrorCode Natural(DM da, Vec v, Vec *out)
{
  Vec        nat;
  VecScatter sc;

  PetscFunctionBeginUser;
  PetscCall(DMDACreateNaturalVector(da, &nat));
  PetscCall(DMDAGlobalToNaturalBegin(da, v, INSERT_VALUES, nat));
  PetscCall(DMDAGlobalToNaturalEnd(da, v, INSERT_VALUES, nat));
  PetscCall(VecScatterCreateToAll(nat, &sc, out));
  PetscCall(VecScatterBegin(sc, nat, *out, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(sc, nat, *out, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterDestroy(&sc));
  PetscCall(VecDestroy(&nat));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Natural-order copies of u, p, eps. */
static PetscErrorCode Fields(TestCpl *t, Vec out[3])
{
  DM  cda, fda;
  Vec u, p, e;

  PetscFunctionBeginUser;
  PetscCall(FluidGetDMs(t->fl, &cda, &fda));
  PetscCall(FluidGetVelocity(t->fl, &u));
  PetscCall(FluidGetPressure(t->fl, &p));
  PetscCall(FluidGetPorosity(t->fl, &e));
  PetscCall(Natural(fda, u, &out[0]));
  PetscCall(Natural(cda, p, &out[1]));
  PetscCall(Natural(cda, e, &out[2]));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode CoupledRun(PetscBool balance, PetscInt steps, double *x, PetscInt *np, PetscReal field_diff[3], PetscBool *moved)
{
  TestCpl  t;
  Balance  lb;
  CplStats st;
  PetscInt cnt, n;
  Vec      before[3], after[3];

  PetscFunctionBeginUser;
  PetscCall(TestCplCreate("-options_file cases/fluidized_bed/small.opts -io_dir /tmp -da_processors_x 1 -da_processors_y 1 -lb_verbose 0", &t));
  PetscCall(BalanceCreate(&t.dom, t.dem, t.cpl, &lb));
  PetscCall(BalanceSetFromOptions(lb));
  PetscCall(BalanceSetUp(lb));
  PetscCall(TestCplRun(&t, 5, &st));
  if (balance) {
    double *x0, *x1;
    PetscCall(DemGetLocalCount(t.dem, &n));
    PetscCallMPI(MPIU_Allreduce(MPI_IN_PLACE, &n, 1, MPIU_INT, MPI_SUM, PETSC_COMM_WORLD));
    PetscCall(PetscMalloc2(3 * n, &x0, 3 * n, &x1));
    PetscCall(Fields(&t, before));
    PetscCall(Gather(t.dem, n, x0, NULL, &cnt));
    PetscCall(BalanceCheck(lb, PETSC_TRUE, moved));
    PetscCall(Fields(&t, after));
    PetscCall(Gather(t.dem, n, x1, NULL, &cnt));
    for (int f = 0; f < 3; f++) {
      PetscCall(VecAXPY(after[f], -1.0, before[f]));
      PetscCall(VecNorm(after[f], NORM_INFINITY, &field_diff[f]));
      PetscCall(VecDestroy(&before[f]));
      PetscCall(VecDestroy(&after[f]));
    }
    field_diff[2] = PetscMax(field_diff[2], MaxDiff(x0, x1, 3 * n)); /* particles too */
    PetscCall(PetscFree2(x0, x1));
  }
  PetscCall(TestCplRun(&t, steps, &st));
  PetscCall(DemGetLocalCount(t.dem, &n));
  PetscCallMPI(MPIU_Allreduce(MPI_IN_PLACE, &n, 1, MPIU_INT, MPI_SUM, PETSC_COMM_WORLD));
  PetscCall(Gather(t.dem, n, x, NULL, &cnt));
  *np = n;
  PetscCall(BalanceDestroy(&lb));
  PetscCall(TestCplDestroy(&t));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode TestCoupled(void)
{
  double     *a, *b;
  PetscReal   diff[3] = {0, 0, 0};
  PetscInt    na, nb;
  PetscBool   moved = PETSC_FALSE;
  PetscMPIInt size;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));
  PetscCall(PetscMalloc2(3 * 100000, &a, 3 * 100000, &b));
  PetscCall(CoupledRun(PETSC_FALSE, 10, a, &na, diff, &moved));
  PetscCall(CoupledRun(PETSC_TRUE, 10, b, &nb, diff, &moved));
  const double dx = (na == nb ? MaxDiff(a, b, 3 * na) : 1e300) / 16.0; /* the bed case is 16 d tall */
  PetscCall(CheckTrue(CheckName("coupled bed, %d ranks: a forced rebalance moves the cuts", size), moved, NULL));
  PetscCall(CheckEqualReal(CheckName("coupled bed, %d ranks: max change of the velocity over the move", size), diff[0], 0));
  PetscCall(CheckEqualReal(CheckName("coupled bed, %d ranks: max change of the pressure over the move", size), diff[1], 0));
  PetscCall(CheckEqualReal(CheckName("coupled bed, %d ranks: max change of the porosity and the particle positions over the move", size), diff[2], 0));
  PetscCall(CheckEqual(CheckName("coupled bed, %d ranks: particles after 10 more steps, with the rebalance vs without", size), nb, na));
  PetscCall(CheckBelow(CheckName("coupled bed, %d ranks: 10 more fluid steps after the rebalance vs without: max |dx|/L (the Poisson tolerance 1e-8 and another summation order)", size), dx, 1e-9));
  PetscCall(PetscFree2(a, b));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(TestColumnMove());
  PetscCall(TestColumnTrajectories());
  PetscCall(TestCoupled());
  PetscCall(PetscFinalize());
  return check_failures ? 1 : 0;
}
