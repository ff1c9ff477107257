/* HDF5 + XDMF output (see io.h). Layout of a frame file:
 *   /particles/<name>  [N] or [N, ncomp], rows in rank order (ids identify particles)
 *   /fluid/<name>      [nz, ny, nx] or [nz, ny, nx, ncomp], cell centred
 *   attribute "time" on the root group.
 *   /surface/points [P, 3], /surface/tag [P], /surface/triangles [T, 3] (global point indices)
 *   /particles/vertex [N]: 0..N-1, the Polyvertex connectivity (for the Xdmf3 readers).
 * The XDMF index holds one temporal collection per kind: a Polyvertex grid per frame for the
 * particles, a Triangle grid for the surface (when written), a 3DCoRectMesh for the fluid. */
#include "io/io.h"
#include <hdf5.h>
#include <errno.h>
#include <sys/stat.h>

#define IO_MAX_SETS 32

/* HDF5 prints its own error stack (a dozen lines) before returning the failure that our checks
 * turn into one message: silence it. Called before every HDF5 use of this file. */
static void io_quiet(void)
{
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
}

typedef struct {
  char    name[64];
  PetscInt ncomp;
  PetscBool isint;
} IoSet;

typedef struct {
  PetscReal t;
  char      file[PETSC_MAX_PATH_LEN];
  PetscInt  np;                         /* global particle count */
  IoSet     part[IO_MAX_SETS], fluid[IO_MAX_SETS];
  PetscInt  npart, nfluid;
  long long nsurfp, nsurft;             /* surface points and triangles (0: none) */
} IoFrame;

struct _p_Io {
  MPI_Comm  comm;
  char      dir[PETSC_MAX_PATH_LEN], prefix[64], index[PETSC_MAX_PATH_LEN];
  PetscReal interval, next;
  PetscBool fluidmesh;
  PetscReal flo[3], fh[3];
  PetscInt  fcells[3];
  IoFrame  *frames;
  PetscInt  nframes, capframes;
  hid_t     file, gpart, gfluid;
  char      tmpname[PETSC_MAX_PATH_LEN];
};

