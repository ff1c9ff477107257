/* Exact checkpoints of a dry DEM run: the whole per-rank state a step reads from the previous one,
 * so that a run stopped and continued on the same rank count ends bitwise where the uninterrupted
 * run does. Restoring the particles alone is not enough: the rebuild that would follow lists the
 * pairs in another order and every force sum changes at round-off. So a checkpoint holds, per
 * rank and in the rank's own order: the particles and their ghosts (x, v, w, q, f, tq, x0, id,
 * shape), the half Verlet list (CSR start, nbr, own) with its tangential springs, the ghost
 * exchange's send lists and receive counts, the walls' positions, travel, lists and springs, and
 * the counters (time, step, list builds and sorts, the rebuild flag, the next id, the state
 * stamp, the particle count and id checksum of -dem_check_every) and the cell grid's size.
 * Datasets dem/<name> of a checkpoint file (io/checkpoint.c: rank-major rows with per-rank
 * counts); with a coupling also its per-particle arrays (external.c). Convex
 * shapes (DemCkptWriteConvex): the narrow phase's separating-axis cache (per Verlet entry
 * an axis and a touched flag; it decides which test runs, and a test near contact can round
 * differently) is saved as dem/convex_sepax, valid for the saved list build. The rotation matrices
 * of the pair loop (narrow.rot) are formed from q in every pass before they are read, whichever
 * of the eager or lazy ways rot_pairs picks, and libccd and geom/ keep nothing between calls.
 * Wall motion (DemCkptWriteWalls): a translating plane's position and travel are in wall_state; a
 * removed plane's flag is dem/wall_removed. Mesh walls (walls_mesh.c): their travel, local
 * triangles, candidates and spring slots; their pose is a function of the time. The particles that entered and left (dem->flow) and
 * the outlets' totals are dem/flow (sinks.c). A drum (cylinder and caps turning at omega) has no
 *  angle: its geometry is invariant under its rotation and its surface velocity is given.
 * Read on another rank count or process grid, the state is redistributed (checkpoint_remap.c). */
#include "dem/dem_core.h"
#include "dem/dem_walls.h"
#include "dem/dem_sources.h"
#include "dem/dem_checkpoint.h"
#include "dem/dem_fields.h"

