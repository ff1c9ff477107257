/* Checkpoint files (see io.h): one HDF5 file written and read through MPI-IO by every rank.
 * A quantity is a 1-D dataset of the ranks' rows one after another (rank-major) with a dataset
 * <name>_n of every rank's row count, so that the same rank count reads its own rows back and
 * another rank count can read any range. Names may hold groups ("dem/x"); the groups are made on
 * the way. Root attributes: "sable_checkpoint_version" and "ranks". A checkpoint being written
 * lives under PATH.tmp and is renamed by rank 0 once every rank closed it. Every failure is one
 * line naming the file and the dataset. */
#include "io/io_private.h"

struct _p_IoCkpt {
  MPI_Comm  comm;
  hid_t     file, lcpl, xfer;
  PetscBool writing;
  int       ranks; /* of the run that wrote it */
  char      path[PETSC_MAX_PATH_LEN], tmp[PETSC_MAX_PATH_LEN + 8];
};

static hid_t IoCkptH5Type(IoCkptType t)
{
  switch (t) {
  case IO_CKPT_REAL:
    return H5T_NATIVE_DOUBLE;
  case IO_CKPT_INT:
    return sizeof(PetscInt) == 8 ? H5T_NATIVE_INT64 : H5T_NATIVE_INT32;
  case IO_CKPT_LLONG:
    return H5T_NATIVE_LLONG;
  default:
    return H5T_NATIVE_UCHAR;
  }
}

size_t IoCkptTypeSize(IoCkptType t)
{
  switch (t) {
  case IO_CKPT_REAL:
    return sizeof(double);
  case IO_CKPT_INT:
    return sizeof(PetscInt);
  case IO_CKPT_LLONG:
    return sizeof(long long);
  default:
    return 1;
  }
}

static PetscErrorCode IoCkptAttr(hid_t file, const char *name, int v)
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

