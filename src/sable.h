/* Sable-wide helpers shared by every module: checked calls into HDF5, the check that every
 * option given was read by somebody, and the version string. Nothing physical lives here. */
#pragma once
#include <petsc.h>

#define SABLE_VERSION "0.1"

/* HDF5 returns a negative value on failure; turn it into a PETSc error naming the call. */
#define SableCallH5(call) \
  do { \
    if ((call) < 0) SETERRQ(PETSC_COMM_SELF, PETSC_ERR_LIB, "HDF5 call failed: %s", #call); \
  } while (0)

/* Collective. Errors when an option in the database was never read (a typo cannot silently run
 * the wrong physics). Call after every object has done its SetFromOptions. */
PetscErrorCode SableCheckOptionsUsed(MPI_Comm comm);
/* Collective. Errors when an option under prefix ("-fluid_") is not one Sable's sources name
 * (a typo), with the closest known name ("did you mean ..."), as SableCheckOptionsUsed does at
 * start-up; a PETSc solver's option under -fluid_poisson_ or -fluid_viscous_ is let through. For
 * the prefixes whose mere presence decides something (the solver mode): call it before. */
PetscErrorCode SableCheckOptionsKnown(MPI_Comm comm, const char *prefix);
/* Not collective. The first all-digit word of an option name (no dash) replaced by %d
 * ("dem_plane_%d_velocity" for "dem_plane_3_velocity") in pat, and that word in index (an empty
 * string, and pat the name, when there is none). */
void SableIndexPattern(const char *name, char *pat, size_t size, char *index, size_t isize);
/* Collective. At the end of a run: a warning per option left unread among those the start-up
 * check has to let through (multigrid level options, read when a solver is set up). */
PetscErrorCode SableWarnOptionsUnused(MPI_Comm comm);

/* Collective. Errors when one of Sable's options (-dem_, -fluid_, -cpl_, -domain_, -io_, -lb_)
 * that takes a value has none, or has an item that reads as NaN or inf. Call once at start-up. */
PetscErrorCode SableCheckOptionValues(MPI_Comm comm);
/* A run loop's length and cadences, as its driver's options give them. */
typedef struct {
  const char *prefix;                           /* "dem" or "cpl": -<prefix>_t_end, -<prefix>_progress_interval */
  const char *step;                             /* what one step is called: "time step", "coupling step" */
  const char *dt_text;                          /* how the step is set: "-dem_dt", "-cpl_substeps 5 x -dem_dt 1e-05 s" */
  const char *raise;                            /* the option that lengthens the step */
  const char *counted;                          /* what the step counter counts: "steps", "DEM steps" */
  PetscBool   end_set;                          /* -<prefix>_t_end was given */
  PetscReal   t, t_end, dt, progress_dt, io_dt; /* s */
  PetscInt    per_step;                         /* counter increments per step (DEM substeps) */
  PetscInt    counter;                          /* the counter now */
  const char *io_opt;                           /* the option that set io_dt (IoGetInterval; NULL: -io_interval) */
} SableRunLength;
/* Collective. A run must have an end; its steps must fit the step counter (PetscInt: beyond it
 * the count wraps and the run never ends); a progress or output interval must not be shorter
 * than a step (0 turns it off). An end equal to the start runs 0 steps, and says so. */
PetscErrorCode SableCheckRunLength(MPI_Comm comm, const SableRunLength *r);
/* Not collective. The number of comma-separated items given to option opt (0 if not given). */
PetscErrorCode SableOptionCount(const char *opt, PetscInt *count);

/* Stopping early (stop.c). Not collective: installs the handlers of SIGTERM, SIGINT and SIGUSR1,
 * which record the signal (a second one, or none acted on within a grace time, ends the process
 * at once after removing the registered temporary file). */
PetscErrorCode SableSignalsInstall(void);
/* The signal caught by this process (0 if none) and its name. */
int         SableSignalCaught(void);
const char *SableSignalName(int sig);
/* Collective on comm, once a step of a run loop that has no reduction of its own to carry it
 * (the dry loop reads the DEM step's): sig is the signal caught by any rank (0 if none), the
 * same on every rank. */
PetscErrorCode SableStopPoll(MPI_Comm comm, int *sig);
/* Not collective. Records the signal the ranks agreed on by another reduction (the DEM step's),
 * for the exit status of ranks that did not catch it themselves. */
void SableStopAgreed(int sig);
/* Not collective. The stop is being acted on at a step boundary: the grace alarm is cancelled,
 * so that a checkpoint written before stopping is not cut by it (a second signal still ends the
 * process at once). */
void SableStopGraceCancel(void);
/* Collective. Ends a run loop on the agreed signal sig at time t, step step: the error of code
 * PETSC_ERR_SIG that main reports as "sable: stopped: ...", naming the checkpoint written at that
 * step (NULL: none) and the index of the frames written (NULL: none). */
PetscErrorCode SableStopError(MPI_Comm comm, int sig, PetscReal t, PetscInt step, const char *ckpt, const char *index);
/* Not collective, cheap (a clock read): marks progress (a step, a dataset written). A signal that
 * finds no progress for a while takes the process as blocked for good and ends it at once. */
void SableProgress(void);
/* Not collective. The temporary file this process is writing (NULL: none): removed by
 * SableTempRemove and by a forced stop, so that no partial file outlives the run. */
void SableTempSet(const char *path);
void SableTempRemove(void);

/* PETSc 3.18 predates PETSC_SUCCESS. */
#ifndef PETSC_SUCCESS
  #define PETSC_SUCCESS 0
#endif

/* Not collective. Whether option name (no dash) is one of Sable's own: under -dem_, -fluid_,
 * -cpl_, -domain_, -io_, -lb_, -mon_, -avg_, except the PETSc solvers' options under -fluid_poisson_ and
 * -fluid_viscous_ (sable.c). */
PetscBool SableOptionIsOwn(const char *name);
/* The -help group of an option name without its dash (0 -domain_, 1 -dem_, 2 -fluid_, 3 -cpl_,
 * 4 -lb_, 5 -io_ and -restart, 6 -mon_, 7 -avg_, 8 -sable_), -1 for PETSc's. */
int SableOptionGroup(const char *name);

/* Readers of numeric options (options.c), inside the PetscOptionsBegin block of the object that
 * owns the option, called with its literal name ("-dem_kn": grep finds it). Each prints its own
 * -help line "-name <default>: text (unit; range)" with the true default, and the value given
 * ("<0.9 (default 0.75)>"); an option without a default shows "<none>". unit: SI unit ("m",
 * "kg/m^3") or NULL for a pure number; range as in mathematics, "(0,1]", "[0,inf)", or NULL.
 * A value given out of range is an error of one line naming the option, the value and the
 * range. */
/* A real: *v is def unless given. A def outside the range is a "not given" marker, shown
 * <none> (say in text what happens then). */
#define SableOptionsReal(opt, text, unit, range, def, v, set) SableOptionsReal_Private(PetscOptionsObject, opt, text, unit, range, def, v, set)
/* An integer, as SableOptionsReal. */
#define SableOptionsInt(opt, text, unit, range, def, v, set) SableOptionsInt_Private(PetscOptionsObject, opt, text, unit, range, def, v, set)
/* A list of at most *n reals ("a,b,c"; more is an error naming the option, where PETSc would
 * drop the surplus silently): on entry v holds the ndef default values (0: no default), on exit
 * the values given (v is left as it was when the option is not given), *n their count (0: not
 * given). */
#define SableOptionsRealArray(opt, text, unit, v, ndef, n, set) SableOptionsRealArray_Private(PetscOptionsObject, opt, text, unit, v, ndef, n, PETSC_FALSE, set)
/* A list of exactly n reals (a wrong count, fewer or more, is an error naming the option); v
 * holds the ndef default values (n or 0). */
#define SableOptionsRealN(opt, text, unit, v, ndef, n, set) SableOptionsRealArray_Private(PetscOptionsObject, opt, text, unit, v, ndef, &(PetscInt){(n)}, PETSC_TRUE, set)
/* One of n names (case as given or not), read into an integer: *v is def (the index of a name)
 * unless given. A name not in names is an error of one line, on every rank alike, listing the
 * valid names. For an enum field, read into a PetscInt and assign (never through a cast
 * pointer: PetscInt may be 64 bits). */
#define SableOptionsEnum(opt, text, names, n, def, v, set) SableOptionsEnum_Private(PetscOptionsObject, opt, text, names, n, def, v, set)
/* A flag: *v is def unless given ("-opt", "-opt true|false|yes|no|1|0"). */
#define SableOptionsBool(opt, text, def, v, set) SableOptionsBool_Private(PetscOptionsObject, opt, text, def, v, set)
/* A word or a path: v (of size bytes) holds the default on entry (an empty one shown <none>) and
 * is left as it was unless given; its help line ends "(text)". A value longer than size - 1 characters is an error naming
 * the option (PETSc would cut it silently). */
#define SableOptionsString(opt, text, v, size, set) SableOptionsString_Private(PetscOptionsObject, opt, text, v, size, set)
/* A list of exactly n integers, each in range (a wrong count, or an item out of range, is an
 * error naming the option); v holds the ndef default values (n or 0). */
#define SableOptionsIntN(opt, text, unit, range, v, ndef, n, set) SableOptionsIntArray_Private(PetscOptionsObject, opt, text, unit, range, v, ndef, &(PetscInt){(n)}, PETSC_TRUE, set)
PetscErrorCode SableOptionsReal_Private(PetscOptionItems *, const char[], const char[], const char[], const char[], PetscReal, PetscReal *, PetscBool *);
PetscErrorCode SableOptionsIntArray_Private(PetscOptionItems *, const char[], const char[], const char[], const char[], PetscInt[], PetscInt, PetscInt *, PetscBool, PetscBool *);
PetscErrorCode SableOptionsEnum_Private(PetscOptionItems *, const char[], const char[], const char *const[], PetscInt, PetscInt, PetscInt *, PetscBool *);
PetscErrorCode SableOptionsBool_Private(PetscOptionItems *, const char[], const char[], PetscBool, PetscBool *, PetscBool *);
PetscErrorCode SableOptionsString_Private(PetscOptionItems *, const char[], const char[], char[], size_t, PetscBool *);
PetscErrorCode SableOptionsInt_Private(PetscOptionItems *, const char[], const char[], const char[], const char[], PetscInt, PetscInt *, PetscBool *);
PetscErrorCode SableOptionsRealArray_Private(PetscOptionItems *, const char[], const char[], const char[], PetscReal[], PetscInt, PetscInt *, PetscBool, PetscBool *);

/* The -help printer (options.c). SableHelpBegin: not collective; call it before PetscInitialize
 * (it installs Sable's PetscHelpPrintf, which keeps the help text when -help is given and
 * passes it through otherwise). SableHelpFlush: not collective; prints the kept text, Sable's
 * options first, grouped by prefix, then PETSc's, each indexed family once (-dem_plane_<k>, its
 * index range, the members given); call it after every object has read its options and before
 * PetscFinalize, which calls it too (the members given are then not known; a second call prints
 * nothing). */
void           SableHelpBegin(void);
PetscErrorCode SableHelpFlush(void);
