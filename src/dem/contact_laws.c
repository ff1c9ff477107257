/* Contact parameters per material pair, precomputed per (shape, shape) and (shape, wall) pair.
 *   linear: kn given, or from E, nu at the impact speed V (Hertz-equivalent stiffness, as the
 *           LIGGGHTS "hooke" model does): kn = 16/15 sqrt(R*) E* (15 m* V^2 / (16 sqrt(R*) E*))^(1/5);
 *           kt = 2/7 kn unless given; gn = 2 zeta sqrt(kn/m*), gt = ratio * gn.
 *   hertz:  E* = 1/((1-nu1^2)/E1 + (1-nu2^2)/E2), G* = 1/((2-nu1)/G1 + (2-nu2)/G2), G = E/(2(1+nu)).
 * The damped Hertz contact x'' = -x^(3/2) - c x^(1/4) x' (x = delta/X, X = (m* V^2/K)^(2/5),
 * K = 4/3 E* sqrt(R*), time unit X/V) has a restitution that depends on c alone; the damping
 * factor of the kernel, c_h = c / sqrt(3/2), is found by bisection on that reduced equation so
 * that the restitution is exactly the one set (the usual closed-form beta(e) is only approximate
 * for Hertz). The same reduced solution gives the contact time at speed V. */
#include "dem/dem_core.h"
#include "dem/dem_walls.h"

/* Integrates the reduced Hertz impact; returns restitution and dimensionless contact time. */
static void dem_hertz_reduced(double c, double *e, double *tau)
{
  const double h = 2e-4;
  double       x = 0, u = 1, t = 0;
  for (;;) {
    if (t > 50) { /* overdamped: the overlap never returns to zero in time, no rebound */
      *tau = t;
      *e   = 0;
      return;
    }
    double k[4][2], xs = x, us = u;
    for (int s = 0; s < 4; s++) {
      const double xx = xs > 0 ? xs : 0;
      k[s][0]         = us;
      k[s][1]         = -xx * sqrt(xx) - c * sqrt(sqrt(xx)) * us;
      const double fr = s < 2 ? 0.5 : 1.0;
      if (s < 3) {
        xs = x + fr * h * k[s][0];
        us = u + fr * h * k[s][1];
      }
    }
    const double xn = x + h / 6 * (k[0][0] + 2 * k[1][0] + 2 * k[2][0] + k[3][0]);
    const double un = u + h / 6 * (k[0][1] + 2 * k[1][1] + 2 * k[2][1] + k[3][1]);
    if (xn <= 0 && t > 0) { /* crossed back through zero overlap: interpolate */
      const double s = x / (x - xn);
      *tau           = t + s * h;
      *e             = -(u + s * (un - u));
      return;
    }
    x = xn;
    u = un;
    t += h;
  }
}

