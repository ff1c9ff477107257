/* Neighbour search in three named parts (after LAMMPS): binning (a linked-cell grid of cell
 * size >= reach = 2 r_max + skin, by counting sort), stencil (the own cell and the 13 forward
 * cells of the 26, so each pair is visited once), and pair list (a half Verlet list in CSR).
 * Rebuild check (dem.c): a particle or a wall has moved more than skin/2 since the last build.
 * Every -dem_sort_interval builds the particles are re-sorted by cell for memory locality.
 * Tangential springs follow their pair across a rebuild: the pair (i,j) is looked up in the old
 * row of i (or, with the sign flipped, of j) through the permutation of the re-sort.
 * Cell coordinates are clamped to the grid, which keeps every pair within reach in adjacent
 * cells even for a particle outside the box (clamping is 1-Lipschitz). */
#include "dem/dem_impl.h"

static PetscErrorCode DemCellsSetUp(Dem dem)
{
  DemNeigh *nl = &dem->nl;
  double    len[3], c = dem->reach, ncell;

  PetscFunctionBeginUser;
  for (int k = 0; k < 3; k++) len[k] = dem->dom->subhi[k] - dem->dom->sublo[k];
  /* never more cells than ~2 per particle (+1000): a huge box with few particles stays cheap */
  for (;;) {
    ncell = 1;
    for (int k = 0; k < 3; k++) ncell *= PetscMax(1.0, PetscFloorReal(len[k] / c));
    if (ncell <= 2.0 * dem->n + 1000) break;
    c *= 1.25;
  }
  PetscCall(PetscFree(nl->cstart));
  nl->ncell = 1;
  for (int k = 0; k < 3; k++) {
    nl->nc[k]  = (PetscInt)PetscMax(1.0, PetscFloorReal(len[k] / c));
    nl->lo[k]  = dem->dom->sublo[k];
    nl->inv[k] = nl->nc[k] / len[k];
    nl->ncell *= nl->nc[k];
  }
  PetscCall(PetscMalloc1(nl->ncell + 1, &nl->cstart));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static inline PetscInt dem_cell_coord(const DemNeigh *nl, const double *x, int k)
{
  PetscInt c = (PetscInt)floor((x[k] - nl->lo[k]) * nl->inv[k]);
  return c < 0 ? 0 : (c >= nl->nc[k] ? nl->nc[k] - 1 : c);
}

/* Binning: cof[i], cstart[] and order[] (particles grouped by cell, ascending index). */
static PetscErrorCode DemBin(Dem dem)
{
  DemNeigh *nl = &dem->nl;

  PetscFunctionBeginUser;
  PetscCall(PetscFree(nl->cof));
  PetscCall(PetscFree(nl->order));
  PetscCall(PetscMalloc1(dem->n + 1, &nl->cof));
  PetscCall(PetscMalloc1(dem->n + 1, &nl->order));
  PetscCall(PetscArrayzero(nl->cstart, nl->ncell + 1));
  for (PetscInt i = 0; i < dem->n; i++) {
    const double *xi = dem->x + 3 * i;
    nl->cof[i]       = dem_cell_coord(nl, xi, 0) + nl->nc[0] * (dem_cell_coord(nl, xi, 1) + nl->nc[1] * dem_cell_coord(nl, xi, 2));
    nl->cstart[nl->cof[i] + 1]++;
  }
  for (PetscInt c = 0; c < nl->ncell; c++) nl->cstart[c + 1] += nl->cstart[c];
  for (PetscInt i = 0; i < dem->n; i++) nl->order[nl->cstart[nl->cof[i]]++] = i;
  for (PetscInt c = nl->ncell; c > 0; c--) nl->cstart[c] = nl->cstart[c - 1];
  nl->cstart[0] = 0;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Stencil: the own cell, then the 13 neighbours lexicographically after it (dz, dy, dx). */
static const int dem_stencil[14][3] = {
  {0, 0, 0}, {1, 0, 0}, {-1, 1, 0}, {0, 1, 0}, {1, 1, 0}, {-1, -1, 1}, {0, -1, 1},
  {1, -1, 1}, {-1, 0, 1}, {0, 0, 1}, {1, 0, 1}, {-1, 1, 1}, {0, 1, 1}, {1, 1, 1},
};

/* Pair list: row i holds every j within r_i + r_j + skin of i, each pair in one row only. */
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
    for (int s = 0; s < 14; s++) {
      PetscInt cc[3];
      int      inside = 1;
      for (int k = 0; k < 3; k++) {
        cc[k] = c[k] + dem_stencil[s][k];
        inside &= cc[k] >= 0 && cc[k] < nl->nc[k];
      }
      if (!inside) continue;
      const PetscInt cell = cc[0] + nl->nc[0] * (cc[1] + nl->nc[1] * cc[2]);
      for (PetscInt a = nl->cstart[cell]; a < nl->cstart[cell + 1]; a++) {
        const PetscInt j = nl->order[a];
        if (s == 0 && j <= i) continue;
        const double *xj = dem->x + 3 * j, rc = ri + dem->shp[dem->shape[j]].r + skin;
        const double  d[3] = {xj[0] - xi[0], xj[1] - xi[1], xj[2] - xi[2]};
        if (dem_dot(d, d) >= rc * rc) continue;
        if (m == nl->cap) {
          nl->cap = 2 * nl->cap + 1024;
          PetscCall(PetscRealloc(sizeof(PetscInt) * (size_t)nl->cap, &nl->nbr));
        }
        nl->nbr[m++] = j;
      }
    }
  }
  nl->start[dem->n] = m;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Springs of the new list from the old one. perm maps new index -> old index (NULL: same). */
static PetscErrorCode DemCarryHistory(Dem dem, const PetscInt *ostart, const PetscInt *onbr, const double *ohist, const PetscInt *perm)
{
  DemNeigh *nl = &dem->nl;
  PetscInt  m  = nl->start[dem->n];

  PetscFunctionBeginUser;
  PetscCall(PetscFree(nl->hist));
  PetscCall(PetscCalloc1(3 * (size_t)m + 3, &nl->hist));
  if (!ohist) PetscFunctionReturn(PETSC_SUCCESS);
  for (PetscInt i = 0; i < dem->n; i++) {
    const PetscInt oi = perm ? perm[i] : i;
    for (PetscInt a = nl->start[i]; a < nl->start[i + 1]; a++) {
      const PetscInt oj = perm ? perm[nl->nbr[a]] : nl->nbr[a];
      double        *h  = nl->hist + 3 * a;
      for (PetscInt b = ostart[oi]; b < ostart[oi + 1]; b++)
        if (onbr[b] == oj) {
          for (int k = 0; k < 3; k++) h[k] = ohist[3 * b + k];
          break;
        }
      if (h[0] != 0 || h[1] != 0 || h[2] != 0) continue;
      for (PetscInt b = ostart[oj]; b < ostart[oj + 1]; b++)
        if (onbr[b] == oi) { /* stored from the partner's side: the spring points the other way */
          for (int k = 0; k < 3; k++) h[k] = -ohist[3 * b + k];
          break;
        }
    }
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective only through the walls (none today). Rebuilds cells, lists and springs. */
PetscErrorCode DemNeighBuild(Dem dem)
{
  DemNeigh *nl = &dem->nl;
  PetscInt *ostart = nl->start, *onbr = NULL, *perm = NULL, *inv = NULL;
  double   *ohist  = nl->hist;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(DEM_Neighbours, 0, 0, 0, 0));
  nl->start = NULL;
  nl->hist  = NULL;
  if (ostart) { /* keep the old pairs for the springs (the array itself is reused below) */
    PetscCall(PetscMalloc1(ostart[dem->n] + 1, &onbr));
    PetscCall(PetscArraycpy(onbr, nl->nbr, ostart[dem->n]));
  }
  if (!nl->cstart || nl->builds == 0) PetscCall(DemCellsSetUp(dem));
  PetscCall(DemBin(dem));
  if (dem->sort_interval > 0 && nl->builds % dem->sort_interval == 0) {
    PetscCall(PetscMalloc2(dem->n + 1, &perm, dem->n + 1, &inv));
    PetscCall(PetscArraycpy(perm, nl->order, dem->n));
    for (PetscInt i = 0; i < dem->n; i++) inv[perm[i]] = i;
    PetscCall(DemParticlesPermute(dem, perm));
    for (PetscInt i = 0; i < dem->n; i++) nl->order[i] = i; /* cells now hold consecutive runs */
    nl->sorts++;
  }
  PetscCall(DemPairList(dem));
  if (dem->law != DEM_LAW_LINEAR_NOHIST) PetscCall(DemCarryHistory(dem, ostart, onbr, ohist, perm));
  PetscCall(DemWallsBuildLists(dem, inv));
  PetscCall(PetscArraycpy(dem->x0, dem->x, 3 * dem->n));
  for (PetscInt w = 0; w < dem->nwall; w++) dem->wall[w].moved = 0;
  nl->builds++;
  dem->need_build = PETSC_FALSE;
  PetscCall(PetscFree(ostart));
  PetscCall(PetscFree(onbr));
  PetscCall(PetscFree(ohist));
  PetscCall(PetscFree2(perm, inv));
  PetscCall(PetscLogEventEnd(DEM_Neighbours, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemNeighDestroy(Dem dem)
{
  DemNeigh *nl = &dem->nl;

  PetscFunctionBeginUser;
  PetscCall(PetscFree(nl->cstart));
  PetscCall(PetscFree(nl->cof));
  PetscCall(PetscFree(nl->order));
  PetscCall(PetscFree(nl->start));
  PetscCall(PetscFree(nl->nbr));
  PetscCall(PetscFree(nl->hist));
  PetscFunctionReturn(PETSC_SUCCESS);
}
