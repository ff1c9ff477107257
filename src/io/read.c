/* Reading Sable HDF5 files (see io.h): whole datasets of numbers, a frame's time, whether a
 * dataset exists. A file given to read is treated as possibly hostile: before any memory is taken
 * or any value read, a dataset's type class (integer or floating point), its dimensions (1 or 2,
 * the expected columns) and its declared size are checked, all size arithmetic in 64 bits. The
 * bounds: at most PETSC_MAX_INT - 1 values (the callers index rows x columns with PetscInt) and
 * at most the physical memory divided by the ranks of the node (every rank holds the whole
 * dataset). Each problem is one message naming the file, the dataset and what was expected;
 * IoReadDatasetAll makes it one message for all ranks. */
#include "io/io_private.h"
#include <errno.h>
#include <unistd.h>

typedef struct {
  char  *buf;
  size_t len;
} IoH5Text;

static herr_t io_h5_walk(unsigned n, const H5E_error2_t *e, void *ctx)
{
  IoH5Text *t = (IoH5Text *)ctx;

  if (n == 0) snprintf(t->buf, t->len, "%s: %s", e->func_name ? e->func_name : "?", e->desc ? e->desc : "failed");
  return 0;
}

void io_h5_last_error(char *buf, size_t len)
{
  IoH5Text t = {buf, len};

  buf[0] = 0;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, io_h5_walk, &t);
  if (!buf[0]) snprintf(buf, len, "no details");
}

/* One dataset to read: the request, the result, and the problem found ("" if none). */
typedef struct {
  const char *file, *name;
  PetscInt    ncomp;    /* columns expected; 0: any */
  double      maxbytes; /* the largest dataset this rank may hold */
  PetscInt    rows, nc;
  PetscReal  *data;
  char        msg[1024];
} IoRead;

static const char *io_class_name(H5T_class_t c)
{
  switch (c) {
  case H5T_STRING:
    return "strings";
  case H5T_COMPOUND:
    return "compound records";
  case H5T_ENUM:
    return "enumerated values (booleans?)";
  case H5T_ARRAY:
    return "arrays";
  case H5T_VLEN:
    return "variable-length sequences";
  case H5T_REFERENCE:
    return "references";
  case H5T_OPAQUE:
    return "opaque bytes";
  case H5T_BITFIELD:
    return "bit fields";
  case H5T_TIME:
    return "times";
  default:
    return "values of an unknown type";
  }
}

/* The checks of a dataset before anything is read (see the file header). */
static void io_read_check(IoRead *r, hid_t d)
{
  hid_t              t = H5Dget_type(d), s = H5Dget_space(d);
  H5T_class_t        cls                = t >= 0 ? H5Tget_class(t) : H5T_NO_CLASS;
  int                nd                 = s >= 0 ? H5Sget_simple_extent_ndims(s) : -1;
  hsize_t            dims[H5S_MAX_RANK] = {0};
  unsigned long long rows, nc, lim = (unsigned long long)PETSC_MAX_INT - 1;
  double             bytes;

  if (nd >= 1 && nd <= H5S_MAX_RANK && H5Sget_simple_extent_dims(s, dims, NULL) < 0) nd = -1;
  if (t >= 0) H5Tclose(t);
  if (s >= 0) H5Sclose(s);
  if (cls != H5T_INTEGER && cls != H5T_FLOAT) {
    snprintf(r->msg, sizeof r->msg, "%s: dataset %s holds %s, expected numbers (integer or floating point)", r->file, r->name, io_class_name(cls));
    return;
  }
  if (nd != 1 && nd != 2) {
    snprintf(r->msg, sizeof r->msg, "%s: dataset %s has %d dimensions, expected 1 or 2 (rows, or rows x columns)", r->file, r->name, nd);
    return;
  }
  rows = dims[0];
  nc   = nd == 2 ? dims[1] : 1;
  if (nc == 0 || (r->ncomp && nc != (unsigned long long)r->ncomp)) {
    snprintf(r->msg, sizeof r->msg, "%s: dataset %s has %llu columns, expected %lld", r->file, r->name, nc, r->ncomp ? (long long)r->ncomp : 1LL);
    return;
  }
  if (rows > lim / nc) {
    snprintf(r->msg, sizeof r->msg, "%s: dataset %s declares %llu x %llu values, more than Sable can index (at most %llu values a dataset)", r->file, r->name, rows, nc, lim);
    return;
  }
  bytes = (double)(rows * nc) * sizeof(PetscReal);
  if (bytes > r->maxbytes) snprintf(r->msg, sizeof r->msg, "%s: dataset %s declares %llu x %llu values (%.3g GB to read), more than a rank can hold (%.3g GB: the physical memory shared by the ranks of a node)", r->file, r->name, rows, nc, bytes / 1e9, r->maxbytes / 1e9);
  r->rows = (PetscInt)rows;
  r->nc   = (PetscInt)nc;
}

