/* ranks: 1 2 4 */
/* Decomposition independence. Three cases: the Poiseuille start-up (periodic channel, 8 x 32 x 4
 * cells, 300 steps, not yet steady, from a 3-D perturbation the first projection makes
 * solenoidal), the porosity-step channel (inlet/outlet, 32 x 16 x 4 cells, 100 steps) and a
 * periodic box (8^3 cells, 3-D Taylor-Green start, TVD advection, 30 steps). Each runs on all
 * ranks of PETSC_COMM_WORLD and, as the reference, on PETSC_COMM_SELF on every rank (one rank's
 * solution); the process grid PETSc chose is printed. The parallel fields, gathered in natural
 * order, must equal the one-rank fields to the solver tolerance (Poisson rtol 1e-12): max
 * difference of the face velocity relative to max |u|, and of the pressure (mean removed)
 * relative to max |p|. */
#include "check.h"
#include "fluid/fluid.h"

typedef struct {
  PetscReal u, p;
  PetscInt  grid[3]; /* process grid of the parallel run */
} Diff;

/* A 3-D perturbation of the channel start-up, so that advection and the projection have work. */
static void Perturbation(const PetscReal x[3], PetscReal v[3], void *ctx)
{
  (void)ctx;
  v[0] = 0.1 * PetscSinReal(2 * PETSC_PI * x[1]) * PetscCosReal(4 * PETSC_PI * x[2]);
  v[1] = 0.1 * PetscSinReal(2 * PETSC_PI * x[0]);
  v[2] = 0.1 * PetscCosReal(2 * PETSC_PI * x[0]) * PetscSinReal(PETSC_PI * x[1]);
}

static void TaylorGreen3(const PetscReal x[3], PetscReal v[3], void *ctx)
{
  (void)ctx;
  v[0] = PetscSinReal(2 * PETSC_PI * x[0]) * PetscCosReal(2 * PETSC_PI * x[1]) * PetscCosReal(2 * PETSC_PI * x[2]);
  v[1] = -PetscCosReal(2 * PETSC_PI * x[0]) * PetscSinReal(2 * PETSC_PI * x[1]) * PetscCosReal(2 * PETSC_PI * x[2]);
  v[2] = 0.2 * PetscSinReal(2 * PETSC_PI * x[1]);
}

static PetscReal StepEps(const PetscReal x[3], void *ctx)
{
  (void)ctx;
  return x[0] < 0.5 ? 1.0 : 0.4;
}

