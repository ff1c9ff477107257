/* Rolling resistance (-dem_rolling_model, contact_laws.h) against rigid-body references.
 * A solid sphere (I = 2/5 m r^2) rolling without slip on a wall with the rolling torque M about
 * its centre and friction F at the contact: m a = m g sin(theta) - F, I a / r = F r - M, so
 *   a = 5/7 (g sin(theta) - M / (m r)).
 *   constant model, M = mu_r r |Fn| = mu_r r m g cos(theta):
 *     a = 5/7 g (sin(theta) - mu_r cos(theta)); on the flat a = -5/7 mu_r g, a stop at v0 / a;
 *     at rest (a = 0) the torque needed is F r = m g r sin(theta), held while tan(theta) <= mu_r.
 *     The cap I |w| / (12 dt) (no reversal within a step) makes the hold a creep at the speed
 *     where I w / (12 dt) = m g r sin(theta): v = r w = 30 g sin(theta) dt (the rest tolerance).
 *   viscous model, M = mu_r r |Fn| |V_w|, |V_w| = r |w|: on the flat dw/dt = -5/7 mu_r g w,
 *     v = v0 exp(-5/7 mu_r g t); on a slope the terminal speed v = tan(theta) / mu_r.
 * A pair (no gravity, no friction, e = 1) pushed apart from an overlap delta0 with spins w_i
 * (perpendicular to n) and w_j = 0: the normal impulse J = delta0 sqrt(kn m*) turns spin by
 * -mu_r R* J / I_i on i and +mu_r R* J / I_j on j (constant model; viscous: times |V_w| = r_i w_i,
 * nearly constant over the contact); I_i w_i + I_j w_j is conserved to round-off.
 * A frictionless sphere in a drum turning at omega spins up at 5/2 mu_r g / r to omega (w_rel
 * counts the wall's rotation) and stays there.
 * Grains3D's k_ms, M = -k_ms |Fn| (w_t + 1e-3 w_n): rolling v ~ exp(-5/7 k_ms g t / r^2), a spin
 * about the normal w ~ exp(-1e-3 k_ms m g t / I).
 * Linear and Hertz laws, one size per shape and spheres of their own sizes. */
#include "dem_common.h"

#define NS 400 /* samples, one per ms */

typedef struct {
  const char *law, *model;
  double      mur, tan_th, v0; /* v0: launched rolling without slip along +x */
  double      wz0;             /* initial spin about the wall's normal (rad/s) */
  PetscBool   own;             /* spheres of their own sizes */
  double      tend;
} RollCase;

typedef struct {
  double v[NS], x[NS], wz[NS]; /* v_x, x and the spin about the normal each ms */
  double vend, wend;
} RollRun;

static const double R = 0.005, G = 9.81, RHO = 2500, KN = 1e5, DT = 5e-6;

