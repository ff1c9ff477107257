/* The output's continuation across a restart (see io.h): what a checkpoint holds of the output
 * (group io/) and the run identity that keeps one run's frames apart from another's.
 *   io/state     LLONG [2]: frames written, run_id (its 64 bits)
 *   io/next      REAL [1]:  the next output time (s) of the particles
 *   io/next_fluid REAL [1]: the fluid's (absent from older checkpoints: the particles')
 *   io/frame_t   REAL [n]:  each frame's time, exact
 *   io/frames    BYTE:      one text line per frame, fields split by tabs: its file, particle
 *                           count, surface points and triangles, then "p name ncomp isint" per
 *                           particle dataset and "f name ncomp" per fluid dataset, and
 *                           "s reals 4" when its reals are 32 bits (-io_precision single)
 *   io/dir       BYTE:      the absolute -io_dir the frames were written to
 *   io/prefix    BYTE:      the -io_prefix (absent: taken to be this run's)
 * A restart in the same place (the same directory, by its absolute path, and prefix) continues
 * the series: its index lists the old frames again, new frames are numbered on from them, and
 * the run_id is kept. A restart into another place starts a new series there (a branch of a
 * study): a new run_id is drawn, its frames are numbered from 0 as a fresh run's, the first one
 * at the checkpoint's time, its index lists only them, and nothing of the old place is touched.
 * Either way the restart refuses, before running, a directory holding a frame numbered from its
 * next one on that is not of this run (another run_id, or none): frames of this run recomputed
 * after a preemption may be overwritten, another run's never. */
#include "io/io_private.h"
#include <ctype.h>
#include <dirent.h>
#include <errno.h>
#include <limits.h>
#include <stdlib.h>
#include <time.h>
#include <unistd.h>

static unsigned long long io_mix64(unsigned long long z)
{
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

PetscErrorCode IoDrawRunId(Io io)
{
  PetscMPIInt rank;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(io->comm, &rank));
  if (!rank) {
    struct timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    io->run_id = io_mix64(((unsigned long long)ts.tv_sec * 1000000000ULL + (unsigned long long)ts.tv_nsec) ^ io_mix64((unsigned long long)getpid()));
    if (!io->run_id) io->run_id = 1;
  }
  PetscCallMPI(MPI_Bcast(&io->run_id, 1, MPI_UNSIGNED_LONG_LONG, 0, io->comm));
  PetscFunctionReturn(PETSC_SUCCESS);
}

herr_t io_write_run_id(hid_t file, unsigned long long id)
{
  hid_t  sp = H5Screate(H5S_SCALAR), at = -1;
  herr_t e = -1;

  if (sp >= 0) at = H5Acreate2(file, "run_id", H5T_NATIVE_ULLONG, sp, H5P_DEFAULT, H5P_DEFAULT);
  if (at >= 0) e = H5Awrite(at, H5T_NATIVE_ULLONG, &id);
  if (at >= 0 && H5Aclose(at) < 0) e = -1;
  if (sp >= 0 && H5Sclose(sp) < 0) e = -1;
  return sp < 0 ? -1 : e;
}

/* Not collective. The run_id of a frame file; *has false when it has none or is not HDF5. */
static void io_read_run_id(const char *path, unsigned long long *id, PetscBool *has)
{
  hid_t f, at;

  *has = PETSC_FALSE;
  io_quiet();
  if (H5Fis_hdf5(path) <= 0 || (f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT)) < 0) return;
  if (H5Aexists(f, "run_id") > 0 && (at = H5Aopen(f, "run_id", H5P_DEFAULT)) >= 0) {
    *has = H5Aread(at, H5T_NATIVE_ULLONG, id) >= 0 ? PETSC_TRUE : PETSC_FALSE;
    H5Aclose(at);
  }
  H5Fclose(f);
}

