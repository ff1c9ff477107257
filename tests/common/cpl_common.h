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

/* Particle + fluid + owed momentum P (the conserved total), |fluid momentum| (pf_norm, may be
 * NULL) and sum |m v| over all particles (the scale of P's changes); one mass per shape. */
static inline PetscErrorCode TestCplMomentum(TestCpl *t, PetscReal P[3], PetscReal *pf_norm, PetscReal *scale)
{
  PetscReal pp[3], pf[3], ow[3], s = 0, m;
  DemArrays pa;

  PetscFunctionBeginUser;
  PetscCall(CplGetMomentum(t->cpl, pp, pf, ow));
  for (int k = 0; k < 3; k++) P[k] = pp[k] + pf[k] + ow[k];
  if (pf_norm) *pf_norm = PetscSqrtReal(pf[0] * pf[0] + pf[1] * pf[1] + pf[2] * pf[2]);
  PetscCall(DemGetArrays(t->dem, &pa));
  for (PetscInt p = 0; p < pa.nlocal; p++) {
    PetscCall(DemGetShape(t->dem, pa.shape[p], NULL, &m));
    s += m * PetscSqrtReal(pa.v[3 * p] * pa.v[3 * p] + pa.v[3 * p + 1] * pa.v[3 * p + 1] + pa.v[3 * p + 2] * pa.v[3 * p + 2]);
  }
  PetscCall(MPIU_Allreduce(&s, scale, 1, MPIU_REAL, MPIU_SUM, PETSC_COMM_WORLD));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static inline PetscErrorCode TestCplRun(TestCpl *t, PetscInt nsteps, CplStats *st)
{
  PetscFunctionBeginUser;
  for (PetscInt s = 0; s < nsteps; s++) PetscCall(CplStep(t->cpl, st));
  PetscFunctionReturn(PETSC_SUCCESS);
}
