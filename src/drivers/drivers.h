/* The run drivers: the dry loop (dry.c) and the coupled loop (coupled.c), their options (the
 * run's length and progress cadence), progress lines and summaries. main builds the Domain, the
 * Dem, the Balance and the Io, picks a driver and hands them over. Life cycle of each driver:
 * XRunCreate -> XRunSetFromOptions -> XRunCase (sets up, runs, reports) -> XRunDestroy.
 * All collective. */
#pragma once
#include "balance/balancer.h"

/* Collective. Whether the run is coupled: -sable_solver coupled, or (auto, the default) any -cpl_
 * or -fluid_ option given (the fluid has defaults for all its properties, so one fluid option is
 * enough to ask for it). First an unknown -cpl_/-fluid_ name is an error with its "did you mean";
 * then the other mode's options are refused (-sable_solver dry with a -fluid_ option, -dem_t_end
 * in a coupled run). Under -help it only reads -sable_solver. */
PetscErrorCode DriverIsCoupled(PetscBool *on);

/* Checkpoints, shared by both drivers (checkpoint.c): -io_checkpoint_interval (s, 0 = none; a
 * positive one also writes one at the end; a stop signal writes one in any case),
 * -io_checkpoint_keep (newest kept), -restart PATH. */
#define DRIVER_KEEP_MAX 64
typedef struct {
  MPI_Comm  comm;
  PetscReal dt;                                         /* -io_checkpoint_interval (s; 0: none) */
  PetscBool mon_resumed;                                /* at a restart: the monitor continued */
  PetscInt  keep, n, step;                              /* kept, written so far, step of the last one */
  char      files[DRIVER_KEEP_MAX][PETSC_MAX_PATH_LEN]; /* the newest ones written, oldest first */
  char      restart[PETSC_MAX_PATH_LEN];                /* -restart ("" for none) */
} DriverCkpt;
typedef PetscErrorCode (*DriverCkptWriter)(void *ctx, IoCkpt ck);
PetscErrorCode DriverCkptSetFromOptions(DriverCkpt *c, MPI_Comm comm);
/* Collective. Writes <io_dir>/<prefix>_checkpoint_<step>.h5 through write (once per step; not
 * without io), announces it ("checkpoint: PATH") and removes this run's checkpoints beyond the
 * newest -io_checkpoint_keep. */
PetscErrorCode DriverCkptWrite(DriverCkpt *c, Io io, PetscInt step, DriverCkptWriter write, void *ctx);
/* Collective. Announces the restart ("restart: PATH") and its wall time since t0 (PetscTime
 * before the checkpoint was opened) with the file's size, then where the output goes from the
 * checkpoint's time t on (IoViewRestart; io and mon may be NULL). */
PetscErrorCode DriverCkptRestarted(DriverCkpt *c, PetscLogDouble t0, Io io, Mon mon, PetscReal t);
/* Collective. A run loop's stop on the agreed signal sig at time t, step step: writes this
 * step's checkpoint through write (when c, io and write are given: the grace alarm cancelled
 * first) and ends with SableStopError naming it and the index. Never returns success. */
PetscErrorCode DriverCkptStop(DriverCkpt *c, Io io, int sig, PetscReal t, PetscInt step, DriverCkptWriter write, void *ctx);
/* Collective. The parts of a checkpoint that are the run's, not the physics': the output's
 * continuation (io/, IoCheckpointWrite) and the options given (run/options). A driver's write
 * callback calls DriverCkptWriteRun; its restart calls DriverCkptReadRun (io and mon may be NULL
 * there), which restores the output and the monitor (IoCheckpointRead, MonCheckpointRead: the
 * same place continues, another starts a new series; another run's frames are refused) and
 * prints one warning line per
 * physics option changed, added or removed since the checkpoint's run ("restart: -dem_friction
 * was 0.5 in the checkpoint's run, now 0.3: ..."); the run's length, output, checkpoint,
 * progress and logging options may change silently. */
PetscErrorCode DriverCkptWriteRun(Io io, IoCkpt ck);
PetscErrorCode DriverCkptReadRun(DriverCkpt *c, Io io, Mon mon, IoCkpt ck);