/* The frames as text (see the header); *text allocated, PetscFree it. */
static PetscErrorCode IoFramesEncode(Io io, char **text, size_t *len)
{
  size_t cap = 1, n = 0;

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < io->nframes; i++) cap += strlen(io->frames[i].file) + 100 + 100 * (size_t)(io->frames[i].npart + io->frames[i].nfluid);
  PetscCall(PetscMalloc1(cap, text));
  for (PetscInt i = 0; i < io->nframes; i++) {
    const IoFrame *fr = &io->frames[i];
    n += (size_t)snprintf(*text + n, cap - n, "%s\t%lld\t%lld\t%lld", fr->file, fr->np, fr->nsurfp, fr->nsurft);
    for (PetscInt k = 0; k < fr->npart; k++) n += (size_t)snprintf(*text + n, cap - n, "\tp %s %d %d", fr->part[k].name, (int)fr->part[k].ncomp, (int)fr->part[k].isint);
    for (PetscInt k = 0; k < fr->nfluid; k++) n += (size_t)snprintf(*text + n, cap - n, "\tf %s %d", fr->fluid[k].name, (int)fr->fluid[k].ncomp);
    if (fr->prec == 4) n += (size_t)snprintf(*text + n, cap - n, "\ts reals 4"); /* -io_precision single */
    n += (size_t)snprintf(*text + n, cap - n, "\n");
  }
  *len = n;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* One line of io/frames into fr; false when it does not parse. */
static PetscBool io_frame_decode(char *line, IoFrame *fr)
{
  char *save = NULL, *tok = strtok_r(line, "\t", &save);
  char  kind, name[64];
  int   nc, isint;

  if (!tok || strlen(tok) >= sizeof fr->file) return PETSC_FALSE;
  strcpy(fr->file, tok);
  tok = strtok_r(NULL, "\t", &save);
  if (!tok || sscanf(tok, "%lld", &fr->np) != 1) return PETSC_FALSE;
  tok = strtok_r(NULL, "\t", &save);
  if (!tok || sscanf(tok, "%lld", &fr->nsurfp) != 1) return PETSC_FALSE;
  tok = strtok_r(NULL, "\t", &save);
  if (!tok || sscanf(tok, "%lld", &fr->nsurft) != 1) return PETSC_FALSE;
  while ((tok = strtok_r(NULL, "\t", &save))) {
    isint = 0;
    if (sscanf(tok, "%c %63s %d %d", &kind, name, &nc, &isint) < 3) return PETSC_FALSE;
    if (kind == 's') { /* the bytes of the frame's reals */
      fr->prec = nc;
      continue;
    }
    if ((kind != 'p' && kind != 'f') || fr->npart >= IO_MAX_SETS || fr->nfluid >= IO_MAX_SETS) return PETSC_FALSE;
    IoSet *s = kind == 'p' ? &fr->part[fr->npart++] : &fr->fluid[fr->nfluid++];
    strcpy(s->name, name);
    s->ncomp = nc;
    s->isint = isint ? PETSC_TRUE : PETSC_FALSE;
  }
  return PETSC_TRUE;
}

