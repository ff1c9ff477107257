/* Normal impact, sphere-sphere and sphere-wall, linear and Hertz laws, no gravity, no friction.
 * References: restitution = the set value e (both laws are calibrated to give it exactly);
 * contact time: linear, the damped oscillator's half period sqrt(m* (pi^2 + ln^2 e) / kn),
 * computed here from the options; Hertz, undamped (e = 1), the closed form 2.8683 (m*^2 / (R*
 * E*^2 v))^(1/5) (Hertz 1882; Johnson, Contact Mechanics §11.4), and damped, the reduced Hertz
 * equation solved at fine resolution by the code (DemGetContactFigures: this checks the DEM
 * integrator against an accurate solution of the same law). dt = Tc/50 (>= 50 steps per contact).
 * Bounds: restitution within 1%, contact time within 2%. Contact start and end
 * are located by linear interpolation of the overlap between steps. */
#include "dem_common.h"

typedef struct {
  const char *law;
  PetscBool   wall;
  double      e, v;
} Impact;

static PetscErrorCode RunImpact(const Impact *c, double dt_over_tc, double *e_meas, double *tc_meas, double *tc_ref)
{
  const double r = 0.005;
  char         opts[1024];
  double       tc = 0, e, dt = 1e-9, t_in = -1, t_out = -1, dprev = -1, vrel0 = 2 * c->v;

  PetscFunctionBeginUser;
  for (int pass = 0; pass < 2; pass++) { /* pass 0 only asks the parameters for Tc */
    Domain dom;
    Dem    dem;
    PetscCall(PetscSNPrintf(opts, sizeof opts, "-domain_lo -0.05,-0.05,-0.05 -domain_hi 0.05,0.05,0.05 -dem_radius %g -dem_density 2500 -dem_contact_law %s %s -dem_restitution %g -dem_friction 0 -dem_gravity 0,0,0 -dem_dt %g -dem_impact_velocity %g %s", r, c->law, strcmp(c->law, "hertz") ? "-dem_kn 1e4" : "-dem_youngs_modulus 1e7 -dem_poisson_ratio 0.3", c->e, dt, c->wall ? c->v : 2 * c->v, c->wall ? "-dem_plane_0 0,0,0,0,0,1" : ""));
    PetscCall(TestDemCreate(opts, &dom, &dem));
    DemParticle a = {.id = 0, .shape = 0, .x = {0, 0, 1.01 * r}, .v = {0, 0, -c->v}, .q = {1, 0, 0, 0}};
    DemParticle b = {.id = 1, .shape = 0, .x = {0, 0, -1.01 * r}, .v = {0, 0, c->v}, .q = {1, 0, 0, 0}};
    PetscCall(DemAddParticle(dem, &a));
    if (!c->wall) PetscCall(DemAddParticle(dem, &b));
    else {
      a.x[2] = 1.02 * r;
      PetscCall(DemSetParticle(dem, 0, &a));
      vrel0 = c->v;
    }
    PetscCall(DemSetUp(dem));
    if (pass == 0) {
      PetscCall(DemGetContactFigures(dem, 0, c->wall ? -1 : 0, vrel0, &tc, &e));
      dt = tc * dt_over_tc;
      PetscCall(TestDemDestroy(&dom, &dem));
      continue;
    }
    for (int s = 0; s < 1000000 && t_out < 0; s++) {
      DemParticle pa = TestGet(dem, 0), pb = TestGet(dem, 1);
      double      delta = c->wall ? r - pa.x[2] : 2 * r - (pa.x[2] - pb.x[2]), t;
      PetscCall(DemGetTime(dem, &t, NULL));
      if (dprev <= 0 && delta > 0 && t_in < 0) t_in = t - dt * delta / (delta - dprev);
      if (dprev > 0 && delta <= 0 && t_in >= 0) {
        t_out   = t - dt * delta / (delta - dprev);
        *e_meas = (c->wall ? pa.v[2] : pa.v[2] - pb.v[2]) / vrel0;
      }
      dprev = delta;
      PetscCall(DemStep(dem));
    }
    *tc_meas = t_out - t_in;
    *tc_ref  = tc;
    PetscCall(TestDemDestroy(&dom, &dem));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  const Impact cases[] = {
    {"linear", PETSC_FALSE, 0.75, 0.5},
    {"linear", PETSC_TRUE, 0.75, 0.5},
    {"linear_nohist", PETSC_FALSE, 0.75, 0.5},
    {"hertz", PETSC_FALSE, 0.75, 0.5},
    {"hertz", PETSC_TRUE, 0.75, 0.5},
    {"hertz", PETSC_FALSE, 1.0, 0.5},
  };

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
    const Impact *c  = &cases[k];
    double        em = 0, tm = 0, tr = 1;
    PetscCall(RunImpact(c, 1.0 / 50, &em, &tm, &tr));
    /* linear: the closed form, not the code's figure: x'' + 2 zeta w x' + w^2 x = 0 with
       e = exp(-zeta pi / sqrt(1 - zeta^2)) lasts pi / w_d = sqrt(m* (pi^2 + ln^2 e) / kn) */
    if (strncmp(c->law, "linear", 6) == 0) {
      const double r = 0.005, m = 2500 * 4.0 / 3.0 * PETSC_PI * r * r * r, ms = c->wall ? m : m / 2, le = log(c->e);
      tr = sqrt(ms * (PETSC_PI * PETSC_PI + le * le) / 1e4);
    }
    PetscCall(CheckClose(CheckName("restitution %s %s e=%g", c->law, c->wall ? "sphere-wall" : "sphere-sphere", c->e), em, c->e, 0.01));
    PetscCall(CheckClose(CheckName("contact time %s %s e=%g [s]", c->law, c->wall ? "sphere-wall" : "sphere-sphere", c->e), tm, tr, 0.02));
    if (!strcmp(c->law, "hertz") && c->e == 1.0) { /* the closed-form Hertz time, independent of our reduced solver */
      const double r = 0.005, m = 2500 * 4.0 / 3.0 * PETSC_PI * r * r * r, ms = m / 2, rs = r / 2;
      const double es = 1e7 / (2 * (1 - 0.09)), v = 1.0;
      const double th = 2.8683 * pow(ms * ms / (rs * es * es * v), 0.2);
      PetscCall(CheckClose("contact time hertz e=1 vs closed form 2.8683 (m*^2/(R* E*^2 v))^(1/5) [s]", tm, th, 0.02));
    }
  }
  { /* strong damping: the dashpot sees the half-step velocity, so the restitution error is
       at least first order in dt; it must fall > 3x from dt = Tc/50 to Tc/200 */
    const Impact c  = {"linear_nohist", PETSC_FALSE, 0.3, 0.5};
    double       e1 = 0, e2 = 0, tm, tr;
    PetscCall(RunImpact(&c, 1.0 / 50, &e1, &tm, &tr));
    PetscCall(RunImpact(&c, 1.0 / 200, &e2, &tm, &tr));
    const double r1 = PetscAbsReal(e1 - 0.3) / 0.3, r2 = PetscAbsReal(e2 - 0.3) / 0.3;
    CheckDetail("errors %.2e at Tc/50, %.2e at Tc/200", r1, r2);
    PetscCall(CheckAbove("restitution e=0.3 converges in dt (first order or better): error ratio Tc/50 to Tc/200", r1 / r2, 3.0));
    PetscCall(CheckClose("restitution e=0.3 at Tc/200", e2, 0.3, 0.015));
  }
  PetscCall(PetscFinalize());
  return check_failures ? 1 : 0;
}