static PetscErrorCode Run(const RollCase *c, RollRun *o)
{
  const double th = atan(c->tan_th), m = RHO * 4.0 / 3.0 * PETSC_PI * R * R * R;
  char         opts[1024], stiff[64];
  Domain       dom;
  Dem          dem;
  double       t = 0;
  PetscInt     s = 0;

  PetscFunctionBeginUser;
  if (strcmp(c->law, "hertz")) PetscCall(PetscSNPrintf(stiff, sizeof stiff, "-dem_kn %g", KN));
  else PetscCall(PetscSNPrintf(stiff, sizeof stiff, "-dem_youngs_modulus 5e7"));
  PetscCall(PetscSNPrintf(opts, sizeof opts, "-domain_lo -1,-1,-0.1 -domain_hi 4,1,0.1 -dem_radius %g -dem_density %g -dem_contact_law %s %s -dem_restitution 0.5 -dem_friction 0.5 -dem_gravity %.17g,0,%.17g -dem_dt %g -dem_impact_velocity 0.1 -dem_plane_0 0,0,0,0,0,1 -dem_rolling_model %s -dem_rolling_friction %g", R, RHO, c->law, stiff, G * sin(th), -G * cos(th), DT, c->model, c->mur));
  PetscCall(TestDemCreate(opts, &dom, &dem));
  if (c->own) PetscCall(DemSetOwnSizes(dem, 0.5 * R, R));
  DemParticle p = {.id = 7, .shape = 0, .x = {0, 0, R - m * G * cos(th) / KN}, .v = {c->v0, 0, 0}, .w = {0, c->v0 / R, c->wz0}, .q = {1, 0, 0, 0}, .r = c->own ? R : 0};
  PetscCall(DemAddParticle(dem, &p));
  PetscCall(DemSetUp(dem));
  while (t < c->tend - 1e-9) {
    const DemParticle q = TestGet(dem, 7);
    if (s % 200 == 0 && s / 200 < NS) {
      o->v[s / 200]  = q.v[0];
      o->x[s / 200]  = q.x[0];
      o->wz[s / 200] = q.w[2];
    }
    PetscCall(DemStep(dem));
    PetscCall(DemGetTime(dem, &t, NULL));
    s++;
  }
  o->vend = TestGet(dem, 7).v[0];
  o->wend = TestGet(dem, 7).w[1];
  PetscCall(TestDemDestroy(&dom, &dem));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Deceleration and stop on the flat, constant model. */
static PetscErrorCode FlatConstant(const char *law, PetscBool own)
{
  const double   mur = 0.05, v0 = 0.05, a = 5.0 / 7.0 * mur * G, ts = v0 / a; /* stop at 0.143 s */
  const RollCase c = {law, "constant", mur, 0, v0, 0, own, 0.3};
  RollRun        o;

  PetscFunctionBeginUser;
  PetscCall(Run(&c, &o));
  const double am = -(o.v[120] - o.v[20]) / 0.1; /* 0.02 s .. 0.12 s, before the stop */
  PetscCall(CheckClose(CheckName("%s%s constant: deceleration [m/s^2] vs 5/7 mu_r g", law, own ? " own sizes" : ""), am, a, 0.01));
  PetscCall(CheckClose(CheckName("%s%s constant: distance to the stop [m] vs v0^2 / (2 a)", law, own ? " own sizes" : ""), o.x[NS / 4 * 3 - 1] - o.x[0], 0.5 * v0 * ts, 0.01));
  /* at rest: an uncapped torque (flipping with the spin) keeps a limit cycle of 0.04-0.35 a dt
     with the tangential spring (measured, linear and Hertz); the cap lets the spring's recoil
     after the stop decay geometrically, well below 1e-3 a dt by 2 t_stop */
  PetscCall(CheckBelow(CheckName("%s%s constant: |v| at 2 t_stop [m/s] vs 1e-3 a dt (at rest, no chatter)", law, own ? " own sizes" : ""), PetscAbsReal(o.vend), 1e-3 * a * DT));
  PetscCall(CheckBelow(CheckName("%s%s constant: |r w| at 2 t_stop [m/s] vs 1e-3 a dt (at rest, no chatter)", law, own ? " own sizes" : ""), PetscAbsReal(R * o.wend), 1e-3 * a * DT));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* At rest below tan(theta) = mu_r (creep of the cap only), rolling above at 5/7 g (sin - mu_r cos). */
static PetscErrorCode Slope(const char *law)
{
  const double mur = 0.05, f[4] = {0.5, 0.9, 2.0, 4.0};

  PetscFunctionBeginUser;
  for (int k = 0; k < 4; k++) {
    const double   th = atan(f[k] * mur);
    const RollCase c  = {law, "constant", mur, f[k] * mur, 0, 0, PETSC_FALSE, 0.2};
    RollRun        o;
    PetscCall(Run(&c, &o));
    if (f[k] < 1) {
      const double creep = 30 * G * sin(th) * DT, free = 0.5 * 5.0 / 7.0 * G * sin(th) * 0.2 * 0.2;
      PetscCall(CheckBelow(CheckName("%s tan(theta) = %.1f mu_r: distance in 0.2 s [m] vs the cap's creep 30 g sin dt t (rolling freely: %.2g m)", law, f[k], free), o.x[199] - o.x[0], 1.5 * creep * 0.2));
    } else {
      const double a = (o.v[199] - o.v[100]) / 0.099, ref = 5.0 / 7.0 * G * (sin(th) - mur * cos(th));
      PetscCall(CheckClose(CheckName("%s tan(theta) = %.1f mu_r: a [m/s^2] vs 5/7 g (sin - mu_r cos)", law, f[k]), a, ref, 0.01));
    }
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode Viscous(const char *law)
{
  const double mur = 0.5, v0 = 0.05, k = 5.0 / 7.0 * mur * G; /* mu_r in s/m */
  RollRun      o;

  PetscFunctionBeginUser;
  {
    const RollCase c = {law, "viscous", mur, 0, v0, 0, PETSC_FALSE, 0.2};
    PetscCall(Run(&c, &o));
    PetscCall(CheckClose(CheckName("%s viscous: v(0.15 s) / v(0.05 s) vs exp(-5/7 mu_r g 0.1 s)", law), o.v[150] / o.v[50], exp(-k * 0.1), 0.01));
  }
  {
    const double   muv = 5, tn = 0.1; /* relaxes at 5/7 muv g = 35 /s: terminal within 0.3 s */
    const RollCase c = {law, "viscous", muv, tn, 0, 0, PETSC_FALSE, 0.3};
    PetscCall(Run(&c, &o));
    PetscCall(CheckClose(CheckName("%s viscous on tan(theta) = %g: terminal speed [m/s] vs tan(theta) / mu_r", law, tn), o.vend, tn / muv, 0.01));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Grains3D's k_ms: rolling decays at 5/7 k_ms g / r^2, a spin about the normal at 1e-3 k_ms m g / I. */
static PetscErrorCode Kms(const char *law)
{
  const double kms = 1e-5, v0 = 0.05, k = 5.0 / 7.0 * kms * G / (R * R); /* 2.8 /s */
  const double kt = 1e-2, W = 10, kz = 1e-3 * kt * G / (0.4 * R * R);    /* 9.8 /s */
  RollRun      o;

  PetscFunctionBeginUser;
  {
    const RollCase c = {law, "kms", kms, 0, v0, 0, PETSC_FALSE, 0.2};
    PetscCall(Run(&c, &o));
    PetscCall(CheckClose(CheckName("%s kms: v(0.15 s) / v(0.05 s) vs exp(-5/7 k_ms g / r^2 0.1 s)", law), o.v[150] / o.v[50], exp(-k * 0.1), 0.01));
  }
  {
    const RollCase c = {law, "kms", kt, 0, 0, W, PETSC_FALSE, 0.2};
    PetscCall(Run(&c, &o));
    PetscCall(CheckClose(CheckName("%s kms: spin about the normal w(0.15 s) / w(0.05 s) vs exp(-1e-3 k_ms m g / I 0.1 s)", law), o.wz[150] / o.wz[50], exp(-kz * 0.1), 0.01));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* A frictionless sphere resting in a drum turning at omega about y: w_rel = w - omega u, so the
 * constant model spins it up at 5/2 mu_r g / r until w = omega u, then holds it there. */
static PetscErrorCode Drum(void)
{
  const double mur = 0.01, om = 1.0, Rd = 0.05, m = RHO * 4.0 / 3.0 * PETSC_PI * R * R * R, al = 2.5 * mur * G / R; /* 49 rad/s^2 */
  char         opts[1024];
  Domain       dom;
  Dem          dem;
  double       t = 0, w1 = 0;

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(opts, sizeof opts, "-domain_lo -0.06,-0.06,-0.06 -domain_hi 0.06,0.06,0.06 -dem_radius %g -dem_density %g -dem_kn %g -dem_restitution 0.5 -dem_friction 0 -dem_dt %g -dem_cylinder 0,0,0,0,1,0,%g -dem_cylinder_omega %g -dem_rolling_model constant -dem_rolling_friction %g", R, RHO, KN, DT, Rd, om, mur));
  PetscCall(TestDemCreate(opts, &dom, &dem));
  DemParticle p = {.id = 7, .shape = 0, .x = {0, 0, -Rd + R - m * G / KN}, .q = {1, 0, 0, 0}};
  PetscCall(DemAddParticle(dem, &p));
  PetscCall(DemSetUp(dem));
  while (t < 0.1 - 1e-9) {
    if (PetscAbsReal(t - 0.01) < 0.5 * DT) w1 = TestGet(dem, 7).w[1];
    PetscCall(DemStep(dem));
    PetscCall(DemGetTime(dem, &t, NULL));
  }
  PetscCall(CheckClose(CheckName("drum at omega, frictionless sphere: spin at 0.01 s [rad/s] vs 5/2 mu_r g t / r"), w1, al * 0.01, 0.01));
  PetscCall(CheckBelow(CheckName("drum at omega: |w - omega| / omega at 0.1 s (spun up to the wall's rotation, no overshoot)"), PetscAbsReal(TestGet(dem, 7).w[1] - om) / om, 1e-6));
  PetscCall(TestDemDestroy(&dom, &dem));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Two spheres pushed apart from an overlap, spinning about z (n along x). */
static PetscErrorCode Pair(const char *model, PetscBool own)
{
  const double ri = R, rj = own ? 0.8 * R : R, mi = RHO * 4.0 / 3.0 * PETSC_PI * ri * ri * ri, mj = RHO * 4.0 / 3.0 * PETSC_PI * rj * rj * rj;
  const double Ii = 0.4 * mi * ri * ri, Ij = 0.4 * mj * rj * rj, ms = mi * mj / (mi + mj), rs = ri * rj / (ri + rj);
  const double d0 = 1e-5, W = 10, mur = strcmp(model, "kms") ? 0.05 : 1e-5, J = d0 * sqrt(KN * ms);
  char         opts[1024];
  Domain       dom;
  Dem          dem;

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(opts, sizeof opts, "-domain_lo -0.05,-0.05,-0.05 -domain_hi 0.05,0.05,0.05 -dem_radius %g -dem_density %g -dem_kn %g -dem_restitution 1 -dem_friction 0 -dem_gravity 0,0,0 -dem_dt 1e-6 -dem_rolling_model %s -dem_rolling_friction %g", R, RHO, KN, model, mur));
  PetscCall(TestDemCreate(opts, &dom, &dem));
  if (own) PetscCall(DemSetOwnSizes(dem, rj, ri));
  DemParticle a = {.id = 0, .shape = 0, .x = {-ri + 0.5 * d0, 0, 0}, .w = {0, 0, W}, .q = {1, 0, 0, 0}, .r = own ? ri : 0};
  DemParticle b = {.id = 1, .shape = 0, .x = {rj - 0.5 * d0, 0, 0}, .q = {1, 0, 0, 0}, .r = own ? rj : 0};
  PetscCall(DemAddParticle(dem, &a));
  PetscCall(DemAddParticle(dem, &b));
  PetscCall(DemSetUp(dem));
  for (int s = 0; s < 2000; s++) PetscCall(DemStep(dem)); /* the contact lasts pi/2 sqrt(m* / kn), 0.13 ms */
  const DemParticle pa = TestGet(dem, 0), pb = TestGet(dem, 1);
  const char       *tag = own ? " own sizes" : "";
  if (!strcmp(model, "constant")) {
    PetscCall(CheckClose(CheckName("pair%s constant: spin change of i [rad/s] vs -mu_r R* J / I_i", tag), pa.w[2] - W, -mur * rs * J / Ii, 1e-3));
    PetscCall(CheckClose(CheckName("pair%s constant: spin change of j [rad/s] vs +mu_r R* J / I_j", tag), pb.w[2], mur * rs * J / Ij, 1e-3));
  } else if (!strcmp(model, "viscous")) /* |V_w| = r_i W, frozen over the contact: the spin itself changes by 0.4% */
    PetscCall(CheckClose(CheckName("pair%s viscous: spin change of i [rad/s] vs -mu_r R* J r_i W / I_i", tag), pa.w[2] - W, -mur * rs * J * ri * W / Ii, 1e-2));
  else /* linear in w_rel: w_rel' = -k_ms Fn (1/I_i + 1/I_j) w_rel */
    PetscCall(CheckClose(CheckName("pair%s kms: w_i - w_j [rad/s] vs W exp(-k_ms J (1/I_i + 1/I_j))", tag), pa.w[2] - pb.w[2], W * exp(-mur * J * (1 / Ii + 1 / Ij)), 1e-3));
  PetscCall(CheckBelow(CheckName("pair%s %s: spin angular momentum I_i w_i + I_j w_j, relative change", tag, model), PetscAbsReal((Ii * pa.w[2] + Ij * pb.w[2]) / (Ii * W) - 1), 1e-13));
  PetscCall(TestDemDestroy(&dom, &dem));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  const char *laws[] = {"linear", "hertz"};

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  for (int l = 0; l < 2; l++) {
    PetscCall(FlatConstant(laws[l], PETSC_FALSE));
    PetscCall(Slope(laws[l]));
    PetscCall(Viscous(laws[l]));
    PetscCall(Kms(laws[l]));
  }
  PetscCall(FlatConstant("linear", PETSC_TRUE));
  PetscCall(Drum());
  PetscCall(Pair("constant", PETSC_FALSE));
  PetscCall(Pair("constant", PETSC_TRUE));
  PetscCall(Pair("viscous", PETSC_FALSE));
  PetscCall(Pair("kms", PETSC_TRUE));
  PetscCall(PetscFinalize());
  return check_failures ? 1 : 0;
}
