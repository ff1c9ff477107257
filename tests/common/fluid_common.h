/* Shared by the fluid tests: Domain + Fluid from the options database, set up, and with the
 * initial porosity of fn (when given). */
#pragma once
#include "check.h"
#include "scene.h"
#include "fluid/fluid.h"

static inline PetscErrorCode TestFluidCreate(PetscReal default_cell, FluidScalarFn fn, void *ctx, Domain *dom, Fluid *fl)
{
  PetscFunctionBeginUser;
  PetscCall(DomainCreate(PETSC_COMM_WORLD, default_cell, 1, dom));
  PetscCall(FluidCreate(dom, fl));
  PetscCall(FluidSetFromOptions(*fl));
  PetscCall(FluidSetUp(*fl));
  if (fn) {
    PetscCall(FluidSetPorosityFunction(*fl, fn, ctx));
    PetscCall(FluidInitPorosity(*fl));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}
