/* Output: one HDF5 file per output time (particles under /particles, fluid fields under /fluid)
 * and one XDMF file indexing them as a time series that ParaView opens. Each HDF5 file is
 * written under a temporary name and renamed when complete, and the XDMF index is rewritten the
 * same way, so a killed run never leaves a half-written file behind a name ParaView reads.
 * Writes are collective (MPI-IO); each rank passes its own block. Options: -io_dir, -io_prefix,
 * -io_interval, -io_particle_interval and -io_fluid_interval (the two cadences: a frame holds
 * the kinds due at its time), -io_fields (the datasets written; the writers may call the others,
 * which are skipped), -io_compress (chunked datasets, shuffle + deflate). */
#pragma once
#include "sable.h"

typedef struct _p_Io *Io;

PetscErrorCode IoCreate(MPI_Comm comm, Io *io);
/* Reads -io_dir (default out), -io_prefix (default sable), -io_interval (s, 0 = no output),
 * -io_particle_interval, -io_fluid_interval (s, default -io_interval), -io_fields, -io_compress. */
PetscErrorCode IoSetFromOptions(Io io);
PetscErrorCode IoDestroy(Io *io);
/* Not collective (the same on every rank). Whether a frame is due at simulated time t: the
 * particles' or the fluid's cadence (first call: both, when on); the next IoFrameBegin takes
 * the kinds due. */
PetscErrorCode IoDue(Io io, PetscReal t, PetscBool *due);
/* Not collective (the same on every rank). At the end of a run: whether the state at t still
 * needs a frame (output is on and the last frame is older than t), so that a run always leaves
 * its final state, also when the end time is not a multiple of -io_interval. */
PetscErrorCode IoDueFinal(Io io, PetscReal t, PetscBool *due);
/* Not collective. The shorter of the two cadences (s; 0 = no output) and the option that set it
 * (-io_interval, -io_particle_interval or -io_fluid_interval), for the drivers' check that it is
 * not shorter than their time step. */
PetscErrorCode IoGetInterval(Io io, PetscReal *interval, const char **opt);
/* The XDMF index path, for messages; NULL when this run wrote no frame (-io_interval 0). */
PetscErrorCode IoGetIndexPath(Io io, const char **path);
/* Collective. <dir>/<prefix>_<suffix> for a file of the run beside its frames (a checkpoint);
 * creates -io_dir if needed. */
PetscErrorCode IoGetFilePath(Io io, const char *suffix, char *path, size_t len);

/* Collective. Opens <dir>/<prefix>_<frame>.h5 (under a temporary name). */
PetscErrorCode IoFrameBegin(Io io, PetscReal t, PetscInt step);
/* Collective. A particle array: nlocal rows of ncomp reals on this rank ("position" must be
 * written for the frame to show particles). */
PetscErrorCode IoWriteParticles(Io io, const char *name, PetscInt nlocal, PetscInt ncomp, const PetscReal *data);
PetscErrorCode IoWriteParticlesInt(Io io, const char *name, PetscInt nlocal, const PetscInt *data);
/* Collective. A triangle surface for the frame (the drawn shapes of non-spherical particles):
 * np points xyz (3 each) with an integer tag per point (the particle id) and nt triangles whose
 * corner indices count from this rank's first point. Written under /surface, shown in the XDMF
 * as the grid "surface". At most once per frame. */
PetscErrorCode IoWriteSurface(Io io, PetscInt np, const PetscReal *xyz, const PetscInt *tag, PetscInt nt, const PetscInt *tri);
/* Collective, once before the first frame: the fluid mesh (uniform cells from lo, spacing h). */
PetscErrorCode IoSetFluidMesh(Io io, const PetscReal lo[3], const PetscReal h[3], const PetscInt cells[3]);
/* Collective. A cell-centred field block: count[0..2] cells from start[0..2], x fastest, the
 * ncomp components of a cell contiguous. */
PetscErrorCode IoWriteField(Io io, const char *name, PetscInt ncomp, const PetscInt start[3], const PetscInt count[3], const PetscReal *data);
/* Not collective. Whether the open frame takes dataset group/name ("particles", "surface" or
 * "fluid"; name NULL: any dataset of the group): its kind is due and -io_fields chose it. The
 * writers skip their work when not; the Io* writers skip such a dataset by themselves. */
PetscErrorCode IoFrameWants(Io io, const char *group, const char *name, PetscBool *wants);
/* Collective. Closes, renames into place, rewrites the XDMF index. A frame that received no
 * dataset is removed instead (not counted, not indexed). */