PetscErrorCode IoCheckpointWrite(Io io, IoCkpt ck)
{
  long long  state[2] = {io->nframes, (long long)io->run_id};
  PetscReal *t;
  char      *text, dir[PATH_MAX] = "";
  size_t     len = 0;

  PetscFunctionBeginUser;
  PetscCall(IoCkptWriteShared(ck, "io/state", IO_CKPT_LLONG, 2, state));
  PetscCall(IoCkptWriteShared(ck, "io/next", IO_CKPT_REAL, 1, &io->next));
  PetscCall(IoCkptWriteShared(ck, "io/next_fluid", IO_CKPT_REAL, 1, &io->fnext));
  PetscCall(PetscMalloc1(io->nframes + 1, &t));
  for (PetscInt i = 0; i < io->nframes; i++) t[i] = io->frames[i].t;
  PetscCall(IoCkptWriteShared(ck, "io/frame_t", IO_CKPT_REAL, io->nframes, t));
  PetscCall(PetscFree(t));
  PetscCall(IoFramesEncode(io, &text, &len));
  PetscCall(IoCkptWriteShared(ck, "io/frames", IO_CKPT_BYTE, (PetscInt)len, text));
  PetscCall(PetscFree(text));
  if (!realpath(io->dir, dir)) PetscCall(PetscStrncpy(dir, io->dir, sizeof dir)); /* the checkpoint lives there: it exists */
  PetscCallMPI(MPI_Bcast(dir, sizeof dir, MPI_CHAR, 0, io->comm));                /* rank 0's, as written */
  PetscCall(IoCkptWriteShared(ck, "io/dir", IO_CKPT_BYTE, (PetscInt)strlen(dir), dir));
  PetscCall(IoCkptWriteShared(ck, "io/prefix", IO_CKPT_BYTE, (PetscInt)strlen(io->prefix), io->prefix));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. A shared byte dataset as a string (allocated, PetscFree it). */
static PetscErrorCode IoCkptReadText(IoCkpt ck, const char *name, char **text)
{
  long long n;

  PetscFunctionBeginUser;
  PetscCall(IoCkptGetSize(ck, name, &n));
  PetscCall(PetscCalloc1(n + 1, text));
  PetscCall(IoCkptReadShared(ck, name, IO_CKPT_BYTE, (PetscInt)n, *text));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. The frames of io/frame_t and io/frames into io (the frames of the series this
 * restart continues, in the same directory). */
static PetscErrorCode IoFramesRead(Io io, IoCkpt ck, PetscInt n)
{
  PetscReal  *t;
  char       *text, *line, *save = NULL;
  const char *path;

  PetscFunctionBeginUser;
  PetscCall(IoCkptGetPath(ck, &path));
  PetscCall(PetscMalloc1(n + 1, &t));
  PetscCall(IoCkptReadShared(ck, "io/frame_t", IO_CKPT_REAL, n, t));
  PetscCall(IoCkptReadText(ck, "io/frames", &text));
  io->capframes = n + 16;
  PetscCall(PetscFree(io->frames));
  PetscCall(PetscCalloc1(io->capframes, &io->frames));
  line = strtok_r(text, "\n", &save);
  for (PetscInt i = 0; i < n; i++, line = strtok_r(NULL, "\n", &save)) {
    IoFrame *fr = &io->frames[i];
    PetscCheck(line && io_frame_decode(line, fr), io->comm, PETSC_ERR_FILE_UNEXPECTED, "-restart %s: the dataset io/frames does not describe frame %" PetscInt_FMT " of %" PetscInt_FMT, path, i, n);
    fr->t = t[i];
  }
  io->nframes = n;
  PetscCall(PetscFree(t));
  PetscCall(PetscFree(text));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. Whether this run writes where the checkpoint's run did: the same directory (by
 * its absolute path, rank 0's view of the file system) and the same prefix. */
static PetscErrorCode IoSamePlace(Io io, IoCkpt ck, PetscBool *same)
{
  char     *olddir, *oldprefix = NULL, here[PATH_MAX];
  PetscBool has;

  PetscFunctionBeginUser;
  PetscCall(IoCkptReadText(ck, "io/dir", &olddir));
  PetscCall(IoCkptHas(ck, "io/prefix", &has));
  if (has) PetscCall(IoCkptReadText(ck, "io/prefix", &oldprefix));
  *same = (PetscBool)(realpath(io->dir, here) && !strcmp(here, olddir) && (!oldprefix || !strcmp(oldprefix, io->prefix)));
  PetscCallMPI(MPI_Bcast(same, 1, MPIU_BOOL, 0, io->comm));
  PetscCall(PetscStrncpy(io->from, olddir, sizeof io->from));
  PetscCall(PetscFree(olddir));
  PetscCall(PetscFree(oldprefix));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Rank 0. The lowest-numbered frame file <dir>/<prefix>_<k>.h5 with k >= from whose run_id is
 * not id (found[0] = 0: none); its number and run_id (has: whether it carries one). */
static void io_find_foreign(Io io, PetscInt from, unsigned long long id, char found[PETSC_MAX_PATH_LEN], long long *num, unsigned long long *other, PetscBool *has)
{
  DIR           *d = opendir(io->dir);
  struct dirent *e;
  size_t         lp = strlen(io->prefix);

  found[0] = 0;
  if (!d) return;
  while ((e = readdir(d))) {
    const char *s = e->d_name;
    char       *end;
    long long   k;
    if (strncmp(s, io->prefix, lp) || s[lp] != '_' || !isdigit((unsigned char)s[lp + 1])) continue;
    k = strtoll(s + lp + 1, &end, 10);
    if (strcmp(end, ".h5") || k < from || (found[0] && k >= *num)) continue;
    char               path[2 * PETSC_MAX_PATH_LEN];
    unsigned long long fid = 0;
    PetscBool          fhas;
    snprintf(path, sizeof path, "%s/%s", io->dir, s);
    io_read_run_id(path, &fid, &fhas);
    if (fhas && fid == id) continue;
    size_t l = PetscMin(strlen(path), (size_t)PETSC_MAX_PATH_LEN - 1); /* -io_dir is shorter */
    memcpy(found, path, l);
    found[l] = 0;
    *num     = k;
    *other   = fid;
    *has     = fhas;
  }
  closedir(d);
}

/* Collective. Refuses to run when -io_dir holds a frame numbered from the next one on of another
 * run: one line naming the file and -io_dir. */
static PetscErrorCode IoRefuseForeignFrames(Io io)
{
  struct {
    char               path[PETSC_MAX_PATH_LEN];
    long long          num;
    unsigned long long other;
    PetscBool          has;
  } f;
  PetscMPIInt rank;
  char        whose[96];

  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(&f, sizeof f));
  PetscCallMPI(MPI_Comm_rank(io->comm, &rank));
  if (!rank) io_find_foreign(io, io->nframes, io->run_id, f.path, &f.num, &f.other, &f.has);
  PetscCallMPI(MPI_Bcast(&f, sizeof f, MPI_BYTE, 0, io->comm));
  if (!f.path[0]) PetscFunctionReturn(PETSC_SUCCESS);
  if (f.has) PetscCall(PetscSNPrintf(whose, sizeof whose, "run_id %llu", f.other));
  else PetscCall(PetscStrcpy(whose, "no run_id"));
  SETERRQ(io->comm, PETSC_ERR_FILE_UNEXPECTED, "-io_dir %s: %s is a frame of another run (%s; this run's is %llu) that this restart would overwrite from frame %" PetscInt_FMT " on: choose another -io_dir (or move that run's frames away)", io->dir, f.path, whose, io->run_id, io->nframes);
}

PetscErrorCode IoCheckpointRead(Io io, IoCkpt ck)
{
  long long state[2];
  PetscBool same, has;
  PetscReal next, fnext;

  PetscFunctionBeginUser;
  PetscCall(IoCkptReadShared(ck, "io/state", IO_CKPT_LLONG, 2, state));
  PetscCall(IoCkptReadShared(ck, "io/next", IO_CKPT_REAL, 1, &next));
  PetscCall(IoCkptHas(ck, "io/next_fluid", &has));
  if (has) PetscCall(IoCkptReadShared(ck, "io/next_fluid", IO_CKPT_REAL, 1, &fnext));
  else fnext = next; /* a checkpoint of one cadence */
  PetscCheck(state[0] >= 0, io->comm, PETSC_ERR_FILE_UNEXPECTED, "-restart: the dataset io/state holds a frame count %lld, expected >= 0", state[0]);
  PetscCall(IoSamePlace(io, ck, &same));
  if (same) { /* the series goes on: the old frames listed again, the run_id kept */
    io->next   = next;
    io->fnext  = fnext;
    io->run_id = (unsigned long long)state[1];
    PetscCall(IoFramesRead(io, ck, (PetscInt)state[0]));
  } else { /* a new series: this run's own run_id (drawn), a frame at once, numbered from 0 */
    io->next  = -PETSC_MAX_REAL;
    io->fnext = -PETSC_MAX_REAL;
    io->fresh = PETSC_TRUE;
  }
  PetscCall(IoRefuseForeignFrames(io));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IoViewRestart(Io io, const char *mpath, PetscBool mon_resumed, PetscReal t)
{
  char frames[PETSC_MAX_PATH_LEN + 128], monitor[PETSC_MAX_PATH_LEN + 64] = "";

  PetscFunctionBeginUser;
  if (io->pinterval > 0 || io->finterval > 0) PetscCall(PetscSNPrintf(frames, sizeof frames, "frames from %s_%06" PetscInt_FMT ".h5 on (index %s)", io->prefix, io->nframes, io->index));
  else PetscCall(PetscStrcpy(frames, "no frames (no output interval)"));
  if (mpath) PetscCall(PetscSNPrintf(monitor, sizeof monitor, "; monitor %s%s", mpath, mon_resumed ? " continued (cut back to the checkpoint's rows)" : (io->fresh ? "" : " (a new series)")));
  if (io->fresh) PetscCall(PetscPrintf(io->comm, "restart: new output series in %s from t = %g: %s%s; the checkpoint's run's frames in %s are left as they are\n", io->dir, (double)t, frames, monitor, io->from));
  else PetscCall(PetscPrintf(io->comm, "restart: output continued in %s from t = %g: %s%s\n", io->dir, (double)t, frames, monitor));
  PetscFunctionReturn(PETSC_SUCCESS);
}
