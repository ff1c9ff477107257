/* Contact laws as small stateless kernels, shared by particle-particle and particle-wall pairs.
 *
 * Normal (n points from particle i to its partner, delta > 0 the overlap, vn = v_rel . n with
 * v_rel the partner's contact-point velocity relative to i's, so vn < 0 when approaching):
 *   linear:  Fn = kn delta - gn m* vn,  gn = 2 zeta sqrt(kn/m*), zeta = -ln e / sqrt(pi^2 + ln^2 e)
 *            (exact restitution e, contact time Tc = pi / sqrt(kn/m* - (gn/2)^2)).
 *   hertz:   Fn = 4/3 E* sqrt(R* delta) delta - c_h sqrt(m* S_n) vn, S_n = 2 E* sqrt(R* delta),
 *            c_h from the exact restitution map of the reduced Hertz ODE (contact_laws.c).
 * Tangential:
 *   no history (Grains3D): Ft = -min(mu |Fn|, gt m* |vt|) vt/|vt|;
 *   history (linear / Mindlin): xi projected on the tangent plane, xi += vt dt, Ft = -kt xi - gt m* vt,
 *            capped at mu |Fn| with xi reset to the capped spring (Cundall-Strack slip).
 * Rolling resistance (torque on i; w_rel = w_i - w_j, a wall's angular velocity for j), as Lethe
 * defines its two models (Lethe docs, DEM "rolling resistance"; Ai et al. 2011, Powder Technol.
 * 206:269, doi:10.1016/j.powtec.2010.09.030, model A):
 *   constant: M_r = -mu_r R* |Fn| w_rel/|w_rel|                     (mu_r dimensionless)
 *   viscous:  M_r = -mu_r R* |Fn| |V_w| w_rel/|w_rel|,  V_w = (r_i w_i + r_j w_j) x n   (mu_r s/m)
 * and Grains3D's k_ms (the HO-D-C model of Wachs et al. 2012, Powder Technol. 224:374, as its
 * source HODCContactForceModel.cpp computes it; w_n = (w_rel.n) n, w_t = w_rel - w_n):
 *   kms:      M_r = -k_ms |Fn| (w_t + 1e-3 w_n)                    (k_ms m s; no R*, no unit vector)
 * All are capped at I* |w_rel| / (12 dt), I* = I_i I_j / (I_i + I_j) (I_i for a wall): the
 * torque alone cannot reverse w_rel within one step, so the constant model does not chatter as
 * w_rel -> 0 (Ai et al.'s objection to model A) and decays |w_rel| geometrically once the cap
 * binds; the 12 keeps the summed torques of a sphere's contacts (at most 12 equal neighbours)
 * within the explicit step's stability limit, which a cap of I* |w_rel| / dt per contact does not
 * (a dense bed with a large k_ms diverged with it).
 * No per-contact history (an elastic-plastic rolling spring, Ai's model C, would need a second
 * spring per list entry); the price: a sphere held by the torque below its threshold creeps at
 * an angular speed of order 12 (driving torque) dt / I*, which vanishes with dt (README.md).
 * Forces returned act on the partner; i receives the opposite (Newton's third law).
 * Units SI. No allocation, no branching on options other than the law and the rolling model. */
#pragma once
#include <math.h>

typedef enum {
  DEM_LAW_LINEAR_NOHIST,
  DEM_LAW_LINEAR,
  DEM_LAW_HERTZ
} DemLaw;

typedef enum {
  DEM_ROLL_NONE,
  DEM_ROLL_CONSTANT,
  DEM_ROLL_VISCOUS,
  DEM_ROLL_KMS
} DemRoll;

