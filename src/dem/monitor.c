/* The DEM's figures for the monitor file, each one a function of the particles alone so that a
 * user can compute it again from a frame (position, id and the shapes' masses, or each sphere's
 * radius and the density in a scene of own sizes):
 *   bed height h95: along gravity, the centre coordinate of the particle at which the solids mass
 *     counted from the bottom first reaches 95% (the smallest particle coordinate c with
 *     m(x <= c) >= 0.95 M (1 - 1e-12), "bottom" and "<=" in the sense of gravity; the slack keeps
 *     the round-off of the mass sums from choosing between two particles); exact, found by radix
 *     selection on the ordered bit patterns of the coordinates (8 bits a pass: at most 8 passes
 *     and reductions, no gather);
 *   mean height: the mass-weighted mean centre coordinate along gravity (the centre of mass);
 *   mass and count of the particles whose centres (wrapped into periodic boxes, as the frames
 *     store them) lie in a box [lo, hi).
 *   highest particle: the largest centre coordinate plus radius along gravity (a convex shape's
 *     bounding radius: the frames' radius);
 *   bed surface: the solids volume of the particles whose centres lie in a box, as a profile in
 *     slabs of thickness dz along gravity from the box's bottom, each particle's volume (a convex
 *     shape's as its volume-equivalent sphere) shared among the slabs it spans by the exact
 *     volumes of its spherical caps; the surface is where the profile, read from the top down,
 *     first reaches frac times its densest slab, linear between the centres of that slab and
 *     the one above it (the cross-section's area cancels in the ratio);
 *   mass flow through a plane: the slab estimator sum(m v.n) / w over the particles whose centre
 *     lies within w/2 of the plane and inside its rectangle (kg/s; a steady flow's mean is the
 *     flow for any w).
 * All collective; the selection's sums are per rank in local order, so h95 is exact on any rank
 * count unless a partial mass sum sits within roundoff of 0.95 M; the highest particle is exact;
 * the slab volumes and the mass flow are sums over ranks (the last bits depend on the rank
 * count). */
#include "dem/dem_core.h"
#include <stdint.h>

static inline double dem_mass_of(const Dem dem, PetscInt i)
{
  if (dem->p.m) return dem->p.m[i]; /* spheres of their own sizes */
  return dem->shapes.shp[dem->shapes.nshape == 1 ? 0 : dem->p.shape[i]].m;
}

/* The axis of gravity (the largest component; z without gravity) and the sign that turns a
 * coordinate into a height (-1 when gravity points to +axis). */
static void DemGravityAxis(const Dem dem, int *axis, double *up)
{
  *axis = 2;
  for (int k = 1; k >= 0; k--)
    if (PetscAbsReal(dem->g[k]) > PetscAbsReal(dem->g[*axis])) *axis = k;
  *up = dem->g[*axis] > 0 ? -1.0 : 1.0;
}

/* A key whose unsigned order is the order of the doubles (finite values). */
static inline uint64_t dem_order_key(double x)
{
  uint64_t u;
  memcpy(&u, &x, sizeof u);
  return (u >> 63) ? ~u : u | (1ULL << 63);
}

static inline double dem_key_value(uint64_t k)
{
  uint64_t u = (k >> 63) ? k & ~(1ULL << 63) : ~k;
  double   x;
  memcpy(&x, &u, sizeof x);
  return x;
}

