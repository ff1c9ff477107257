/* Neighbour search in three named parts (after LAMMPS): binning (a linked-cell grid over the
 * rank's box plus the halo, cell size >= reach = 2 r_max + skin, by counting sort), stencil (the
 * own cell and its 26 neighbours), and pair list (CSR rows for local particles).
 *   Half list (default): a local-local pair is listed once (own cell j > i, or the 13 forward
 *   cells); a local-ghost pair is listed in the local particle's row on both ranks.
 *   Full list (-dem_deterministic): every partner in every row, rows sorted by partner id, so a
 *   particle's force is summed in the same order whatever the decomposition or the sort.
 * Rebuild (dem.c decides when: a particle or a wall moved more than skin/2, agreed by all
 * ranks): springs saved by id pair -> migration -> re-sort of the locals by cell every
 * -dem_sort_interval builds -> ghost creation -> bins -> rows -> springs restored by id pair
 * (in the half list a pair found under (j, i) takes the opposite spring). Cell coordinates are
 * clamped to the grid, which keeps every pair within reach in adjacent cells even for a particle
 * outside the box (clamping is 1-Lipschitz). */
#include "dem/dem_impl.h"

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

/* Morton key of a cell: the bits of cx, cy, cz interleaved. */
static uint64_t dem_morton(PetscInt cx, PetscInt cy, PetscInt cz)
{
  uint64_t key = 0;
  for (int b = 0; b < 21; b++)
    key |= (((uint64_t)cx >> b) & 1) << (3 * b) | (((uint64_t)cy >> b) & 1) << (3 * b + 1) | (((uint64_t)cz >> b) & 1) << (3 * b + 2);
  return key;
}

static int dem_u64pair_cmp(const void *a, const void *b)
{
  const uint64_t x = ((const uint64_t *)a)[0], y = ((const uint64_t *)b)[0];
  return x < y ? -1 : (x > y);
}

/* zrank[c]: position of cell c along the Z-order curve. Particles re-sorted by it sit near their
 * neighbours in memory along all three axes, not only along x (measured: fewer cache misses in
 * the pair loop of a 10^5-particle bed than the plain cell order). */
