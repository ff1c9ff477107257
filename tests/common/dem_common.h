/* Shared by the DEM tests: a Domain + Dem built from an options string or a scene file,
 * particles found by id, and positions gathered by id over the ranks. */
#pragma once
#include "check.h"
#include "scene.h"
#include "dem/dem.h"

/* Builds Domain + Dem on comm from the options database (not yet set up). */
static inline PetscErrorCode TestDemBuildOn(MPI_Comm comm, Domain *dom, Dem *dem)
{
  PetscFunctionBeginUser;
  PetscCall(DomainCreate(comm, 0.05, 1, dom));
  PetscCall(DemCreate(dom, dem));
  PetscCall(DemSetFromOptions(*dem));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Replaces the options database by opts and builds Domain + Dem on comm (not yet set up). */
static inline PetscErrorCode TestDemCreateOn(MPI_Comm comm, const char *opts, Domain *dom, Dem *dem)
{
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsClear(NULL));
  PetscCall(PetscOptionsInsertString(NULL, opts));
  PetscCall(TestDemBuildOn(comm, dom, dem));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static inline PetscErrorCode TestDemCreate(const char *opts, Domain *dom, Dem *dem)
{
  PetscFunctionBeginUser;
  PetscCall(TestDemCreateOn(PETSC_COMM_WORLD, opts, dom, dem));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The same from the scene file `scene` of the test's folder and the options string extra
 * (scene.h). */
static inline PetscErrorCode TestDemCreateSceneOn(MPI_Comm comm, const char *scene, const char *extra, Domain *dom, Dem *dem)
{
  PetscFunctionBeginUser;
  PetscCall(TestSceneLoad(comm, scene, extra));
  PetscCall(TestDemBuildOn(comm, dom, dem));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static inline PetscErrorCode TestDemCreateScene(const char *scene, const char *extra, Domain *dom, Dem *dem)
{
  PetscFunctionBeginUser;
  PetscCall(TestDemCreateSceneOn(PETSC_COMM_WORLD, scene, extra, dom, dem));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static inline PetscErrorCode TestDemDestroy(Domain *dom, Dem *dem)
{
  PetscFunctionBeginUser;
  PetscCall(DemDestroy(dem));
  PetscCall(DomainDestroy(dom));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Local index of the particle with this id (-1 if not here). */
static inline PetscInt TestFind(Dem dem, PetscInt id)
{
  PetscInt    n;
  DemParticle p = {0};

  DemGetLocalCount(dem, &n);
  for (PetscInt i = 0; i < n; i++) {
    DemGetParticle(dem, i, &p);
    if (p.id == id) return i;
  }
  return -1;
}

static inline DemParticle TestGet(Dem dem, PetscInt id)
{
  DemParticle p = {0};
  memset(&p, 0, sizeof p);
  PetscInt i = TestFind(dem, id);
  if (i >= 0) DemGetParticle(dem, i, &p);
  return p;
}

/* Positions (and velocities) of all particles by id, gathered on every rank of comm; ids must
 * be 0..N-1. Returns the global count. */
static inline PetscErrorCode TestGatherById(Dem dem, MPI_Comm comm, PetscInt N, double *x, double *v, PetscInt *count)
{
  PetscInt    n;
  double     *loc, *all;
  PetscMPIInt size, *cnt, *dsp;
  int         nl;

  PetscFunctionBeginUser;
  PetscCall(DemGetLocalCount(dem, &n));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(PetscMalloc1(7 * n + 1, &loc));
  for (PetscInt i = 0; i < n; i++) {
    DemParticle p = {0};
    PetscCall(DemGetParticle(dem, i, &p));
    loc[7 * i] = (double)p.id;
    for (int k = 0; k < 3; k++) {
      loc[7 * i + 1 + k] = p.x[k];
      loc[7 * i + 4 + k] = p.v[k];
    }
  }
  PetscCall(PetscMalloc3(size, &cnt, size, &dsp, 7 * (N + 1), &all));
  nl = (int)(7 * n);
  PetscCallMPI(MPI_Allgather(&nl, 1, MPI_INT, cnt, 1, MPI_INT, comm));
  dsp[0] = 0;
  for (int r = 1; r < size; r++) dsp[r] = dsp[r - 1] + cnt[r - 1];
  *count = (dsp[size - 1] + cnt[size - 1]) / 7;
  PetscCheck(*count <= N, comm, PETSC_ERR_PLIB, "%" PetscInt_FMT " particles, expected at most %" PetscInt_FMT, *count, N);
  PetscCallMPI(MPI_Allgatherv(loc, nl, MPI_DOUBLE, all, cnt, dsp, MPI_DOUBLE, comm));
  for (PetscInt a = 0; a < *count; a++) {
    const PetscInt id = (PetscInt)all[7 * a];
    for (int k = 0; k < 3; k++) {
      x[3 * id + k] = all[7 * a + 1 + k];
      if (v) v[3 * id + k] = all[7 * a + 4 + k];
    }
  }
  PetscCall(PetscFree(loc));
  PetscCall(PetscFree3(cnt, dsp, all));
  PetscFunctionReturn(PETSC_SUCCESS);
}