PetscErrorCode IoFrameEnd(Io io);
/* Collective; io may be NULL (no output). The run's output line: "output: INDEX (open it in
 * ParaView), N frames, X MB, Y s writing (Z% of the run's W s)", the run timed from IoCreate. */
PetscErrorCode IoView(Io io, PetscViewer v);

/* The simulated time of a frame (its root attribute "time"); has = false if it has none. */
PetscErrorCode IoReadTime(const char *file, PetscReal *t, PetscBool *has);
/* Not collective. Reads a whole dataset of numbers of an HDF5 file (rows x ncomp, as written) as
 * reals; free with PetscFree. The type, the dimensions and the declared size are checked before
 * anything is read; errors name the file and the dataset. */
PetscErrorCode IoReadDataset(const char *file, const char *name, PetscInt *rows, PetscInt *ncomp, PetscReal **data);
/* Collective on comm: every rank reads the whole dataset, which must have ncomp columns (1: a
 * vector [N] or [N, 1]). A problem found by any rank ends every rank with one message. */
PetscErrorCode IoReadDatasetAll(MPI_Comm comm, const char *file, const char *name, PetscInt ncomp, PetscInt *rows, PetscReal **data);
/* Whether a Sable HDF5 file holds the dataset /<group>/<name> (group and name given as one
 * path, e.g. "/particles/shape"). Not collective. */
PetscErrorCode IoHasDataset(const char *file, const char *name, PetscBool *has);
/* Collective on comm. Errors, naming the option opt, unless file can be opened as HDF5. */
PetscErrorCode IoCheckReadable(MPI_Comm comm, const char *opt, const char *file);

/* The output's continuation (continue.c), under io/ of a checkpoint: the frame count, the next
 * output time, the frames written, the directory and prefix, and the run identity (run_id: drawn
 * at a fresh start, written as the attribute "run_id" of every frame file and into the index).
 * Collective. IoCheckpointRead continues the series when this run's -io_dir (by its absolute
 * path) and -io_prefix are the checkpoint's (the index lists the old frames, then the new ones,
 * numbered on; the run_id is kept), and otherwise starts a new series there as a fresh run would
 * (a new run_id; frames numbered from 0, the first at once; the index lists only them). It
 * refuses, in one line naming the file and -io_dir, a directory holding a frame numbered from
 * the next one on that is not of this run (another run_id or none); this run's own frames may
 * be overwritten. IoViewRestart, after it: the log line that says where the
 * output goes from time t on ("restart: new output series in DIR from t = ...: frames from
 * FILE on (index ...); monitor PATH; ..." or "restart: output continued in DIR ..."), the
 * monitor file mpath (NULL: none) continued or not as MonCheckpointRead said. */
typedef struct _p_IoCkpt *IoCkpt;
PetscErrorCode            IoCheckpointWrite(Io io, IoCkpt ck);
PetscErrorCode            IoCheckpointRead(Io io, IoCkpt ck);
PetscErrorCode            IoViewRestart(Io io, const char *mpath, PetscBool mon_resumed, PetscReal t);

/* Checkpoint files (checkpoint.c): one HDF5 file per checkpoint, written and read collectively
 * through MPI-IO. A quantity is a 1-D dataset of the ranks' rows in rank order, with <name>_n
 * holding every rank's row count; a shared quantity is one dataset written by rank 0. Names may
 * hold groups ("dem/x"). Root attributes: sable_checkpoint_version (IO_CKPT_VERSION) and ranks
 * (the rank count that wrote it). Written under PATH.tmp and renamed by IoCkptClose; every read
 * failure stops the run with one line "-restart PATH: ... dataset NAME ...". */
#define IO_CKPT_VERSION 2
typedef struct _p_IoCkpt *IoCkpt;
typedef enum {
  IO_CKPT_REAL,
  IO_CKPT_INT, /* PetscInt */
  IO_CKPT_LLONG,
  IO_CKPT_BYTE
} IoCkptType;
size_t IoCkptTypeSize(IoCkptType type);
/* Collective. A new checkpoint, written to path.tmp until IoCkptClose renames it. */
PetscErrorCode IoCkptCreate(MPI_Comm comm, const char *path, IoCkpt *ck);
/* Collective. Opens a checkpoint for reading; refuses a file that is not HDF5, lacks the
 * attributes or has another format version. */
