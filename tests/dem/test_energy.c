/* Conservation: no damping (e = 1), no friction, no gravity, a small dense box of spheres in
 * constant collision with each other and the walls. The total energy (kinetic + elastic) of a
 * symplectic integrator oscillates at O((w dt)^2) during contacts but must not drift: the drift,
 * the change of its mean between the first and the last tenth of 10^5 steps, stays below
 * 1e-4 relative (the required bound), at dt = Tc/200. The linear force has a kink at first touch
 * (F = kn delta switches on), which breaks the shadow energy of velocity Verlet once per contact:
 * the drift is second order in dt (measured ~7e-4 at Tc/50 for 64 spheres over 1e5 steps), and
 * that order is checked too. Linear and Hertz. */
#include "dem_common.h"

static PetscErrorCode Run(const char *law, double dt, double *drift_out)
{
  const double r = 0.005, a = 2 * r * 1.002;
  const int    N = 100000, L = 4;
  char         opts[1024];
  Domain       dom;
  Dem          dem;
  DemStats     st;
  double       e0 = 0, first = 0, last = 0, maxdev = 0;
  int          nf = 0, nl = 0;

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(opts, sizeof opts, "-domain_lo 0,0,0 -domain_hi %.17g,%.17g,%.17g -dem_box 0,0,0,%.17g,%.17g,%.17g -dem_radius %g -dem_contact_law %s %s -dem_restitution 1 -dem_friction 0 -dem_gravity 0,0,0 -dem_dt %g -dem_impact_velocity 0.5 -dem_lattice %d,%d,%d -dem_lattice_spacing %.17g -dem_lattice_jitter 1 -dem_lattice_speed 0.5", L * a, L * a, L * a, L * a, L * a, L * a, r, law, strcmp(law, "hertz") ? "-dem_kn 1e4" : "-dem_youngs_modulus 1e7", dt, L, L, L, a));
  PetscCall(TestDemCreate(opts, &dom, &dem));
  PetscCall(DemSetUp(dem));
  for (int s = 0; s <= N; s++) {
    if (s % 10 == 0) {
      PetscCall(DemGetStats(dem, &st));
      const double e = st.ke + st.ke_rot + st.pe_spring;
      if (s == 0) e0 = e;
      maxdev = PetscMax(maxdev, PetscAbsReal(e - e0) / e0);
      if (s < N / 10) {
        first += e;
        nf++;
      }
      if (s > N - N / 10) {
        last += e;
        nl++;
      }
    }
    if (s < N) PetscCall(DemStep(dem));
  }
  const double drift = PetscAbsReal(last / nl - first / nf) / e0;
  *drift_out         = drift;
  PetscCall(PetscInfo(NULL, "%s dt %g: drift %g, largest excursion %g\n", law, dt, drift, maxdev));
  if (dt < 5e-6) {
    CheckDetail("largest excursion %.2e", maxdev);
    PetscCall(CheckBelow(CheckName("%s energy drift over 1e5 steps at dt = Tc/200, 64 spheres, e=1 (relative)", law), drift, 1e-4));
  }
  PetscCall(TestDemDestroy(&dom, &dem));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  const double tc = 8.04e-4; /* linear pair contact time at kn = 1e4, r = 5 mm */
  double       d50, d100, d200;
  PetscCall(Run("linear", tc / 200, &d200));
  PetscCall(Run("hertz", tc / 200, &d200));
  PetscCall(Run("linear", tc / 50, &d50));
  PetscCall(Run("linear", tc / 100, &d100));
  CheckDetail("%.2e at Tc/50, %.2e at Tc/100", d50, d100);
  PetscCall(CheckAbove("linear energy drift is second order in dt: ratio of the drifts at Tc/50 and Tc/100", d50 / d100, 3));
  PetscCall(PetscFinalize());
  return check_failures ? 1 : 0;
}
