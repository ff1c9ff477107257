/* Polygon, hopper and rotating-cylinder walls (src/dem/walls_polygon.c, walls_cylinder.c) against
 * rigid-body references; one sphere, gravity -z, m = rho 4/3 pi r^3, linear law unless stated.
 *  1. A sphere at rest in a static horizontal cylinder of radius R sits at R - r + mg/kn from
 *     the axis (the overlap balances its weight); bound 1% of the overlap.
 *  2. A rotating drum is a moving wall: a sphere at rest on the bottom of a drum whose surface
 *     moves at V = omega R is dragged by kinetic friction mu m g like a sphere dropped on a belt,
 *     its contact-point slip decays at 3.5 mu g, so it rolls without slip from t* = 2V/(7 mu g)
 *     on, with speed 2/7 V (R = 0.5 m: the climb by t* is 4e-5 of R); the contact-point velocity
 *     of the sphere then equals the drum's (slip < 1% of V). Same for a co-rotating end cap
 *     (-dem_cylinder_caps), sphere at rho from the axis: v(t*) = 2/7 omega rho.
 *  3. A sphere on a hopper plate at theta = 62.5 deg slides at g (sin theta - mu cos theta) when
 *     tan theta > 3.5 mu (mu = 0.5), rolls at 5/7 g sin theta below (mu = 0.6); 1%.
 *  4. The orifice rim: a sphere wider than the opening (a < r < a / sin theta: no face contact)
 *     rests on the four rim edges at height h with sqrt(a^2 + h^2) = r - delta and
 *     4 kn delta h / (r - delta) = m g (frictionless: with friction the rest height depends on
 *     the history); a sphere narrower than the opening falls through.
 *  5. A horizontal convex quadrilateral (-dem_quad_0, a kite): a sphere over it rests at
 *     z = r - mg/kn (1% of the overlap); one beside it, inside its bounding box, falls past.
 * Run on 1 and 2 ranks: the sphere migrates with its wall springs. */
/* ranks: 1 2 */
#include "dem_common.h"

static const double g = 9.81, rho = 2500;