PetscErrorCode IoCreate(MPI_Comm comm, Io *io)
{
  PetscFunctionBeginUser;
  PetscCall(PetscNew(io));
  (*io)->comm = comm;
  PetscCall(PetscStrcpy((*io)->dir, "out"));
  PetscCall(PetscStrcpy((*io)->prefix, "sable"));
  (*io)->interval = 0;
  (*io)->file     = -1;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IoSetFromOptions(Io io)
{
  PetscFunctionBeginUser;
  PetscOptionsBegin(io->comm, NULL, "Output (HDF5 + XDMF)", NULL);
  PetscCall(PetscOptionsString("-io_dir", "Output directory", NULL, io->dir, io->dir, sizeof io->dir, NULL));
  PetscCall(PetscOptionsString("-io_prefix", "Output file name prefix", NULL, io->prefix, io->prefix, sizeof io->prefix, NULL));
  PetscCall(PetscOptionsReal("-io_interval", "Simulated time between outputs (s); 0 = no output", NULL, io->interval, &io->interval, NULL));
  PetscOptionsEnd();
  PetscCheck(io->interval >= 0, io->comm, PETSC_ERR_ARG_OUTOFRANGE, "-io_interval %g must be >= 0", (double)io->interval);
  { /* the raw values: PETSc cuts a string at the buffer's size without a word */
    const char *v;
    PetscBool   set;
    PetscCall(PetscOptionsFindPair(NULL, NULL, "-io_prefix", &v, &set));
    PetscCheck(!set || (v && strlen(v) < sizeof io->prefix), io->comm, PETSC_ERR_ARG_OUTOFRANGE, "-io_prefix %s: at most %d characters", v ? v : "(none)", (int)sizeof io->prefix - 1);
    PetscCheck(!strchr(io->prefix, '/') && io->prefix[0], io->comm, PETSC_ERR_ARG_WRONG, "-io_prefix %s: a file name prefix, without '/' (the directory is -io_dir)", io->prefix);
    PetscCall(PetscOptionsFindPair(NULL, NULL, "-io_dir", &v, &set));
    PetscCheck(!set || (v && strlen(v) < sizeof io->dir - 80), io->comm, PETSC_ERR_ARG_OUTOFRANGE, "-io_dir: at most %d characters", (int)sizeof io->dir - 81);
  }
  PetscCall(PetscSNPrintf(io->index, sizeof io->index, "%s/%s.xmf", io->dir, io->prefix));
  io->next = 0;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IoGetInterval(Io io, PetscReal *interval)
{
  PetscFunctionBeginUser;
  *interval = io->interval;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IoGetIndexPath(Io io, const char **path)
{
  PetscFunctionBeginUser;
  *path = io->nframes ? io->index : NULL;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IoDue(Io io, PetscReal t, PetscBool *due)
{
  PetscFunctionBeginUser;
  /* t is a sum of steps and drifts from the multiples of the interval: the same tolerance decides
     whether a frame is due and which multiple comes next, so a frame taken just below k*interval
     is not followed by another just above it */
  *due = (io->interval > 0 && t >= io->next - 1e-6 * io->interval) ? PETSC_TRUE : PETSC_FALSE;
  if (*due) io->next = (PetscFloorReal(t / io->interval + 1e-6) + 1) * io->interval;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IoDueFinal(Io io, PetscReal t, PetscBool *due)
{
  PetscFunctionBeginUser;
  *due = (PetscBool)(io->interval > 0 && (io->nframes == 0 || io->frames[io->nframes - 1].t < t));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IoDestroy(Io *io)
{
  PetscFunctionBeginUser;
  if (!*io) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscFree((*io)->frames));
  PetscCall(PetscFree(*io));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode IoMakeDir(Io io)
{
  PetscMPIInt rank;
  int         err = 0;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(io->comm, &rank));
  if (!rank && mkdir(io->dir, 0755) != 0 && errno != EEXIST) err = errno;
  PetscCallMPI(MPI_Bcast(&err, 1, MPI_INT, 0, io->comm));
  PetscCheck(!err, io->comm, PETSC_ERR_FILE_OPEN, "-io_dir %s: cannot create the directory (%s)", io->dir, strerror(err));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IoFrameBegin(Io io, PetscReal t, PetscInt step)
{
  hid_t    fapl, attr, space;
  IoFrame *fr;

  PetscFunctionBeginUser;
  io_quiet();
  (void)step;
  if (!io->nframes) PetscCall(IoMakeDir(io));
  if (io->nframes == io->capframes) {
    IoFrame *nf;
    io->capframes = 2 * io->capframes + 16;
    PetscCall(PetscCalloc1(io->capframes, &nf));
    if (io->nframes) PetscCall(PetscArraycpy(nf, io->frames, io->nframes));
    PetscCall(PetscFree(io->frames));
    io->frames = nf;
  }
  fr = &io->frames[io->nframes];
  PetscCall(PetscMemzero(fr, sizeof *fr));
  fr->t = t;
  PetscCall(PetscSNPrintf(fr->file, sizeof fr->file, "%s_%06" PetscInt_FMT ".h5", io->prefix, io->nframes));
  PetscCall(PetscSNPrintf(io->tmpname, sizeof io->tmpname, "%s/%s.tmp", io->dir, fr->file));
  SableTempSet(io->tmpname); /* removed if the run ends before the rename */
  fapl = H5Pcreate(H5P_FILE_ACCESS);
  SableCallH5(fapl);
  SableCallH5(H5Pset_fapl_mpio(fapl, io->comm, MPI_INFO_NULL));
  io->file = H5Fcreate(io->tmpname, H5F_ACC_TRUNC, H5P_DEFAULT, fapl);
  SableCallH5(H5Pclose(fapl));
  PetscCheck(io->file >= 0, io->comm, PETSC_ERR_FILE_OPEN, "-io_dir: cannot create %s", io->tmpname);
  io->gpart  = H5Gcreate2(io->file, "particles", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  io->gfluid = H5Gcreate2(io->file, "fluid", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  SableCallH5(io->gpart);
  SableCallH5(io->gfluid);
  space = H5Screate(H5S_SCALAR);
  attr  = H5Acreate2(io->file, "time", H5T_NATIVE_DOUBLE, space, H5P_DEFAULT, H5P_DEFAULT);
  SableCallH5(attr);
  SableCallH5(H5Awrite(attr, H5T_NATIVE_DOUBLE, &t));
  SableCallH5(H5Aclose(attr));
  SableCallH5(H5Sclose(space));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective write of a block [start, start+count) of a dataset of global dims (rank-1..4). */
static PetscErrorCode IoWriteBlock(hid_t group, const char *name, hid_t type, int rank, const hsize_t *dims, const hsize_t *start, const hsize_t *count, const void *data)
{
  hid_t    fspace, mspace, dset, dxpl;
  hsize_t  n = 1;

  PetscFunctionBeginUser;
  for (int k = 0; k < rank; k++) n *= count[k];
  fspace = H5Screate_simple(rank, dims, NULL);
  SableCallH5(fspace);
  dset = H5Dcreate2(group, name, type, fspace, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  SableCallH5(dset);
  mspace = H5Screate_simple(1, &n, NULL);
  SableCallH5(mspace);
  if (n) SableCallH5(H5Sselect_hyperslab(fspace, H5S_SELECT_SET, start, NULL, count, NULL));
  else {
    SableCallH5(H5Sselect_none(fspace));
    SableCallH5(H5Sselect_none(mspace));
  }
  { /* an empty dataset (a scene with no particles) is created but not written: HDF5's
       collective write of nothing fails */
    hsize_t total = 1;
    for (int k = 0; k < rank; k++) total *= dims[k];
    if (total) {
      dxpl = H5Pcreate(H5P_DATASET_XFER);
      SableCallH5(H5Pset_dxpl_mpio(dxpl, H5FD_MPIO_COLLECTIVE));
      SableCallH5(H5Dwrite(dset, type, mspace, fspace, dxpl, data));
      SableCallH5(H5Pclose(dxpl));
    }
  }
  SableCallH5(H5Sclose(mspace));
  SableCallH5(H5Sclose(fspace));
  SableCallH5(H5Dclose(dset));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode IoWriteRows(Io io, const char *name, PetscInt nlocal, PetscInt ncomp, hid_t type, const void *data, PetscBool isint)
{
  long long n = nlocal, off = 0, total = 0;
  hsize_t   dims[2], start[2] = {0, 0}, count[2];
  IoFrame  *fr = &io->frames[io->nframes];

  PetscFunctionBeginUser;
  PetscCheck(fr->npart < IO_MAX_SETS, io->comm, PETSC_ERR_SUP, "too many particle datasets in one frame");
  PetscCallMPI(MPI_Exscan(&n, &off, 1, MPI_LONG_LONG, MPI_SUM, io->comm));
  PetscCallMPI(MPI_Allreduce(&n, &total, 1, MPI_LONG_LONG, MPI_SUM, io->comm));
  dims[0]  = (hsize_t)total;
  dims[1]  = (hsize_t)ncomp;
  start[0] = (hsize_t)off;
  count[0] = (hsize_t)n;
  count[1] = (hsize_t)ncomp;
  PetscCall(IoWriteBlock(io->gpart, name, type, ncomp > 1 ? 2 : 1, dims, start, count, data));
  if (!strcmp(name, "position")) { /* the Polyvertex connectivity 0..N-1: the Xdmf3 readers make no cells without it */
    long long *vtx;
    PetscCall(PetscMalloc1(n + 1, &vtx));
    for (long long i = 0; i < n; i++) vtx[i] = off + i;
    PetscCall(IoWriteBlock(io->gpart, "vertex", H5T_NATIVE_LLONG, 1, dims, start, count, vtx));
    PetscCall(PetscFree(vtx));
  }
  PetscCall(PetscStrncpy(fr->part[fr->npart].name, name, sizeof fr->part[0].name));
  fr->part[fr->npart].ncomp = ncomp;
  fr->part[fr->npart].isint = isint;
  fr->npart++;
  fr->np = (PetscInt)total;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IoWriteParticles(Io io, const char *name, PetscInt nlocal, PetscInt ncomp, const PetscReal *data)
{
  PetscFunctionBeginUser;
  PetscCall(IoWriteRows(io, name, nlocal, ncomp, H5T_NATIVE_DOUBLE, data, PETSC_FALSE));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IoWriteParticlesInt(Io io, const char *name, PetscInt nlocal, const PetscInt *data)
{
  PetscFunctionBeginUser;
  PetscCall(IoWriteRows(io, name, nlocal, 1, sizeof(PetscInt) == 8 ? H5T_NATIVE_INT64 : H5T_NATIVE_INT32, data, PETSC_TRUE));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IoWriteSurface(Io io, PetscInt np, const PetscReal *xyz, const PetscInt *tag, PetscInt nt, const PetscInt *tri)
{
  long long n[2] = {np, nt}, off[2] = {0, 0}, tot[2] = {0, 0}, *gtri, *gtag;
  hsize_t   dims[2], start[2] = {0, 0}, count[2];
  IoFrame  *fr = &io->frames[io->nframes];
  hid_t     g;

  PetscFunctionBeginUser;
  PetscCheck(!fr->nsurft, io->comm, PETSC_ERR_ORDER, "IoWriteSurface: at most one surface per frame");
  PetscCallMPI(MPI_Exscan(n, off, 2, MPI_LONG_LONG, MPI_SUM, io->comm));
  PetscCallMPI(MPI_Allreduce(n, tot, 2, MPI_LONG_LONG, MPI_SUM, io->comm));
  PetscCall(PetscMalloc2(3 * nt + 1, &gtri, np + 1, &gtag));
  for (PetscInt k = 0; k < 3 * nt; k++) gtri[k] = off[0] + tri[k];
  for (PetscInt k = 0; k < np; k++) gtag[k] = tag[k];
  g = H5Gcreate2(io->file, "surface", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  SableCallH5(g);
  dims[0] = (hsize_t)tot[0], dims[1] = 3, start[0] = (hsize_t)off[0], count[0] = (hsize_t)np, count[1] = 3;
  PetscCall(IoWriteBlock(g, "points", H5T_NATIVE_DOUBLE, 2, dims, start, count, xyz));
  PetscCall(IoWriteBlock(g, "tag", H5T_NATIVE_LLONG, 1, dims, start, count, gtag));
  dims[0] = (hsize_t)tot[1], start[0] = (hsize_t)off[1], count[0] = (hsize_t)nt;
  PetscCall(IoWriteBlock(g, "triangles", H5T_NATIVE_LLONG, 2, dims, start, count, gtri));
  SableCallH5(H5Gclose(g));
  PetscCall(PetscFree2(gtri, gtag));
  fr->nsurfp = tot[0];
  fr->nsurft = tot[1];
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IoSetFluidMesh(Io io, const PetscReal lo[3], const PetscReal h[3], const PetscInt cells[3])
{
  PetscFunctionBeginUser;
  for (int k = 0; k < 3; k++) {
    io->flo[k]    = lo[k];
    io->fh[k]     = h[k];
    io->fcells[k] = cells[k];
  }
  io->fluidmesh = PETSC_TRUE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IoWriteField(Io io, const char *name, PetscInt ncomp, const PetscInt start[3], const PetscInt count[3], const PetscReal *data)
{
  hsize_t  dims[4], st[4] = {0, 0, 0, 0}, cnt[4];
  IoFrame *fr = &io->frames[io->nframes];

  PetscFunctionBeginUser;
  PetscCheck(io->fluidmesh, io->comm, PETSC_ERR_ORDER, "IoSetFluidMesh must precede IoWriteField");
  PetscCheck(fr->nfluid < IO_MAX_SETS, io->comm, PETSC_ERR_SUP, "too many fluid datasets in one frame");
  for (int k = 0; k < 3; k++) { /* HDF5 order is z, y, x */
    dims[k] = (hsize_t)io->fcells[2 - k];
    st[k]   = (hsize_t)start[2 - k];
    cnt[k]  = (hsize_t)count[2 - k];
  }
  dims[3] = cnt[3] = (hsize_t)ncomp;
  PetscCall(IoWriteBlock(io->gfluid, name, H5T_NATIVE_DOUBLE, ncomp > 1 ? 4 : 3, dims, st, cnt, data));
  PetscCall(PetscStrncpy(fr->fluid[fr->nfluid].name, name, sizeof fr->fluid[0].name));
  fr->fluid[fr->nfluid].ncomp = ncomp;
  fr->nfluid++;
  PetscFunctionReturn(PETSC_SUCCESS);
}

static void IoXdmfAttribute(FILE *fp, const char *file, const char *group, const IoSet *s, const char *center, const char *dims)
{
  const char *type = s->ncomp == 3 ? "Vector" : (s->ncomp == 1 ? "Scalar" : "Matrix");
  fprintf(fp, "        <Attribute Name=\"%s\" AttributeType=\"%s\" Center=\"%s\">\n", s->name, type, center);
  if (s->ncomp > 1) fprintf(fp, "          <DataItem Dimensions=\"%s %d\" NumberType=\"%s\" Precision=\"8\" Format=\"HDF\">%s:/%s/%s</DataItem>\n", dims, (int)s->ncomp, s->isint ? "Int" : "Float", file, group, s->name);
  else fprintf(fp, "          <DataItem Dimensions=\"%s\" NumberType=\"%s\" Precision=\"8\" Format=\"HDF\">%s:/%s/%s</DataItem>\n", dims, s->isint ? "Int" : "Float", file, group, s->name);
  fprintf(fp, "        </Attribute>\n");
}

/* One frame's grid of one kind (0 particles, 1 surface, 2 fluid), with its time. */
static void IoXdmfGrid(Io io, FILE *fp, const IoFrame *fr, int kind)
{
  char d[64];

  if (kind == 0) {
    PetscSNPrintf(d, sizeof d, "%d", (int)fr->np);
    fprintf(fp, "      <Grid Name=\"particles\" GridType=\"Uniform\">\n        <Time Value=\"%.17g\"/>\n", (double)fr->t);
    fprintf(fp, "        <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"%d\" NodesPerElement=\"1\">\n          <DataItem Dimensions=\"%d\" NumberType=\"Int\" Precision=\"8\" Format=\"HDF\">%s:/particles/vertex</DataItem>\n        </Topology>\n", (int)fr->np, (int)fr->np, fr->file);
    fprintf(fp, "        <Geometry GeometryType=\"XYZ\">\n          <DataItem Dimensions=\"%d 3\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">%s:/particles/position</DataItem>\n        </Geometry>\n", (int)fr->np, fr->file);
    for (PetscInt i = 0; i < fr->npart; i++)
      if (strcmp(fr->part[i].name, "position")) IoXdmfAttribute(fp, fr->file, "particles", &fr->part[i], "Node", d);
  } else if (kind == 1) {
    fprintf(fp, "      <Grid Name=\"surface\" GridType=\"Uniform\">\n        <Time Value=\"%.17g\"/>\n", (double)fr->t);
    fprintf(fp, "        <Topology TopologyType=\"Triangle\" NumberOfElements=\"%lld\">\n          <DataItem Dimensions=\"%lld 3\" NumberType=\"Int\" Precision=\"8\" Format=\"HDF\">%s:/surface/triangles</DataItem>\n        </Topology>\n", fr->nsurft, fr->nsurft, fr->file);
    fprintf(fp, "        <Geometry GeometryType=\"XYZ\">\n          <DataItem Dimensions=\"%lld 3\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">%s:/surface/points</DataItem>\n        </Geometry>\n", fr->nsurfp, fr->file);
    fprintf(fp, "        <Attribute Name=\"id\" AttributeType=\"Scalar\" Center=\"Node\">\n          <DataItem Dimensions=\"%lld\" NumberType=\"Int\" Precision=\"8\" Format=\"HDF\">%s:/surface/tag</DataItem>\n        </Attribute>\n", fr->nsurfp, fr->file);
  } else {
    PetscSNPrintf(d, sizeof d, "%d %d %d", (int)io->fcells[2], (int)io->fcells[1], (int)io->fcells[0]);
    fprintf(fp, "      <Grid Name=\"fluid\" GridType=\"Uniform\">\n        <Time Value=\"%.17g\"/>\n", (double)fr->t);
    fprintf(fp, "        <Topology TopologyType=\"3DCoRectMesh\" Dimensions=\"%d %d %d\"/>\n", (int)io->fcells[2] + 1, (int)io->fcells[1] + 1, (int)io->fcells[0] + 1);
    fprintf(fp, "        <Geometry GeometryType=\"ORIGIN_DXDYDZ\">\n");
    fprintf(fp, "          <DataItem Dimensions=\"3\" Format=\"XML\">%.17g %.17g %.17g</DataItem>\n", (double)io->flo[2], (double)io->flo[1], (double)io->flo[0]);
    fprintf(fp, "          <DataItem Dimensions=\"3\" Format=\"XML\">%.17g %.17g %.17g</DataItem>\n        </Geometry>\n", (double)io->fh[2], (double)io->fh[1], (double)io->fh[0]);
    for (PetscInt i = 0; i < fr->nfluid; i++) IoXdmfAttribute(fp, fr->file, "fluid", &fr->fluid[i], "Cell", d);
  }
  fprintf(fp, "      </Grid>\n");
}

/* The index: one temporal collection per kind (particles, surface, fluid) directly in the
 * domain, so that ParaView's XDMF reader keeps one block of a fixed name ("particles", ...)
 * through time (a spatial collection per frame gave particles[1], particles[2], ... and broke
 * Extract Block after the first frame). */
static PetscErrorCode IoWriteIndex(Io io)
{
  const char *kinds[3] = {"particles", "surface", "fluid"};
  char        tmp[PETSC_MAX_PATH_LEN];
  FILE       *fp;

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(tmp, sizeof tmp, "%s.tmp", io->index));
  SableTempSet(tmp);
  fp = fopen(tmp, "w");
  PetscCheck(fp, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "-io_dir: cannot write %s", tmp);
  fprintf(fp, "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n  <Domain>\n");
  for (int k = 0; k < 3; k++) {
    PetscInt n = 0;
    for (PetscInt i = 0; i < io->nframes; i++) n += k == 0 ? io->frames[i].npart > 0 : (k == 1 ? io->frames[i].nsurft > 0 : io->frames[i].nfluid > 0);
    if (!n) continue;
    fprintf(fp, "    <Grid Name=\"%s\" GridType=\"Collection\" CollectionType=\"Temporal\">\n", kinds[k]);
    for (PetscInt i = 0; i < io->nframes; i++) {
      const IoFrame *fr = &io->frames[i];
      if (k == 0 ? fr->npart > 0 : (k == 1 ? fr->nsurft > 0 : fr->nfluid > 0)) IoXdmfGrid(io, fp, fr, k);
    }
    fprintf(fp, "    </Grid>\n");
  }
  fprintf(fp, "  </Domain>\n</Xdmf>\n");
  PetscCheck(fclose(fp) == 0, PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "-io_dir: cannot finish %s", tmp);
  PetscCheck(rename(tmp, io->index) == 0, PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "cannot rename %s to %s", tmp, io->index);
  SableTempSet(NULL);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IoFrameEnd(Io io)
{
  PetscMPIInt rank;
  char        final[PETSC_MAX_PATH_LEN];
  int         err = 0;

  PetscFunctionBeginUser;
  SableCallH5(H5Gclose(io->gpart));
  SableCallH5(H5Gclose(io->gfluid));
  SableCallH5(H5Fclose(io->file));
  io->file = -1;
  PetscCallMPI(MPI_Comm_rank(io->comm, &rank));
  PetscCall(PetscSNPrintf(final, sizeof final, "%s/%s", io->dir, io->frames[io->nframes].file));
  io->nframes++;
  if (!rank) {
    if (rename(io->tmpname, final) != 0) err = errno;
    else PetscCall(IoWriteIndex(io));
  }
  PetscCallMPI(MPI_Bcast(&err, 1, MPI_INT, 0, io->comm));
  if (!err) SableTempSet(NULL);
  PetscCheck(!err, io->comm, PETSC_ERR_FILE_WRITE, "cannot rename %s to %s (%s)", io->tmpname, final, strerror(err));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IoReadDataset(const char *file, const char *name, PetscInt *rows, PetscInt *ncomp, PetscReal **data)
{
  hid_t   f, d, s;
  hsize_t dims[2] = {0, 1};
  int     rank;

  PetscFunctionBeginUser;
  io_quiet();
  f = H5Fopen(file, H5F_ACC_RDONLY, H5P_DEFAULT);
  PetscCheck(f >= 0, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "%s is not an HDF5 file (or cannot be opened as one)", file);
  d = H5Dopen2(f, name, H5P_DEFAULT);
  PetscCheck(d >= 0, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "file %s has no dataset %s", file, name);
  s    = H5Dget_space(d);
  rank = H5Sget_simple_extent_ndims(s);
  PetscCheck(rank == 1 || rank == 2, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "%s:%s has rank %d, expected 1 or 2", file, name, rank);
  SableCallH5(H5Sget_simple_extent_dims(s, dims, NULL));
  *rows  = (PetscInt)dims[0];
  *ncomp = rank == 2 ? (PetscInt)dims[1] : 1;
  PetscCall(PetscMalloc1(PetscMax(1, *rows * *ncomp), data));
  if (*rows) SableCallH5(H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, *data));
  SableCallH5(H5Sclose(s));
  SableCallH5(H5Dclose(d));
  SableCallH5(H5Fclose(f));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IoReadTime(const char *file, PetscReal *t, PetscBool *has)
{
  hid_t  f, a;
  double v = 0;

  PetscFunctionBeginUser;
  io_quiet();
  f = H5Fopen(file, H5F_ACC_RDONLY, H5P_DEFAULT);
  PetscCheck(f >= 0, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "%s is not an HDF5 file (or cannot be opened as one)", file);
  *has = (PetscBool)(H5Aexists(f, "time") > 0);
  if (*has) {
    a = H5Aopen(f, "time", H5P_DEFAULT);
    SableCallH5(a);
    SableCallH5(H5Aread(a, H5T_NATIVE_DOUBLE, &v));
    SableCallH5(H5Aclose(a));
  }
  *t = v;
  SableCallH5(H5Fclose(f));
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
  SableCallH5(H5Fclose(f));
  PetscFunctionReturn(PETSC_SUCCESS);
}