/* Runs the case on comm; returns u and p gathered onto every rank in natural order. */
static PetscErrorCode RunCase(MPI_Comm comm, int which, PetscInt nsteps, Vec *U, Vec *P, PetscInt grid[3])
{
  Domain     dom = {0};
  Fluid      fl;
  FluidStats st;
  DM         cda, fda;
  Vec        u, p, nat;
  VecScatter sc;
  DM         dms[2];
  Vec        in[2], *out[2] = {U, P};

  PetscFunctionBeginUser;
  PetscCall(DomainCreate(comm, 1.0, 1, &dom));
  for (int d = 0; d < 3; d++) grid[d] = dom.nranks[d];
  PetscCall(FluidCreate(&dom, &fl));
  PetscCall(FluidSetFromOptions(fl));
  PetscCall(FluidSetUp(fl));
  if (which == 1) PetscCall(FluidSetPorosityFunction(fl, StepEps, NULL));
  if (which == 0) PetscCall(FluidSetVelocityFunction(fl, Perturbation, NULL));
  if (which == 2) PetscCall(FluidSetVelocityFunction(fl, TaylorGreen3, NULL));
  PetscCall(FluidInitPorosity(fl));
  for (PetscInt n = 0; n < nsteps; n++) PetscCall(FluidStep(fl, 2e-3, &st));
  PetscCall(FluidGetDMs(fl, &cda, &fda));
  PetscCall(FluidGetVelocity(fl, &u));
  PetscCall(FluidGetPressure(fl, &p));
  dms[0] = fda;
  dms[1] = cda;
  in[0]  = u;
  in[1]  = p;
  for (int i = 0; i < 2; i++) {
    PetscCall(DMDACreateNaturalVector(dms[i], &nat));
    PetscCall(DMDAGlobalToNaturalBegin(dms[i], in[i], INSERT_VALUES, nat));
    PetscCall(DMDAGlobalToNaturalEnd(dms[i], in[i], INSERT_VALUES, nat));
    PetscCall(VecScatterCreateToAll(nat, &sc, out[i]));
    PetscCall(VecScatterBegin(sc, nat, *out[i], INSERT_VALUES, SCATTER_FORWARD));
    PetscCall(VecScatterEnd(sc, nat, *out[i], INSERT_VALUES, SCATTER_FORWARD));
    PetscCall(VecScatterDestroy(&sc));
    PetscCall(VecDestroy(&nat));
  }
  PetscCall(FluidDestroy(&fl));
  PetscCall(DomainDestroy(&dom));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode Compare(int which, PetscInt nsteps, Diff *d)
{
  Vec       U[2], P[2];
  PetscReal nu, np, mean[2];
  PetscInt  n, one[3];

  PetscFunctionBeginUser;
  PetscCall(RunCase(PETSC_COMM_WORLD, which, nsteps, &U[0], &P[0], d->grid));
  PetscCall(RunCase(PETSC_COMM_SELF, which, nsteps, &U[1], &P[1], one));
  PetscCall(VecGetSize(P[0], &n));
  for (int i = 0; i < 2; i++) {
    PetscCall(VecSum(P[i], &mean[i]));
    PetscCall(VecShift(P[i], -mean[i] / n));
  }
  PetscCall(VecNorm(U[1], NORM_INFINITY, &nu));
  PetscCall(VecNorm(P[1], NORM_INFINITY, &np));
  PetscCall(VecAXPY(U[0], -1.0, U[1]));
  PetscCall(VecAXPY(P[0], -1.0, P[1]));
  PetscCall(VecNorm(U[0], NORM_INFINITY, &d->u));
  PetscCall(VecNorm(P[0], NORM_INFINITY, &d->p));
  d->u /= nu;
  d->p = np > 0 ? d->p / np : d->p;
  for (int i = 0; i < 2; i++) {
    PetscCall(VecDestroy(&U[i]));
    PetscCall(VecDestroy(&P[i]));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode Report(const char *name, const Diff *d)
{
  PetscMPIInt size;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));
  CheckDetail("process grid %dx%dx%d", (int)d->grid[0], (int)d->grid[1], (int)d->grid[2]);
  PetscCall(CheckBelow(CheckName("%s_velocity_vs_1_rank_rel_diff_np%d", name, (int)size), d->u, 1e-9));
  PetscCall(CheckBelow(CheckName("%s_pressure_vs_1_rank_rel_diff_np%d", name, (int)size), d->p, 1e-9));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  Diff d;

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(PetscOptionsSetValue(NULL, "-fluid_density", "1"));
  PetscCall(PetscOptionsSetValue(NULL, "-fluid_poisson_ksp_rtol", "1e-12"));
  PetscCall(PetscOptionsSetValue(NULL, "-fluid_poisson_ksp_norm_type", "unpreconditioned"));
  PetscCall(PetscOptionsSetValue(NULL, "-domain_lo", "0,0,0"));
  PetscCall(PetscOptionsSetValue(NULL, "-da_grid_z", "4"));
  /* Poiseuille start-up */
  PetscCall(PetscOptionsSetValue(NULL, "-domain_hi", "1,1,0.5"));
  PetscCall(PetscOptionsSetValue(NULL, "-domain_periodic_x", "1"));
  PetscCall(PetscOptionsSetValue(NULL, "-domain_periodic_z", "1"));
  PetscCall(PetscOptionsSetValue(NULL, "-da_grid_x", "8"));
  PetscCall(PetscOptionsSetValue(NULL, "-da_grid_y", "32"));
  PetscCall(PetscOptionsSetValue(NULL, "-fluid_viscosity", "0.05"));
  PetscCall(PetscOptionsSetValue(NULL, "-fluid_pressure_gradient", "-1,0,0"));
  PetscCall(Compare(0, 300, &d));
  PetscCall(Report("poiseuille", &d));
  /* porosity step with through-flow */
  PetscCall(PetscOptionsClearValue(NULL, "-domain_periodic_x"));
  PetscCall(PetscOptionsClearValue(NULL, "-fluid_pressure_gradient"));
  PetscCall(PetscOptionsSetValue(NULL, "-domain_hi", "1,0.5,0.125"));
  PetscCall(PetscOptionsSetValue(NULL, "-da_grid_x", "32"));
  PetscCall(PetscOptionsSetValue(NULL, "-da_grid_y", "16"));
  PetscCall(PetscOptionsSetValue(NULL, "-fluid_viscosity", "0.01"));
  PetscCall(PetscOptionsSetValue(NULL, "-fluid_bc_xlo", "inlet"));
  PetscCall(PetscOptionsSetValue(NULL, "-fluid_bc_xlo_velocity", "0.1,0,0"));
  PetscCall(PetscOptionsSetValue(NULL, "-fluid_bc_xhi", "outlet"));
  PetscCall(Compare(1, 100, &d));
  PetscCall(Report("porosity_step", &d));
  /* periodic box, 3-D Taylor-Green start, TVD advection */
  PetscCall(PetscOptionsClear(NULL));
  PetscCall(PetscOptionsSetValue(NULL, "-fluid_density", "1"));
  PetscCall(PetscOptionsSetValue(NULL, "-fluid_viscosity", "0.01"));
  PetscCall(PetscOptionsSetValue(NULL, "-fluid_advection", "tvd"));
  PetscCall(PetscOptionsSetValue(NULL, "-fluid_poisson_ksp_rtol", "1e-12"));
  PetscCall(PetscOptionsSetValue(NULL, "-fluid_poisson_ksp_norm_type", "unpreconditioned"));
  PetscCall(PetscOptionsSetValue(NULL, "-domain_lo", "0,0,0"));
  PetscCall(PetscOptionsSetValue(NULL, "-domain_hi", "1,1,1"));
  PetscCall(PetscOptionsSetValue(NULL, "-domain_periodic_x", "1"));
  PetscCall(PetscOptionsSetValue(NULL, "-domain_periodic_y", "1"));
  PetscCall(PetscOptionsSetValue(NULL, "-domain_periodic_z", "1"));
  PetscCall(PetscOptionsSetValue(NULL, "-da_grid_x", "8"));
  PetscCall(PetscOptionsSetValue(NULL, "-da_grid_y", "8"));
  PetscCall(PetscOptionsSetValue(NULL, "-da_grid_z", "8"));
  PetscCall(Compare(2, 30, &d));
  PetscCall(Report("periodic_box_tvd", &d));
  PetscCall(PetscFinalize());
  return check_failures ? 1 : 0;
}
