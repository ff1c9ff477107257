/* Spheres of their own sizes (a scene declared with DemSetOwnSizes): normal impacts of two
 * unequal spheres head-on and of a small and a large sphere on a wall, no gravity, no friction.
 * Each contact uses the pair's own effective mass m* = m1 m2/(m1 + m2) and radius
 * R* = r1 r2/(r1 + r2) (a wall: m* = m, R* = r), never the shapes' (material) radius.
 * References, computed here from the radii and the options, not from the code:
 *   linear, -dem_kn given: the damped oscillator's half period Tc = sqrt(m* (pi^2 + ln^2 e)/kn);
 *   linear, kn from -dem_youngs_modulus: the same with the Hertz-equivalent stiffness at the
 *     impact speed V, kn = 16/15 sqrt(R*) E* (15 m* V^2 / (16 sqrt(R*) E*))^(1/5);
 *   hertz, undamped (e = 1): the closed form 2.8683 (m*^2 / (R* E*^2 v))^(1/5) (Hertz 1882;
 *     Johnson, Contact Mechanics §11.4); damped: the law's restitution map at the pair's m*, R*
 *     (DemGetContactFiguresSized).
 * Restitution equal to the set e. dt = Tc/50. Bounds: restitution 1%, contact time 2% (the
 * linear law is exact up to the step; the contact start and end are interpolated). A control:
 * the material shape's radius (5 mm) is neither size, so a loop that read it would be off by far
 * more than the bounds. */
#include "dem_common.h"

typedef struct {
  const char *law, *stiff; /* -dem_contact_law; "kn" or "E" (linear) */
  PetscBool   wall;
  double      ra, rb, e, v; /* radii (m; rb: the partner, unused on a wall), restitution, speed of each (m/s) */
} PolyImpact;

static const double rho = 2500, kn = 1e4, E = 1e7, nu = 0.3;

static double mass(double r)
{
  return rho * 4.0 / 3.0 * PETSC_PI * r * r * r;
}

