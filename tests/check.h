/* Shared by the test executables: one line per check, and a Dem built from an options string.
 * A check prints "PASS name: measured ... (bound ...)" or "FAIL ..." on rank 0 and counts. */
#pragma once
#include "dem/dem.h"

static int check_failures = 0;

static void check(PetscBool ok, const char *fmt, ...)
{
  va_list ap;
  char    buf[1024];

  va_start(ap, fmt);
  vsnprintf(buf, sizeof buf, fmt, ap);
  va_end(ap);
  if (!ok) check_failures++;
  PetscPrintf(PETSC_COMM_WORLD, "%s %s\n", ok ? "PASS" : "FAIL", buf);
}

/* Replaces the options database by opts and builds Domain + Dem (not yet set up). */
static PetscErrorCode TestDemCreate(const char *opts, Domain *dom, Dem *dem)
{
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsClear(NULL));
  PetscCall(PetscOptionsInsertString(NULL, opts));
  PetscCall(DomainCreate(PETSC_COMM_WORLD, 0.05, 1, dom));
  PetscCall(DemCreate(dom, dem));
  PetscCall(DemSetFromOptions(*dem));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode TestDemDestroy(Domain *dom, Dem *dem)
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
  DemParticle p;

  DemGetLocalCount(dem, &n);
  for (PetscInt i = 0; i < n; i++) {
    DemGetParticle(dem, i, &p);
    if (p.id == id) return i;
  }
  return -1;
}

static inline DemParticle TestGet(Dem dem, PetscInt id)
{
  DemParticle p;
  memset(&p, 0, sizeof p);
  PetscInt i = TestFind(dem, id);
  if (i >= 0) DemGetParticle(dem, i, &p);
  return p;
}
