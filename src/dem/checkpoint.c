/* Exact checkpoints of a dry DEM run: the whole per-rank state a step reads from the previous one,
 * so that a run stopped and continued on the same rank count ends bitwise where the uninterrupted
 * run does. Restoring the particles alone is not enough: the rebuild that would follow lists the
 * pairs in another order and every force sum changes at round-off. So a checkpoint holds, per
 * rank and in the rank's own order: the particles and their ghosts (x, v, w, q, f, tq, x0, id,
 * shape), the half Verlet list (CSR start, nbr, own) with its tangential springs, the ghost
 * exchange's send lists and receive counts, the walls' positions, travel, lists and springs, and
 * the counters (time, step, list builds and sorts, the rebuild flag, the next id, the state
 * stamp, the particle count and id checksum of -dem_check_every) and the cell grid's size.
 * Layout: one HDF5 file written through MPI-IO; each quantity is a 1-D dataset of the ranks' rows
 * one after another (rank-major), with a dataset <name>_n of the row count of every rank; root
 * attributes "sable_checkpoint_version" and "ranks". Written to PATH.tmp, renamed by rank 0
 * after every rank closed it. Spheres only, without a coupling (the convex caches and the
 * coupling arrays are not saved). */
#include "dem/dem_impl.h"
#include <hdf5.h>

#define DEM_CKPT_VERSION 1
#define DEM_CKPT_NCOUNT  14 /* per-rank counters, see DemCkptCounters */

static hid_t DemCkptIntType(void)
{
  return sizeof(PetscInt) == 8 ? H5T_NATIVE_INT64 : H5T_NATIVE_INT32;
}

/* Collective. Writes this rank's n values as its rows of dataset name, and its count into
 * name_n[rank]. */
