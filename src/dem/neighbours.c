/* Neighbour search in three named parts (after LAMMPS): binning (a linked-cell grid over the
 * rank's box plus the halo, cell size >= reach = 2 r_max + skin, by counting sort), stencil (the
 * own cell and its 26 neighbours), and pair list (CSR rows for local particles).
 *   Half list (default): a local-local pair is listed once (own cell j > i, or the 13 forward
 *   cells); a local-ghost pair is listed in the local particle's row on both ranks.
 *   Full list (-dem_deterministic): every partner in every row, rows sorted by partner id, so a
 *   particle's force is summed in the same order whatever the decomposition or the sort.
 * This file only builds lists: the rebuild that calls it (rebuild.c) also migrates, creates the
 * ghosts and carries the springs. Between migration and ghost creation the locals are re-sorted
 * along a Z-order curve of the cells every -dem_sort_interval builds (DemNeighSort); after it the
 * bins and rows cover locals and ghosts (DemNeighBuildList). Cell coordinates are clamped to the
 * grid, which keeps every pair within reach in adjacent cells even for a particle outside the box
 * (clamping is 1-Lipschitz). */
#include "dem/dem_core.h"

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

/* The cell grid over the box plus its halo with nc[k] cells along k (a checkpoint restores the
 * grid of the run that wrote it: the count depends on the particles at its set-up). */
PetscErrorCode DemNeighSetCells(Dem dem, const PetscInt nc[3])
{
  DemNeigh *nl = &dem->nl;
  double    len[3];

  PetscFunctionBeginUser;
  for (int k = 0; k < 3; k++) len[k] = dem->dom->subhi[k] - dem->dom->sublo[k] + 2 * dem->nl.reach;
  PetscCall(PetscFree(nl->cstart));
  nl->ncell = 1;
  for (int k = 0; k < 3; k++) {
    nl->nc[k]  = nc[k];
    nl->lo[k]  = dem->dom->sublo[k] - dem->nl.reach;
    nl->inv[k] = nl->nc[k] / len[k];
    nl->ncell *= nl->nc[k];
  }
  PetscCall(PetscMalloc1(nl->ncell + 1, &nl->cstart));
  PetscCall(DemCellsZOrder(nl));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode DemCellsSetUp(Dem dem)
{
  double len[3], c = dem->nl.reach, ncell;

  PetscFunctionBeginUser;
  for (int k = 0; k < 3; k++) len[k] = dem->dom->subhi[k] - dem->dom->sublo[k] + 2 * dem->nl.reach;
  /* never more than ~8 cells per particle (+1000): a huge box with few particles stays cheap,
     and a tall column whose bed fills a fifth of it (a fluidized bed) keeps cells of one reach
     (at 2 per particle its cells grew to 1.56 reach: 3.8x the candidate pairs, +23% list time) */
  for (;;) {
    ncell = 1;
    for (int k = 0; k < 3; k++) ncell *= PetscMax(1.0, PetscFloorReal(len[k] / c));
    if (ncell <= 8.0 * dem->p.n + 1000) break;
    c *= 1.25;
  }
  PetscInt nc[3];
  for (int k = 0; k < 3; k++) nc[k] = (PetscInt)PetscMax(1.0, PetscFloorReal(len[k] / c));
  PetscCall(DemNeighSetCells(dem, nc));
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
    const double *xi = dem->p.x + 3 * i;
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
  {0, 0, 0},
  {1, 0, 0},
  {-1, 1, 0},
  {0, 1, 0},
  {1, 1, 0},
  {-1, -1, 1},
  {0, -1, 1},
  {1, -1, 1},
  {-1, 0, 1},
  {0, 0, 1},
  {1, 0, 1},
  {-1, 1, 1},
  {0, 1, 1},
  {1, 1, 1},
};

static int dem_nbr_id_cmp(const void *a, const void *b, const Dem dem)
{
  const PetscInt x = dem->p.id[*(const PetscInt *)a], y = dem->p.id[*(const PetscInt *)b];
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
  DemNeigh    *nl   = &dem->nl;
  PetscInt     m    = 0;
  const double skin = dem->nl.skin;

  PetscFunctionBeginUser;
  PetscCall(PetscFree(nl->start));
  PetscCall(PetscMalloc1(dem->p.n + 1, &nl->start));
  for (PetscInt i = 0; i < dem->p.n; i++) {
    const double *xi = dem->p.x + 3 * i, ri = DemRadius(&dem->p, &dem->shapes, i);
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
        if (!dem->nl.full_list && j < dem->p.n && (s >= 14 || (s == 0 && j < i))) continue; /* the pair is in j's row */
        const double *xj = dem->p.x + 3 * j, rc = ri + DemRadius(&dem->p, &dem->shapes, j) + skin;
        const double  d[3] = {xj[0] - xi[0], xj[1] - xi[1], xj[2] - xi[2]};
        if (dem_dot(d, d) >= rc * rc) continue;
        if (m == nl->cap) {
          nl->cap = nl->cap + nl->cap / 4 + 1024;
          PetscCall(PetscRealloc(sizeof(PetscInt) * (size_t)nl->cap, &nl->nbr));
        }
        nl->nbr[m++] = j;
      }
    }
    if (dem->nl.full_list) dem_row_sort(dem, nl->nbr + nl->start[i], m - nl->start[i]);
  }
  nl->start[dem->p.n] = m;
  PetscCall(PetscFree(nl->own));
  PetscCall(PetscMalloc1(m + 1, &nl->own));
  for (PetscInt i = 0; i < dem->p.n; i++)
    for (PetscInt a = nl->start[i]; a < nl->start[i + 1]; a++) nl->own[a] = i;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Not collective. At each rebuild, after migration: sets up the cells over the box if there are
 * none (the first build, or after DemNeighResetCells) and, every -dem_sort_interval builds,
 * re-sorts the local particles along the Z-order of the cells. */
PetscErrorCode DemNeighSort(Dem dem)
{
  DemNeigh *nl = &dem->nl;

  PetscFunctionBeginUser;
  if (!nl->cstart) PetscCall(DemCellsSetUp(dem));
  if (dem->nl.sort_interval > 0 && nl->builds % dem->nl.sort_interval == 0) {
    PetscCall(DemBin(dem, dem->p.n, nl->zrank));
    PetscCall(DemParticlesPermute(dem, nl->order));
    nl->sorts++;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Not collective. Bins the local particles and the ghosts and builds the pair list. */
PetscErrorCode DemNeighBuildList(Dem dem)
{
  PetscFunctionBeginUser;
  PetscCall(DemBin(dem, dem->p.n + dem->p.ng, NULL));
  PetscCall(DemPairList(dem));
  dem->nl.builds++;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The cell grid is set up anew at the next build (the rank's box changed). */
PetscErrorCode DemNeighResetCells(Dem dem)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree(dem->nl.cstart));
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
