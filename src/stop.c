/* Stopping a run early without leaving a mess: signals and temporary files.
 *
 * SIGTERM, SIGINT and SIGUSR1 (a batch system's preemption, Ctrl-C, a user's request) are caught:
 * the handler only records the signal. Every rank must learn of it at the same step: the dry loop
 * reads it from the DEM step's own reduction (no extra message), the coupled loop polls
 * SableStopPoll once a fluid step (one small reduction beside a Poisson solve's dozens); the loop
 * then writes a checkpoint where it can (drivers/checkpoint.c: DriverCkptStop cancels the grace
 * alarm first, SableStopGraceCancel) and ends the run (SableStopError) with an error of code
 * PETSC_ERR_SIG naming it, after the output being written, if any, is complete. A second signal, or
 * a first one not acted on within SABLE_STOP_GRACE seconds (a rank stuck in a collective whose
 * partner died), ends the process at once: the handler removes the temporary file this process
 * is writing and exits with status 128 + signal.
 *
 * A signal that finds the process blocked without progress for SABLE_STUCK_MS (a rank waiting in
 * a collective for one that has failed, which the launcher is ending) ends it at once instead:
 * the run loops, the DEM step and the frame writer mark progress (SableProgress).
 *
 * Every writer registers the temporary file it is writing (SableTempSet) and clears it once the
 * file is renamed into place, so that whatever ends the process early can remove it. Only
 * async-signal-safe calls (unlink, write, _exit, alarm) are made inside the handlers. */
#include "sable.h"
#include <signal.h>
#include <stdatomic.h>
#include <time.h>
#include <unistd.h>

/* s between a signal and a forced exit when no step boundary comes: longer than a step or a frame
 * of any run this machine class holds, shorter than the minute a batch system usually leaves
 * between SIGTERM and SIGKILL */
#define SABLE_STOP_GRACE 30
/* ms without progress after which a signalled process is taken to be blocked for good: a rank
 * waiting in a collective for a rank that has failed (main.c lets a failed rank wait 0.5 s for
 * the others before it exits, so its partners have waited longer when the launcher's SIGTERM
 * comes); far longer than a DEM step, a frame dataset or a coupled run's poll */
#define SABLE_STUCK_MS 400

static volatile sig_atomic_t stop_sig, temp_valid, progress_ms; /* progress_ms: 0 before the first mark */
static int                   stop_agreed;                       /* the signal the ranks agreed on at a poll */
static char                  temp_path[PETSC_MAX_PATH_LEN];

const char *SableSignalName(int sig)
{
  switch (sig) {
  case SIGTERM:
    return "SIGTERM";
  case SIGINT:
    return "SIGINT";
  case SIGUSR1:
    return "SIGUSR1";
  case SIGALRM:
    return "SIGALRM";
  default:
    return "a signal";
  }
}

static void SableWriteStr(const char *s)
{
  size_t n = 0;
  while (s[n]) n++;
  if (write(STDERR_FILENO, s, n) < 0) return;
}

/* Ends the process now: removes the temporary being written, says why, exits 128 + sig. */
static void SableStopNow(int sig)
{
  if (temp_valid) unlink(temp_path);
  SableWriteStr("sable: stopped: ");
  SableWriteStr(SableSignalName(sig));
  SableWriteStr(sig == SIGALRM ? " (no step boundary came within the grace time after a signal); the file being written was removed\n" : " received twice; the file being written was removed\n");
  _exit(128 + (sig == SIGALRM ? (int)stop_sig : sig));
}

/* Milliseconds of the monotonic clock, modulo 2^30 (never 0); clock_gettime is async-signal-safe. */
static int SableNowMs(void)
{
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (int)(((long long)ts.tv_sec * 1000 + ts.tv_nsec / 1000000) & 0x3fffffff) | 1;
}

void SableProgress(void)
{
  progress_ms = SableNowMs();
}

static void SableSignalHandler(int sig)
{
  if (sig == SIGALRM && !stop_sig) return; /* not ours: no stop is pending */
  if (sig == SIGALRM || stop_sig) SableStopNow(sig);
  if (progress_ms && ((SableNowMs() - progress_ms) & 0x3fffffff) > SABLE_STUCK_MS) {
    /* blocked for good (the launcher ending a run after another rank failed, which printed the
       run's one line): go at once, quietly, leaving no temporary */
    if (temp_valid) unlink(temp_path);
    _exit(128 + sig);
  }
  stop_sig = sig;
  alarm(SABLE_STOP_GRACE);
}

PetscErrorCode SableSignalsInstall(void)
{
  struct sigaction sa;
  const int        sigs[] = {SIGTERM, SIGINT, SIGUSR1, SIGALRM};

  PetscFunctionBeginUser;
  memset(&sa, 0, sizeof sa);
  sa.sa_handler = SableSignalHandler;
  sa.sa_flags   = SA_RESTART; /* a write interrupted by the signal goes on */
  sigemptyset(&sa.sa_mask);
  for (size_t k = 0; k < sizeof sigs / sizeof sigs[0]; k++) PetscCheck(sigaction(sigs[k], &sa, NULL) == 0, PETSC_COMM_SELF, PETSC_ERR_SYS, "cannot install the handler of %s", SableSignalName(sigs[k]));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int SableSignalCaught(void)
{
  return stop_sig ? (int)stop_sig : stop_agreed;
}

void SableTempSet(const char *path)
{
  temp_valid = 0;
  if (!path) return;
  strncpy(temp_path, path, sizeof temp_path - 1);
  temp_path[sizeof temp_path - 1] = 0;
  atomic_signal_fence(memory_order_seq_cst); /* the path is whole before the handler may read it */
  temp_valid = 1;
}

void SableTempRemove(void)
{
  if (temp_valid) unlink(temp_path);
  temp_valid = 0;
}

void SableStopAgreed(int sig)
{
  if (!stop_agreed) stop_agreed = sig;
}

PetscErrorCode SableStopPoll(MPI_Comm comm, int *sig)
{
  int local = (int)stop_sig;

  PetscFunctionBeginUser;
  SableProgress();
  PetscCallMPI(MPI_Allreduce(&local, sig, 1, MPI_INT, MPI_MAX, comm));
  if (*sig) SableStopAgreed(*sig);
  PetscFunctionReturn(PETSC_SUCCESS);
}

void SableStopGraceCancel(void)
{
  alarm(0);
}

PetscErrorCode SableStopError(MPI_Comm comm, int sig, PetscReal t, PetscInt step, const char *ckpt, const char *index)
{
  char said[PETSC_MAX_PATH_LEN + 64] = "";

  PetscFunctionBeginUser;
  SableStopAgreed(sig);
  alarm(0); /* the stop is being acted on: no forced exit */
  if (ckpt) PetscCall(PetscSNPrintf(said, sizeof said, "checkpoint %s (continue with -restart %s); ", ckpt, ckpt));
  SETERRQ(comm, PETSC_ERR_SIG, "%s received at t = %g s, step %" PetscInt_FMT "; %s%s%s", SableSignalName(sig), (double)t, step, said, index ? "the frames written are complete: " : "no output was written", index ? index : "");
}
