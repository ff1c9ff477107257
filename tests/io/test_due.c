/* Output cadence: a run's time is a sum of steps (t += dt), which drifts away from the multiples
 * of -io_interval by roundoff. Over 1.4 million steps of 1e-5 s with frames every 0.1 s (the silo
 * discharge), exactly one frame must fall within one step of every multiple of the interval and
 * no other frame be written (a frame just below k*interval was once followed by a second one
 * just above it). */
#include "check.h"
#include "io/io.h"

int main(int argc, char **argv)
{
  Io        io;
  PetscBool due;
  PetscReal t = 0, dt = 1e-5, interval = 0.1, worst = 0;
  PetscInt  frames = 0, steps = 1400000, wrong = 0;

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(PetscOptionsSetValue(NULL, "-io_interval", "0.1"));
  PetscCall(IoCreate(PETSC_COMM_WORLD, &io));
  PetscCall(IoSetFromOptions(io));
  for (PetscInt s = 0; s <= steps; s++, t += dt) {
    PetscCall(IoDue(io, t, &due));
    if (!due) continue;
    const PetscReal k = PetscFloorReal(t / interval + 0.5), off = PetscAbsReal(t - k * interval);
    if (k != frames || off > dt) wrong++;
    worst = PetscMax(worst, off);
    frames++;
  }
  const PetscInt expect = (PetscInt)PetscFloorReal(steps * dt / interval + 1e-6) + 1;
  PetscCall(CheckEqual(CheckName("frames every 0.1 s over %" PetscInt_FMT " steps of 1e-5 s: frames written", steps), frames, expect));
  CheckDetail("largest offset from k*interval %.2e s", (double)worst);
  PetscCall(CheckEqual("frames out of place (not the k-th frame, or more than one step, 1e-5 s, from k*interval)", wrong, 0));
  PetscCall(IoDestroy(&io));
  PetscCall(PetscFinalize());
  return check_failures ? 1 : 0;
}
