/* A state that became non-finite stops the DEM at once: a particle whose velocity is NaN (as a
 * diverging force would leave it) makes the next DemStep fail with PETSC_ERR_FP and a message
 * naming -dem_dt, in a bed of 27 particles where every other displacement is finite (the
 * largest-displacement reduction must not drop the NaN). The inputs themselves cannot be NaN:
 * tests/drivers/test_options_values.sh. */
#include "dem_common.h"

static char last_msg[1024];

static PetscErrorCode Record(MPI_Comm comm, int line, const char *func, const char *file, PetscErrorCode n, PetscErrorType p, const char *mess, void *ctx)
{
  (void)comm, (void)line, (void)func, (void)file, (void)ctx;
  if (p == PETSC_ERROR_INITIAL && mess) snprintf(last_msg, sizeof last_msg, "%s", mess);
  return n;
}

int main(int argc, char **argv)
{
  Domain         dom;
  Dem            dem;
  PetscErrorCode ierr  = 0;
  PetscInt       steps = 0;

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(TestDemCreate("-domain_lo 0,0,0 -domain_hi 0.1,0.1,0.1 -dem_box 0,0,0,0.1,0.1,0.1 -dem_radius 0.005 -dem_kn 1e4 -dem_lattice 3,3,3 -dem_lattice_speed 0.1", &dom, &dem));
  PetscCall(DemSetUp(dem));
  for (int s = 0; s < 5; s++) PetscCall(DemStep(dem));
  {
    DemParticle p = {0};
    PetscCall(DemGetParticle(dem, 13, &p));
    p.v[1] = NAN;
    PetscCall(DemSetParticle(dem, 13, &p));
  }
  PetscCall(PetscPushErrorHandler(Record, NULL));
  for (; steps < 100 && !ierr; steps++) ierr = DemStep(dem);
  PetscCall(PetscPopErrorHandler());
  PetscCall(CheckEqual("a NaN velocity stops the next step: error code (PETSC_ERR_FP)", ierr, PETSC_ERR_FP));
  PetscCall(CheckEqual("a NaN velocity stops the next step: steps taken", steps, 1));
  PetscCall(CheckTrue("a NaN velocity stops the next step: the message says non-finite and names -dem_dt", (PetscBool)(strstr(last_msg, "non-finite") && strstr(last_msg, "-dem_dt")), last_msg));
  PetscCall(PetscFinalize());
  return check_failures ? 1 : 0;
}