static PetscErrorCode DemCkptWrite(Dem dem, hid_t file, const char *name, hid_t type, PetscInt n, const void *data)
{
  long long   cnt = n, off = 0, tot = 0, one = 1;
  PetscMPIInt rank, size;
  hsize_t     dims, start, count;
  hid_t       fs, ms, ds, xp;
  char        cname[64];

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(dem->comm, &rank));
  PetscCallMPI(MPI_Comm_size(dem->comm, &size));
  PetscCallMPI(MPI_Exscan(&cnt, &off, 1, MPI_LONG_LONG, MPI_SUM, dem->comm));
  if (!rank) off = 0;
  PetscCallMPI(MPI_Allreduce(&cnt, &tot, 1, MPI_LONG_LONG, MPI_SUM, dem->comm));
  SableCallH5(xp = H5Pcreate(H5P_DATASET_XFER));
  SableCallH5(H5Pset_dxpl_mpio(xp, H5FD_MPIO_COLLECTIVE));
  for (int pass = 0; pass < 2; pass++) { /* the rows, then the counts */
    const void *buf = pass ? (const void *)&cnt : data;
    hid_t       t   = pass ? H5T_NATIVE_LLONG : type;
    dims            = pass ? (hsize_t)size : (hsize_t)tot;
    start           = pass ? (hsize_t)rank : (hsize_t)off;
    count           = pass ? (hsize_t)one : (hsize_t)cnt;
    PetscCall(PetscSNPrintf(cname, sizeof cname, pass ? "%s_n" : "%s", name));
    SableCallH5(fs = H5Screate_simple(1, &dims, NULL));
    SableCallH5(ds = H5Dcreate2(file, cname, t, fs, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
    SableCallH5(ms = H5Screate_simple(1, &count, NULL));
    if (count) SableCallH5(H5Sselect_hyperslab(fs, H5S_SELECT_SET, &start, NULL, &count, NULL));
    else {
      SableCallH5(H5Sselect_none(fs));
      SableCallH5(H5Sselect_none(ms));
    }
    if (dims) SableCallH5(H5Dwrite(ds, t, ms, fs, xp, count ? buf : (const void *)&cnt)); /* HDF5's collective write of nothing fails */
    SableCallH5(H5Sclose(ms));
    SableCallH5(H5Dclose(ds));
    SableCallH5(H5Sclose(fs));
  }
  SableCallH5(H5Pclose(xp));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. Reads this rank's rows of dataset name (allocated, PetscFree it; at least one
 * element) and their count; refuses a missing or inconsistent dataset in one line. */
static PetscErrorCode DemCkptRead(Dem dem, hid_t file, const char *path, const char *name, hid_t type, size_t esize, PetscInt *n, void **data)
{
  PetscMPIInt rank, size;
  hsize_t     dims = 0, start, count;
  long long  *cnt, off = 0, tot = 0;
  hid_t       fs, ms, ds, xp;
  char        cname[64];
  int         ok;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(dem->comm, &rank));
  PetscCallMPI(MPI_Comm_size(dem->comm, &size));
  PetscCall(PetscSNPrintf(cname, sizeof cname, "%s_n", name));
  for (int k = 0; k < 2; k++) {
    const char *dn = k ? cname : name;
    PetscCheck(H5Lexists(file, dn, H5P_DEFAULT) > 0, dem->comm, PETSC_ERR_FILE_UNEXPECTED, "-restart %s: the dataset %s is missing (not a complete Sable checkpoint)", path, dn);
  }
  PetscCall(PetscMalloc1(size, &cnt));
  SableCallH5(ds = H5Dopen2(file, cname, H5P_DEFAULT));
  SableCallH5(fs = H5Dget_space(ds));
  ok = H5Sget_simple_extent_ndims(fs) == 1 && H5Sget_simple_extent_dims(fs, &dims, NULL) == 1 && dims == (hsize_t)size;
  PetscCheck(ok, dem->comm, PETSC_ERR_FILE_UNEXPECTED, "-restart %s: the dataset %s has %llu entries, expected %d (one per rank)", path, cname, (unsigned long long)dims, size);
  SableCallH5(H5Dread(ds, H5T_NATIVE_LLONG, H5S_ALL, H5S_ALL, H5P_DEFAULT, cnt));
  SableCallH5(H5Sclose(fs));
  SableCallH5(H5Dclose(ds));
  for (PetscMPIInt r = 0; r < size; r++) {
    if (r < rank) off += cnt[r];
    tot += cnt[r];
  }
  *n = (PetscInt)cnt[rank];
  PetscCall(PetscFree(cnt));
  SableCallH5(ds = H5Dopen2(file, name, H5P_DEFAULT));
  SableCallH5(fs = H5Dget_space(ds));
  ok = H5Sget_simple_extent_ndims(fs) == 1 && H5Sget_simple_extent_dims(fs, &dims, NULL) == 1 && dims == (hsize_t)tot;
  PetscCheck(ok, dem->comm, PETSC_ERR_FILE_UNEXPECTED, "-restart %s: the dataset %s has %llu entries, its counts %s say %lld", path, name, (unsigned long long)dims, cname, tot);
  PetscCall(PetscMalloc(esize * ((size_t)*n + 1), data));
  start = (hsize_t)off;
  count = (hsize_t)*n;
  SableCallH5(ms = H5Screate_simple(1, &count, NULL));
  if (count) SableCallH5(H5Sselect_hyperslab(fs, H5S_SELECT_SET, &start, NULL, &count, NULL));
  else {
    SableCallH5(H5Sselect_none(fs));
    SableCallH5(H5Sselect_none(ms));
  }
  SableCallH5(xp = H5Pcreate(H5P_DATASET_XFER));
  SableCallH5(H5Pset_dxpl_mpio(xp, H5FD_MPIO_COLLECTIVE));
  if (tot) SableCallH5(H5Dread(ds, type, ms, fs, xp, *data));
  SableCallH5(H5Pclose(xp));
  SableCallH5(H5Sclose(ms));
  SableCallH5(H5Sclose(fs));
  SableCallH5(H5Dclose(ds));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The per-rank counters, in the order they are stored. */
static void DemCkptCounters(Dem dem, PetscInt c[DEM_CKPT_NCOUNT], PetscBool get)
{
  PetscInt *v[DEM_CKPT_NCOUNT] = {&dem->p.n, &dem->p.ng, &dem->p.next_id, &dem->nl.builds, &dem->nl.sorts, &dem->clock.step, &dem->state, &dem->initial.n, &dem->walls.nwall, &dem->ex.migrated, &dem->nl.nc[0], &dem->nl.nc[1], &dem->nl.nc[2], NULL};
  for (int k = 0; k < DEM_CKPT_NCOUNT - 1; k++) {
    if (get) c[k] = *v[k];
    else *v[k] = c[k];
  }
  if (get) c[DEM_CKPT_NCOUNT - 1] = dem->need_build;
  else dem->need_build = (PetscBool)(c[DEM_CKPT_NCOUNT - 1] != 0);
}

static PetscErrorCode DemCkptSupported(Dem dem, const char *what, const char *path)
{
  PetscFunctionBeginUser;
  PetscCheck(!dem->shapes.convex, dem->comm, PETSC_ERR_SUP, "%s %s: checkpoints hold spheres only (the convex caches are not saved)", what, path);
  PetscCheck(!dem->ext.on, dem->comm, PETSC_ERR_SUP, "%s %s: checkpoints hold dry runs only (the coupling's arrays are not saved)", what, path);
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode DemCkptWriteAttr(hid_t file, const char *name, int v)
{
  hid_t sp, at;

  PetscFunctionBeginUser;
  SableCallH5(sp = H5Screate(H5S_SCALAR));
  SableCallH5(at = H5Acreate2(file, name, H5T_NATIVE_INT, sp, H5P_DEFAULT, H5P_DEFAULT));
  SableCallH5(H5Awrite(at, H5T_NATIVE_INT, &v));
  SableCallH5(H5Aclose(at));
  SableCallH5(H5Sclose(sp));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. The per-rank variable-length lists: ghost send lists, wall lists and springs. */
static PetscErrorCode DemCkptWriteLists(Dem dem, hid_t file, hid_t it)
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
    for (int k = 0; k < 3; k++) wd[4 * w + k] = wl->p[k];
    wd[4 * w + 3] = wl->moved;
    wcnt[w]       = wl->cnt;
    for (PetscInt a = 0; a < wl->cnt; a++, nw++) {
      widx[nw] = wl->idx[a];
      for (int k = 0; k < 3; k++) whist[3 * nw + k] = wl->hist[3 * a + k];
    }
  }
  PetscCall(DemCkptWrite(dem, file, "ex_counts", it, 81, ex));
  PetscCall(DemCkptWrite(dem, file, "ex_send", it, ns, send));
  PetscCall(DemCkptWrite(dem, file, "wall_state", H5T_NATIVE_DOUBLE, 4 * W->nwall, wd));
  PetscCall(DemCkptWrite(dem, file, "wall_cnt", it, W->nwall, wcnt));
  PetscCall(DemCkptWrite(dem, file, "wall_idx", it, nw, widx));
  PetscCall(DemCkptWrite(dem, file, "wall_hist", H5T_NATIVE_DOUBLE, 3 * nw, whist));
  PetscCall(PetscFree5(send, widx, whist, wd, wcnt));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemCheckpointWrite(Dem dem, const char *path)
{
  char        tmp[PETSC_MAX_PATH_LEN + 8];
  hid_t       fapl, file, it = DemCkptIntType();
  PetscMPIInt rank, size;
  PetscInt    c[DEM_CKPT_NCOUNT], N, m;
  double      clk[3];

  PetscFunctionBeginUser;
  PetscCall(DemCkptSupported(dem, "checkpoint", path));
  PetscCallMPI(MPI_Comm_rank(dem->comm, &rank));
  PetscCallMPI(MPI_Comm_size(dem->comm, &size));
  PetscCall(PetscSNPrintf(tmp, sizeof tmp, "%s.tmp", path));
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  SableCallH5(fapl = H5Pcreate(H5P_FILE_ACCESS));
  SableCallH5(H5Pset_fapl_mpio(fapl, dem->comm, MPI_INFO_NULL));
  file = H5Fcreate(tmp, H5F_ACC_TRUNC, H5P_DEFAULT, fapl);
  H5Pclose(fapl);
  PetscCheck(file >= 0, dem->comm, PETSC_ERR_FILE_OPEN, "checkpoint %s: cannot create the file", tmp);
  PetscCall(DemCkptWriteAttr(file, "sable_checkpoint_version", DEM_CKPT_VERSION));
  PetscCall(DemCkptWriteAttr(file, "ranks", size));
  DemCkptCounters(dem, c, PETSC_TRUE);
  clk[0] = dem->clock.t;
  clk[1] = dem->initial.checksum;
  clk[2] = dem->clock.dt;
  N      = dem->p.n + dem->p.ng;
  m      = dem->p.n ? dem->nl.start[dem->p.n] : 0;
  PetscCall(DemCkptWrite(dem, file, "counters", it, DEM_CKPT_NCOUNT, c));
  PetscCall(DemCkptWrite(dem, file, "clock", H5T_NATIVE_DOUBLE, 3, clk));
  PetscCall(DemCkptWrite(dem, file, "x", H5T_NATIVE_DOUBLE, 3 * N, dem->p.x));
  PetscCall(DemCkptWrite(dem, file, "v", H5T_NATIVE_DOUBLE, 3 * N, dem->p.v));
  PetscCall(DemCkptWrite(dem, file, "w", H5T_NATIVE_DOUBLE, 3 * N, dem->p.w));
  PetscCall(DemCkptWrite(dem, file, "q", H5T_NATIVE_DOUBLE, 4 * N, dem->p.q));
  PetscCall(DemCkptWrite(dem, file, "f", H5T_NATIVE_DOUBLE, 3 * N, dem->p.f));
  PetscCall(DemCkptWrite(dem, file, "tq", H5T_NATIVE_DOUBLE, 3 * N, dem->p.tq));
  PetscCall(DemCkptWrite(dem, file, "x0", H5T_NATIVE_DOUBLE, 3 * dem->p.n, dem->p.x0));
  PetscCall(DemCkptWrite(dem, file, "id", it, N, dem->p.id));
  PetscCall(DemCkptWrite(dem, file, "shape", it, N, dem->p.shape));
  PetscCall(DemCkptWrite(dem, file, "nl_start", it, dem->p.n ? dem->p.n + 1 : 0, dem->nl.start));
  PetscCall(DemCkptWrite(dem, file, "nl_nbr", it, m, dem->nl.nbr));
  PetscCall(DemCkptWrite(dem, file, "nl_own", it, m, dem->nl.own));
  PetscCall(DemCkptWrite(dem, file, "nl_hist", H5T_NATIVE_DOUBLE, dem->nl.hist ? 3 * m : 0, dem->nl.hist));
  PetscCall(DemCkptWriteLists(dem, file, it));
  SableCallH5(H5Fclose(file));
  PetscCallMPI(MPI_Barrier(dem->comm));
  if (!rank) PetscCheck(rename(tmp, path) == 0, PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "checkpoint %s: cannot rename %s into place", path, tmp);
  PetscCallMPI(MPI_Barrier(dem->comm));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. Opens a checkpoint for reading and refuses another format version or rank count. */
static PetscErrorCode DemCkptOpen(Dem dem, const char *path, hid_t *file)
{
  hid_t       fapl, at;
  PetscMPIInt size;
  int         v[2]    = {-1, -1};
  const char *attr[2] = {"sable_checkpoint_version", "ranks"};

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(dem->comm, &size));
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  PetscCheck(H5Fis_hdf5(path) > 0, dem->comm, PETSC_ERR_FILE_OPEN, "-restart %s: not a readable HDF5 file (missing or truncated)", path);
  SableCallH5(fapl = H5Pcreate(H5P_FILE_ACCESS));
  SableCallH5(H5Pset_fapl_mpio(fapl, dem->comm, MPI_INFO_NULL));
  *file = H5Fopen(path, H5F_ACC_RDONLY, fapl);
  H5Pclose(fapl);
  PetscCheck(*file >= 0, dem->comm, PETSC_ERR_FILE_OPEN, "-restart %s: HDF5 cannot open the file (truncated?)", path);
  for (int k = 0; k < 2; k++) {
    PetscCheck(H5Aexists(*file, attr[k]) > 0, dem->comm, PETSC_ERR_FILE_UNEXPECTED, "-restart %s: the attribute %s is missing (not a Sable checkpoint)", path, attr[k]);
    SableCallH5(at = H5Aopen(*file, attr[k], H5P_DEFAULT));
    SableCallH5(H5Aread(at, H5T_NATIVE_INT, &v[k]));
    SableCallH5(H5Aclose(at));
  }
  PetscCheck(v[0] == DEM_CKPT_VERSION, dem->comm, PETSC_ERR_FILE_UNEXPECTED, "-restart %s: attribute sable_checkpoint_version %d, this Sable reads version %d", path, v[0], DEM_CKPT_VERSION);
  PetscCheck(v[1] == size, dem->comm, PETSC_ERR_FILE_UNEXPECTED, "-restart %s: attribute ranks %d, this run has %d ranks (a checkpoint continues on the rank count that wrote it)", path, v[1], size);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Reads dataset name, which must hold exactly want entries on this rank, into dst. */
static PetscErrorCode DemCkptReadInto(Dem dem, hid_t file, const char *path, const char *name, hid_t type, size_t esize, PetscInt want, void *dst)
{
  PetscInt n;
  void    *buf;

  PetscFunctionBeginUser;
  PetscCall(DemCkptRead(dem, file, path, name, type, esize, &n, &buf));
  PetscCheck(n == want, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "-restart %s: the dataset %s has %" PetscInt_FMT " entries on this rank, expected %" PetscInt_FMT, path, name, n, want);
  if (n) PetscCall(PetscMemcpy(dst, buf, esize * (size_t)n));
  PetscCall(PetscFree(buf));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. The Verlet list and its springs. */
static PetscErrorCode DemCkptReadList(Dem dem, hid_t file, const char *path, hid_t it)
{
  DemNeigh *nl = &dem->nl;
  PetscInt  n, m;

  PetscFunctionBeginUser;
  PetscCall(PetscFree(nl->start));
  PetscCall(PetscFree(nl->nbr));
  PetscCall(PetscFree(nl->own));
  PetscCall(PetscFree(nl->hist));
  PetscCall(DemCkptRead(dem, file, path, "nl_start", it, sizeof(PetscInt), &n, (void **)&nl->start));
  PetscCheck(n == (dem->p.n ? dem->p.n + 1 : 0), PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "-restart %s: the dataset nl_start has %" PetscInt_FMT " entries on this rank, expected %" PetscInt_FMT, path, n, dem->p.n ? dem->p.n + 1 : 0);
  if (!dem->p.n) nl->start[0] = 0;
  m = nl->start[dem->p.n];
  PetscCall(DemCkptRead(dem, file, path, "nl_nbr", it, sizeof(PetscInt), &n, (void **)&nl->nbr));
  PetscCheck(n == m, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "-restart %s: the dataset nl_nbr has %" PetscInt_FMT " entries on this rank, expected %" PetscInt_FMT, path, n, m);
  nl->cap = m + 1;
  PetscCall(DemCkptRead(dem, file, path, "nl_own", it, sizeof(PetscInt), &n, (void **)&nl->own));
  PetscCheck(n == m, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "-restart %s: the dataset nl_own has %" PetscInt_FMT " entries on this rank, expected %" PetscInt_FMT, path, n, m);
  if (dem->contact.law != DEM_LAW_LINEAR_NOHIST) {
    PetscCall(PetscCalloc1(3 * (size_t)m + 3, &nl->hist));
    PetscCall(DemCkptReadInto(dem, file, path, "nl_hist", H5T_NATIVE_DOUBLE, sizeof(double), 3 * m, nl->hist));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. The ghost exchange's tables and the walls' state, lists and springs. */
static PetscErrorCode DemCkptReadLists(Dem dem, hid_t file, const char *path, hid_t it)
{
  PetscInt  ex[81], ns = 0, nw = 0, *send, *widx, *wcnt, n;
  double   *wd, *whist;
  DemWalls *W = &dem->walls;

  PetscFunctionBeginUser;
  PetscCall(DemCkptReadInto(dem, file, path, "ex_counts", it, sizeof(PetscInt), 81, ex));
  PetscCall(DemCkptRead(dem, file, path, "ex_send", it, sizeof(PetscInt), &n, (void **)&send));
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
  PetscCall(DemCkptReadInto(dem, file, path, "wall_state", H5T_NATIVE_DOUBLE, sizeof(double), 4 * W->nwall, wd));
  PetscCall(DemCkptReadInto(dem, file, path, "wall_cnt", it, sizeof(PetscInt), W->nwall, wcnt));
  PetscCall(DemCkptRead(dem, file, path, "wall_idx", it, sizeof(PetscInt), &n, (void **)&widx));
  PetscCall(DemCkptRead(dem, file, path, "wall_hist", H5T_NATIVE_DOUBLE, sizeof(double), &ns, (void **)&whist));
  for (PetscInt w = 0; w < W->nwall; w++) {
    DemWall *wl = &W->wall[w];
    for (int k = 0; k < 3; k++) wl->p[k] = wd[4 * w + k];
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

PetscErrorCode DemCheckpointRead(Dem dem, const char *path)
{
  hid_t    file = -1, it = DemCkptIntType();
  PetscInt c[DEM_CKPT_NCOUNT], N, nwall = dem->walls.nwall;
  double   clk[3];

  PetscFunctionBeginUser;
  PetscCall(DemCkptSupported(dem, "-restart", path));
  PetscCall(DemCkptOpen(dem, path, &file));
  PetscCall(DemCkptReadInto(dem, file, path, "counters", it, sizeof(PetscInt), DEM_CKPT_NCOUNT, c));
  PetscCall(DemCkptReadInto(dem, file, path, "clock", H5T_NATIVE_DOUBLE, sizeof(double), 3, clk));
  PetscCheck(c[8] == nwall, dem->comm, PETSC_ERR_FILE_UNEXPECTED, "-restart %s: the checkpoint has %" PetscInt_FMT " walls, the case's options make %" PetscInt_FMT, path, c[8], nwall);
  DemCkptCounters(dem, c, PETSC_FALSE);
  PetscCall(DemNeighSetCells(dem, dem->nl.nc)); /* the grid's cell count depends on the particles at its set-up */
  dem->clock.t          = clk[0];
  dem->initial.checksum = clk[1];
  dem->ex.remap         = PETSC_FALSE;
  dem->stop_sig         = 0;
  N                     = dem->p.n + dem->p.ng;
  PetscCall(DemParticlesReserve(dem, N));
  PetscCall(DemCkptReadInto(dem, file, path, "x", H5T_NATIVE_DOUBLE, sizeof(double), 3 * N, dem->p.x));
  PetscCall(DemCkptReadInto(dem, file, path, "v", H5T_NATIVE_DOUBLE, sizeof(double), 3 * N, dem->p.v));
  PetscCall(DemCkptReadInto(dem, file, path, "w", H5T_NATIVE_DOUBLE, sizeof(double), 3 * N, dem->p.w));
  PetscCall(DemCkptReadInto(dem, file, path, "q", H5T_NATIVE_DOUBLE, sizeof(double), 4 * N, dem->p.q));
  PetscCall(DemCkptReadInto(dem, file, path, "f", H5T_NATIVE_DOUBLE, sizeof(double), 3 * N, dem->p.f));
  PetscCall(DemCkptReadInto(dem, file, path, "tq", H5T_NATIVE_DOUBLE, sizeof(double), 3 * N, dem->p.tq));
  PetscCall(DemCkptReadInto(dem, file, path, "x0", H5T_NATIVE_DOUBLE, sizeof(double), 3 * dem->p.n, dem->p.x0));
  PetscCall(DemCkptReadInto(dem, file, path, "id", it, sizeof(PetscInt), N, dem->p.id));
  PetscCall(DemCkptReadInto(dem, file, path, "shape", it, sizeof(PetscInt), N, dem->p.shape));
  PetscCall(DemCkptReadList(dem, file, path, it));
  PetscCall(DemCkptReadLists(dem, file, path, it));
  SableCallH5(H5Fclose(file));
  PetscFunctionReturn(PETSC_SUCCESS);
}
