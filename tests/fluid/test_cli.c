/* A fluid-only driver configured by options, as bin/sable will be: domain, fluid, the check that
 * every option was read, -test_steps steps of -fluid_dt, and HDF5/XDMF output of the last state.
 * Without options it runs a small inlet/outlet channel with a porosity step and checks
 *   - every step's continuity residual relative to the inlet velocity scale U/h (< 1e-6, Poisson
 *     rtol 1e-8 default), and
 *   - the output: eps read back from /fluid/eps of the written HDF5 file equals the field set
 *     (0.4 or 1 in each cell) exactly.
 * tests/fluid/test_badinput.sh drives it with bad options and checks the error messages. */
#include "check.h"
#include "fluid/fluid.h"
#include <hdf5.h>

static PetscReal StepEps(const PetscReal x[3], void *ctx)
{
  (void)ctx;
  return x[0] < 0.5 ? 1.0 : 0.4;
}

static PetscErrorCode Default(const char *name, const char *value)
{
  PetscBool has;

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsHasName(NULL, NULL, name, &has));
  if (!has) PetscCall(PetscOptionsSetValue(NULL, name, value));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Every rank reads /fluid/eps of the frame file and compares it with StepEps at cell centres. */
static PetscErrorCode CheckOutput(const char *file, const Domain *dom, PetscReal *maxdiff)
{
  hid_t      f, d;
  PetscReal *buf;
  PetscInt   n = dom->cells[0] * dom->cells[1] * dom->cells[2];

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(n, &buf));
  f = H5Fopen(file, H5F_ACC_RDONLY, H5P_DEFAULT);
  PetscCheck(f >= 0, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "cannot open %s", file);
  d = H5Dopen2(f, "/fluid/eps", H5P_DEFAULT);
  PetscCheck(d >= 0, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "%s has no /fluid/eps", file);
  SableCallH5(H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf));
  SableCallH5(H5Dclose(d));
  SableCallH5(H5Fclose(f));
  *maxdiff = 0;
  for (PetscInt k = 0, o = 0; k < dom->cells[2]; k++)
    for (PetscInt j = 0; j < dom->cells[1]; j++)
      for (PetscInt i = 0; i < dom->cells[0]; i++, o++) {
        PetscReal x[3] = {dom->lo[0] + (i + 0.5) * dom->h[0], 0, 0};
        *maxdiff       = PetscMax(*maxdiff, PetscAbsReal(buf[o] - StepEps(x, NULL)));
      }
  PetscCall(PetscFree(buf));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  Domain     dom = {0};
  Fluid      fl;
  Io         io;
  FluidStats st;
  PetscInt   steps = 20;
  PetscReal  dt, t = 0, worst = 0, diff = -1, U = 0.5;
  char       dir[PETSC_MAX_PATH_LEN], file[2 * PETSC_MAX_PATH_LEN];
  PetscBool  has;

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-test_steps", &steps, NULL));
  PetscCall(Default("-domain_lo", "0,0,0"));
  PetscCall(Default("-domain_hi", "1,0.5,0.125"));
  PetscCall(Default("-domain_periodic_z", "1"));
  PetscCall(Default("-da_grid_x", "16"));
  PetscCall(Default("-da_grid_y", "8"));
  PetscCall(Default("-da_grid_z", "2"));
  PetscCall(PetscOptionsHasName(NULL, NULL, "-fluid_bc_xlo", &has));
  if (!has) {
    PetscCall(Default("-fluid_bc_xlo", "inlet"));
    PetscCall(Default("-fluid_bc_xlo_velocity", "0.5,0,0"));
    PetscCall(Default("-fluid_bc_xhi", "outlet"));
  }
  PetscCall(Default("-fluid_dt", "0.01"));
  PetscCall(Default("-io_dir", "/tmp/sable_test_fluid_cli"));
  PetscCall(Default("-io_interval", "1"));
  PetscCall(DomainCreate(PETSC_COMM_WORLD, 1.0, 1, &dom));
  PetscCall(FluidCreate(&dom, &fl));
  PetscCall(FluidSetFromOptions(fl));
  PetscCall(IoCreate(PETSC_COMM_WORLD, &io));
  PetscCall(IoSetFromOptions(io));
  PetscCall(SableCheckOptionsUsed(PETSC_COMM_WORLD));
  PetscCall(FluidSetUp(fl));
  PetscCall(FluidSetPorosityFunction(fl, StepEps, NULL));
  PetscCall(FluidInitPorosity(fl));
  PetscCall(FluidGetTimeStep(fl, &dt, NULL));
  for (PetscInt n = 0; n < steps; n++) {
    PetscCall(FluidStep(fl, dt, &st));
    t += st.dt;
    worst = PetscMax(worst, st.div_max * dom.h[0] / U);
  }
  PetscCall(IoFrameBegin(io, t, steps));
  PetscCall(FluidWriteOutput(fl, io));
  PetscCall(IoFrameEnd(io));
  PetscCall(PetscOptionsGetString(NULL, NULL, "-io_dir", dir, sizeof dir, NULL));
  PetscCall(PetscSNPrintf(file, sizeof file, "%s/sable_000000.h5", dir));
  PetscCall(CheckOutput(file, &dom, &diff));
  CheckDetail("%d steps, last CFL %.3f, Poisson its %d", (int)steps, (double)st.cfl, (int)st.poisson_its);
  PetscCall(CheckBelow("fluid_cli_continuity_rel_residual", worst, 1e-6));
  PetscCall(CheckEqualReal("fluid_output_eps_roundtrip_max_diff", diff, 0));
  PetscCall(IoDestroy(&io));
  PetscCall(FluidDestroy(&fl));
  PetscCall(DomainDestroy(&dom));
  PetscCall(PetscFinalize());
  return check_failures ? 1 : 0;
}