static PetscErrorCode RunPolyImpact(const PolyImpact *c, double *e_meas, double *tc_meas, double *tc_code)
{
  const double vrel0 = c->wall ? c->v : 2 * c->v;
  char         opts[1024];
  double       dt = 1e-9, t_in = -1, t_out = -1, dprev = -1, tc = 0, e;

  PetscFunctionBeginUser;
  for (int pass = 0; pass < 2; pass++) { /* pass 0 asks the code's Tc for the time step only */
    Domain dom;
    Dem    dem;
    PetscCall(PetscSNPrintf(opts, sizeof opts, "-domain_lo -0.05,-0.05,-0.05 -domain_hi 0.05,0.05,0.05 -dem_radius 0.005 -dem_density %g -dem_contact_law %s %s -dem_restitution %g -dem_friction 0 -dem_gravity 0,0,0 -dem_dt %g -dem_impact_velocity %g %s", rho, c->law, strcmp(c->stiff, "kn") ? "-dem_youngs_modulus 1e7 -dem_poisson_ratio 0.3" : "-dem_kn 1e4", c->e, dt, vrel0, c->wall ? "-dem_plane_0 0,0,0,0,0,1" : ""));
    PetscCall(TestDemCreate(opts, &dom, &dem));
    PetscCall(DemSetOwnSizes(dem, PetscMin(c->ra, c->rb), PetscMax(c->ra, c->rb)));
    DemParticle a = {.id = 0, .shape = 0, .x = {0, 0, 1.01 * c->ra}, .v = {0, 0, -c->v}, .q = {1, 0, 0, 0}, .r = c->ra};
    DemParticle b = {.id = 1, .shape = 0, .x = {0, 0, -1.01 * c->rb}, .v = {0, 0, c->v}, .q = {1, 0, 0, 0}, .r = c->rb};
    PetscCall(DemAddParticle(dem, &a));
    if (!c->wall) PetscCall(DemAddParticle(dem, &b));
    PetscCall(DemSetUp(dem));
    if (pass == 0) {
      PetscCall(DemGetContactFiguresSized(dem, 0, c->wall ? -1 : 0, c->ra, c->rb, vrel0, &tc, &e));
      dt = tc / 50;
      PetscCall(TestDemDestroy(&dom, &dem));
      continue;
    }
    for (int s = 0; s < 1000000 && t_out < 0; s++) {
      DemParticle pa = TestGet(dem, 0), pb = TestGet(dem, 1);
      double      delta = c->wall ? c->ra - pa.x[2] : c->ra + c->rb - (pa.x[2] - pb.x[2]), t;
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
    *tc_code = tc;
    PetscCall(TestDemDestroy(&dom, &dem));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The analytic contact time of case c (see the header); hertz damped: NAN (the code's map). */
static double PolyReference(const PolyImpact *c)
{
  const double ma = mass(c->ra), mb = mass(c->rb), ms = c->wall ? ma : ma * mb / (ma + mb), rs = c->wall ? c->ra : c->ra * c->rb / (c->ra + c->rb);
  const double es = c->wall ? 1.0 / ((1 - nu * nu) / E + (1 - nu * nu) / E) : E / (2 * (1 - nu * nu)), le = log(c->e), V = c->wall ? c->v : 2 * c->v;
  if (!strcmp(c->law, "hertz")) return c->e == 1.0 ? 2.8683 * pow(ms * ms / (rs * es * es * V), 0.2) : NAN;
  const double k = strcmp(c->stiff, "kn") ? 16.0 / 15.0 * sqrt(rs) * es * pow(15.0 * ms * V * V / (16.0 * sqrt(rs) * es), 0.2) : kn;
  return sqrt(ms * (PETSC_PI * PETSC_PI + le * le) / k);
}

int main(int argc, char **argv)
{
  const PolyImpact cases[] = {
    {"linear", "kn", PETSC_FALSE, 0.003, 0.008, 0.75, 0.5},
    {"linear", "E", PETSC_FALSE, 0.003, 0.008, 0.75, 0.5},
    {"linear_nohist", "kn", PETSC_FALSE, 0.008, 0.004, 0.6, 0.5},
    {"hertz", "E", PETSC_FALSE, 0.003, 0.008, 0.75, 0.5},
    {"hertz", "E", PETSC_FALSE, 0.003, 0.008, 1.0, 0.5},
    {"linear", "kn", PETSC_TRUE, 0.003, 0.003, 0.75, 0.5},
    {"linear", "E", PETSC_TRUE, 0.008, 0.008, 0.75, 0.5},
    {"hertz", "E", PETSC_TRUE, 0.008, 0.008, 0.75, 0.5},
    {"hertz", "E", PETSC_TRUE, 0.003, 0.003, 1.0, 0.5},
  };

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
    const PolyImpact *c  = &cases[k];
    double            em = 0, tm = 0, tcode = 1, tr = PolyReference(c);
    char              what[128];
    PetscCall(RunPolyImpact(c, &em, &tm, &tcode));
    if (c->wall) PetscCall(PetscSNPrintf(what, sizeof what, "%s (%s) r=%.0f mm on a wall", c->law, c->stiff, 1e3 * c->ra));
    else PetscCall(PetscSNPrintf(what, sizeof what, "%s (%s) r=%.0f mm with r=%.0f mm", c->law, c->stiff, 1e3 * c->ra, 1e3 * c->rb));
    PetscCall(CheckClose(CheckName("restitution %s, e=%g", what, c->e), em, c->e, 0.01));
    if (tr != tr) PetscCall(CheckClose(CheckName("contact time %s, e=%g vs the law's restitution map at m*, R* [s]", what, c->e), tm, tcode, 0.02));
    else PetscCall(CheckClose(CheckName("contact time %s, e=%g vs the analytic Tc of m*, R* [s]", what, c->e), tm, tr, 0.02));
  }
  PetscCall(PetscFinalize());
  return check_failures ? 1 : 0;
}