static PetscErrorCode IoCkptProps(IoCkpt ck)
{
  PetscFunctionBeginUser;
  SableCallH5(ck->lcpl = H5Pcreate(H5P_LINK_CREATE));
  SableCallH5(H5Pset_create_intermediate_group(ck->lcpl, 1));
  SableCallH5(ck->xfer = H5Pcreate(H5P_DATASET_XFER));
  SableCallH5(H5Pset_dxpl_mpio(ck->xfer, H5FD_MPIO_COLLECTIVE));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IoCkptCreate(MPI_Comm comm, const char *path, IoCkpt *ckp)
{
  IoCkpt      ck;
  hid_t       fapl;
  PetscMPIInt size;

  PetscFunctionBeginUser;
  PetscCall(PetscNew(&ck));
  ck->comm    = comm;
  ck->writing = PETSC_TRUE;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  ck->ranks = size;
  PetscCall(PetscStrncpy(ck->path, path, sizeof ck->path));
  PetscCall(PetscSNPrintf(ck->tmp, sizeof ck->tmp, "%s.tmp", path));
  io_quiet();
  SableCallH5(fapl = H5Pcreate(H5P_FILE_ACCESS));
  SableCallH5(H5Pset_fapl_mpio(fapl, comm, MPI_INFO_NULL));
  ck->file = H5Fcreate(ck->tmp, H5F_ACC_TRUNC, H5P_DEFAULT, fapl);
  H5Pclose(fapl);
  PetscCheck(ck->file >= 0, comm, PETSC_ERR_FILE_OPEN, "checkpoint %s: cannot create the file", ck->tmp);
  SableTempSet(ck->tmp); /* removed if the run ends in an error before the rename */
  PetscCall(IoCkptProps(ck));
  PetscCall(IoCkptAttr(ck->file, "sable_checkpoint_version", IO_CKPT_VERSION));
  PetscCall(IoCkptAttr(ck->file, "ranks", size));
  *ckp = ck;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IoCkptOpen(MPI_Comm comm, const char *path, IoCkpt *ckp)
{
  IoCkpt      ck;
  hid_t       fapl, at;
  int         v[2]    = {-1, -1};
  const char *attr[2] = {"sable_checkpoint_version", "ranks"};

  PetscFunctionBeginUser;
  io_quiet();
  PetscCheck(H5Fis_hdf5(path) > 0, comm, PETSC_ERR_FILE_OPEN, "-restart %s: not a readable HDF5 file (missing or truncated)", path);
  PetscCall(PetscNew(&ck));
  ck->comm = comm;
  PetscCall(PetscStrncpy(ck->path, path, sizeof ck->path));
  SableCallH5(fapl = H5Pcreate(H5P_FILE_ACCESS));
  SableCallH5(H5Pset_fapl_mpio(fapl, comm, MPI_INFO_NULL));
  ck->file = H5Fopen(path, H5F_ACC_RDONLY, fapl);
  H5Pclose(fapl);
  PetscCheck(ck->file >= 0, comm, PETSC_ERR_FILE_OPEN, "-restart %s: HDF5 cannot open the file (truncated?)", path);
  PetscCall(IoCkptProps(ck));
  for (int k = 0; k < 2; k++) {
    PetscCheck(H5Aexists(ck->file, attr[k]) > 0, comm, PETSC_ERR_FILE_UNEXPECTED, "-restart %s: the attribute %s is missing (not a Sable checkpoint)", path, attr[k]);
    SableCallH5(at = H5Aopen(ck->file, attr[k], H5P_DEFAULT));
    SableCallH5(H5Aread(at, H5T_NATIVE_INT, &v[k]));
    SableCallH5(H5Aclose(at));
  }
  PetscCheck(v[0] == IO_CKPT_VERSION, comm, PETSC_ERR_FILE_UNEXPECTED, "-restart %s: attribute sable_checkpoint_version %d, this Sable reads version %d", path, v[0], IO_CKPT_VERSION);
  PetscCheck(v[1] >= 1, comm, PETSC_ERR_FILE_UNEXPECTED, "-restart %s: attribute ranks %d, expected >= 1", path, v[1]);
  ck->ranks = v[1];
  *ckp      = ck;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IoCkptClose(IoCkpt *ckp)
{
  IoCkpt      ck = *ckp;
  PetscMPIInt rank;

  PetscFunctionBeginUser;
  if (!ck) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCallMPI(MPI_Comm_rank(ck->comm, &rank));
  H5Pclose(ck->lcpl);
  H5Pclose(ck->xfer);
  SableCallH5(H5Fclose(ck->file));
  if (ck->writing) {
    PetscCallMPI(MPI_Barrier(ck->comm));
    if (!rank) PetscCheck(rename(ck->tmp, ck->path) == 0, PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "checkpoint %s: cannot rename %s into place", ck->path, ck->tmp);
    SableTempSet(NULL);
    PetscCallMPI(MPI_Barrier(ck->comm));
  }
  PetscCall(PetscFree(*ckp));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IoCkptGetRanks(IoCkpt ck, int *ranks)
{
  PetscFunctionBeginUser;
  *ranks = ck->ranks;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IoCkptGetPath(IoCkpt ck, const char **path)
{
  PetscFunctionBeginUser;
  *path = ck->path;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IoCkptHas(IoCkpt ck, const char *name, PetscBool *has)
{
  PetscFunctionBeginUser;
  *has = (PetscBool)(H5Lexists(ck->file, name, H5P_DEFAULT) > 0);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. Writes count rows from start of a 1-D dataset of dims entries (created here). */
static PetscErrorCode IoCkptWriteSlab(IoCkpt ck, const char *name, hid_t type, hsize_t dims, hsize_t start, hsize_t count, const void *buf)
{
  hid_t fs, ms, ds;

  PetscFunctionBeginUser;
  SableCallH5(fs = H5Screate_simple(1, &dims, NULL));
  ds = H5Dcreate2(ck->file, name, type, fs, ck->lcpl, H5P_DEFAULT, H5P_DEFAULT);
  PetscCheck(ds >= 0, PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "checkpoint %s: cannot create the dataset %s", ck->tmp, name);
  SableCallH5(ms = H5Screate_simple(1, &count, NULL));
  if (count) SableCallH5(H5Sselect_hyperslab(fs, H5S_SELECT_SET, &start, NULL, &count, NULL));
  else {
    SableCallH5(H5Sselect_none(fs));
    SableCallH5(H5Sselect_none(ms));
  }
  if (dims) { /* HDF5's collective write of nothing fails */
    const long long dummy = 0;
    PetscCheck(H5Dwrite(ds, type, ms, fs, ck->xfer, count ? buf : (const void *)&dummy) >= 0, PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "checkpoint %s: writing the dataset %s failed (disk full?)", ck->tmp, name);
  }
  SableCallH5(H5Sclose(ms));
  SableCallH5(H5Dclose(ds));
  SableCallH5(H5Sclose(fs));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IoCkptWriteRows(IoCkpt ck, const char *name, IoCkptType type, PetscInt n, const void *data)
{
  long long   cnt = n, off = 0, tot = 0;
  PetscMPIInt rank, size;
  char        cname[PETSC_MAX_PATH_LEN];

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(ck->comm, &rank));
  PetscCallMPI(MPI_Comm_size(ck->comm, &size));
  PetscCallMPI(MPI_Exscan(&cnt, &off, 1, MPI_LONG_LONG, MPI_SUM, ck->comm));
  if (!rank) off = 0;
  PetscCallMPI(MPI_Allreduce(&cnt, &tot, 1, MPI_LONG_LONG, MPI_SUM, ck->comm));
  PetscCall(IoCkptWriteSlab(ck, name, IoCkptH5Type(type), (hsize_t)tot, (hsize_t)off, (hsize_t)cnt, data));
  PetscCall(PetscSNPrintf(cname, sizeof cname, "%s_n", name));
  PetscCall(IoCkptWriteSlab(ck, cname, H5T_NATIVE_LLONG, (hsize_t)size, (hsize_t)rank, 1, &cnt));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IoCkptWriteShared(IoCkpt ck, const char *name, IoCkptType type, PetscInt n, const void *data)
{
  PetscMPIInt rank;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(ck->comm, &rank));
  PetscCall(IoCkptWriteSlab(ck, name, IoCkptH5Type(type), (hsize_t)n, 0, rank ? 0 : (hsize_t)n, data));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. The 1-D extent of dataset name, refused in one line when missing or not 1-D. */
static PetscErrorCode IoCkptExtent(IoCkpt ck, const char *name, long long *tot)
{
  hid_t   ds, fs;
  hsize_t dims = 0;
  int     ok;

  PetscFunctionBeginUser;
  PetscCheck(H5Lexists(ck->file, name, H5P_DEFAULT) > 0, ck->comm, PETSC_ERR_FILE_UNEXPECTED, "-restart %s: the dataset %s is missing (not a complete Sable checkpoint)", ck->path, name);
  SableCallH5(ds = H5Dopen2(ck->file, name, H5P_DEFAULT));
  SableCallH5(fs = H5Dget_space(ds));
  ok = H5Sget_simple_extent_ndims(fs) == 1 && H5Sget_simple_extent_dims(fs, &dims, NULL) == 1;
  SableCallH5(H5Sclose(fs));
  SableCallH5(H5Dclose(ds));
  PetscCheck(ok, ck->comm, PETSC_ERR_FILE_UNEXPECTED, "-restart %s: the dataset %s is not a 1-D array", ck->path, name);
  *tot = (long long)dims;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IoCkptGetSize(IoCkpt ck, const char *name, long long *tot)
{
  PetscFunctionBeginUser;
  PetscCall(IoCkptExtent(ck, name, tot));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. Reads count entries from start into buf (any rank may ask for none). */
static PetscErrorCode IoCkptReadSlab(IoCkpt ck, const char *name, hid_t type, hsize_t start, hsize_t count, void *buf)
{
  hid_t     ds, fs, ms;
  long long dummy;

  PetscFunctionBeginUser;
  SableCallH5(ds = H5Dopen2(ck->file, name, H5P_DEFAULT));
  SableCallH5(fs = H5Dget_space(ds));
  SableCallH5(ms = H5Screate_simple(1, &count, NULL));
  if (count) SableCallH5(H5Sselect_hyperslab(fs, H5S_SELECT_SET, &start, NULL, &count, NULL));
  else {
    SableCallH5(H5Sselect_none(fs));
    SableCallH5(H5Sselect_none(ms));
  }
  if (H5Sget_simple_extent_npoints(fs) > 0) /* HDF5's collective read of an empty dataset fails */
    PetscCheck(H5Dread(ds, type, ms, fs, ck->xfer, count ? buf : (void *)&dummy) >= 0, PETSC_COMM_SELF, PETSC_ERR_FILE_READ, "-restart %s: reading the dataset %s failed (truncated file?)", ck->path, name);
  SableCallH5(H5Sclose(ms));
  SableCallH5(H5Sclose(fs));
  SableCallH5(H5Dclose(ds));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IoCkptReadCounts(IoCkpt ck, const char *name, long long **cnt)
{
  char      cname[PETSC_MAX_PATH_LEN];
  long long n, tot = 0, sum = 0;

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(cname, sizeof cname, "%s_n", name));
  PetscCall(IoCkptExtent(ck, name, &tot));
  PetscCall(IoCkptExtent(ck, cname, &n));
  PetscCheck(n == ck->ranks, ck->comm, PETSC_ERR_FILE_UNEXPECTED, "-restart %s: the dataset %s has %lld entries, expected %d (one per rank that wrote it)", ck->path, cname, n, ck->ranks);
  PetscCall(PetscMalloc1(n, cnt));
  PetscCall(IoCkptReadSlabAll(ck, cname, IO_CKPT_LLONG, 0, n, *cnt));
  for (long long r = 0; r < n; r++) sum += (*cnt)[r];
  PetscCheck(sum == tot, ck->comm, PETSC_ERR_FILE_UNEXPECTED, "-restart %s: the dataset %s has %lld entries, its counts %s say %lld", ck->path, name, tot, cname, sum);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IoCkptReadSlabAll(IoCkpt ck, const char *name, IoCkptType type, long long start, long long count, void *buf)
{
  long long tot;

  PetscFunctionBeginUser;
  PetscCall(IoCkptExtent(ck, name, &tot));
  PetscCheck(start >= 0 && count >= 0 && start + count <= tot, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "-restart %s: the dataset %s has %lld entries, %lld wanted from %lld", ck->path, name, tot, count, start);
  PetscCall(IoCkptReadSlab(ck, name, IoCkptH5Type(type), (hsize_t)start, (hsize_t)count, buf));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IoCkptReadRows(IoCkpt ck, const char *name, IoCkptType type, PetscInt *n, void **data)
{
  PetscMPIInt rank, size;
  long long  *cnt, off = 0;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(ck->comm, &rank));
  PetscCallMPI(MPI_Comm_size(ck->comm, &size));
  PetscCheck(size == ck->ranks, ck->comm, PETSC_ERR_FILE_UNEXPECTED, "-restart %s: the dataset %s holds the rows of %d ranks, this run has %d", ck->path, name, ck->ranks, size);
  PetscCall(IoCkptReadCounts(ck, name, &cnt));
  for (PetscMPIInt r = 0; r < rank; r++) off += cnt[r];
  *n = (PetscInt)cnt[rank];
  PetscCall(PetscFree(cnt));
  PetscCall(PetscMalloc(IoCkptTypeSize(type) * ((size_t)*n + 1), data));
  PetscCall(IoCkptReadSlab(ck, name, IoCkptH5Type(type), (hsize_t)off, (hsize_t)*n, *data));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IoCkptReadRowsInto(IoCkpt ck, const char *name, IoCkptType type, PetscInt want, void *dst)
{
  PetscInt n;
  void    *buf;

  PetscFunctionBeginUser;
  PetscCall(IoCkptReadRows(ck, name, type, &n, &buf));
  PetscCheck(n == want, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "-restart %s: the dataset %s has %" PetscInt_FMT " entries on this rank, expected %" PetscInt_FMT, ck->path, name, n, want);
  if (n) PetscCall(PetscMemcpy(dst, buf, IoCkptTypeSize(type) * (size_t)n));
  PetscCall(PetscFree(buf));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IoCkptReadShared(IoCkpt ck, const char *name, IoCkptType type, PetscInt want, void *dst)
{
  long long tot;

  PetscFunctionBeginUser;
  PetscCall(IoCkptExtent(ck, name, &tot));
  PetscCheck(tot == want, ck->comm, PETSC_ERR_FILE_UNEXPECTED, "-restart %s: the dataset %s has %lld entries, expected %" PetscInt_FMT, ck->path, name, tot, want);
  PetscCall(IoCkptReadSlab(ck, name, IoCkptH5Type(type), 0, (hsize_t)want, dst));
  PetscFunctionReturn(PETSC_SUCCESS);
}
