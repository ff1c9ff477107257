/* HDF5 + XDMF output (see io.h). Layout of a frame file:
 *   /particles/<name>  [N] or [N, ncomp], rows in rank order (ids identify particles)
 *   /fluid/<name>      [nz, ny, nx] or [nz, ny, nx, ncomp], cell centred
 *   attributes "time" and "run_id" (the run's identity, see continue.c) on the root group.
 *   /surface/points [P, 3], /surface/tag [P], /surface/triangles [T, 3] (global point indices)
 *   /particles/vertex [N]: 0..N-1, the Polyvertex connectivity (for the Xdmf3 readers).
 * The XDMF index that lists the frames is written by xdmf.c.
 * Failures (a full disk, an I/O error): a frame is written in steps (open, one per dataset,
 * close); the ranks agree after each step whether any of them failed (a collective write can fail
 * on one rank only), and if so all of them close every handle of the frame, rank 0 removes the
 * temporary, and the run ends with one error naming the file, the step and the reason. Frames
 * already renamed into place and the index listing them stay valid. */
#include "io/io_private.h"
#include <errno.h>
#include <stdarg.h>
#include <fcntl.h>
#include <unistd.h>
#include <sys/stat.h>
#include <sys/statvfs.h>

/* A failed write on a file system with less free space than the write needed plus this margin
   (bytes, for HDF5's metadata) is reported as a full disk. */
#define IO_FULL_MARGIN (1LL << 20)
/* Disk space (bytes) rank 0 holds in -io_dir while the run writes frames and gives back when a
   frame fails: closing the failed frame's file flushes HDF5's metadata, and a close whose flush
   fails leaves HDF5 (1.10) holding a freed file, which crashes at exit. Measured: a 100-particle
   frame failing on a full tmpfs closed cleanly with 14 kB given back; 64 kB leaves room for the
   fluid fields and surfaces of larger frames. */
#define IO_RESERVE (64 * 1024)