PetscErrorCode DemHertzRestitutionMap(double e, double *ch, double *tau)
{
  double lo = 0, hi = 1, ee, tt;

  PetscFunctionBeginUser;
  if (e >= 1) {
    dem_hertz_reduced(0, &ee, tau);
    *ch = 0;
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  for (dem_hertz_reduced(hi, &ee, &tt); ee > e; dem_hertz_reduced(hi, &ee, &tt)) hi *= 2;
  for (int it = 0; it < 48; it++) { /* restitution decreases with c */
    const double mid = 0.5 * (lo + hi);
    dem_hertz_reduced(mid, &ee, &tt);
    if (ee > e) lo = mid;
    else hi = mid;
  }
  dem_hertz_reduced(0.5 * (lo + hi), &ee, tau);
  *ch = 0.5 * (lo + hi) / sqrt(1.5);
  PetscFunctionReturn(PETSC_SUCCESS);
}

static double dem_zeta(double e)
{
  const double l = log(e);
  return -l / sqrt(PETSC_PI * PETSC_PI + l * l);
}

/* Fills one pair. mb <= 0 / rb <= 0 mean the wall (infinite mass and radius). */
static PetscErrorCode DemPairFill(Dem dem, const DemMaterial *a, const DemMaterial *b, double ma, double ra, double mb, double rb, double ch, DemPairParams *p)
{
  const double e = PetscMin(a->e, b->e), mu = PetscMin(a->mu, b->mu);

  PetscFunctionBeginUser;
  p->meff = mb > 0 ? ma * mb / (ma + mb) : ma;
  p->reff = rb > 0 ? ra * rb / (ra + rb) : ra;
  p->mu   = mu;
  if (a->E_set) {
    const double Ga = a->E / (2 * (1 + a->nu)), Gb = b->E / (2 * (1 + b->nu));
    p->es = 1.0 / ((1 - a->nu * a->nu) / a->E + (1 - b->nu * b->nu) / b->E);
    p->g8 = 8.0 / ((2 - a->nu) / Ga + (2 - b->nu) / Gb);
  }
  p->ch     = ch;
  p->hratio = dem->contact.tdamp_ratio;
  if (b->kn_set) p->kn = b->kn;
  else {
    const double V = dem->contact.vimpact, sr = sqrt(p->reff);
    p->kn = 16.0 / 15.0 * sr * p->es * pow(15.0 * p->meff * V * V / (16.0 * sr * p->es), 0.2);
  }
  p->kt       = b->kt_set ? b->kt : 2.0 / 7.0 * p->kn;
  p->gn       = 2 * dem_zeta(e) * sqrt(p->kn / p->meff);
  p->gt       = dem->contact.tdamp_ratio * p->gn;
  p->zeta     = dem_zeta(e); /* sizes of their own: dem_pair_sized (contact_laws.h) */
  p->vimp     = b->kn_set ? 0 : dem->contact.vimpact;
  p->kt_given = b->kt_set;
  p->mur      = b->mur; /* the particles' for a pair, the walls' for a wall */
  p->ieff     = dem_pair_inertia(ma, ra, mb, rb);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemMaterialsSetUp(Dem dem)
{
  double chp = 0, chw = 0, tau;

  PetscFunctionBeginUser;
  if (dem->contact.law == DEM_LAW_HERTZ) {
    PetscCheck(dem->contact.mat.E_set && dem->contact.wmat.E_set, dem->comm, PETSC_ERR_ARG_WRONG, "-dem_contact_law hertz needs -dem_youngs_modulus (Pa)");
    PetscCall(DemHertzRestitutionMap(dem->contact.mat.e, &chp, &tau));
    PetscCall(DemHertzRestitutionMap(PetscMin(dem->contact.mat.e, dem->contact.wmat.e), &chw, &tau));
  } else {
    PetscCheck(dem->contact.mat.kn_set || dem->contact.mat.E_set, dem->comm, PETSC_ERR_ARG_WRONG, "the linear laws need -dem_kn (N/m) or -dem_youngs_modulus (Pa)");
  }
  for (PetscInt s = 0; s < dem->shapes.nshape; s++) {
    const DemShape *a = &dem->shapes.shp[s];
    for (PetscInt t = 0; t < dem->shapes.nshape; t++) {
      const DemShape *b = &dem->shapes.shp[t];
      PetscCall(DemPairFill(dem, &dem->contact.mat, &dem->contact.mat, a->m, a->req, b->m, b->req, chp, &dem->contact.pp[s * dem->shapes.nshape + t]));
    }
    PetscCall(DemPairFill(dem, &dem->contact.mat, &dem->contact.wmat, a->m, a->req, 0, 0, chw, &dem->contact.pw[s]));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Contact time at impact speed v of the pair parameters p of restitution ee. */
static PetscErrorCode DemPairFigures(Dem dem, const DemPairParams *p, double ee, PetscReal v, PetscReal *tc)
{
  PetscFunctionBeginUser;
  if (dem->contact.law == DEM_LAW_HERTZ) {
    double ch, tau;
    PetscCall(DemHertzRestitutionMap(ee, &ch, &tau));
    const double K = 4.0 / 3.0 * p->es * sqrt(p->reff), X = pow(p->meff * v * v / K, 0.4);
    *tc = tau * X / v;
  } else {
    const double w0 = p->kn / p->meff, g = 0.5 * p->gn;
    *tc = PETSC_PI / sqrt(w0 - g * g);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The (shape, wall) pair parameters of a wall of material wm (a mesh's own material) and their
 * contact times at -dem_impact_velocity (s). */
PetscErrorCode DemWallPairsFill(Dem dem, const DemMaterial *wm, DemPairParams *pw, PetscReal *tc)
{
  double ch = 0, tau;

  PetscFunctionBeginUser;
  if (dem->contact.law == DEM_LAW_HERTZ) PetscCall(DemHertzRestitutionMap(PetscMin(dem->contact.mat.e, wm->e), &ch, &tau));
  for (PetscInt s = 0; s < dem->shapes.nshape; s++) {
    const DemShape *a = &dem->shapes.shp[s];
    PetscCall(DemPairFill(dem, &dem->contact.mat, wm, a->m, a->req, 0, 0, ch, &pw[s]));
    PetscCall(DemPairFigures(dem, &pw[s], PetscMin(dem->contact.mat.e, wm->e), dem->contact.vimpact, &tc[s]));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemGetContactFigures(Dem dem, PetscInt s, PetscInt t, PetscReal v, PetscReal *tc, PetscReal *e)
{
  PetscFunctionBeginUser;
  PetscCheck(s >= 0 && s < dem->shapes.nshape && t < dem->shapes.nshape, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "shape pair (%" PetscInt_FMT ", %" PetscInt_FMT ") out of range", s, t);
  const DemPairParams *p = t < 0 ? &dem->contact.pw[s] : &dem->contact.pp[s * dem->shapes.nshape + t];
  *e                     = t < 0 ? PetscMin(dem->contact.mat.e, dem->contact.wmat.e) : dem->contact.mat.e;
  PetscCall(DemPairFigures(dem, p, *e, v, tc));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemGetContactFiguresSized(Dem dem, PetscInt s, PetscInt t, PetscReal ri, PetscReal rj, PetscReal v, PetscReal *tc, PetscReal *e)
{
  DemPairParams q;

  PetscFunctionBeginUser;
  PetscCheck(s >= 0 && s < dem->shapes.nshape && t < dem->shapes.nshape, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "shape pair (%" PetscInt_FMT ", %" PetscInt_FMT ") out of range", s, t);
  PetscCheck(ri > 0 && (t < 0 || rj > 0), PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "radii %g, %g must be > 0 (m)", (double)ri, (double)rj);
  const DemPairParams *b  = t < 0 ? &dem->contact.pw[s] : &dem->contact.pp[s * dem->shapes.nshape + t];
  const double         mi = dem_sphere_mass(dem->shapes.shp[s].rho, ri), mj = t < 0 ? 0 : dem_sphere_mass(dem->shapes.shp[t].rho, rj);
  dem_pair_sized(dem->contact.law, b, mi, ri, mj, t < 0 ? 0 : rj, &q);
  *e = t < 0 ? PetscMin(dem->contact.mat.e, dem->contact.wmat.e) : dem->contact.mat.e;
  PetscCall(DemPairFigures(dem, &q, *e, v, tc));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Spheres of their own sizes: dt against the contact time of the smallest and largest radii a
 * source can add (r_source_min, r_source_max; the shapes' radii where unset), with each other
 * and with the walls, for every material pair; -dem_dt_tc takes the shortest of them too. */
PetscErrorCode DemCheckTimeStepSizes(Dem dem)
{
  double r[2] = {PETSC_MAX_REAL, 0};

  PetscFunctionBeginUser;
  for (PetscInt s = 0; s < dem->shapes.nshape; s++) {
    r[0] = PetscMin(r[0], dem->shapes.shp[s].r);
    r[1] = PetscMax(r[1], dem->shapes.shp[s].r);
  }
  if (dem->shapes.r_source_min > 0) r[0] = PetscMin(r[0], dem->shapes.r_source_min);
  r[1] = PetscMax(r[1], dem->shapes.r_source_max);
  for (int pass = 0; pass < 2; pass++)
    for (PetscInt s = 0; s < dem->shapes.nshape; s++)
      for (PetscInt t = -1; t < dem->shapes.nshape; t++)
        for (int a = 0; a < 2; a++)
          for (int b = 0; b < (t < 0 ? 1 : 2); b++) {
            PetscReal tc = 0, e;
            PetscCall(DemGetContactFiguresSized(dem, s, t, r[a], r[b], dem->contact.vimpact, &tc, &e));
            if (pass == 0 && dem->clock.dt_tc > 0) dem->clock.dt = PetscMin(dem->clock.dt, dem->clock.dt_tc * tc);
            if (pass == 0 || dem->clock.dt <= dem->clock.dt_frac * tc) continue;
            char with[64] = "a wall";
            if (t >= 0) PetscCall(PetscSNPrintf(with, sizeof with, "a sphere of radius %g m", (double)r[b]));
            SETERRQ(dem->comm, PETSC_ERR_ARG_OUTOFRANGE, "%s %g s exceeds -dem_dt_max_fraction %g x the contact time %g s of a sphere of radius %g m with %s (sizes of their own, from a source's size distribution or an init file): use -dem_dt <= %g, or raise the smallest size (a source's -dem_insert_<k>_psd_min)", dem->clock.dt_tc > 0 ? "-dem_dt_tc gives dt" : "-dem_dt", (double)dem->clock.dt, (double)dem->clock.dt_frac, (double)tc, (double)r[a], with, (double)(dem->clock.dt_frac * tc));
          }
  PetscFunctionReturn(PETSC_SUCCESS);
}
