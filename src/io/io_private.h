/* Private to src/io: what the frame writer (io.c), the index writer (xdmf.c) and the reader (read.c)
 * share. HDF5's own error stack is silenced (a dozen lines per failure); each failure becomes one
 * message of ours naming the file, the dataset and, from the innermost entry of the stack, what
 * HDF5 says went wrong. */
#pragma once
#include "io/io.h"
#include <hdf5.h>

/* Silences HDF5's printing of its error stack. Called before every HDF5 use of src/io. */
static inline void io_quiet(void)
{
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
}

/* The innermost entry of HDF5's error stack, "function: description", in buf ("" when the stack
 * is empty). Call right after the failed call: any later HDF5 call clears the stack. */
void io_h5_last_error(char *buf, size_t len);

/* The writer's state, shared by io.c (frames) and xdmf.c (the index). */
#define IO_MAX_SETS 32
typedef struct {
  char      name[64];
  PetscInt  ncomp;
  PetscBool isint;
} IoSet;

typedef struct {
  PetscReal t;
  char      file[PETSC_MAX_PATH_LEN];
  long long np; /* global particle count */
  IoSet     part[IO_MAX_SETS], fluid[IO_MAX_SETS];
  PetscInt  npart, nfluid;
  long long nsurfp, nsurft; /* surface points and triangles (0: none) */
  PetscInt  prec;           /* bytes of its particle and fluid reals: 8 (0 read as 8) or 4 (-io_precision single) */
} IoFrame;

typedef unsigned long long IoRunId; /* a run's identity (continue.c) */

/* The datasets -io_fields chooses from (fields.c): their group and name in a frame. */
#define IO_MAX_FIELDS 64

struct _p_Io {
  MPI_Comm       comm;
  char           dir[PETSC_MAX_PATH_LEN], prefix[64], index[PETSC_MAX_PATH_LEN];
  PetscReal      interval;                 /* -io_interval (s): the default of the two below */
  PetscReal      pinterval, finterval;     /* -io_particle_interval, -io_fluid_interval (s; 0: never) */
  PetscReal      next, fnext;              /* the next particle and fluid output times */
  PetscBool      kind[2];                  /* what the frame due or open takes: 0 particles (and surface), 1 fluid (and averages) */
  PetscBool      armed;                    /* kind[] was set by IoDue / IoDueFinal for the next frame */
  PetscBool      skip[IO_MAX_FIELDS];      /* datasets of the table in io.c that -io_fields leaves out */
  PetscInt       compress;                 /* -io_compress: deflate level (0: none) */
  PetscBool      single;                   /* -io_precision single: particle and fluid reals stored in 32 bits */
  PetscLogDouble t_create, t_frame, wtime; /* wall clock at IoCreate, at IoFrameBegin; seconds spent writing frames */
  long long      written, bytes;           /* frames written by this process and their bytes (rank 0) */
  PetscBool      fluidmesh;
  PetscReal      flo[3], fh[3];
  PetscInt       fcells[3];
  IoFrame       *frames;
  PetscInt       nframes, capframes;
  hid_t          file, gpart, gfluid;
  char           tmpname[PETSC_MAX_PATH_LEN];
  PetscBool      dirmade; /* -io_dir made (and the reserve taken) before the first frame of this process */
  int            reserve; /* rank 0: the descriptor of the reserve (an unlinked file), or -1 */
  IoRunId        run_id;  /* drawn at a fresh start, kept across restarts (continue.c) */

  /* a restart (continue.c): whether it started a new output series; the checkpoint's -io_dir */
  PetscBool fresh;
  char      from[PETSC_MAX_PATH_LEN];
};

/* Collective, inside IoSetFromOptions' options block. Reads -io_fields into io->skip; an unknown
 * or ambiguous name is one error line listing the valid ones (fields.c). */
PetscErrorCode IoReadFields(Io io, PetscOptionItems *PetscOptionsObject);
/* Whether -io_fields chose a dataset of kind (0 particles, 1 fluid) (fields.c). */
PetscBool IoKindChosen(Io io, int kind);

/* Collective. A fresh run's identity: rank 0 mixes the clock and its pid (continue.c). */
PetscErrorCode IoDrawRunId(Io io);
/* Writes the root attribute "run_id" (unsigned 64 bits) of an open HDF5 file; < 0 on failure. */
herr_t io_write_run_id(hid_t file, IoRunId id);

/* Rank 0. Rewrites the XDMF index listing io's frames (xdmf.c): written to <index>.tmp and
 * renamed into place; *err is the errno of the first failure (0: none), after which the
 * temporary is removed. */
PetscErrorCode IoWriteIndex(Io io, int *err);