/* The monitor file's contents, shared by both drivers (monitor.c): -mon_interval, -mon_file
 * (io/monitor.c), -mon_box_<k>, -mon_surface_<k> (-mon_surface_dz, -mon_surface_fraction),
 * -mon_flux_<k> (-mon_flux_width), and for coupled runs -mon_probe_<k>, -mon_dp_<k>,
 * -mon_line_<k>, -mon_plane_<k> (-mon_average_fields), any number of each; a coupled run
 * reports every fluid patch (-fluid_patch_<k>_type) too. */
typedef struct {
  PetscInt  k;            /* the option's index */
  PetscReal lo[3], hi[3]; /* a box, a segment's ends, a plane's rectangle (flat along axis), a probe (lo) */
  int       axis;         /* a plane's normal */
  PetscInt  ab[2];        /* a pressure drop's probes (positions in DriverMon.probe) */
  char      name[32];     /* the option */
} DriverMonRegion;
typedef struct {
  MPI_Comm         comm;
  Mon              mon;
  PetscBool        coupled, ready; /* ready: columns declared (DriverMonSetUp with a monitor file) */
  PetscInt         nbox, nsurf, nflux, nprobe, ndp, nline, nplane, ncol;
  DriverMonRegion *box, *surf, *flux, *probe, *dp, *line, *plane;
  PetscReal        surf_dz, surf_frac, flux_width; /* m, -, m (0: the default, set at the first row) */
  PetscBool        fields[3];                      /* p, eps, u in the line and plane averages */
  FluidSpan       *spans;                          /* the lines, then the planes */
  PetscReal       *row;
  PetscLogDouble   wall0, wall_last;
  PetscInt         step_last;
  PetscInt         npatch, *patch; /* the fluid's patches -fluid_patch_<k>_type: their indices k, sorted */
} DriverMon;
/* What a row is made of: the time and step counter, the DEM, and for a coupled run the fluid and
 * the last coupling step's statistics (NULL before the first). */
typedef struct {
  PetscReal       t;
  PetscInt        step;
  Dem             dem;
  Fluid           fluid;
  const CplStats *cst;
} DriverMonInput;
PetscErrorCode DriverMonSetFromOptions(DriverMon *m, MPI_Comm comm, PetscBool coupled);
/* Collective. The file's default name from io; declares the columns; the loop's wall clock
 * starts. */
PetscErrorCode DriverMonSetUp(DriverMon *m, Io io);
/* Collective. A row when one is due at in->t. */
PetscErrorCode DriverMonRow(DriverMon *m, const DriverMonInput *in);
PetscErrorCode DriverMonDestroy(DriverMon *m);

/* The dry run: -dem_t_end (s, required), -dem_progress_interval (s, 0 = none). */
typedef struct _p_DryRun *DryRun;
PetscErrorCode            DryRunCreate(MPI_Comm comm, DryRun *run);
PetscErrorCode            DryRunSetFromOptions(DryRun run);
/* Sets up the Dem (options read) and the Balance, runs, prints the summary lines; lb and io
 * may be NULL (no balancing, no output). */
PetscErrorCode DryRunCase(DryRun run, Domain *dom, Dem dem, Balance lb, Io io);
/* The loop alone (the Dem set up): from the DEM's time to -dem_t_end; lb and io may be NULL. */
PetscErrorCode DryRunLoop(DryRun run, Dem dem, Balance lb, Io io);
PetscErrorCode DryRunDestroy(DryRun *run);

/* The coupled run: -cpl_t_end (s, required), -cpl_progress_interval (s), -cpl_probe_z z1,z2 (m). */
typedef struct _p_CoupledRun *CoupledRun;
PetscErrorCode                CoupledRunCreate(Domain *dom, CoupledRun *run);
PetscErrorCode                CoupledRunSetFromOptions(CoupledRun run);
/* Builds the Fluid and the coupling beside dem (options read, not set up), sets everything up,
 * runs and prints the summary. With help set it only reads the options (-help lists them). */
PetscErrorCode CoupledRunCase(CoupledRun run, Dem dem, Balance lb, Io io, PetscBool help);
PetscErrorCode CoupledRunDestroy(CoupledRun *run);
