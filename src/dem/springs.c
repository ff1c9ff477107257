/* The tangential springs across a list rebuild. A spring belongs to a contact, and the contact
 * to a pair of particles (or a particle and a wall), not to a list entry: before a rebuild every
 * non-zero spring of the pair list and of the wall lists is saved as a record keyed by ids
 * (owner, partner; a wall is partner -1 - its index), sorted by (owner, partner); migration
 * carries a particle's records with it (exchange.c, redistribute.c); after the rebuild each new
 * entry takes its spring back by a binary search. In the half list a pair listed under (j, i)
 * takes the opposite of the spring saved under (i, j); when particles may move to another rank a
 * pair listed once is saved from both sides, so that each particle takes its own side along.
 * This file calls no other of the DEM: it reads the lists and writes the springs only. */
#include "dem/dem_core.h"

static int dem_spring_cmp(const void *a, const void *b)
{
  const DemSpring *x = (const DemSpring *)a, *y = (const DemSpring *)b;
  if (x->owner != y->owner) return x->owner < y->owner ? -1 : 1;
  return x->partner < y->partner ? -1 : (x->partner > y->partner);
}

PetscErrorCode DemSpringsSort(DemSpring *r, PetscInt n)
{
  PetscFunctionBeginUser;
  if (n > 1) qsort(r, (size_t)n, sizeof *r, dem_spring_cmp);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The record (owner, partner), or with partner = PETSC_MIN_INT the first record of owner. */
const DemSpring *DemSpringFind(const DemSpring *r, PetscInt n, PetscInt owner, PetscInt partner)
{
  PetscInt lo = 0, hi = n; /* first record >= (owner, partner) */
  while (lo < hi) {
    const PetscInt m = (lo + hi) / 2;
    if (r[m].owner < owner || (r[m].owner == owner && r[m].partner < partner)) lo = m + 1;
    else hi = m;
  }
  if (lo == n || r[lo].owner != owner) return NULL;
  if (partner != PETSC_MIN_INT && r[lo].partner != partner) return NULL;
  return r + lo;
}

/* Not collective. The current springs as id-keyed records, sorted (pairs and walls); the caller
 * frees *recs. */
PetscErrorCode DemSpringsSave(Dem dem, DemSpring **recs, PetscInt *nrec, PetscInt *cap)
{
  DemNeigh *nl = &dem->nl;
  PetscInt  n  = 0;
  /* a pair listed once is saved from both sides when particles may move to another rank, so
     that each takes its own side of the spring along */
  const PetscBool twice = (PetscBool)(!dem->nl.full_list && dem->ex.active);

  PetscFunctionBeginUser;
  for (int pass = 0; pass < 2; pass++) { /* count, then fill: the records are a transient peak */
    if (pass) {
      *cap = n + 64;
      PetscCall(PetscMalloc1(*cap, recs));
    }
    n = 0;
    if (nl->hist && nl->start)
      for (PetscInt i = 0; i < dem->p.n; i++)
        for (PetscInt a = nl->start[i]; a < nl->start[i + 1]; a++) {
          const double  *h = nl->hist + 3 * a;
          const PetscInt j = nl->nbr[a];
          if (h[0] == 0 && h[1] == 0 && h[2] == 0) continue;
          if (pass) (*recs)[n] = (DemSpring){dem->p.id[i], dem->p.id[j], {h[0], h[1], h[2]}};
          n++;
          if (!twice || j >= dem->p.n) continue;
          if (pass) (*recs)[n] = (DemSpring){dem->p.id[j], dem->p.id[i], {-h[0], -h[1], -h[2]}};
          n++;
        }
    if (dem->contact.law != DEM_LAW_LINEAR_NOHIST)
      for (PetscInt w = 0; w < dem->walls.nwall; w++)
        for (PetscInt a = 0; a < dem->walls.wall[w].cnt; a++) {
          const double *h = dem->walls.wall[w].hist + 3 * a;
          if (h[0] == 0 && h[1] == 0 && h[2] == 0) continue;
          if (pass) (*recs)[n] = (DemSpring){dem->p.id[dem->walls.wall[w].idx[a]], -1 - w, {h[0], h[1], h[2]}};
          n++;
        }
  }
  *nrec = n;
  PetscCall(DemSpringsSort(*recs, n));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Not collective. The springs of the new pair-list rows from the records (a pair without one
 * starts unloaded). */
PetscErrorCode DemSpringsRestore(Dem dem, const DemSpring *recs, PetscInt nrec)
{
  DemNeigh *nl = &dem->nl;
  PetscInt  m  = nl->start[dem->p.n];

  PetscFunctionBeginUser;
  PetscCall(PetscFree(nl->hist));
  PetscCall(PetscCalloc1(3 * (size_t)m + 3, &nl->hist));
  if (!nrec) PetscFunctionReturn(PETSC_SUCCESS);
  for (PetscInt i = 0; i < dem->p.n; i++)
    for (PetscInt a = nl->start[i]; a < nl->start[i + 1]; a++) {
      const PetscInt   j = nl->nbr[a];
      const DemSpring *r = DemSpringFind(recs, nrec, dem->p.id[i], dem->p.id[j]);
      double          *h = nl->hist + 3 * a;
      if (r)
        for (int k = 0; k < 3; k++) h[k] = r->xi[k];
      else if (!dem->nl.full_list && (r = DemSpringFind(recs, nrec, dem->p.id[j], dem->p.id[i])))
        for (int k = 0; k < 3; k++) h[k] = -r->xi[k]; /* stored from the partner's side */
    }
  PetscFunctionReturn(PETSC_SUCCESS);
}