/* Parameters of one (shape, shape) or (shape, wall) pair, precomputed at set-up. */
typedef struct {
  double kn, kt;     /* linear stiffness (N/m) */
  double gn, gt;     /* damping rate per unit effective mass (1/s), linear law */
  double es, g8;     /* hertz: effective Young's modulus E* and 8 G* (Pa) */
  double ch;         /* hertz: damping factor c_h (dimensionless) */
  double mu;         /* Coulomb friction coefficient */
  double meff, reff; /* effective mass (kg) and radius (m) */
  double hratio;     /* hertz: gt/gn ratio applied to sqrt(m* S) damping */
  double mur;        /* rolling friction coefficient (constant: -, viscous: s/m) */
  double ieff;       /* effective moment of inertia I_i I_j / (I_i + I_j), I_i for a wall (kg m^2) */
  /* for spheres of their own sizes (dem_pair_sized): zeta of the restitution, the impact speed
     of a kn from Young's modulus (0: kn given), and whether kt was given */
  double zeta, vimp;
  int    kt_given;
} DemPairParams;

static inline double dem_dot(const double *a, const double *b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static inline void dem_cross(const double *a, const double *b, double *c)
{
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}

/* The parameters of a pair of spheres of their own sizes: the material's (b, from the (shape,
 * shape) or (shape, wall) table) with m* and R* of masses mi, mj and radii ri, rj (mj = rj = 0:
 * a wall), and for the linear laws kn (Hertz-equivalent at the impact speed when it came from
 * Young's modulus), kt = 2/7 kn unless given, gn = 2 zeta sqrt(kn/m*), gt = ratio gn — the
 * expressions of DemPairFill (contact_laws.c). Symmetric in i and j to the bit. */
static inline void dem_pair_sized(DemLaw law, const DemPairParams *b, double mi, double ri, double mj, double rj, DemPairParams *o)
{
  *o      = *b;
  o->meff = mj > 0 ? mi * mj / (mi + mj) : mi;
  o->reff = rj > 0 ? ri * rj / (ri + rj) : ri;
  if (law == DEM_LAW_HERTZ) return;
  if (b->vimp > 0) {
    const double V = b->vimp, sr = sqrt(o->reff);
    o->kn = 16.0 / 15.0 * sr * o->es * pow(15.0 * o->meff * V * V / (16.0 * sr * o->es), 0.2);
  }
  if (!b->kt_given) o->kt = 2.0 / 7.0 * o->kn;
  o->gn = 2 * b->zeta * sqrt(o->kn / o->meff);
  o->gt = b->hratio * o->gn;
}

/* Normal force magnitude (N, positive = repulsive) and, through *kt_out / *gt_out, the
 * tangential stiffness and damping (per unit mass) valid at this overlap. */
static inline double dem_normal_force(DemLaw law, const DemPairParams *p, double delta, double vn, double *kt_out, double *gt_out)
{
  if (law == DEM_LAW_HERTZ) {
    const double a  = sqrt(p->reff * delta); /* contact radius (m) */
    const double sn = 2.0 * p->es * a;       /* normal contact stiffness S_n (N/m) */
    *kt_out         = p->g8 * a;             /* tangential stiffness S_t = 8 G* a (N/m) */
    *gt_out         = p->hratio * p->ch * sqrt(*kt_out / p->meff);
    return (4.0 / 3.0) * p->es * a * delta - p->ch * sqrt(sn / p->meff) * p->meff * vn;
  }
  *kt_out = p->kt;
  *gt_out = p->gt;
  return p->kn * delta - p->gn * p->meff * vn;
}

/* Tangential force on the partner (3-vector ft) from the tangential relative velocity vt.
 * xi is the pair's tangential spring (m), NULL for the law without history. */
static inline void dem_tangential_force(const DemPairParams *p, double fn, double kt, double gt, const double *nrm, const double *vt, double *xi, double dt, double *ft)
{
  const double fmax = p->mu * fabs(fn);
  if (!xi) {
    const double vtn = sqrt(dem_dot(vt, vt));
    if (vtn <= 0.0) {
      ft[0] = ft[1] = ft[2] = 0.0;
      return;
    }
    const double mag = fmin(fmax, gt * p->meff * vtn) / vtn;
    for (int k = 0; k < 3; k++) ft[k] = -mag * vt[k];
    return;
  }
  /* keep the spring in the current tangent plane by projection (as LAMMPS' granular history
     models do; the length lost is second order in the rotation per step) */
  const double xn = dem_dot(xi, nrm);
  for (int k = 0; k < 3; k++) xi[k] -= xn * nrm[k];
  for (int k = 0; k < 3; k++) xi[k] += vt[k] * dt;
  for (int k = 0; k < 3; k++) ft[k] = -kt * xi[k] - gt * p->meff * vt[k];
  const double f2 = dem_dot(ft, ft);
  if (f2 > fmax * fmax) {
    const double s = fmax / sqrt(f2);
    for (int k = 0; k < 3; k++) {
      ft[k] *= s;
      xi[k] = kt > 0.0 ? -(ft[k] + gt * p->meff * vt[k]) / kt : 0.0;
    }
  }
}

/* The rolling torque of one contact is capped at I* |w_rel| / (12 dt): alone it removes at most
 * 1/12 of w_rel per step (no reversal), and the 12 contacts a sphere can have keep the explicit
 * step of their summed damping stable (Gershgorin: dt * 2 * 12 / 12 per I < 2). */
#define DEM_ROLL_CAP_CONTACTS 12.0

/* I* of two solid spheres (I = 2/5 m r^2) of masses mi, mj and radii ri, rj; mj = 0: a wall (I_i). */
static inline double dem_pair_inertia(double mi, double ri, double mj, double rj)
{
  const double Ii = 0.4 * mi * ri * ri, Ij = 0.4 * mj * rj * rj;
  return mj > 0 ? Ii * Ij / (Ii + Ij) : Ii;
}

/* Rolling-resistance torque mr on i (j receives -mr) of model roll (not NONE): wrel = w_i - w_j,
 * vw = V_w (the viscous model's rotational contact velocity), nrm the normal, ieff the pair's I*. */
static inline void dem_rolling_torque(DemRoll roll, const DemPairParams *p, double fn, double ieff, const double *wrel, const double *vw, const double *nrm, double dt, double *mr)
{
  const double wn  = sqrt(dem_dot(wrel, wrel));
  double       mag = p->mur * p->reff * fabs(fn);
  if (!(wn > 0.0)) {
    mr[0] = mr[1] = mr[2] = 0.0;
    return;
  }
  if (roll == DEM_ROLL_KMS) { /* linear in w: the cap binds only when k_ms |Fn| dt > I* / 12 */
    const double c = fmin(p->mur * fabs(fn), ieff / (DEM_ROLL_CAP_CONTACTS * dt)), wnn = dem_dot(wrel, nrm);
    for (int k = 0; k < 3; k++) mr[k] = -c * (wrel[k] - (1.0 - 1e-3) * wnn * nrm[k]);
    return;
  }
  if (roll == DEM_ROLL_VISCOUS) mag *= sqrt(dem_dot(vw, vw));
  mag = fmin(mag, ieff * wn / (DEM_ROLL_CAP_CONTACTS * dt)) / wn; /* cannot reverse w_rel within the step */
  for (int k = 0; k < 3; k++) mr[k] = -mag * wrel[k];
}

/* The same for a sphere pair: w_i, w_j, radii ri, rj, n from i to j. */
static inline void dem_rolling_pair(DemRoll roll, const DemPairParams *p, double fn, double ieff, const double *wi, const double *wj, double ri, double rj, const double *nrm, double dt, double *mr)
{
  double wrel[3], ws[3], vw[3];
  for (int k = 0; k < 3; k++) {
    wrel[k] = wi[k] - wj[k];
    ws[k]   = ri * wi[k] + rj * wj[k];
  }
  dem_cross(ws, nrm, vw);
  dem_rolling_torque(roll, p, fn, ieff, wrel, vw, nrm, dt, mr);
}
