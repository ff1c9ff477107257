/* Cost of a fluid step in a periodic box, and the driver of tools/bench_fluid.sh.
 * The box [0, 2 pi]^3 (-test_cells per axis, default 16) starts from the 3-D Taylor-Green field
 * u = sin x cos y cos z, v = -cos x sin y cos z, w = 0 (rho = 1, mu = 1e-3, Re = 1000 on the
 * box) so every step's predictor is far from solenoidal and the Poisson solve has real work.
 * It takes -test_steps steps (default 10) of dt = 0.1 h with the Poisson solve to rtol 1e-8
 * (KSP CG + BoomerAMG, overridable by -fluid_poisson_*), times each step, and prints the medians
 * of the step time, of the time per cell and step, and of the Poisson iterations; the first
 * step, which sets up BoomerAMG, is excluded from the medians and printed apart.
 * As a test (no -test_cells) it runs 8^3 and 16^3 and checks that the Poisson iterations do
 * not grow with the grid (multigrid's mesh independence: at most 2 more on the finer grid) and
 * that every step leaves |div u| below 1e-6 of the velocity scale 1/h.
 * With -test_vessel the fluid is bounded by a cylinder along z of radius 0.45 x the box side
 * (FluidSetVessel: 64% of the cells open, the rest closed) and the line also gives the time per
 * open cell (cells of volume fraction > 0), to compare with the box's time per cell. */
#include "check.h"
#include "fluid/fluid.h"

static void TaylorGreen3(const PetscReal x[3], PetscReal v[3], void *ctx)
{
  (void)ctx;
  v[0] = PetscSinReal(x[0]) * PetscCosReal(x[1]) * PetscCosReal(x[2]);
  v[1] = -PetscCosReal(x[0]) * PetscSinReal(x[1]) * PetscCosReal(x[2]);
  v[2] = 0;
}

static PetscReal Cylinder(const PetscReal x[3], void *ctx)
{
  const PetscReal L = 2 * PETSC_PI, dx = x[0] - 0.5 * L, dy = x[1] - 0.5 * L;
  (void)ctx;
  return 0.45 * L - PetscSqrtReal(dx * dx + dy * dy);
}

static int CmpReal(const void *a, const void *b)
{
  const PetscReal x = *(const PetscReal *)a, y = *(const PetscReal *)b;
  return (x > y) - (x < y);
}

