/* Adaptive coupling steps (-fluid_adaptive_dt in a coupled run, coupling/exchange.c). The
 * closed periodic box of test_conserve.opts with fast particles (lattice speed 10 d/s) and long
 * coupling steps (40 DEM steps of 1e-3, 0.04): the fluid starts at rest, picks up the
 * particles' momentum, and its velocity rises until the fixed step would break the CFL limit
 * -fluid_cfl_max 0.3. References are the scheme's identities and limits:
 *  1. the fixed step would violate the limit: at some step start, the stability limit
 *     FluidGetStableTimeStep is below 40 x dt_dem (so the run without adaptive steps stops);
 *  2. every step is a whole number n of DEM steps with 1 <= n <= 40, within 0.9 of the limit,
 *     and some steps are shorter than 40 (measured 27 to 40): the DEM clock (steps x -dem_dt)
 *     equals the coupling's (1e-12 relative), and the CFL number of every fluid step is
 *     <= 0.9 x 0.3;
 *  3. particle + fluid + owed momentum stays constant to 1e-10 of sum |m v| (as test_conserve),
 *     and the solid volume on the grid is the particles' (1e-12), with the steps varying;
 * One rank: on 2 ranks this box at these speeds stops, with fixed steps as well, when a particle
 * crosses the periodic boundary between list rebuilds (its kernel reaches beyond the ghost
 * cells: a limitation of the periodic migration, not of the adaptive step). Two ranks, and the
 * exact restart, are tested in test_adaptive_restart.sh on a walled bed. */
#include "cpl_common.h"

int main(int argc, char **argv)
{
  TestCpl   t;
  CplStats  st;
  PetscReal P0[3], P1[3], s0, s1, err = 0, dtd, dt, tc, td, lim, lim_min = PETSC_MAX_REAL, cfl_max = 0, g1, p1, nsum = 0;
  PetscInt  n_min = 1000, n_max = 0, ds, nsteps = 60;
  PetscBool bad = PETSC_FALSE;

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(TestSceneLoad(PETSC_COMM_WORLD, "test_conserve.opts", "-dem_lattice_speed 10 -cpl_substeps 40 -fluid_adaptive_dt -fluid_cfl_max 0.3"));
  PetscCall(TestCplBuild(NULL, &t));
  PetscCall(DemGetTimeStep(t.dem, &dtd));
  PetscCall(TestCplMomentum(&t, P0, NULL, &s0));
  for (PetscInt s = 0; s < nsteps; s++) {
    PetscInt n;
    PetscCall(FluidGetStableTimeStep(t.fl, &lim));
    lim_min = PetscMin(lim_min, lim);
    PetscCall(CplStep(t.cpl, &st));
    PetscCall(CplGetTimeStep(t.cpl, &dt));
    n = (PetscInt)PetscFloorReal(dt / dtd + 0.5);
    if (PetscAbsReal(n * dtd - dt) > 1e-12 * dt || n < 1 || n > 40 || dt > 0.9 * lim * (1 + 1e-12)) bad = PETSC_TRUE;
    n_min = PetscMin(n_min, n);
    n_max = PetscMax(n_max, n);
    nsum += n;
    cfl_max = PetscMax(cfl_max, st.fluid.cfl);
  }
  PetscCall(TestCplMomentum(&t, P1, NULL, &s1));
  PetscCall(CplGetSolidVolume(t.cpl, &g1, &p1));
  for (int k = 0; k < 3; k++) err = PetscMax(err, PetscAbsReal(P1[k] - P0[k]) / s0);
  PetscCall(CplGetTime(t.cpl, &tc, NULL));
  PetscCall(DemGetTime(t.dem, &td, &ds));
  CheckDetail("bound 40 x dt_dem = %g s; smallest limit %g s", (double)(40 * dtd), (double)lim_min);
  PetscCall(CheckBelow("the fixed step would break the CFL limit: smallest stability limit at a step start (s)", lim_min, 40 * dtd));
  CheckDetail("DEM steps per fluid step from %d to %d over %d steps, %g on average", (int)n_min, (int)n_max, (int)nsteps, (double)(nsum / nsteps));
  PetscCall(CheckTrue("every step is a whole number of DEM steps in [1, 40] within 0.9 of the stability limit", (PetscBool)!bad, bad ? "a step broke it" : "all"));
  PetscCall(CheckBelow("some steps are cut: fewest DEM steps in a fluid step", (PetscReal)n_min, 40));
  PetscCall(CheckClose(CheckName("the DEM clock (%d steps of -dem_dt) vs the coupling's", (int)ds), (PetscReal)ds * dtd, tc, 1e-12));
  PetscCall(CheckAtMost("CFL number of every fluid step vs 0.9 x -fluid_cfl_max 0.3", cfl_max, 0.27 * (1 + 1e-12)));
  PetscCall(CheckBelow("particle + fluid + owed momentum over the adaptive steps: max change / sum|m v|", err, 1e-10));
  PetscCall(CheckClose("solid volume on the grid vs the particles', after the adaptive steps", g1, p1, 1e-12));
  PetscCall(TestCplDestroy(&t));
  PetscCall(PetscFinalize());
  return check_failures ? 1 : 0;
}