static double dot3(const double *a, const double *b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void cross3(const double *a, const double *b, double *c)
{
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}

/* x, v, w of particle 0, from whichever rank owns it, and in s[9] the number of owners; when
 * that is not 1 (lost, or doubled) x, v, w are NaN, which fails every check made on them. */
static PetscErrorCode Get(Dem dem, double s[10])
{
  double   loc[10] = {0};
  PetscInt i       = TestFind(dem, 0);

  PetscFunctionBeginUser;
  if (i >= 0) {
    DemParticle p = {0};
    PetscCall(DemGetParticle(dem, i, &p));
    for (int k = 0; k < 3; k++) {
      loc[k]     = p.x[k];
      loc[3 + k] = p.v[k];
      loc[6 + k] = p.w[k];
    }
    loc[9] = 1;
  }
  PetscCallMPI(MPI_Allreduce(loc, s, 10, MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD));
  if (s[9] != 1)
    for (int k = 0; k < 9; k++) s[k] = NAN;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Builds the scene, puts particle 0 at x0 (rank 0 adds it), runs to t1 (state s1) and t2 (s2). */
static PetscErrorCode Run(const char *opts, const double x0[3], double t1, double t2, double s1[10], double s2[10])
{
  Domain      dom;
  Dem         dem;
  PetscReal   t = 0;
  PetscMPIInt rank;

  PetscFunctionBeginUser;
  PetscCall(TestDemCreate(opts, &dom, &dem));
  PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
  if (!rank) {
    DemParticle p = {.id = 0, .shape = 0, .x = {x0[0], x0[1], x0[2]}, .q = {1, 0, 0, 0}};
    PetscCall(DemAddParticle(dem, &p));
  }
  PetscCall(DemSetUp(dem));
  PetscBool got1 = PETSC_FALSE;
  while (t < t2 - 1e-12) {
    if (!got1 && t >= t1 - 1e-12) {
      PetscCall(Get(dem, s1));
      got1 = PETSC_TRUE;
    }
    PetscCall(DemStep(dem));
    PetscCall(DemGetTime(dem, &t, NULL));
  }
  if (!got1) PetscCall(Get(dem, s1));
  PetscCall(Get(dem, s2));
  PetscCall(TestDemDestroy(&dom, &dem));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode StaticCylinder(void)
{
  const double r = 0.005, R = 0.05, kn = 1e3, m = rho * 4.0 / 3.0 * PETSC_PI * r * r * r, delta = m * g / kn;
  const double x0[3] = {0, 0, -(R - r) + 0.2 * r};
  double       s1[10], s2[10];
  char         opts[1024];

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(opts, sizeof opts, "-domain_lo -0.06,-0.06,-0.06 -domain_hi 0.06,0.06,0.06 -dem_radius %g -dem_density %g -dem_contact_law linear -dem_kn %g -dem_restitution 0.3 -dem_friction 0.3 -dem_dt 1e-5 -dem_cylinder 0,0,0,1,0,0,%g", r, rho, kn, R));
  PetscCall(Run(opts, x0, 0.3, 0.3, s1, s2));
  const double d = sqrt(s2[1] * s2[1] + s2[2] * s2[2]), ref = R - r + delta;
  CheckDetail("bound 1e-2 of the overlap mg/kn = %.3g m", delta);
  PetscCall(CheckCloseAbs("static cylinder: rest distance from the axis [m] vs analytic R - r + mg/kn", d, ref, 1e-2 * delta));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Sphere at rest on a rotating surface moving at V under it: v(t*) = 2/7 V, then no slip. */
static PetscErrorCode Belt(const char *what, const char *law, const char *walls, const double x0[3], const double dir[3], double V, const double axp[3], const double axu[3], double omega)
{
  const double r = 0.005, mu = 0.3, ts = 2 * V / (7 * mu * g);
  double       s1[10], s2[10];
  char         opts[1024];

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(opts, sizeof opts, "-domain_lo -0.55,-0.55,-0.55 -domain_hi 0.55,0.55,0.55 -dem_radius %g -dem_density %g -dem_contact_law %s -dem_kn 1e5 -dem_restitution 0.5 -dem_friction %g -dem_dt 2e-6 -dem_impact_velocity 0.1 %s", r, rho, law, mu, walls));
  PetscCall(Run(opts, x0, ts, 2 * ts, s1, s2));
  const double v1 = dot3(s1 + 3, dir), ref = 2.0 / 7.0 * V;
  PetscCall(CheckClose(CheckName("%s (%s): v(t* = 2V/(7 mu g)) [m/s] vs analytic 2/7 V", what, law), v1, ref, 1e-2));
  /* slip at 2 t*: sphere contact point x - r e (e from the wall to the centre: -g for a floor
     under the sphere) against the wall's omega u x (c - a) */
  const double e[3] = {0, 0, 1};
  double       c[3], vc[3], vw[3], t[3], d[3];
  for (int k = 0; k < 3; k++) c[k] = s2[k] - r * e[k];
  cross3(s2 + 6, (double[3]){-r * e[0], -r * e[1], -r * e[2]}, t);
  for (int k = 0; k < 3; k++) {
    vc[k] = s2[3 + k] + t[k];
    d[k]  = c[k] - axp[k];
  }
  cross3(axu, d, vw);
  for (int k = 0; k < 3; k++) vw[k] = omega * vw[k] - vc[k];
  const double slip = sqrt(dot3(vw, vw)) / V;
  PetscCall(CheckBelow(CheckName("%s (%s): rolls without slip at 2 t*: |v_contact - v_wall| / V", what, law), slip, 1e-2));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode HopperPlate(double mu)
{
  const double r = 0.005, kn = 1e5, m = rho * 4.0 / 3.0 * PETSC_PI * r * r * r, th = atan(1.729 / 0.9);
  const double n[3] = {sin(th), 0, cos(th)}, up[3] = {-cos(th), 0, sin(th)}, s = 1.5, delta = m * g * cos(th) / kn;
  const double x0[3] = {-(0.1 + s * cos(th)) + (r - delta) * n[0], 0, s * sin(th) + (r - delta) * n[2]};
  double       s1[10], s2[10];
  char         opts[1024];

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(opts, sizeof opts, "-domain_lo -1.1,-1.1,-0.5 -domain_hi 1.1,1.1,2 -dem_radius %g -dem_density %g -dem_contact_law linear -dem_kn %g -dem_restitution 0.5 -dem_friction %g -dem_dt 5e-6 -dem_impact_velocity 0.1 -dem_hopper 0,0,1.729,1.0,0,0.1", r, rho, kn, mu));
  PetscCall(Run(opts, x0, 0.1, 0.3, s1, s2));
  const PetscBool roll = (PetscBool)(tan(th) <= 3.5 * mu);
  const double    a = -(dot3(s2 + 3, up) - dot3(s1 + 3, up)) / 0.2, ref = roll ? 5.0 / 7.0 * g * sin(th) : g * (sin(th) - mu * cos(th));
  PetscCall(CheckClose(CheckName("hopper plate at %.2f deg, mu %.1f (%s): a [m/s^2] vs analytic", th * 180 / PETSC_PI, mu, roll ? "rolling, 5/7 g sin" : "sliding, g (sin - mu cos)"), a, ref, 1e-2));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode Orifice(void)
{
  const double a = 0.02, th = 62.5 * PETSC_PI / 180, zt = 0.08 * tan(th), kn = 1e4;
  double       s1[10], s2[10];
  char         opts[1024];

  PetscFunctionBeginUser;
  { /* a < r < a/sin(theta): held by the rim edges only */
    const double r = 0.021, m = rho * 4.0 / 3.0 * PETSC_PI * r * r * r;
    double       dl = 0, h = 0;
    for (int it = 0; it < 100; it++) { /* 4 kn dl h/(r - dl) = m g, h = sqrt((r - dl)^2 - a^2) */
      h  = sqrt((r - dl) * (r - dl) - a * a);
      dl = m * g * (r - dl) / (4 * kn * h);
    }
    const double x0[3] = {0, 0, h + 0.002};
    PetscCall(PetscSNPrintf(opts, sizeof opts, "-domain_lo -0.12,-0.12,-0.3 -domain_hi 0.12,0.12,0.2 -dem_radius %g -dem_density %g -dem_contact_law linear -dem_kn %g -dem_restitution 0.3 -dem_friction 0 -dem_dt 1e-5 -dem_hopper 0,0,%.17g,0.1,0,%g", r, rho, kn, zt, a));
    PetscCall(Run(opts, x0, 0.5, 0.5, s1, s2));
    CheckDetail("bound 1e-2 of the overlap %.3g m", dl);
    PetscCall(CheckCloseAbs(CheckName("sphere r = %g wider than the orifice half-width %g (< a/sin theta = %.4f): rests on the rim at z [m] vs analytic", r, a, a / sin(th)), s2[2], h, 1e-2 * dl));
  }
  { /* r < a: slides down a plate and through */
    const double r = 0.015, x0[3] = {-0.05, 0, 0.12};
    PetscCall(PetscSNPrintf(opts, sizeof opts, "-domain_lo -0.12,-0.12,-0.3 -domain_hi 0.12,0.12,0.2 -dem_radius %g -dem_density %g -dem_contact_law linear -dem_kn %g -dem_restitution 0.3 -dem_friction 0.3 -dem_dt 1e-5 -dem_hopper 0,0,%.17g,0.1,0,%g", r, rho, kn, zt, a));
    PetscCall(Run(opts, x0, 0.3, 0.3, s1, s2));
    PetscCall(CheckBelow(CheckName("sphere r = %g narrower than the orifice half-width %g: falls through, z(0.3 s) [m]", r, a), s2[2], -0.1));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode Quad(void)
{
  const double r = 0.005, kn = 1e4, m = rho * 4.0 / 3.0 * PETSC_PI * r * r * r, delta = m * g / kn;
  const double inside[3] = {0.01, 0, r}, beside[3] = {-0.03, 0.02, r};
  double       s1[10], s2[10];
  char         opts[1024];

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(opts, sizeof opts, "-domain_lo -0.06,-0.06,-0.2 -domain_hi 0.06,0.06,0.05 -dem_radius %g -dem_density %g -dem_contact_law linear -dem_kn %g -dem_restitution 0.3 -dem_friction 0.3 -dem_dt 1e-5 -dem_quad_0 0,-0.05,0,0.05,0,0,0,0.05,0,-0.02,0,0", r, rho, kn));
  PetscCall(Run(opts, inside, 0.2, 0.2, s1, s2));
  CheckDetail("bound 1e-2 of the overlap mg/kn = %.3g m", delta);
  PetscCall(CheckCloseAbs("quad wall: sphere over it rests at z [m] vs analytic r - mg/kn", s2[2], r - delta, 1e-2 * delta));
  PetscCall(Run(opts, beside, 0.15, 0.15, s1, s2));
  PetscCall(CheckBelow("quad wall: sphere beside it (inside its bounding box) falls past, z(0.15 s) [m]", s2[2], -0.08));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(StaticCylinder());
  {
    const double R = 0.5, r = 0.005, V = 0.1, om = V / R, axp[3] = {0, 0, 0}, axu[3] = {1, 0, 0};
    const double x0[3] = {0, 0, -(R - r) + 1e-7}, dir[3] = {0, 1, 0};
    char         w[256];
    PetscCall(PetscSNPrintf(w, sizeof w, "-dem_cylinder 0,0,0,1,0,0,%g -dem_cylinder_omega %g", R, om));
    PetscCall(Belt("rotating drum bottom", "linear", w, x0, dir, V, axp, axu, om));
    PetscCall(Belt("rotating drum bottom", "linear_nohist", w, x0, dir, V, axp, axu, om));
  }
  {
    const double R = 0.5, r = 0.005, om = 0.2, rho_c = 0.3, axp[3] = {0, 0, -0.5}, axu[3] = {0, 0, 1};
    const double x0[3] = {rho_c, 0, -0.5 + r - 1e-7}, dir[3] = {0, 1, 0};
    char         w[256];
    PetscCall(PetscSNPrintf(w, sizeof w, "-dem_cylinder 0,0,-0.5,0,0,1,%g -dem_cylinder_omega %g -dem_cylinder_caps 0,1", R, om));
    PetscCall(Belt("rotating end cap", "linear", w, x0, dir, om * rho_c, axp, axu, om));
  }
  PetscCall(HopperPlate(0.5));
  PetscCall(HopperPlate(0.6));
  PetscCall(Orifice());
  PetscCall(Quad());
  PetscCall(PetscFinalize());
  return check_failures ? 1 : 0;
}
