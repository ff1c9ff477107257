/* Redistribution of the particles after the decomposition changed (load balancing, DESIGN §1).
 * The process grid stays, only the per-axis cuts move, so a particle may now belong to any rank,
 * not only to a neighbour: one all-to-all exchange sends every particle to the rank whose box
 * holds its centre, with the same record as a migration (state, force and torque of the last
 * step, coupling state, tangential springs keyed by ids), after wrapping positions across
 * periodic boundaries. The owner is found from the cut positions computed exactly as the rank
 * boxes are (lo + cells * h), so the global and the neighbour migrations agree on every
 * particle. DemRedistribute (rebuild.c) runs it as the migration of a full rebuild, the cell grid
 * set up anew over the new box. Also here: what the balancer measures (the halo width, the
 * particles per grid cell, the compute time). */
#include "dem/dem_core.h"

/* Rank column along axis k whose box holds coordinate x: box r is [lo + s_r h, lo + s_{r+1} h)
 * with s_r the cells before column r; below lo the first, from hi on the last. */
static PetscMPIInt dem_owner_column(const Domain *dom, const PetscInt *l, int k, double x)
{
  PetscInt c = 0, s = l[0];
  for (PetscInt r = 1; r < dom->nranks[k]; s += l[r], r++) {
    if (x < dom->lo[k] + s * dom->h[k]) break;
    c = r;
  }
  return (PetscMPIInt)c;
}

PetscErrorCode DemMigrateGlobal(Dem dem, DemSpring **recs, PetscInt *nrec, PetscInt *caprec)
{
  const Domain   *dom = dem->dom;
  DemExchange    *ex  = &dem->ex;
  const PetscInt *l[3];
  PetscMPIInt     size, me, *owner, *scnt, *sdsp, *rcnt, *rdsp;
  PetscInt       *keep, nkeep = 0;
  const double    zero[3] = {0, 0, 0};
  size_t          total = 0, rtotal = 0;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(dem->comm, &size));
  PetscCallMPI(MPI_Comm_rank(dem->comm, &me));
  PetscCall(DMDAGetOwnershipRanges(dom->da, &l[0], &l[1], &l[2]));
  PetscCall(PetscMalloc2(dem->p.n + 1, &owner, dem->p.n + 1, &keep));
  PetscCall(PetscCalloc4(size, &scnt, size + 1, &sdsp, size, &rcnt, size + 1, &rdsp));
  for (PetscInt i = 0; i < dem->p.n; i++) {
    double     *x = dem->p.x + 3 * i;
    PetscMPIInt c[3];
    for (int k = 0; k < 3; k++) {
      if (dom->periodic[k] && x[k] < dom->lo[k]) x[k] += dom->len[k];
      else if (dom->periodic[k] && x[k] >= dom->hi[k]) x[k] -= dom->len[k];
      c[k] = dem_owner_column(dom, l[k], k, x[k]);
    }
    owner[i] = c[0] + (PetscMPIInt)dom->nranks[0] * (c[1] + (PetscMPIInt)dom->nranks[1] * c[2]);
    if (owner[i] == me) {
      keep[nkeep++] = i;
      continue;
    }
    const size_t sz = DemMigSize(dem, i, *recs, *nrec);
    scnt[owner[i]] += (PetscMPIInt)sz;
    total += sz;
  }
  PetscCheck(total < (size_t)PETSC_MPI_INT_MAX, PETSC_COMM_SELF, PETSC_ERR_SUP, "redistribution message of %zu doubles exceeds the MPI count limit", total);
  for (PetscMPIInt r = 0; r < size; r++) sdsp[r + 1] = sdsp[r] + scnt[r];
  PetscCall(PetscArraycpy(rdsp, sdsp, size)); /* running positions while packing */
  PetscCall(DemBufReserve(&ex->sbuf, &ex->capsbuf, total + 1));
  for (PetscInt i = 0; i < dem->p.n; i++)
    if (owner[i] != me) rdsp[owner[i]] += (PetscMPIInt)DemMigPack(dem, i, *recs, *nrec, zero, ex->sbuf + rdsp[owner[i]]);
  ex->migrated = dem->p.n - nkeep;
  dem->p.n     = nkeep;
  PetscCall(DemParticlesPermute(dem, keep));
  PetscCallMPI(MPI_Alltoall(scnt, 1, MPI_INT, rcnt, 1, MPI_INT, dem->comm));
  rdsp[0] = 0;
  for (PetscMPIInt r = 0; r < size; r++) {
    rdsp[r + 1] = rdsp[r] + rcnt[r];
    rtotal += (size_t)rcnt[r];
  }
  PetscCheck(rtotal < (size_t)PETSC_MPI_INT_MAX, PETSC_COMM_SELF, PETSC_ERR_SUP, "redistribution message of %zu doubles exceeds the MPI count limit", rtotal);
  PetscCall(DemBufReserve(&ex->rbuf, &ex->caprbuf, rtotal + 1));
  PetscCallMPI(MPI_Alltoallv(ex->sbuf, scnt, sdsp, MPI_DOUBLE, ex->rbuf, rcnt, rdsp, MPI_DOUBLE, dem->comm));
  for (size_t o = 0, used; o < rtotal; o += used) PetscCall(DemMigUnpack(dem, ex->rbuf + o, recs, nrec, caprec, &used));
  PetscCall(DemSpringsSort(*recs, *nrec));
  PetscCall(PetscFree2(owner, keep));
  PetscCall(PetscFree4(scnt, sdsp, rcnt, rdsp));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemGetHaloWidth(Dem dem, PetscReal *reach)
{
  PetscFunctionBeginUser;
  *reach = dem->nl.reach;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The global grid cell of particle i's centre, clamped to this rank's cells (a particle a little
 * outside its box counts in its edge cell). */
static PetscInt dem_cell_of(const Dem dem, PetscInt i)
{
  const Domain *dom = dem->dom;
  PetscInt      c[3];

  for (int k = 0; k < 3; k++) {
    c[k] = (PetscInt)PetscFloorReal((dem->p.x[3 * i + k] - dom->lo[k]) / dom->h[k]);
    c[k] = PetscMin(PetscMax(c[k], dom->cstart[k]), dom->cstart[k] + dom->ccount[k] - 1);
  }
  return c[0] + dom->cells[0] * (c[1] + dom->cells[1] * c[2]);
}

PetscErrorCode DemGetCellCounts(Dem dem, PetscInt *count)
{
  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < dem->p.n; i++) count[dem_cell_of(dem, i)] += 1;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemGetMeshCount(Dem dem, PetscInt *n)
{
  PetscFunctionBeginUser;
  *n = dem->meshes.n;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemGetCellMeshCounts(Dem dem, PetscInt *count)
{
  PetscFunctionBeginUser;
  for (PetscInt k = 0; k < dem->meshes.n; k++) {
    const DemMesh *m = &dem->meshes.m[k];
    if (!m->cstart) continue; /* no triangle near this rank */
    for (PetscInt i = 0; i < dem->p.n; i++) count[dem_cell_of(dem, i)] += m->cstart[i + 1] - m->cstart[i];
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemGetMeshTime(Dem dem, PetscLogDouble *t, PetscReal *cand)
{
  PetscFunctionBeginUser;
  *t    = dem->t_mesh;
  *cand = dem->mesh_cand;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemGetComputeTime(Dem dem, PetscLogDouble *t)
{
  PetscFunctionBeginUser;
  *t = dem->t_compute;
  PetscFunctionReturn(PETSC_SUCCESS);
}