/* This rank's read: opens, checks, reads, closes. File problems go to r->msg (r->data NULL). */
static PetscErrorCode IoReadLocal(IoRead *r)
{
  hid_t f, d;
  char  h5[256];

  PetscFunctionBeginUser;
  io_quiet();
  r->data = NULL;
  f       = H5Fopen(r->file, H5F_ACC_RDONLY, H5P_DEFAULT);
  if (f < 0) {
    io_h5_last_error(h5, sizeof h5);
    snprintf(r->msg, sizeof r->msg, "%s: cannot open as an HDF5 file (HDF5: %s)", r->file, h5);
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  d = H5Dopen2(f, r->name, H5P_DEFAULT);
  if (d < 0) snprintf(r->msg, sizeof r->msg, "%s has no dataset %s", r->file, r->name);
  else {
    io_read_check(r, d);
    if (!r->msg[0]) {
      PetscCall(PetscMalloc1(PetscMax(1, r->rows * r->nc), &r->data));
      if (r->rows && H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, r->data) < 0) {
        io_h5_last_error(h5, sizeof h5);
        snprintf(r->msg, sizeof r->msg, "%s: cannot read dataset %s as numbers (HDF5: %s)", r->file, r->name, h5);
        PetscCall(PetscFree(r->data));
      }
    }
    H5Dclose(d);
  }
  H5Fclose(f);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The physical memory of this machine (bytes); 0 if unknown (then no bound). */
static double io_phys_bytes(void)
{
  long pages = sysconf(_SC_PHYS_PAGES), size = sysconf(_SC_PAGESIZE);

  return pages > 0 && size > 0 ? (double)pages * (double)size : 0;
}

PetscErrorCode IoReadDataset(const char *file, const char *name, PetscInt *rows, PetscInt *ncomp, PetscReal **data)
{
  IoRead r;

  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(&r, sizeof r));
  r.file     = file;
  r.name     = name;
  r.maxbytes = io_phys_bytes();
  if (r.maxbytes == 0) r.maxbytes = PETSC_MAX_REAL;
  PetscCall(IoReadLocal(&r));
  PetscCheck(!r.msg[0], PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "%s", r.msg);
  *rows  = r.rows;
  *ncomp = r.nc;
  *data  = r.data;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IoReadDatasetAll(MPI_Comm comm, const char *file, const char *name, PetscInt ncomp, PetscInt *rows, PetscReal **data)
{
  IoRead      r;
  MPI_Comm    node;
  PetscMPIInt nnode, rank, size, mine, first;

  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(&r, sizeof r));
  r.file  = file;
  r.name  = name;
  r.ncomp = ncomp;
  PetscCallMPI(MPI_Comm_split_type(comm, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node));
  PetscCallMPI(MPI_Comm_size(node, &nnode));
  PetscCallMPI(MPI_Comm_free(&node));
  r.maxbytes = io_phys_bytes() / nnode;
  if (r.maxbytes == 0) r.maxbytes = PETSC_MAX_REAL;
  PetscCall(IoReadLocal(&r));
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  mine = r.msg[0] ? rank : size;
  PetscCallMPI(MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, comm));
  if (first < size) { /* the first failing rank's words, on every rank */
    PetscCallMPI(MPI_Bcast(r.msg, sizeof r.msg, MPI_CHAR, first, comm));
    PetscCall(PetscFree(r.data));
    SETERRQ(comm, PETSC_ERR_FILE_UNEXPECTED, "%s", r.msg);
  }
  *rows = r.rows;
  *data = r.data;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IoReadTime(const char *file, PetscReal *t, PetscBool *has)
{
  hid_t  f, a;
  double v = 0;
  char   h5[256];

  PetscFunctionBeginUser;
  io_quiet();
  f = H5Fopen(file, H5F_ACC_RDONLY, H5P_DEFAULT);
  PetscCheck(f >= 0, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "%s is not an HDF5 file (or cannot be opened as one)", file);
  *has = (PetscBool)(H5Aexists(f, "time") > 0);
  if (*has) {
    herr_t ok = -1;
    a         = H5Aopen(f, "time", H5P_DEFAULT);
    if (a >= 0) ok = H5Aread(a, H5T_NATIVE_DOUBLE, &v);
    if (ok < 0) io_h5_last_error(h5, sizeof h5);
    if (a >= 0) H5Aclose(a);
    if (ok < 0) H5Fclose(f);
    PetscCheck(ok >= 0, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "%s: the attribute time cannot be read as a number (HDF5: %s)", file, h5);
  }
  *t = v;
  PetscCheck(H5Fclose(f) >= 0, PETSC_COMM_SELF, PETSC_ERR_FILE_READ, "%s: cannot close the file after reading it", file);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IoCheckReadable(MPI_Comm comm, const char *opt, const char *file)
{
  FILE *fp;

  PetscFunctionBeginUser;
  io_quiet();
  fp = fopen(file, "r");
  PetscCheck(fp, comm, PETSC_ERR_FILE_OPEN, "%s %s: cannot open (%s)", opt, file, strerror(errno));
  fclose(fp);
  PetscCheck(H5Fis_hdf5(file) > 0, comm, PETSC_ERR_FILE_UNEXPECTED, "%s %s: not an HDF5 file (Sable reads the frames it writes, *_NNNNNN.h5)", opt, file);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IoHasDataset(const char *file, const char *name, PetscBool *has)
{
  hid_t f;
  char  group[PETSC_MAX_PATH_LEN], *slash;

  PetscFunctionBeginUser;
  io_quiet();
  f = H5Fopen(file, H5F_ACC_RDONLY, H5P_DEFAULT);
  PetscCheck(f >= 0, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "%s is not an HDF5 file (or cannot be opened as one)", file);
  PetscCall(PetscStrncpy(group, name, sizeof group));
  slash = strrchr(group, '/');
  if (slash && slash != group) *slash = 0;
  *has = (PetscBool)((!slash || slash == group || H5Lexists(f, group, H5P_DEFAULT) > 0) && H5Lexists(f, name, H5P_DEFAULT) > 0);
  PetscCheck(H5Fclose(f) >= 0, PETSC_COMM_SELF, PETSC_ERR_FILE_READ, "%s: cannot close the file after reading it", file);
  PetscFunctionReturn(PETSC_SUCCESS);
}
