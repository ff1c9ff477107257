/* Implicit viscous predictor (placeholder until implemented). */
#include "fluid/fluid_impl.h"

PetscErrorCode FluidViscousSolve(Fluid fl, PetscReal dt, Vec rhs, Vec uhat)
{
  PetscFunctionBeginUser;
  (void)dt; (void)rhs; (void)uhat;
  SETERRQ(fl->comm, PETSC_ERR_SUP, "-fluid_viscous implicit is not implemented yet");
}