static PetscErrorCode DemCellsZOrder(DemNeigh *nl)
{
  uint64_t *kv;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(2 * (size_t)nl->ncell, &kv));
  for (PetscInt c = 0; c < nl->ncell; c++) {
    kv[2 * c]     = dem_morton(c % nl->nc[0], (c / nl->nc[0]) % nl->nc[1], c / (nl->nc[0] * nl->nc[1]));
    kv[2 * c + 1] = (uint64_t)c;
  }
  qsort(kv, (size_t)nl->ncell, 2 * sizeof(uint64_t), dem_u64pair_cmp);
  PetscCall(PetscFree(nl->zrank));
  PetscCall(PetscMalloc1(nl->ncell, &nl->zrank));
  for (PetscInt r = 0; r < nl->ncell; r++) nl->zrank[kv[2 * r + 1]] = r;
  PetscCall(PetscFree(kv));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode DemCellsSetUp(Dem dem)
{
  DemNeigh *nl = &dem->nl;
  double    len[3], c = dem->reach, ncell;

  PetscFunctionBeginUser;
  for (int k = 0; k < 3; k++) len[k] = dem->dom->subhi[k] - dem->dom->sublo[k] + 2 * dem->reach;
  /* never more than ~8 cells per particle (+1000): a huge box with few particles stays cheap,
     and a tall column whose bed fills a fifth of it (a fluidized bed) keeps cells of one reach
     (at 2 per particle its cells grew to 1.56 reach: 3.8x the candidate pairs, +23% list time) */
  for (;;) {
    ncell = 1;
    for (int k = 0; k < 3; k++) ncell *= PetscMax(1.0, PetscFloorReal(len[k] / c));
    if (ncell <= 8.0 * dem->n + 1000) break;
    c *= 1.25;
  }
  PetscCall(PetscFree(nl->cstart));
  nl->ncell = 1;
  for (int k = 0; k < 3; k++) {
    nl->nc[k]  = (PetscInt)PetscMax(1.0, PetscFloorReal(len[k] / c));
    nl->lo[k]  = dem->dom->sublo[k] - dem->reach;
    nl->inv[k] = nl->nc[k] / len[k];
    nl->ncell *= nl->nc[k];
  }
  PetscCall(PetscMalloc1(nl->ncell + 1, &nl->cstart));
  PetscCall(DemCellsZOrder(nl));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static inline PetscInt dem_cell_coord(const DemNeigh *nl, const double *x, int k)
{
  PetscInt c = (PetscInt)floor((x[k] - nl->lo[k]) * nl->inv[k]);
  return c < 0 ? 0 : (c >= nl->nc[k] ? nl->nc[k] - 1 : c);
}

/* Binning of particles 0..m-1: cstart[] and order[] (grouped by cell, ascending index). With
 * key, the buckets are key[cell] instead (the Z-order of the re-sort). */
static PetscErrorCode DemBin(Dem dem, PetscInt m, const PetscInt *key)
{
  DemNeigh *nl = &dem->nl;

  PetscFunctionBeginUser;
  PetscCall(PetscFree(nl->cof));
  PetscCall(PetscFree(nl->order));
  PetscCall(PetscMalloc1(m + 1, &nl->cof));
  PetscCall(PetscMalloc1(m + 1, &nl->order));
  PetscCall(PetscArrayzero(nl->cstart, nl->ncell + 1));
  for (PetscInt i = 0; i < m; i++) {
    const double *xi = dem->x + 3 * i;
    nl->cof[i]       = dem_cell_coord(nl, xi, 0) + nl->nc[0] * (dem_cell_coord(nl, xi, 1) + nl->nc[1] * dem_cell_coord(nl, xi, 2));
    if (key) nl->cof[i] = key[nl->cof[i]];
    nl->cstart[nl->cof[i] + 1]++;
  }
  for (PetscInt c = 0; c < nl->ncell; c++) nl->cstart[c + 1] += nl->cstart[c];
  for (PetscInt i = 0; i < m; i++) nl->order[nl->cstart[nl->cof[i]]++] = i;
  for (PetscInt c = nl->ncell; c > 0; c--) nl->cstart[c] = nl->cstart[c - 1];
  nl->cstart[0] = 0;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Stencil: the own cell, the 13 neighbours lexicographically after it (dz, dy, dx), then the 13
 * before it (searched for ghosts only in the half list). */
static const int dem_stencil[14][3] = {
  {0, 0, 0}, {1, 0, 0}, {-1, 1, 0}, {0, 1, 0}, {1, 1, 0}, {-1, -1, 1}, {0, -1, 1},
  {1, -1, 1}, {-1, 0, 1}, {0, 0, 1}, {1, 0, 1}, {-1, 1, 1}, {0, 1, 1}, {1, 1, 1},
};

static int dem_nbr_id_cmp(const void *a, const void *b, const Dem dem)
{
  const PetscInt x = dem->id[*(const PetscInt *)a], y = dem->id[*(const PetscInt *)b];
  return x < y ? -1 : (x > y);
}

/* insertion sort of a short row by partner id */
static void dem_row_sort(Dem dem, PetscInt *row, PetscInt len)
{
  for (PetscInt a = 1; a < len; a++) {
    const PetscInt v = row[a];
    PetscInt       b = a - 1;
    while (b >= 0 && dem_nbr_id_cmp(&row[b], &v, dem) > 0) {
      row[b + 1] = row[b];
      b--;
    }
    row[b + 1] = v;
  }
}

/* Pair list: row i (local) holds the partners j within r_i + r_j + skin (see file header). */
static PetscErrorCode DemPairList(Dem dem)
{
  DemNeigh    *nl = &dem->nl;
  PetscInt     m = 0;
  const double skin = dem->skin;

  PetscFunctionBeginUser;
  PetscCall(PetscFree(nl->start));
  PetscCall(PetscMalloc1(dem->n + 1, &nl->start));
  for (PetscInt i = 0; i < dem->n; i++) {
    const double *xi = dem->x + 3 * i, ri = dem->shp[dem->shape[i]].r;
    PetscInt      c[3];
    nl->start[i] = m;
    for (int k = 0; k < 3; k++) c[k] = dem_cell_coord(nl, xi, k);
    for (int s = 0; s < 27; s++) {
      const int sign = s < 14 ? 1 : -1, *o = dem_stencil[s < 14 ? s : s - 13];
      PetscInt  cc[3];
      int       inside = 1;
      for (int k = 0; k < 3; k++) {
        cc[k] = c[k] + sign * o[k];
        inside &= cc[k] >= 0 && cc[k] < nl->nc[k];
      }
      if (!inside) continue;
      const PetscInt cell = cc[0] + nl->nc[0] * (cc[1] + nl->nc[1] * cc[2]);
      for (PetscInt a = nl->cstart[cell]; a < nl->cstart[cell + 1]; a++) {
        const PetscInt j = nl->order[a];
        if (j == i) continue;
        if (!dem->full_list && j < dem->n && (s >= 14 || (s == 0 && j < i))) continue; /* the pair is in j's row */
        const double *xj = dem->x + 3 * j, rc = ri + dem->shp[dem->shape[j]].r + skin;
        const double  d[3] = {xj[0] - xi[0], xj[1] - xi[1], xj[2] - xi[2]};
        if (dem_dot(d, d) >= rc * rc) continue;
        if (m == nl->cap) {
          nl->cap = nl->cap + nl->cap / 4 + 1024;
          PetscCall(PetscRealloc(sizeof(PetscInt) * (size_t)nl->cap, &nl->nbr));
        }
        nl->nbr[m++] = j;
      }
    }
    if (dem->full_list) dem_row_sort(dem, nl->nbr + nl->start[i], m - nl->start[i]);
  }
  nl->start[dem->n] = m;
  PetscCall(PetscFree(nl->own));
  PetscCall(PetscMalloc1(m + 1, &nl->own));
  for (PetscInt i = 0; i < dem->n; i++)
    for (PetscInt a = nl->start[i]; a < nl->start[i + 1]; a++) nl->own[a] = i;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The current springs as id-keyed records, sorted (pairs and walls). */
static PetscErrorCode DemSpringsSave(Dem dem, DemSpring **recs, PetscInt *nrec, PetscInt *cap)
{
  DemNeigh *nl = &dem->nl;
  PetscInt  n  = 0;
  /* a pair listed once is saved from both sides when particles may move to another rank, so
     that each takes its own side of the spring along */
  const PetscBool twice = (PetscBool)(!dem->full_list && dem->ex.active);

  PetscFunctionBeginUser;
  for (int pass = 0; pass < 2; pass++) { /* count, then fill: the records are a transient peak */
    if (pass) {
      *cap = n + 64;
      PetscCall(PetscMalloc1(*cap, recs));
    }
    n = 0;
    if (nl->hist && nl->start)
      for (PetscInt i = 0; i < dem->n; i++)
        for (PetscInt a = nl->start[i]; a < nl->start[i + 1]; a++) {
          const double  *h = nl->hist + 3 * a;
          const PetscInt j = nl->nbr[a];
          if (h[0] == 0 && h[1] == 0 && h[2] == 0) continue;
          if (pass) (*recs)[n] = (DemSpring){dem->id[i], dem->id[j], {h[0], h[1], h[2]}};
          n++;
          if (!twice || j >= dem->n) continue;
          if (pass) (*recs)[n] = (DemSpring){dem->id[j], dem->id[i], {-h[0], -h[1], -h[2]}};
          n++;
        }
    if (dem->law != DEM_LAW_LINEAR_NOHIST)
      for (PetscInt w = 0; w < dem->nwall; w++)
        for (PetscInt a = 0; a < dem->wall[w].cnt; a++) {
          const double *h = dem->wall[w].hist + 3 * a;
          if (h[0] == 0 && h[1] == 0 && h[2] == 0) continue;
          if (pass) (*recs)[n] = (DemSpring){dem->id[dem->wall[w].idx[a]], -1 - w, {h[0], h[1], h[2]}};
          n++;
        }
  }
  *nrec = n;
  PetscCall(DemSpringsSort(*recs, n));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Springs of the new rows from the records. */
static PetscErrorCode DemSpringsRestore(Dem dem, const DemSpring *recs, PetscInt nrec)
{
  DemNeigh *nl = &dem->nl;
  PetscInt  m  = nl->start[dem->n];

  PetscFunctionBeginUser;
  PetscCall(PetscFree(nl->hist));
  PetscCall(PetscCalloc1(3 * (size_t)m + 3, &nl->hist));
  if (!nrec) PetscFunctionReturn(PETSC_SUCCESS);
  for (PetscInt i = 0; i < dem->n; i++)
    for (PetscInt a = nl->start[i]; a < nl->start[i + 1]; a++) {
      const PetscInt   j = nl->nbr[a];
      const DemSpring *r = DemSpringFind(recs, nrec, dem->id[i], dem->id[j]);
      double          *h = nl->hist + 3 * a;
      if (r) for (int k = 0; k < 3; k++) h[k] = r->xi[k];
      else if (!dem->full_list && (r = DemSpringFind(recs, nrec, dem->id[j], dem->id[i])))
        for (int k = 0; k < 3; k++) h[k] = -r->xi[k]; /* stored from the partner's side */
    }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. Rebuilds exchange, cells, lists and springs. */
PetscErrorCode DemNeighBuild(Dem dem)
{
  DemNeigh  *nl = &dem->nl;
  DemSpring *recs;
  PetscInt   nrec, caprec;

  PetscFunctionBeginUser;
  dem->state++; /* migration and re-sorting change the local order */
  PetscCall(PetscLogEventBegin(DEM_Neighbours, 0, 0, 0, 0));
  PetscCall(DemSpringsSave(dem, &recs, &nrec, &caprec));
  dem->ng = 0;
  PetscCall(PetscLogEventBegin(DEM_Exchange, 0, 0, 0, 0));
  PetscCall(DemCheckInDomain(dem));
  if (dem->remap) PetscCall(DemMigrateGlobal(dem, &recs, &nrec, &caprec));
  else PetscCall(DemMigrate(dem, &recs, &nrec, &caprec));
  dem->remap = PETSC_FALSE;
  PetscCall(PetscLogEventEnd(DEM_Exchange, 0, 0, 0, 0));
  if (!nl->cstart) PetscCall(DemCellsSetUp(dem));
  if (dem->sort_interval > 0 && nl->builds % dem->sort_interval == 0) {
    PetscCall(DemBin(dem, dem->n, nl->zrank));
    PetscCall(DemParticlesPermute(dem, nl->order));
    nl->sorts++;
  }
  PetscCall(PetscLogEventBegin(DEM_Exchange, 0, 0, 0, 0));
  PetscCall(DemGhostsCreate(dem));
  PetscCall(PetscLogEventEnd(DEM_Exchange, 0, 0, 0, 0));
  PetscCall(DemBin(dem, dem->n + dem->ng, NULL));
  PetscCall(DemPairList(dem));
  if (dem->law != DEM_LAW_LINEAR_NOHIST) PetscCall(DemSpringsRestore(dem, recs, nrec));
  PetscCall(DemWallsBuildLists(dem, recs, nrec));
  PetscCall(PetscArraycpy(dem->x0, dem->x, 3 * dem->n));
  for (PetscInt w = 0; w < dem->nwall; w++) dem->wall[w].moved = 0;
  nl->builds++;
  dem->need_build = PETSC_FALSE;
  PetscCall(PetscFree(recs));
  PetscCall(PetscLogEventEnd(DEM_Neighbours, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemNeighDestroy(Dem dem)
{
  DemNeigh *nl = &dem->nl;

  PetscFunctionBeginUser;
  PetscCall(PetscFree(nl->cstart));
  PetscCall(PetscFree(nl->zrank));
  PetscCall(PetscFree(nl->cof));
  PetscCall(PetscFree(nl->order));
  PetscCall(PetscFree(nl->start));
  PetscCall(PetscFree(nl->nbr));
  PetscCall(PetscFree(nl->own));
  PetscCall(PetscFree(nl->hist));
  PetscFunctionReturn(PETSC_SUCCESS);
}