PetscErrorCode IoCkptOpen(MPI_Comm comm, const char *path, IoCkpt *ck);
/* Collective. Closes; a checkpoint being written is renamed into place. */
PetscErrorCode IoCkptClose(IoCkpt *ck);
/* Not collective. The rank count of the run that wrote it; the path given at open. */
PetscErrorCode IoCkptGetRanks(IoCkpt ck, int *ranks);
PetscErrorCode IoCkptGetPath(IoCkpt ck, const char **path);
/* Not collective. Whether the checkpoint holds dataset name. */
PetscErrorCode IoCkptHas(IoCkpt ck, const char *name, PetscBool *has);
/* Collective. This rank's n values as its rows of dataset name (and n into name_n). */
PetscErrorCode IoCkptWriteRows(IoCkpt ck, const char *name, IoCkptType type, PetscInt n, const void *data);
/* Collective. n values the same on every rank, written once (rank 0's). */
PetscErrorCode IoCkptWriteShared(IoCkpt ck, const char *name, IoCkptType type, PetscInt n, const void *data);
/* Collective, same rank count as the writer. This rank's rows of dataset name: *data allocated
 * (PetscFree it; room for one entry more than *n). */
PetscErrorCode IoCkptReadRows(IoCkpt ck, const char *name, IoCkptType type, PetscInt *n, void **data);
/* Collective, same rank count. As IoCkptReadRows into dst, which must receive exactly want. */
PetscErrorCode IoCkptReadRowsInto(IoCkpt ck, const char *name, IoCkptType type, PetscInt want, void *dst);
/* Collective. A shared dataset, which must hold exactly want values, into dst on every rank. */
PetscErrorCode IoCkptReadShared(IoCkpt ck, const char *name, IoCkptType type, PetscInt want, void *dst);
/* Collective, any rank count. The total length of dataset name; the row counts of the ranks
 * that wrote it (an array of IoCkptGetRanks entries, PetscFree it); count values from start. */
PetscErrorCode IoCkptGetSize(IoCkpt ck, const char *name, long long *total);
PetscErrorCode IoCkptReadCounts(IoCkpt ck, const char *name, long long **counts);
PetscErrorCode IoCkptReadSlabAll(IoCkpt ck, const char *name, IoCkptType type, long long start, long long count, void *buf);

/* The monitor file (monitor.c): a CSV time series, header "name [unit]" per column, one row per
 * -mon_interval of simulated time, written by rank 0 and flushed row by row; announced by the log
 * line "monitor: PATH" at its first row. Life cycle: MonCreate -> MonSetFromOptions -> MonSetUp ->
 * MonAddColumn (all columns, before the first row) -> MonDue / MonWriteRow -> MonDestroy. */
typedef struct _p_Mon *Mon;
PetscErrorCode         MonCreate(MPI_Comm comm, Mon *mon);
/* Reads -mon_interval (s, 0 = none) and -mon_file (default <io_dir>/<io_prefix>_monitor.csv). */
PetscErrorCode MonSetFromOptions(Mon mon);
/* Collective. The default file name from io (its directory made). */
PetscErrorCode MonSetUp(Mon mon, Io io);
/* Not collective. Whether a monitor file is asked for (NULL: no). */
PetscErrorCode MonIsActive(Mon mon, PetscBool *on);
PetscErrorCode MonAddColumn(Mon mon, const char *name, const char *unit);
PetscErrorCode MonGetColumnCount(Mon mon, PetscInt *n);
/* Not collective. Errors (PETSC_ERR_PLIB, naming both) unless column c was added with this name
 * and unit: a row's filler calls it with each value it places, so that a value cannot land under
 * another column's name (a count check alone lets two swapped columns pass). */
PetscErrorCode MonCheckColumn(Mon mon, PetscInt c, const char *name, const char *unit);
/* Not collective (the same on every rank). Whether a row is due at simulated time t (the first
 * call: always). */
PetscErrorCode MonDue(Mon mon, PetscReal t, PetscBool *due);
/* Collective. One row: a value per column (rank 0's are written). */
PetscErrorCode MonWriteRow(Mon mon, const PetscReal *values);
/* The file's path, NULL when there is none. */
PetscErrorCode MonGetPath(Mon mon, const char **path);
/* Collective. The monitor's place in a checkpoint (mon/state: next time, rows, file length;
 * mon/file: its absolute path). At a restart whose monitor file is the checkpoint's, the file is
 * cut back to the checkpoint's rows and continued (*resumed true; refused when the file is
 * missing or shorter); with another file a new series starts there: its header, then a row at
 * once (*resumed false). resumed may be NULL. */
PetscErrorCode MonCheckpointWrite(Mon mon, IoCkpt ck);
PetscErrorCode MonCheckpointRead(Mon mon, IoCkpt ck, PetscBool *resumed);
PetscErrorCode MonDestroy(Mon *mon);
