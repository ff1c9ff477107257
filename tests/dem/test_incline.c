/* A sphere on an incline (gravity tilted by theta over a floor plane) and a sphere launched
 * sliding on a floor. Rigid-body references (Coulomb friction, solid sphere I = 2/5 m r^2):
 *   rolling without slip when tan(theta) <= 3.5 mu:  a = 5/7 g sin(theta);
 *   sliding otherwise:                               a = g (sin(theta) - mu cos(theta));
 *   launched at v0 without spin on a flat floor: friction decelerates at mu g and spins the
 *   sphere up until it rolls, at t* = 2 v0 / (7 mu g), with speed 5/7 v0 from then on.
 * Accelerations are measured from the velocity change between t = 0.1 s and 0.3 s (after the
 * spring transients); bound 1%. */
#include "dem_common.h"

static PetscErrorCode Run(const char *law, double theta, double v0, double t1, double t2, double *va, double *vb)
{
  const double r = 0.005, g = 9.81, m = 2500 * 4.0 / 3.0 * PETSC_PI * r * r * r, kn = 1e5;
  char         opts[1024];
  Domain       dom;
  Dem          dem;
  double       t = 0;
  char         stiff[64]; /* kn for the linear laws, E for hertz: the other would be ignored */

  PetscFunctionBeginUser;
  if (strcmp(law, "hertz")) PetscCall(PetscSNPrintf(stiff, sizeof stiff, "-dem_kn %g", kn));
  else PetscCall(PetscSNPrintf(stiff, sizeof stiff, "-dem_youngs_modulus 5e7"));
  PetscCall(PetscSNPrintf(opts, sizeof opts, "-domain_lo -1,-1,-0.1 -domain_hi 4,1,0.1 -dem_radius %g -dem_density 2500 -dem_contact_law %s %s -dem_restitution 0.5 -dem_friction 0.3 -dem_gravity %.17g,0,%.17g -dem_dt 5e-6 -dem_impact_velocity 0.1 -dem_plane_0 0,0,0,0,0,1", r, law, stiff, g * sin(theta), -g * cos(theta)));
  PetscCall(TestDemCreate(opts, &dom, &dem));
  DemParticle p = {.id = 7, .shape = 0, .x = {0, 0, r - m * g * cos(theta) / kn}, .v = {v0, 0, 0}, .q = {1, 0, 0, 0}};
  PetscCall(DemAddParticle(dem, &p));
  PetscCall(DemSetUp(dem));
  while (t < t2 - 1e-9) {
    if (PetscAbsReal(t - t1) < 2.5e-6) *va = TestGet(dem, 7).v[0];
    PetscCall(DemStep(dem));
    PetscCall(DemGetTime(dem, &t, NULL));
  }
  *vb = TestGet(dem, 7).v[0];
  PetscCall(TestDemDestroy(&dom, &dem));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  const char  *laws[] = {"linear", "hertz"};
  const double g = 9.81, mu = 0.3;

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  for (int l = 0; l < 2; l++) {
    const double f[4] = {0.5, 0.95, 1.05, 2.0}; /* tan(theta) / (3.5 mu): both sides of the transition */
    for (int k = 0; k < 4; k++) {
      const double th = atan(f[k] * 3.5 * mu), roll = f[k] < 1;
      double       va = 0, vb = 0;
      PetscCall(Run(laws[l], th, 0, 0.1, 0.3, &va, &vb));
      const double a = (vb - va) / 0.2, ref = roll ? 5.0 / 7.0 * g * sin(th) : g * (sin(th) - mu * cos(th));
      PetscCall(CheckClose(CheckName("%s %s, tan(theta) = %.2f x 3.5 mu: a [m/s^2] vs analytic", laws[l], roll ? "rolling" : "sliding", f[k]), a, ref, 0.01));
    }
    double va = 0, vb = 0, v0 = 1.0, ts = 2 * v0 / (7 * mu * g);
    PetscCall(Run(laws[l], 0, v0, ts, 2 * ts, &va, &vb));
    PetscCall(CheckClose(CheckName("%s launched sliding: v(t* = 2 v0/(7 mu g)) [m/s] vs analytic 5/7 v0", laws[l]), va, 5.0 / 7.0 * v0, 0.01));
    PetscCall(CheckClose(CheckName("%s then rolls: v(2 t*) [m/s] vs analytic 5/7 v0", laws[l]), vb, 5.0 / 7.0 * v0, 0.01));
  }
  { /* the law without history slides with the same kinetic friction */
    const double th = atan(2.0 * 3.5 * mu);
    double       va = 0, vb = 0;
    PetscCall(Run("linear_nohist", th, 0, 0.1, 0.3, &va, &vb));
    const double a = (vb - va) / 0.2, ref = g * (sin(th) - mu * cos(th));
    PetscCall(CheckClose("linear_nohist sliding: a [m/s^2] vs analytic", a, ref, 0.01));
  }
  PetscCall(PetscFinalize());
  return check_failures ? 1 : 0;
}