/* Collective. Every per-particle dataset of the field table (dem_fields.h), this rank's rows. */
static PetscErrorCode DemCkptFields(Dem dem, IoCkpt ck, PetscBool write)
{
  PetscFunctionBeginUser;
  for (int f = 0; f < dem_nfields; f++) {
    const DemField  *fd   = &dem_fields[f];
    const IoCkptType type = fd->type == DEM_FIELD_INT ? IO_CKPT_INT : IO_CKPT_REAL;
    const PetscInt   rows = fd->width * (dem->p.n + (fd->flags & DEM_FIELD_CKPT_GHOSTS ? dem->p.ng : 0));
    if (!(fd->flags & DEM_FIELD_CKPT) || !DemFieldOn(dem, fd)) continue;
    if (write) PetscCall(IoCkptWriteRows(ck, fd->ckpt, type, rows, *DemFieldPtr(dem, fd)));
    else PetscCall(IoCkptReadRowsInto(ck, fd->ckpt, type, rows, *DemFieldPtr(dem, fd)));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. A checkpoint of spheres of their own sizes (dem/radius) continues only such a scene,
 * and the other way round. */
static PetscErrorCode DemCkptPolyCheck(Dem dem, IoCkpt ck, const char *path)
{
  PetscBool has;

  PetscFunctionBeginUser;
  PetscCall(IoCkptHas(ck, "dem/radius", &has));
  PetscCheck(has == dem->shapes.poly, dem->comm, PETSC_ERR_FILE_UNEXPECTED, "-restart %s: the checkpoint's spheres %s sizes of their own (dataset dem/radius) and this case's %s: give the options of the run that wrote it (its sources or -dem_init_file_radii)", path, has ? "have" : "have no", has ? "have not" : "have");
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The per-rank counters, in the order they are stored. */
static void DemCkptCounters(Dem dem, PetscInt c[DEM_CKPT_NCOUNT], PetscBool get)
{
  PetscInt *v[DEM_CKPT_NCOUNT] = {[CK_N] = &dem->p.n, [CK_NG] = &dem->p.ng, [CK_NEXT_ID] = &dem->p.next_id, [CK_BUILDS] = &dem->nl.builds, [CK_SORTS] = &dem->nl.sorts, [CK_STEP] = &dem->clock.step, [CK_STATE] = &dem->state, [CK_INITIAL_N] = &dem->initial.n, [CK_NWALL] = &dem->walls.nwall, [CK_MIGRATED] = &dem->ex.migrated, [CK_NC0] = &dem->nl.nc[0], [CK_NC1] = &dem->nl.nc[1], [CK_NC2] = &dem->nl.nc[2]};
  for (int k = 0; k < CK_NEED_BUILD; k++) {
    if (get) c[k] = *v[k];
    else *v[k] = c[k];
  }
  if (get) c[CK_NEED_BUILD] = dem->need_build;
  else dem->need_build = (PetscBool)(c[CK_NEED_BUILD] != 0);
}

/* Collective. The per-rank variable-length lists: ghost send lists, wall lists and springs. */
static PetscErrorCode DemCkptWriteLists(Dem dem, IoCkpt ck)
{
  PetscInt  ns = 0, nw = 0, *send, *widx, ex[81], *wcnt;
  double   *wd, *whist;
  DemWalls *W = &dem->walls;

  PetscFunctionBeginUser;
  for (int d = 0; d < 27; d++) {
    ex[d]      = dem->ex.nsend[d];
    ex[27 + d] = dem->ex.nrecv[d];
    ex[54 + d] = dem->ex.recvstart[d];
    ns += dem->ex.nsend[d];
  }
  for (PetscInt w = 0; w < W->nwall; w++) nw += W->wall[w].cnt;
  PetscCall(PetscMalloc5(ns + 1, &send, nw + 1, &widx, 3 * nw + 1, &whist, 4 * W->nwall + 1, &wd, W->nwall + 1, &wcnt));
  ns = nw = 0;
  for (int d = 0; d < 27; d++)
    for (PetscInt a = 0; a < dem->ex.nsend[d]; a++) send[ns++] = dem->ex.send[d][a];
  for (PetscInt w = 0; w < W->nwall; w++) {
    const DemWall *wl = &W->wall[w];
    for (int k = 0; k < 3; k++) wd[4 * w + k] = wl->s.p[k];
    wd[4 * w + 3] = wl->moved;
    wcnt[w]       = wl->cnt;
    for (PetscInt a = 0; a < wl->cnt; a++, nw++) {
      widx[nw] = wl->idx[a];
      for (int k = 0; k < 3; k++) whist[3 * nw + k] = wl->hist[3 * a + k];
    }
  }
  PetscCall(IoCkptWriteRows(ck, "dem/ex_counts", IO_CKPT_INT, 81, ex));
  PetscCall(IoCkptWriteRows(ck, "dem/ex_send", IO_CKPT_INT, ns, send));
  PetscCall(IoCkptWriteRows(ck, "dem/wall_state", IO_CKPT_REAL, 4 * W->nwall, wd));
  PetscCall(IoCkptWriteRows(ck, "dem/wall_cnt", IO_CKPT_INT, W->nwall, wcnt));
  PetscCall(IoCkptWriteRows(ck, "dem/wall_idx", IO_CKPT_INT, nw, widx));
  PetscCall(IoCkptWriteRows(ck, "dem/wall_hist", IO_CKPT_REAL, 3 * nw, whist));
  PetscCall(PetscFree5(send, widx, whist, wd, wcnt));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. Convex shapes: the separating-axis cache of the Verlet list's entries (zeros, as
 * the next pass would start it, if it belongs to an older list). */
static PetscErrorCode DemCkptWriteConvex(Dem dem, IoCkpt ck)
{
  const PetscInt m     = dem->p.n ? dem->nl.start[dem->p.n] : 0;
  double        *sepax = dem->narrow.sepax, *zero = NULL;

  PetscFunctionBeginUser;
  if (!dem->shapes.convex) PetscFunctionReturn(PETSC_SUCCESS);
  if (!sepax || dem->narrow.sepax_build != dem->nl.builds) {
    PetscCall(PetscCalloc1(4 * (size_t)m + 4, &zero));
    sepax = zero;
  }
  PetscCall(IoCkptWriteRows(ck, "dem/convex_sepax", IO_CKPT_REAL, 4 * m, sepax));
  PetscCall(PetscFree(zero));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. The walls' removal flags (the positions and travel are in dem/wall_state). */
static PetscErrorCode DemCkptWriteWalls(Dem dem, IoCkpt ck)
{
  PetscInt removed[DEM_MAX_WALLS];

  PetscFunctionBeginUser;
  for (PetscInt w = 0; w < dem->walls.nwall; w++) removed[w] = dem->walls.wall[w].removed;
  PetscCall(IoCkptWriteShared(ck, "dem/wall_removed", IO_CKPT_INT, dem->walls.nwall, removed));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemCheckpointWrite(Dem dem, IoCkpt ck)
{
  PetscInt c[DEM_CKPT_NCOUNT], m;
  double   clk[3];

  PetscFunctionBeginUser;
  DemCkptCounters(dem, c, PETSC_TRUE);
  clk[0] = dem->clock.t;
  clk[1] = dem->initial.checksum;
  clk[2] = dem->clock.dt;
  m      = dem->p.n ? dem->nl.start[dem->p.n] : 0;
  PetscCall(IoCkptWriteRows(ck, "dem/counters", IO_CKPT_INT, DEM_CKPT_NCOUNT, c));
  PetscCall(IoCkptWriteRows(ck, "dem/clock", IO_CKPT_REAL, 3, clk));
  PetscCall(DemCkptFields(dem, ck, PETSC_TRUE));
  PetscCall(IoCkptWriteRows(ck, "dem/nl_start", IO_CKPT_INT, dem->p.n ? dem->p.n + 1 : 0, dem->nl.start));
  PetscCall(IoCkptWriteRows(ck, "dem/nl_nbr", IO_CKPT_INT, m, dem->nl.nbr));
  PetscCall(IoCkptWriteRows(ck, "dem/nl_own", IO_CKPT_INT, m, dem->nl.own));
  PetscCall(IoCkptWriteRows(ck, "dem/nl_hist", IO_CKPT_REAL, dem->nl.hist ? 3 * m : 0, dem->nl.hist));
  PetscCall(DemCkptWriteLists(dem, ck));
  PetscCall(DemCkptWriteConvex(dem, ck));
  PetscCall(DemCkptWriteWalls(dem, ck));
  PetscCall(DemMeshesCheckpoint(dem, ck, PETSC_TRUE)); /* walls_mesh.c */
  PetscCall(DemSinksCheckpoint(dem, ck, PETSC_TRUE));
  PetscCall(DemSourcesCheckpoint(dem, ck, PETSC_TRUE));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. The Verlet list and its springs. */
static PetscErrorCode DemCkptReadList(Dem dem, IoCkpt ck, const char *path)
{
  DemNeigh *nl = &dem->nl;
  PetscInt  n, m;

  PetscFunctionBeginUser;
  PetscCall(PetscFree(nl->start));
  PetscCall(PetscFree(nl->nbr));
  PetscCall(PetscFree(nl->own));
  PetscCall(PetscFree(nl->hist));
  PetscCall(IoCkptReadRows(ck, "dem/nl_start", IO_CKPT_INT, &n, (void **)&nl->start));
  PetscCheck(n == (dem->p.n ? dem->p.n + 1 : 0), PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "-restart %s: the dataset nl_start has %" PetscInt_FMT " entries on this rank, expected %" PetscInt_FMT, path, n, dem->p.n ? dem->p.n + 1 : 0);
  if (!dem->p.n) nl->start[0] = 0;
  m = nl->start[dem->p.n];
  PetscCall(IoCkptReadRows(ck, "dem/nl_nbr", IO_CKPT_INT, &n, (void **)&nl->nbr));
  PetscCheck(n == m, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "-restart %s: the dataset nl_nbr has %" PetscInt_FMT " entries on this rank, expected %" PetscInt_FMT, path, n, m);
  nl->cap = m + 1;
  PetscCall(IoCkptReadRows(ck, "dem/nl_own", IO_CKPT_INT, &n, (void **)&nl->own));
  PetscCheck(n == m, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "-restart %s: the dataset nl_own has %" PetscInt_FMT " entries on this rank, expected %" PetscInt_FMT, path, n, m);
  if (dem->contact.law != DEM_LAW_LINEAR_NOHIST) {
    PetscCall(PetscCalloc1(3 * (size_t)m + 3, &nl->hist));
    PetscCall(IoCkptReadRowsInto(ck, "dem/nl_hist", IO_CKPT_REAL, 3 * m, nl->hist));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. The ghost exchange's tables and the walls' state, lists and springs. */
static PetscErrorCode DemCkptReadLists(Dem dem, IoCkpt ck, const char *path)
{
  PetscInt  ex[81], ns = 0, nw = 0, *send, *widx, *wcnt, n;
  double   *wd, *whist;
  DemWalls *W = &dem->walls;

  PetscFunctionBeginUser;
  PetscCall(IoCkptReadRowsInto(ck, "dem/ex_counts", IO_CKPT_INT, 81, ex));
  PetscCall(IoCkptReadRows(ck, "dem/ex_send", IO_CKPT_INT, &n, (void **)&send));
  for (int d = 0; d < 27; d++) {
    dem->ex.nsend[d]     = ex[d];
    dem->ex.nrecv[d]     = ex[27 + d];
    dem->ex.recvstart[d] = ex[54 + d];
    if (ex[d] > dem->ex.capsend[d]) {
      PetscCall(PetscRealloc(sizeof(PetscInt) * (size_t)ex[d], &dem->ex.send[d]));
      dem->ex.capsend[d] = ex[d];
    }
    PetscCheck(ns + ex[d] <= n, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "-restart %s: the dataset ex_send is shorter than ex_counts say", path);
    for (PetscInt a = 0; a < ex[d]; a++) dem->ex.send[d][a] = send[ns++];
  }
  PetscCall(PetscFree(send));
  PetscCall(PetscMalloc1(4 * W->nwall + 1, &wd));
  PetscCall(PetscMalloc1(W->nwall + 1, &wcnt));
  PetscCall(IoCkptReadRowsInto(ck, "dem/wall_state", IO_CKPT_REAL, 4 * W->nwall, wd));
  PetscCall(IoCkptReadRowsInto(ck, "dem/wall_cnt", IO_CKPT_INT, W->nwall, wcnt));
  PetscCall(IoCkptReadRows(ck, "dem/wall_idx", IO_CKPT_INT, &n, (void **)&widx));
  PetscCall(IoCkptReadRows(ck, "dem/wall_hist", IO_CKPT_REAL, &ns, (void **)&whist));
  for (PetscInt w = 0; w < W->nwall; w++) {
    DemWall *wl = &W->wall[w];
    for (int k = 0; k < 3; k++) wl->s.p[k] = wd[4 * w + k];
    wl->moved = wd[4 * w + 3];
    wl->cnt   = wcnt[w];
    PetscCheck(nw + wl->cnt <= n && 3 * (nw + wl->cnt) <= ns, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "-restart %s: the datasets wall_idx, wall_hist are shorter than wall_cnt says", path);
    if (wl->cnt > wl->cap) {
      wl->cap = wl->cnt;
      PetscCall(PetscRealloc(sizeof(PetscInt) * (size_t)wl->cap, &wl->idx));
      PetscCall(PetscRealloc(3 * sizeof(double) * (size_t)wl->cap, &wl->hist));
    }
    for (PetscInt a = 0; a < wl->cnt; a++, nw++) {
      wl->idx[a] = widx[nw];
      for (int k = 0; k < 3; k++) wl->hist[3 * a + k] = whist[3 * nw + k];
    }
  }
  PetscCall(PetscFree(widx));
  PetscCall(PetscFree(whist));
  PetscCall(PetscFree(wd));
  PetscCall(PetscFree(wcnt));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. Convex shapes: the separating-axis cache, for the restored list build (after
 * DemCkptReadList: the list's length). */
static PetscErrorCode DemCkptReadConvex(Dem dem, IoCkpt ck)
{
  const PetscInt m = dem->p.n ? dem->nl.start[dem->p.n] : 0;

  PetscFunctionBeginUser;
  if (!dem->shapes.convex) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscFree(dem->narrow.sepax));
  PetscCall(PetscCalloc1(4 * (size_t)m + 4, &dem->narrow.sepax));
  PetscCall(IoCkptReadRowsInto(ck, "dem/convex_sepax", IO_CKPT_REAL, 4 * m, dem->narrow.sepax));
  dem->narrow.sepax_build = dem->nl.builds;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. The walls' removal flags. */
static PetscErrorCode DemCkptReadWalls(Dem dem, IoCkpt ck)
{
  PetscInt removed[DEM_MAX_WALLS];

  PetscFunctionBeginUser;
  PetscCall(IoCkptReadShared(ck, "dem/wall_removed", IO_CKPT_INT, dem->walls.nwall, removed));
  for (PetscInt w = 0; w < dem->walls.nwall; w++) {
    DemWall *wl = &dem->walls.wall[w];
    wl->removed = (PetscBool)(removed[w] != 0);
    if (wl->removed) wl->cnt = 0;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemCheckpointRead(Dem dem, IoCkpt ck)
{
  const char *path;
  PetscInt    c[DEM_CKPT_NCOUNT], N, nwall = dem->walls.nwall;
  double      clk[3];
  PetscBool   remap;

  PetscFunctionBeginUser;
  PetscCall(IoCkptGetPath(ck, &path));
  PetscCall(DemCheckpointNeedsRemap(dem, ck, &remap));
  PetscCall(DemSourcesCheckpoint(dem, ck, PETSC_FALSE)); /* first: the remap checks the count with it */
  if (remap) {                                           /* another rank count or other boxes: the state is redistributed (checkpoint_remap.c) */
    PetscCall(DemExternalCheckpointCheck(dem, ck));
    PetscCall(DemCkptPolyCheck(dem, ck, path));
    PetscCall(DemSinksCheckpoint(dem, ck, PETSC_FALSE)); /* the remap checks the count against it */
    PetscCall(DemCheckpointReadRemap(dem, ck));
    PetscCall(DemCkptReadWalls(dem, ck));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(IoCkptReadRowsInto(ck, "dem/counters", IO_CKPT_INT, DEM_CKPT_NCOUNT, c));
  PetscCall(IoCkptReadRowsInto(ck, "dem/clock", IO_CKPT_REAL, 3, clk));
  PetscCheck(c[CK_NWALL] == nwall, dem->comm, PETSC_ERR_FILE_UNEXPECTED, "-restart %s: the checkpoint has %" PetscInt_FMT " walls, the case's options make %" PetscInt_FMT, path, c[CK_NWALL], nwall);
  DemCkptCounters(dem, c, PETSC_FALSE);
  PetscCall(DemNeighSetCells(dem, dem->nl.nc)); /* the grid's cell count depends on the particles at its set-up */
  dem->clock.t          = clk[0];
  dem->initial.checksum = clk[1];
  dem->ex.remap         = PETSC_FALSE;
  dem->stop_sig         = 0;
  N                     = dem->p.n + dem->p.ng;
  PetscCall(DemParticlesReserve(dem, N));
  PetscCall(DemExternalCheckpointCheck(dem, ck));
  PetscCall(DemCkptPolyCheck(dem, ck, path));
  PetscCall(DemCkptFields(dem, ck, PETSC_FALSE));
  PetscCall(DemCkptReadList(dem, ck, path));
  PetscCall(DemCkptReadLists(dem, ck, path));
  PetscCall(DemCkptReadConvex(dem, ck));
  PetscCall(DemCkptReadWalls(dem, ck));
  PetscCall(DemMeshesCheckpoint(dem, ck, PETSC_FALSE)); /* walls_mesh.c */
  PetscCall(DemSinksCheckpoint(dem, ck, PETSC_FALSE));
  PetscFunctionReturn(PETSC_SUCCESS);
}