static PetscReal Median(PetscReal *v, PetscInt n)
{
  qsort(v, (size_t)n, sizeof *v, CmpReal);
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/* One run of `steps` steps on N^3 cells: prints the bench line; returns the largest Poisson
 * iteration count and the worst divergence relative to 1/h. */
static PetscErrorCode BenchRun(PetscInt N, PetscInt steps, PetscBool vessel, PetscInt *maxits_out, PetscReal *worst_out)
{
  Domain      dom = {0};
  Fluid       fl;
  FluidStats  st;
  PetscInt    maxits = 0;
  PetscReal  *tstep, *its, worst = 0, t0, first = 0, h, med_t, med_its;
  char        buf[64];
  PetscMPIInt size;

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(buf, sizeof buf, "%.12g,%.12g,%.12g", 2 * PETSC_PI, 2 * PETSC_PI, 2 * PETSC_PI));
  PetscCall(PetscOptionsSetValue(NULL, "-domain_lo", "0,0,0"));
  PetscCall(PetscOptionsSetValue(NULL, "-domain_hi", buf));
  PetscCall(PetscOptionsSetValue(NULL, "-domain_periodic_x", "1"));
  PetscCall(PetscOptionsSetValue(NULL, "-domain_periodic_y", "1"));
  PetscCall(PetscOptionsSetValue(NULL, "-domain_periodic_z", "1"));
  PetscCall(PetscSNPrintf(buf, sizeof buf, "%d", (int)N));
  PetscCall(PetscOptionsSetValue(NULL, "-da_grid_x", buf));
  PetscCall(PetscOptionsSetValue(NULL, "-da_grid_y", buf));
  PetscCall(PetscOptionsSetValue(NULL, "-da_grid_z", buf));
  PetscCall(PetscOptionsSetValue(NULL, "-fluid_density", "1"));
  PetscCall(PetscOptionsSetValue(NULL, "-fluid_viscosity", "1e-3"));
  PetscCall(DomainCreate(PETSC_COMM_WORLD, 1.0, 1, &dom));
  PetscCall(FluidCreate(&dom, &fl));
  PetscCall(FluidSetFromOptions(fl));
  PetscCall(SableCheckOptionsUsed(PETSC_COMM_WORLD));
  if (vessel) PetscCall(FluidSetVessel(fl, Cylinder, NULL));
  PetscCall(FluidSetUp(fl));
  PetscCall(FluidSetVelocityFunction(fl, TaylorGreen3, NULL));
  PetscCall(PetscMalloc2(steps, &tstep, steps, &its));
  h = 2 * PETSC_PI / N;
  for (PetscInt n = 0; n < steps; n++) {
    PetscCallMPI(MPI_Barrier(PETSC_COMM_WORLD));
    t0 = MPI_Wtime();
    PetscCall(FluidStep(fl, 0.1 * h, &st));
    PetscCallMPI(MPI_Barrier(PETSC_COMM_WORLD));
    tstep[n] = MPI_Wtime() - t0;
    its[n]   = (PetscReal)st.poisson_its;
    maxits   = PetscMax(maxits, st.poisson_its);
    worst    = PetscMax(worst, st.div_max * h);
    if (!n) first = tstep[0];
  }
  med_t   = Median(tstep + 1, steps - 1);
  med_its = Median(its + 1, steps - 1);
  PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "# bench ranks %d cells %d^3 steps %d: first step %.4g s; median step %.4g s, %.4g us per cell per step (x ranks: %.4g); median Poisson its %.1f (max %d)\n", (int)size, (int)N, (int)steps, (double)first, (double)med_t, (double)(1e6 * med_t / (N * N * N)), (double)(1e6 * med_t * size / (N * N * N)), (double)med_its, (int)maxits));
  if (vessel) {
    Vec       vol;
    PetscReal nopen;
    PetscCall(FluidGetOpenFractions(fl, &vol, NULL));
    {
      const PetscScalar *v;
      PetscInt           n, k;
      PetscReal          loc = 0;
      PetscCall(VecGetLocalSize(vol, &n));
      PetscCall(VecGetArrayRead(vol, &v));
      for (k = 0; k < n; k++) loc += PetscRealPart(v[k]) > 0 ? 1 : 0;
      PetscCall(VecRestoreArrayRead(vol, &v));
      PetscCallMPI(MPI_Allreduce(&loc, &nopen, 1, MPIU_REAL, MPI_SUM, PETSC_COMM_WORLD));
    }
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "# bench vessel: open cells %.0f of %d (%.1f%%), %.4g us per open cell per step (x ranks: %.4g)\n", (double)nopen, (int)(N * N * N), (double)(100 * nopen / (N * N * N)), (double)(1e6 * med_t / nopen), (double)(1e6 * med_t * size / nopen)));
  }
  PetscCall(PetscFree2(tstep, its));
  PetscCall(FluidDestroy(&fl));
  PetscCall(DomainDestroy(&dom));
  *maxits_out = maxits;
  *worst_out  = worst;
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  PetscInt  N = 16, steps = 10, its[2];
  PetscReal worst[2];
  PetscBool cells, vessel = PETSC_FALSE;

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-test_cells", &N, &cells));
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-test_steps", &steps, NULL));
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-test_vessel", &vessel, NULL));
  PetscCheck(steps >= 2, PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE, "-test_steps %d must be >= 2", (int)steps);
  if (cells) { /* the benchmark's driver: one size, no checks */
    PetscCall(BenchRun(N, steps, vessel, &its[0], &worst[0]));
  } else {
    PetscCall(BenchRun(8, steps, PETSC_FALSE, &its[0], &worst[0]));
    PetscCall(BenchRun(16, steps, PETSC_FALSE, &its[1], &worst[1]));
    CheckDetail("multigrid: at most 2 more than the %d at 8^3", (int)its[0]);
    PetscCall(CheckAtMost("bench_poisson_iterations_mesh_independent: max at 16^3", its[1], its[0] + 2));
    CheckDetail("%.3e at 8^3, %.3e at 16^3", (double)worst[0], (double)worst[1]);
    PetscCall(CheckBelow("bench_divergence_rel", PetscMax(worst[0], worst[1]), 1e-6));
  }
  PetscCall(PetscFinalize());
  return check_failures ? 1 : 0;
}
