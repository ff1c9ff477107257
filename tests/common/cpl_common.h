/* Shared by the coupling tests: a coupled set-up (Domain, Dem, Fluid, Cpl) from an options
 * string or a scene file, and its tear-down. */
#pragma once
#include "dem_common.h"
#include "balance/balancer.h"

typedef struct {
  Domain dom;
  Dem    dem;
  Fluid  fl;
  Cpl    cpl;
} TestCpl;

/* Builds and sets up everything from the options database; add (may be NULL) adds particles
 * before DemSetUp. */
static inline PetscErrorCode TestCplBuild(PetscErrorCode (*add)(Dem), TestCpl *t)
{
  PetscFunctionBeginUser;
  PetscCall(DomainCreate(PETSC_COMM_WORLD, 1.0, 1, &t->dom));
  PetscCall(DemCreate(&t->dom, &t->dem));
  PetscCall(DemSetFromOptions(t->dem));
  PetscCall(DemExternalSetFromOptions(t->dem));
  PetscCall(FluidCreate(&t->dom, &t->fl));
  PetscCall(FluidSetFromOptions(t->fl));
  PetscCall(CplCreate(&t->dom, t->dem, t->fl, &t->cpl));
  PetscCall(CplSetFromOptions(t->cpl));
  if (add) PetscCall(add(t->dem));
  PetscCall(DemSetUp(t->dem));
  PetscCall(FluidSetUp(t->fl));
  PetscCall(CplSetUp(t->cpl));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Replaces the options database by opts, then as TestCplBuild. */
static inline PetscErrorCode TestCplCreateWith(const char *opts, PetscErrorCode (*add)(Dem), TestCpl *t)
{
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsClear(NULL));
  PetscCall(PetscOptionsInsertString(NULL, opts));
  PetscCall(TestCplBuild(add, t));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static inline PetscErrorCode TestCplCreate(const char *opts, TestCpl *t)
{
  PetscFunctionBeginUser;
  PetscCall(TestCplCreateWith(opts, NULL, t));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Replaces the options database by the scene file `scene` of the test's folder and the options
 * string extra (scene.h), then as TestCplBuild. */
static inline PetscErrorCode TestCplCreateScene(const char *scene, const char *extra, PetscErrorCode (*add)(Dem), TestCpl *t)
{
  PetscFunctionBeginUser;
  PetscCall(TestSceneLoad(PETSC_COMM_WORLD, scene, extra));
  PetscCall(TestCplBuild(add, t));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static inline PetscErrorCode TestCplDestroy(TestCpl *t)
{
  PetscFunctionBeginUser;
  PetscCall(CplDestroy(&t->cpl));
  PetscCall(FluidDestroy(&t->fl));
  PetscCall(DemDestroy(&t->dem));
  PetscCall(DomainDestroy(&t->dom));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static inline PetscErrorCode TestCplRun(TestCpl *t, PetscInt nsteps, CplStats *st)
{
  PetscFunctionBeginUser;
  for (PetscInt s = 0; s < nsteps; s++) PetscCall(CplStep(t->cpl, st));
  PetscFunctionReturn(PETSC_SUCCESS);
}
