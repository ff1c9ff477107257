/* Output: one HDF5 file per output time (particles under /particles, fluid fields under /fluid)
 * and one XDMF file indexing them as a time series that ParaView opens. Each HDF5 file is
 * written under a temporary name and renamed when complete, and the XDMF index is rewritten the
 * same way, so a killed run never leaves a half-written file behind a name ParaView reads.
 * Writes are collective (MPI-IO); each rank passes its own block. Options: -io_dir, -io_prefix,
 * -io_interval. */
#pragma once
#include "sable.h"

typedef struct _p_Io *Io;

PetscErrorCode IoCreate(MPI_Comm comm, Io *io);
/* Reads -io_dir (default out), -io_prefix (default sable), -io_interval (s, 0 = no output). */
PetscErrorCode IoSetFromOptions(Io io);
PetscErrorCode IoDestroy(Io *io);
/* Whether an output is due at simulated time t (first call: always, when output is on). */
PetscErrorCode IoDue(Io io, PetscReal t, PetscBool *due);
/* Not collective (the same on every rank). At the end of a run: whether the state at t still
 * needs a frame (output is on and the last frame is older than t), so that a run always leaves
 * its final state, also when the end time is not a multiple of -io_interval. */
PetscErrorCode IoDueFinal(Io io, PetscReal t, PetscBool *due);
/* Not collective. The simulated time between outputs (s; 0 = no output), for the drivers' check
 * that it is not shorter than their time step. */
PetscErrorCode IoGetInterval(Io io, PetscReal *interval);
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
/* Collective. Closes, renames into place, rewrites the XDMF index. */
PetscErrorCode IoFrameEnd(Io io);

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