PetscErrorCode IoCreate(MPI_Comm comm, Io *io)
{
  PetscFunctionBeginUser;
  PetscCall(PetscNew(io));
  (*io)->comm = comm;
  PetscCall(PetscStrcpy((*io)->dir, "out"));
  PetscCall(PetscStrcpy((*io)->prefix, "sable"));
  (*io)->interval = 0;
  (*io)->file     = -1;
  (*io)->gpart    = -1;
  (*io)->gfluid   = -1;
  (*io)->reserve  = -1;
  PetscCall(PetscTime(&(*io)->t_create));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IoSetFromOptions(Io io)
{
  PetscFunctionBeginUser;
  PetscOptionsBegin(io->comm, NULL, "Output (HDF5 + XDMF)", NULL);
  PetscCall(SableOptionsString("-io_dir", "Output directory, made with its parents if missing", io->dir, sizeof io->dir, NULL));
  PetscCall(SableOptionsString("-io_prefix", "Output file name prefix", io->prefix, sizeof io->prefix, NULL));
  PetscCall(SableOptionsReal("-io_interval", "Simulated time between outputs; 0 = no output", "s", "[0,inf)", io->interval, &io->interval, NULL));
  PetscCall(SableOptionsReal("-io_particle_interval", "Simulated time between frames of the particles (and convex surfaces); 0 = none; default -io_interval", "s", "[0,inf)", io->interval, &io->pinterval, NULL));
  PetscCall(SableOptionsReal("-io_fluid_interval", "Simulated time between frames of the fluid fields and time averages; 0 = none; default -io_interval", "s", "[0,inf)", io->interval, &io->finterval, NULL));
  PetscCall(IoReadFields(io, PetscOptionsObject)); /* fields.c */
  {
    const char *const prec[] = {"double", "single"};
    PetscInt          k      = 0;
    PetscCall(SableOptionsEnum("-io_precision", "Reals of the particle and fluid datasets of a frame: double (64 bits, exact) or single (32 bits, about 7 digits: half the bytes; checkpoints stay exact)", prec, 2, 0, &k, NULL));
    io->single = (PetscBool)(k == 1);
  }
  PetscCall(SableOptionsInt("-io_compress", "Lossless HDF5 compression of the frames (chunked, shuffle + deflate) at this level; 0 = none (checkpoints are never compressed)", NULL, "[0,9]", io->compress, &io->compress, NULL));
  PetscOptionsEnd();
  { /* the raw value of -io_dir: room for the file names under it */
    const char *v;
    PetscBool   set;
    PetscCheck(!strchr(io->prefix, '/') && io->prefix[0], io->comm, PETSC_ERR_ARG_WRONG, "-io_prefix %s: a file name prefix, without '/' (the directory is -io_dir)", io->prefix);
    PetscCall(PetscOptionsFindPair(NULL, NULL, "-io_dir", &v, &set));
    PetscCheck(!set || (v && strlen(v) < sizeof io->dir - 80), io->comm, PETSC_ERR_ARG_OUTOFRANGE, "-io_dir: at most %d characters", (int)sizeof io->dir - 81);
  }
  PetscCall(PetscSNPrintf(io->index, sizeof io->index, "%s/%s.xmf", io->dir, io->prefix));
  io->next = io->fnext = 0;
  PetscCall(IoDrawRunId(io)); /* a restart replaces it with its run's (IoCheckpointRead) */
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IoGetInterval(Io io, PetscReal *interval, const char **opt)
{
  PetscBool particles;

  PetscFunctionBeginUser;
  if (io->pinterval > 0 && io->finterval > 0) particles = (PetscBool)(io->pinterval <= io->finterval);
  else particles = (PetscBool)(io->pinterval > 0);
  *interval = particles ? io->pinterval : io->finterval;
  /* the option that set it: the split one when it differs from -io_interval */
  if (particles) *opt = io->pinterval != io->interval ? "-io_particle_interval" : "-io_interval";
  else *opt = io->finterval != io->interval ? "-io_fluid_interval" : "-io_interval";
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IoGetIndexPath(Io io, const char **path)
{
  PetscFunctionBeginUser;
  *path = io->nframes ? io->index : NULL;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* mkdir -p: the directory and any missing parents (0, or the errno of the first that failed). */
static int io_mkdir_p(const char *dir)
{
  char path[PETSC_MAX_PATH_LEN];
  if (strlen(dir) >= sizeof path) return ENAMETOOLONG;
  strcpy(path, dir);
  for (char *c = path + 1; *c; c++) {
    if (*c != '/') continue;
    *c = 0;
    if (mkdir(path, 0755) != 0 && errno != EEXIST) return errno;
    *c = '/';
  }
  return mkdir(path, 0755) != 0 && errno != EEXIST ? errno : 0;
}

PetscErrorCode IoGetFilePath(Io io, const char *suffix, char *path, size_t len)
{
  PetscMPIInt rank;
  int         err = 0;

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(path, len, "%s/%s_%s", io->dir, io->prefix, suffix));
  PetscCallMPI(MPI_Comm_rank(io->comm, &rank));
  if (!rank) err = io_mkdir_p(io->dir);
  PetscCallMPI(MPI_Bcast(&err, 1, MPI_INT, 0, io->comm));
  PetscCheck(!err, io->comm, PETSC_ERR_FILE_OPEN, "-io_dir %s: cannot create the directory (%s)", io->dir, strerror(err));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IoDue(Io io, PetscReal t, PetscBool *due)
{
  const PetscReal iv[2]   = {io->pinterval, io->finterval};
  PetscReal      *next[2] = {&io->next, &io->fnext};

  PetscFunctionBeginUser;
  /* t is a sum of steps and drifts from the multiples of the interval: the same tolerance decides
     whether a frame is due and which multiple comes next, so a frame taken just below k*interval
     is not followed by another just above it */
  for (int k = 0; k < 2; k++) {
    io->kind[k] = (iv[k] > 0 && t >= *next[k] - 1e-6 * iv[k]) ? PETSC_TRUE : PETSC_FALSE;
    if (io->kind[k]) *next[k] = (PetscFloorReal(t / iv[k] + 1e-6) + 1) * iv[k];
    io->kind[k] = (PetscBool)(io->kind[k] && IoKindChosen(io, k)); /* no file for a kind without datasets */
  }
  *due      = (PetscBool)(io->kind[0] || io->kind[1]);
  io->armed = *due;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Whether frame fr holds data of kind k (0 particles or a surface, 1 fluid fields). */
static PetscBool io_frame_has(const IoFrame *fr, int k)
{
  return (PetscBool)(k ? fr->nfluid > 0 : fr->npart > 0 || fr->nsurft > 0);
}

PetscErrorCode IoDueFinal(Io io, PetscReal t, PetscBool *due)
{
  const PetscReal iv[2] = {io->pinterval, io->finterval};

  PetscFunctionBeginUser;
  for (int k = 0; k < 2; k++) { /* a kind this run writes whose last frame is older than t */
    PetscInt i = io->nframes - 1;
    while (i >= 0 && !io_frame_has(&io->frames[i], k)) i--;
    io->kind[k] = (PetscBool)(iv[k] > 0 && IoKindChosen(io, k) && (i < 0 || io->frames[i].t < t)); /* i < 0: none yet, e.g. averages begun after the last frame */
  }
  *due      = (PetscBool)(io->kind[0] || io->kind[1]);
  io->armed = *due;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IoDestroy(Io *io)
{
  PetscFunctionBeginUser;
  if (!*io) PetscFunctionReturn(PETSC_SUCCESS);
  if ((*io)->reserve >= 0) close((*io)->reserve);
  PetscCall(PetscFree((*io)->frames));
  PetscCall(PetscFree(*io));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Rank 0: takes the reserve of IO_RESERVE bytes, a file unlinked at once and held open (the
 * system frees it however the process ends). Returns an errno; a file system that cannot
 * allocate ahead (not ENOSPC) is written without a reserve. */
static int io_reserve(Io io)
{
  char path[PETSC_MAX_PATH_LEN + 96];
  int  fd, err;

  snprintf(path, sizeof path, "%s/.%s.reserveXXXXXX", io->dir, io->prefix);
  fd = mkstemp(path);
  if (fd < 0) return errno;
  unlink(path);
  err = posix_fallocate(fd, 0, IO_RESERVE);
  if (err) {
    close(fd);
    return err == ENOSPC ? err : 0;
  }
  io->reserve = fd;
  return 0;
}

static PetscErrorCode IoMakeDir(Io io)
{
  PetscMPIInt rank;
  int         err[2] = {0, 0}; /* errno of mkdir, of the reserve */

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(io->comm, &rank));
  if (!rank) err[0] = io_mkdir_p(io->dir);
  if (!rank && !err[0] && io->reserve < 0) err[1] = io_reserve(io);
  PetscCallMPI(MPI_Bcast(err, 2, MPI_INT, 0, io->comm));
  PetscCheck(!err[0], io->comm, PETSC_ERR_FILE_OPEN, "-io_dir %s: cannot create the directory (%s)", io->dir, strerror(err[0]));
  PetscCheck(!err[1], io->comm, PETSC_ERR_FILE_WRITE, "-io_dir %s: cannot write there: %s%s", io->dir, strerror(err[1]), err[1] == ENOSPC ? " (Sable needs 64 kB free there before its first frame, a reserve to end cleanly should the disk fill)" : "");
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The first failure of a step of a frame (its opening, one dataset, its closing): what was being
 * done, what HDF5 says, and how many bytes the step was writing (0: metadata only). */
typedef struct {
  char      what[PETSC_MAX_PATH_LEN];
  char      h5[256];
  long long need;
} IoStep;

static void io_step_failed(IoStep *st, const char *fmt, ...)
{
  va_list ap;

  io_h5_last_error(st->h5, sizeof st->h5);
  va_start(ap, fmt);
  vsnprintf(st->what, sizeof st->what, fmt, ap);
  va_end(ap);
}

/* An HDF5 call of a step: skipped once a call of the step has failed. IoClose always runs (a
 * handle is closed whatever happened before) and records only a first failure. */
#define IoTry(st, call, ...) \
  do { \
    if (!(st)->what[0] && (call) < 0) io_step_failed(st, __VA_ARGS__); \
  } while (0)
#define IoClose(st, call, ...) \
  do { \
    if ((call) < 0 && !(st)->what[0]) io_step_failed(st, __VA_ARGS__); \
  } while (0)

/* Rank 0: the system's reason for a failed step, as far as it is known. errno after a failed
 * HDF5 call says nothing (HDF5 and MPI-IO overwrite it; measured: 0 after a write that hit a
 * full disk), so the free space of -io_dir decides: less than the step needed, plus a margin,
 * is a full disk; otherwise HDF5's own words are all that is known. */
static void io_reason(Io io, const IoStep *st, char *buf, size_t len)
{
  struct statvfs sv;
  long long      avail;

  if (statvfs(io->dir, &sv) != 0) {
    snprintf(buf, len, "the cause is not known (HDF5 says %s), and the free space of %s cannot be checked: %s", st->h5, io->dir, strerror(errno));
    return;
  }
  avail = (long long)sv.f_bavail * (long long)sv.f_frsize;
  if (avail < st->need + IO_FULL_MARGIN) snprintf(buf, len, "%s, with %lld bytes free in %s", strerror(ENOSPC), avail, io->dir);
  else snprintf(buf, len, "the cause is not known (HDF5 says %s), with %lld bytes free in %s", st->h5, avail, io->dir);
}

/* Collective. Ends a frame whose step failed: closes every HDF5 object of the file and the file,
 * and removes the temporary. Rank 0 first gives back the reserve and empties the temporary, so
 * that the closing flush of HDF5's metadata finds room on a full disk. */
static PetscErrorCode IoFrameAbort(Io io)
{
  const unsigned kinds = H5F_OBJ_LOCAL | H5F_OBJ_DATASET | H5F_OBJ_GROUP | H5F_OBJ_DATATYPE | H5F_OBJ_ATTR;
  PetscMPIInt    rank;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(io->comm, &rank));
  if (!rank && io->reserve >= 0) {
    close(io->reserve);
    io->reserve = -1;
  }
  if (!rank && truncate(io->tmpname, 0) != 0) { /* nothing to empty: the file was not created */
  }
  PetscCallMPI(MPI_Barrier(io->comm));
  if (io->file >= 0) {
    ssize_t n = H5Fget_obj_count(io->file, kinds);
    if (n > 0) {
      hid_t *ids;
      PetscCall(PetscMalloc1(n, &ids));
      n = H5Fget_obj_ids(io->file, kinds, (size_t)n, ids);
      for (ssize_t i = 0; i < n; i++) {
        if (H5Iget_type(ids[i]) == H5I_ATTR) H5Aclose(ids[i]);
        else H5Oclose(ids[i]);
      }
      PetscCall(PetscFree(ids));
    }
    H5Fclose(io->file); /* with the reserve given back it succeeds; were it to fail, HDF5 could crash at exit */
  }
  io->file = io->gpart = io->gfluid = -1;
  if (!rank) unlink(io->tmpname);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. The lowest rank whose step failed (the size of the communicator if none did). */
static PetscErrorCode IoFirstFailed(Io io, const IoStep *st, PetscMPIInt *first)
{
  PetscMPIInt rank, size, mine;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(io->comm, &rank));
  PetscCallMPI(MPI_Comm_size(io->comm, &size));
  mine = st->what[0] ? rank : size;
  PetscCallMPI(MPI_Allreduce(&mine, first, 1, MPI_INT, MPI_MIN, io->comm));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. When a step failed on any rank, ends the frame on every rank (IoFrameAbort) and
 * returns one error: the file, the reason (rank 0's diagnosis) and the step (the first failing
 * rank's). */
static PetscErrorCode IoFrameAgree(Io io, IoStep *st)
{
  PetscMPIInt first, rank, size;
  char        reason[PETSC_MAX_PATH_LEN + 512] = "", kept[PETSC_MAX_PATH_LEN + 64] = "";

  PetscFunctionBeginUser;
  PetscCall(IoFirstFailed(io, st, &first));
  PetscCallMPI(MPI_Comm_size(io->comm, &size));
  if (first == size) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCallMPI(MPI_Comm_rank(io->comm, &rank));
  PetscCallMPI(MPI_Bcast(st, sizeof *st, MPI_BYTE, first, io->comm));
  if (!rank) io_reason(io, st, reason, sizeof reason);
  PetscCallMPI(MPI_Bcast(reason, sizeof reason, MPI_CHAR, 0, io->comm));
  PetscCall(IoFrameAbort(io));
  if (io->nframes) PetscCall(PetscSNPrintf(kept, sizeof kept, "; the earlier frame%s (%" PetscInt_FMT ") and %s are complete", io->nframes > 1 ? "s" : "", io->nframes, io->index));
  SETERRQ(io->comm, PETSC_ERR_FILE_WRITE, "cannot write %s/%s: %s (while %s; the partial file was removed%s)", io->dir, io->frames[io->nframes].file, reason, st->what, kept);
}

/* Collective. Creates the frame's temporary file; when that fails, rank 0 says why by creating
 * the file itself (the errno of that open is meaningful, unlike the one after H5Fcreate). */
static PetscErrorCode IoFrameCreate(Io io)
{
  hid_t       fapl;
  IoStep      st;
  PetscMPIInt first, rank, size;
  char        reason[PETSC_MAX_PATH_LEN + 512] = "";

  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(&st, sizeof st));
  fapl = H5Pcreate(H5P_FILE_ACCESS);
  PetscCheck(fapl >= 0 && H5Pset_fapl_mpio(fapl, io->comm, MPI_INFO_NULL) >= 0, io->comm, PETSC_ERR_LIB, "HDF5 cannot set up parallel (MPI-IO) access for %s", io->tmpname);
  /* compressed frames in the HDF5 1.10 format: its chunk indices (a single chunk, a fixed array)
     take a few bytes where the 1.8 format's B-tree takes about 2 kB per dataset, more than a small
     dataset saves; any reader from HDF5 1.10 on (ParaView's since 5.6) reads it */
  PetscCheck(io->compress == 0 || H5Pset_libver_bounds(fapl, H5F_LIBVER_V110, H5F_LIBVER_V110) >= 0, io->comm, PETSC_ERR_LIB, "HDF5 cannot select the 1.10 file format for %s", io->tmpname);
  IoTry(&st, io->file = H5Fcreate(io->tmpname, H5F_ACC_TRUNC, H5P_DEFAULT, fapl), "creating the file");
  H5Pclose(fapl);
  PetscCall(IoFirstFailed(io, &st, &first));
  PetscCallMPI(MPI_Comm_size(io->comm, &size));
  if (first == size) PetscFunctionReturn(PETSC_SUCCESS);
  /* a rank that did create the file cannot close it alone (closing is collective): when ranks
     disagree (not seen: creation fails on all or none), the file stays open until the process
     ends with this error */
  PetscCallMPI(MPI_Bcast(&st, sizeof st, MPI_BYTE, first, io->comm));
  PetscCallMPI(MPI_Comm_rank(io->comm, &rank));
  if (!rank) {
    int fd = open(io->tmpname, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd < 0) PetscCall(PetscStrncpy(reason, strerror(errno), sizeof reason));
    else {
      close(fd);
      unlink(io->tmpname);
      io_reason(io, &st, reason, sizeof reason);
    }
  }
  PetscCallMPI(MPI_Bcast(reason, sizeof reason, MPI_CHAR, 0, io->comm));
  SETERRQ(io->comm, PETSC_ERR_FILE_OPEN, "-io_dir %s: cannot create %s: %s", io->dir, io->tmpname, reason);
}

PetscErrorCode IoFrameBegin(Io io, PetscReal t, PetscInt step)
{
  hid_t    attr = -1, space = -1;
  IoFrame *fr;
  IoStep   st;

  PetscFunctionBeginUser;
  io_quiet();
  (void)step;
  PetscCall(PetscTime(&io->t_frame));
  if (!io->armed) io->kind[0] = io->kind[1] = PETSC_TRUE; /* a frame not asked through IoDue: everything */
  if (!io->dirmade) PetscCall(IoMakeDir(io));
  io->dirmade = PETSC_TRUE;
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
  fr->t    = t;
  fr->prec = io->single ? 4 : 8;
  PetscCall(PetscSNPrintf(fr->file, sizeof fr->file, "%s_%06" PetscInt_FMT ".h5", io->prefix, io->nframes));
  PetscCall(PetscSNPrintf(io->tmpname, sizeof io->tmpname, "%s/%s.tmp", io->dir, fr->file));
  io->gpart = io->gfluid = -1;
  SableTempSet(io->tmpname); /* removed should the run end before the rename */
  PetscCall(IoFrameCreate(io));
  PetscCall(PetscMemzero(&st, sizeof st));
  IoTry(&st, io->gpart = H5Gcreate2(io->file, "particles", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), "creating the group /particles");
  IoTry(&st, io->gfluid = H5Gcreate2(io->file, "fluid", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), "creating the group /fluid");
  IoTry(&st, space = H5Screate(H5S_SCALAR), "writing the attribute time");
  IoTry(&st, attr = H5Acreate2(io->file, "time", H5T_NATIVE_DOUBLE, space, H5P_DEFAULT, H5P_DEFAULT), "writing the attribute time");
  IoTry(&st, H5Awrite(attr, H5T_NATIVE_DOUBLE, &t), "writing the attribute time");
  if (attr >= 0) IoClose(&st, H5Aclose(attr), "closing the attribute time");
  if (space >= 0) IoClose(&st, H5Sclose(space), "closing the attribute time");
  IoTry(&st, io_write_run_id(io->file, io->run_id), "writing the attribute run_id");
  PetscCall(IoFrameAgree(io, &st));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The shape of a block: global dims of a rank-1..4 dataset, this rank's start and count. */
typedef struct {
  int     rank;
  hsize_t dims[4], start[4], count[4];
} IoShape;

/* The bytes of a chunk of a compressed dataset (see io_chunked). Measured on 18,000 beads
   (doc/output.md): 64 kB chunks compress 1% worse than 1 MB ones, 256 kB 0.5%; on 2 ranks
   1 MB chunks wrote slowest (a 432 kB position array is one chunk, which one rank compresses). */
#define IO_CHUNK_BYTES (1 << 18)

/* The creation properties of a compressed dataset of shape sh and elements of size bytes:
 * chunks of whole rows (particles) or whole z-planes (fluid) of at most about IO_CHUNK_BYTES, cut
 * along the slowest axis (then the next) when one row or plane is larger, byte shuffle, then
 * deflate at level. Chunks are allocated as they are written and never filled (every element is
 * written). < 0 on failure. */
static hid_t io_chunked(const IoShape *sh, size_t size, unsigned level)
{
  hsize_t chunk[4], inner = size;
  hid_t   dcpl = H5Pcreate(H5P_DATASET_CREATE);

  if (dcpl < 0) return -1;
  for (int k = sh->rank - 1; k >= 0; k--) { /* the fastest axes whole while they fit */
    hsize_t fit = PetscMax((hsize_t)1, (hsize_t)IO_CHUNK_BYTES / inner);
    chunk[k]    = PetscMin(sh->dims[k], fit);
    inner *= chunk[k];
  }
  if (H5Pset_chunk(dcpl, sh->rank, chunk) < 0 || H5Pset_fill_time(dcpl, H5D_FILL_TIME_NEVER) < 0 || H5Pset_shuffle(dcpl) < 0 || H5Pset_deflate(dcpl, level) < 0) {
    H5Pclose(dcpl);
    return -1;
  }
  return dcpl;
}

/* Collective write of this rank's block of a new dataset group/name. The ranks agree before the
 * write (a rank whose dataset was not created must not leave the others in a collective write)
 * and after it. */
static PetscErrorCode IoWriteBlock(Io io, hid_t group, const char *name, hid_t type, const IoShape *sh, const void *data)
{
  hid_t       fspace = -1, mspace = -1, dset = -1, dxpl = -1, dcpl = -1;
  hsize_t     n = 1, total = 1;
  IoStep      st;
  PetscMPIInt first, size;
  char        path[PETSC_MAX_PATH_LEN] = "";

  PetscFunctionBeginUser;
  SableProgress(); /* a frame being written is progress: a signal waits for it */
  PetscCall(PetscMemzero(&st, sizeof st));
  for (int k = 0; k < sh->rank; k++) n *= sh->count[k], total *= sh->dims[k];
  if (H5Iget_name(group, path, sizeof path) < 0) path[0] = 0;
  PetscCall(PetscStrlcat(path, "/", sizeof path));
  PetscCall(PetscStrlcat(path, name, sizeof path));
  st.need = (long long)(total * H5Tget_size(type));
  IoTry(&st, fspace = H5Screate_simple(sh->rank, sh->dims, NULL), "creating %s", path);
  if (io->compress > 0 && total) IoTry(&st, dcpl = io_chunked(sh, H5Tget_size(type), (unsigned)io->compress), "setting up the compression of %s", path);
  IoTry(&st, dset = H5Dcreate2(group, name, type, fspace, H5P_DEFAULT, dcpl >= 0 ? dcpl : H5P_DEFAULT, H5P_DEFAULT), "creating %s", path);
  IoTry(&st, mspace = H5Screate_simple(1, &n, NULL), "creating %s", path);
  if (n) IoTry(&st, H5Sselect_hyperslab(fspace, H5S_SELECT_SET, sh->start, NULL, sh->count, NULL), "selecting this rank's rows of %s", path);
  else {
    IoTry(&st, H5Sselect_none(fspace), "selecting this rank's rows of %s", path);
    IoTry(&st, H5Sselect_none(mspace), "selecting this rank's rows of %s", path);
  }
  PetscCall(IoFirstFailed(io, &st, &first));
  PetscCallMPI(MPI_Comm_size(io->comm, &size));
  if (first == size && total) { /* an empty dataset (a scene with no particles) is created but
                                   not written: HDF5's collective write of nothing fails */
    IoTry(&st, dxpl = H5Pcreate(H5P_DATASET_XFER), "writing %s", path);
    IoTry(&st, H5Pset_dxpl_mpio(dxpl, H5FD_MPIO_COLLECTIVE), "writing %s", path);
    IoTry(&st, H5Dwrite(dset, type, mspace, fspace, dxpl, data), "writing %s", path);
  }
  if (dxpl >= 0) IoClose(&st, H5Pclose(dxpl), "writing %s", path);
  if (dcpl >= 0) IoClose(&st, H5Pclose(dcpl), "closing %s", path);
  if (mspace >= 0) IoClose(&st, H5Sclose(mspace), "closing %s", path);
  if (fspace >= 0) IoClose(&st, H5Sclose(fspace), "closing %s", path);
  if (dset >= 0) IoClose(&st, H5Dclose(dset), "closing %s", path);
  PetscCall(IoFrameAgree(io, &st));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* With -io_precision single: the n reals of data as floats in *buf (PetscFree it), the type to
 * write; otherwise data itself. */
static PetscErrorCode IoNarrow(Io io, hid_t *type, const void **data, long long n, float **buf)
{
  PetscFunctionBeginUser;
  *buf = NULL;
  if (!io->single || *type != H5T_NATIVE_DOUBLE) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscMalloc1(n + 1, buf));
  for (long long i = 0; i < n; i++) (*buf)[i] = (float)((const double *)*data)[i];
  *type = H5T_NATIVE_FLOAT;
  *data = *buf;
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode IoWriteRows(Io io, const char *name, PetscInt nlocal, PetscInt ncomp, hid_t type, const void *data, PetscBool isint)
{
  float    *buf;
  long long n = nlocal, off = 0, total = 0;
  IoShape   sh = {ncomp > 1 ? 2 : 1, {0, (hsize_t)ncomp}, {0, 0}, {(hsize_t)n, (hsize_t)ncomp}};
  IoFrame  *fr = &io->frames[io->nframes];
  PetscBool want;

  PetscFunctionBeginUser;
  PetscCall(IoFrameWants(io, "particles", name, &want)); /* position: whenever the particles are due */
  if (!want) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCheck(fr->npart < IO_MAX_SETS, io->comm, PETSC_ERR_SUP, "too many particle datasets in one frame");
  PetscCallMPI(MPI_Exscan(&n, &off, 1, MPI_LONG_LONG, MPI_SUM, io->comm));
  PetscCallMPI(MPI_Allreduce(&n, &total, 1, MPI_LONG_LONG, MPI_SUM, io->comm));
  sh.dims[0]  = (hsize_t)total;
  sh.start[0] = (hsize_t)off;
  PetscCall(IoNarrow(io, &type, &data, n * ncomp, &buf));
  PetscCall(IoWriteBlock(io, io->gpart, name, type, &sh, data));
  PetscCall(PetscFree(buf));
  if (!strcmp(name, "position")) { /* the Polyvertex connectivity 0..N-1: the Xdmf3 readers make no cells without it */
    IoShape    sv = {1, {(hsize_t)total}, {(hsize_t)off}, {(hsize_t)n}};
    long long *vtx;
    PetscCall(PetscMalloc1(n + 1, &vtx));
    for (long long i = 0; i < n; i++) vtx[i] = off + i;
    PetscCall(IoWriteBlock(io, io->gpart, "vertex", H5T_NATIVE_LLONG, &sv, vtx));
    PetscCall(PetscFree(vtx));
  }
  PetscCall(PetscStrncpy(fr->part[fr->npart].name, name, sizeof fr->part[0].name));
  fr->part[fr->npart].ncomp = ncomp;
  fr->part[fr->npart].isint = isint;
  fr->npart++;
  fr->np = total;
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
  IoShape   sh;
  IoFrame  *fr = &io->frames[io->nframes];
  IoStep    st;
  hid_t     g = -1;
  PetscBool want;

  PetscFunctionBeginUser;
  PetscCall(IoFrameWants(io, "surface", "surface", &want));
  if (!want) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCheck(!fr->nsurft, io->comm, PETSC_ERR_ORDER, "IoWriteSurface: at most one surface per frame");
  PetscCallMPI(MPI_Exscan(n, off, 2, MPI_LONG_LONG, MPI_SUM, io->comm));
  PetscCallMPI(MPI_Allreduce(n, tot, 2, MPI_LONG_LONG, MPI_SUM, io->comm));
  PetscCall(PetscMalloc2(3 * nt + 1, &gtri, np + 1, &gtag));
  for (PetscInt k = 0; k < 3 * nt; k++) gtri[k] = off[0] + tri[k];
  for (PetscInt k = 0; k < np; k++) gtag[k] = tag[k];
  PetscCall(PetscMemzero(&st, sizeof st));
  IoTry(&st, g = H5Gcreate2(io->file, "surface", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), "creating the group /surface");
  PetscCall(IoFrameAgree(io, &st));
  sh = (IoShape){2, {(hsize_t)tot[0], 3}, {(hsize_t)off[0], 0}, {(hsize_t)np, 3}};
  PetscCall(IoWriteBlock(io, g, "points", H5T_NATIVE_DOUBLE, &sh, xyz));
  sh.rank = 1;
  PetscCall(IoWriteBlock(io, g, "tag", H5T_NATIVE_LLONG, &sh, gtag));
  sh = (IoShape){2, {(hsize_t)tot[1], 3}, {(hsize_t)off[1], 0}, {(hsize_t)nt, 3}};
  PetscCall(IoWriteBlock(io, g, "triangles", H5T_NATIVE_LLONG, &sh, gtri));
  IoClose(&st, H5Gclose(g), "closing the group /surface");
  PetscCall(IoFrameAgree(io, &st));
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
  IoShape   sh = {ncomp > 1 ? 4 : 3, {0}, {0}, {0}};
  IoFrame  *fr = &io->frames[io->nframes];
  PetscBool want;

  PetscFunctionBeginUser;
  PetscCall(IoFrameWants(io, "fluid", name, &want));
  if (!want) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCheck(io->fluidmesh, io->comm, PETSC_ERR_ORDER, "IoSetFluidMesh must precede IoWriteField");
  PetscCheck(fr->nfluid < IO_MAX_SETS, io->comm, PETSC_ERR_SUP, "too many fluid datasets in one frame");
  for (int k = 0; k < 3; k++) { /* HDF5 order is z, y, x */
    sh.dims[k]  = (hsize_t)io->fcells[2 - k];
    sh.start[k] = (hsize_t)start[2 - k];
    sh.count[k] = (hsize_t)count[2 - k];
  }
  sh.dims[3] = sh.count[3] = (hsize_t)ncomp;
  {
    hid_t       type = H5T_NATIVE_DOUBLE;
    const void *d    = data;
    float      *buf;
    PetscCall(IoNarrow(io, &type, &d, (long long)count[0] * count[1] * count[2] * ncomp, &buf));
    PetscCall(IoWriteBlock(io, io->gfluid, name, type, &sh, d));
    PetscCall(PetscFree(buf));
  }
  PetscCall(PetscStrncpy(fr->fluid[fr->nfluid].name, name, sizeof fr->fluid[0].name));
  fr->fluid[fr->nfluid].ncomp = ncomp;
  fr->nfluid++;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. Closes the frame (the ranks agree that every step succeeded), renames it into
 * place and rewrites the index on rank 0; a failure of either ends the run on every rank. */
PetscErrorCode IoFrameEnd(Io io)
{
  PetscMPIInt rank;
  char        final[PETSC_MAX_PATH_LEN];
  int         err[2] = {0, 0}; /* errno of the rename of the frame, of the index */
  IoStep      st;

  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(&st, sizeof st));
  IoClose(&st, H5Gclose(io->gpart), "closing the group /particles");
  IoClose(&st, H5Gclose(io->gfluid), "closing the group /fluid");
  io->gpart = io->gfluid = -1; /* if a close failed, IoFrameAbort finds the group among the file's objects */
  IoTry(&st, H5Fflush(io->file, H5F_SCOPE_GLOBAL), "flushing the file");
  PetscCall(IoFrameAgree(io, &st));
  IoTry(&st, H5Fclose(io->file), "closing the file");
  io->file = -1; /* a failed close is not retried */
  PetscCall(IoFrameAgree(io, &st));
  PetscCallMPI(MPI_Comm_rank(io->comm, &rank));
  PetscCall(PetscSNPrintf(final, sizeof final, "%s/%s", io->dir, io->frames[io->nframes].file));
  io->armed = PETSC_FALSE;
  if (!io_frame_has(&io->frames[io->nframes], 0) && !io_frame_has(&io->frames[io->nframes], 1)) { /* nothing of the kinds due was chosen or written (a dry run has no fluid fields without averages): no frame */
    if (!rank) unlink(io->tmpname);
    SableTempSet(NULL);
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  io->nframes++;
  if (!rank) {
    if (rename(io->tmpname, final) != 0) {
      err[0] = errno;
      unlink(io->tmpname);
    } else {
      struct stat sb;
      if (stat(final, &sb) == 0) io->bytes += (long long)sb.st_size;
      PetscCall(IoWriteIndex(io, &err[1]));
    }
  }
  PetscCallMPI(MPI_Bcast(err, 2, MPI_INT, 0, io->comm));
  SableTempSet(NULL); /* renamed, or removed on failure */
  if (err[0]) io->nframes--;
  PetscCheck(!err[0], io->comm, PETSC_ERR_FILE_WRITE, "cannot rename %s to %s: %s (the frame was removed)", io->tmpname, final, strerror(err[0]));
  PetscCheck(!err[1], io->comm, PETSC_ERR_FILE_WRITE, "cannot write %s.tmp: %s (the temporary was removed; %s is complete, but the index %s, if any, lists only the frames before it)", io->index, strerror(err[1]), final, io->index);
  io->written++;
  {
    PetscLogDouble now;
    PetscCall(PetscTime(&now));
    io->wtime += now - io->t_frame;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IoView(Io io, PetscViewer v)
{
  PetscLogDouble now;

  PetscFunctionBeginUser;
  if (!io || (io->pinterval <= 0 && io->finterval <= 0)) {
    PetscCall(PetscViewerASCIIPrintf(v, io && (io->pinterval != io->interval || io->finterval != io->interval) ? "output: none (-io_particle_interval 0 and -io_fluid_interval 0)\n" : "output: none (-io_interval 0)\n"));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  if (!io->nframes) {
    PetscCall(PetscViewerASCIIPrintf(v, "output: none (no frame was due)\n"));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(PetscTime(&now));
  now -= io->t_create;
  PetscCall(PetscViewerASCIIPrintf(v, "output: %s (open it in ParaView), %lld frames, %.3f MB, %.3g s writing (%.1f%% of the run's %.3g s)", io->index, io->written, io->bytes / 1e6, io->wtime, 100 * io->wtime / PetscMax(now, 1e-9), now));
  if (io->nframes > io->written) PetscCall(PetscViewerASCIIPrintf(v, "; the index lists %" PetscInt_FMT " with the earlier run's", io->nframes));
  PetscCall(PetscViewerASCIIPrintf(v, "\n"));
  PetscFunctionReturn(PETSC_SUCCESS);
}