PetscErrorCode DemGetBedHeights(Dem dem, PetscReal frac, PetscReal *h, PetscReal *mean)
{
  int      axis;
  double   up, loc[2] = {0, 0}, tot[2];
  uint64_t lo = UINT64_MAX, hi = 0, glo, ghi;

  PetscFunctionBeginUser;
  DemGravityAxis(dem, &axis, &up);
  for (PetscInt i = 0; i < dem->p.n; i++) {
    const double   m = dem_mass_of(dem, i), z = up * dem->p.x[3 * i + axis];
    const uint64_t k = dem_order_key(z);
    loc[0] += m;
    loc[1] += m * z;
    lo = PetscMin(lo, k);
    hi = PetscMax(hi, k);
  }
  PetscCallMPI(MPI_Allreduce(loc, tot, 2, MPI_DOUBLE, MPI_SUM, dem->comm));
  PetscCallMPI(MPI_Allreduce(&lo, &glo, 1, MPI_UINT64_T, MPI_MIN, dem->comm));
  PetscCallMPI(MPI_Allreduce(&hi, &ghi, 1, MPI_UINT64_T, MPI_MAX, dem->comm));
  if (tot[0] <= 0) {
    *h = *mean = 0;
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  *mean = up * tot[1] / tot[0];
  /* the smallest key K with m(key <= K) >= frac M lies in [glo, ghi]: radix selection, 8 bits a
   * pass from the highest bit where glo and ghi differ (at most 8 passes and reductions) */
  if (glo < ghi) {
    const double target = frac * tot[0] * (1 - 1e-12); /* slack: with equal masses the count reaching frac M is exact, not its round-off */
    double       below  = 0, hist[2][256];             /* below: the mass of the keys under the range */
    uint64_t     pre    = glo;                         /* the range: the keys whose bits above 'bits' are pre's */
    int          bits   = 64;
    while (bits > 0 && !((glo ^ ghi) >> (bits - 1))) bits--;
    while (bits > 0) {
      const int nb = PetscMin(8, bits), nbin = 1 << nb;
      int       j, last                      = 0;
      bits -= nb;
      PetscCall(PetscArrayzero(hist[0], nbin));
      for (PetscInt i = 0; i < dem->p.n; i++) {
        const uint64_t k = dem_order_key(up * dem->p.x[3 * i + axis]);
        if (bits + nb == 64 || (k >> (bits + nb)) == (pre >> (bits + nb))) hist[0][(k >> bits) & ((1u << nb) - 1)] += dem_mass_of(dem, i);
      }
      PetscCallMPI(MPI_Allreduce(hist[0], hist[1], nbin, MPI_DOUBLE, MPI_SUM, dem->comm));
      for (j = 0; j < nbin; j++) {
        if (hist[1][j] > 0) last = j;
        if (below + hist[1][j] >= target) break;
        below += hist[1][j];
      }
      if (j == nbin) below -= hist[1][j = last]; /* not reached by round-off: the range's highest key */
      pre = (bits + nb == 64 ? 0 : pre >> (bits + nb) << (bits + nb)) | ((uint64_t)j << bits);
    }
    glo = pre;
  }
  *h = up * dem_key_value(glo);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemGetMassInBox(Dem dem, const PetscReal lo[3], const PetscReal hi[3], PetscReal *mass, PetscInt *count)
{
  double   m = 0;
  PetscInt c = 0;

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < dem->p.n; i++) {
    double    x[3] = {dem->p.x[3 * i], dem->p.x[3 * i + 1], dem->p.x[3 * i + 2]};
    PetscBool in   = PETSC_TRUE;
    DemWrapPeriodic(dem->dom, x); /* as the frames show it */
    for (int k = 0; k < 3; k++) in = (PetscBool)(in && x[k] >= lo[k] && x[k] < hi[k]);
    if (in) {
      m += dem_mass_of(dem, i);
      c++;
    }
  }
  PetscCallMPI(MPI_Allreduce(&m, mass, 1, MPI_DOUBLE, MPI_SUM, dem->comm));
  PetscCallMPI(MPI_Allreduce(&c, count, 1, MPIU_INT, MPI_SUM, dem->comm));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemGetHighest(Dem dem, PetscReal *top)
{
  int    axis;
  double up, loc = -PETSC_MAX_REAL, all;

  PetscFunctionBeginUser;
  DemGravityAxis(dem, &axis, &up);
  for (PetscInt i = 0; i < dem->p.n; i++) loc = PetscMax(loc, up * dem->p.x[3 * i + axis] + DemRadius(&dem->p, &dem->shapes, i));
  PetscCallMPI(MPI_Allreduce(&loc, &all, 1, MPI_DOUBLE, MPI_MAX, dem->comm));
  *top = all == -PETSC_MAX_REAL ? 0 : up * all;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The fraction of a sphere of radius r centred at height c that lies below height s. */
static inline double dem_below(double c, double r, double s)
{
  const double h = s - (c - r);
  if (h <= 0) return 0;
  if (h >= 2 * r) return 1;
  return h * h * (3 * r - h) / (4 * r * r * r);
}

PetscErrorCode DemGetBedSurface(Dem dem, const PetscReal lo[3], const PetscReal hi[3], PetscReal dz, PetscReal frac, PetscReal *surface)
{
  int      axis;
  double   up, s0, s1, *loc, *vol, vmax = 0;
  PetscInt n, top = -1;

  PetscFunctionBeginUser;
  DemGravityAxis(dem, &axis, &up);
  { /* along gravity, the box within the domain */
    const double a = PetscMax(lo[axis], dem->dom->lo[axis]), b = PetscMin(hi[axis], dem->dom->hi[axis]);
    s0 = PetscMin(up * a, up * b);
    s1 = PetscMax(up * a, up * b);
  }
  PetscCheck((s1 - s0) / dz <= 100000, dem->comm, PETSC_ERR_ARG_OUTOFRANGE, "-mon_surface_dz %g m: %.3g slabs over the %g m along gravity; at most 100000 (a thicker slab)", (double)dz, (s1 - s0) / dz, s1 - s0);
  n = (PetscInt)PetscCeilReal((s1 - s0) / dz - 1e-9);
  n = PetscMax(n, 1);
  PetscCall(PetscCalloc2(n, &loc, n, &vol));
  for (PetscInt i = 0; i < dem->p.n; i++) {
    double    x[3] = {dem->p.x[3 * i], dem->p.x[3 * i + 1], dem->p.x[3 * i + 2]}, r, v, c;
    PetscBool in   = PETSC_TRUE;
    PetscInt  k0, k1;
    DemWrapPeriodic(dem->dom, x); /* as the frames show it */
    for (int k = 0; k < 3; k++) in = (PetscBool)(in && (k == axis || (x[k] >= lo[k] && x[k] < hi[k])));
    c = up * x[axis];
    if (!in || c < s0 || c >= s1) continue;
    if (dem->p.rad) {
      r = dem->p.rad[i];
      v = 4.0 / 3.0 * PETSC_PI * r * r * r;
    } else {
      const DemShape *sh = &dem->shapes.shp[dem->p.shape[i]];
      v                  = sh->cvx ? sh->vol : 4.0 / 3.0 * PETSC_PI * sh->r * sh->r * sh->r;
      r                  = sh->cvx ? PetscCbrtReal(3 * sh->vol / (4 * PETSC_PI)) : sh->r;
    }
    k0 = PetscMax((PetscInt)PetscFloorReal((c - r - s0) / dz), 0);
    k1 = PetscMin((PetscInt)PetscFloorReal((c + r - s0) / dz), n - 1);
    for (PetscInt k = k0; k <= k1; k++) {
      const double bot = k ? dem_below(c, r, s0 + k * dz) : 0, tp = k < n - 1 ? dem_below(c, r, s0 + (k + 1) * dz) : 1;
      loc[k] += v * (tp - bot); /* the parts beyond the box's ends count in its end slabs */
    }
  }
  PetscCallMPI(MPI_Allreduce(loc, vol, (PetscMPIInt)n, MPI_DOUBLE, MPI_SUM, dem->comm));
  for (PetscInt k = 0; k < n; k++) vmax = PetscMax(vmax, vol[k]);
  for (PetscInt k = n - 1; k >= 0 && top < 0; k--)
    if (vmax > 0 && vol[k] >= frac * vmax) top = k;
  if (top < 0) *surface = 0;
  else {
    const double above = top < n - 1 ? vol[top + 1] : 0, t = frac * vmax;
    *surface = up * (s0 + (top + 0.5) * dz + dz * (vol[top] - t) / (vol[top] - above));
  }
  PetscCall(PetscFree2(loc, vol));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemGetMassFlow(Dem dem, const PetscReal lo[3], const PetscReal hi[3], int axis, PetscReal width, PetscReal *flow)
{
  double loc = 0, all;

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < dem->p.n; i++) {
    double    x[3] = {dem->p.x[3 * i], dem->p.x[3 * i + 1], dem->p.x[3 * i + 2]};
    PetscBool in;
    DemWrapPeriodic(dem->dom, x);
    in = (PetscBool)(PetscAbsReal(x[axis] - lo[axis]) < 0.5 * width);
    for (int k = 0; k < 3; k++) in = (PetscBool)(in && (k == axis || (x[k] >= lo[k] && x[k] < hi[k])));
    if (in) loc += dem_mass_of(dem, i) * dem->p.v[3 * i + axis];
  }
  PetscCallMPI(MPI_Allreduce(&loc, &all, 1, MPI_DOUBLE, MPI_SUM, dem->comm));
  *flow = all / width;
  PetscFunctionReturn(PETSC_SUCCESS);
}
