/* The DEM's figures for the monitor file, each one a function of the particles alone so that a
 * user can compute it again from a frame (position, id and the shapes' masses, or each sphere's
 * radius and the density in a scene of own sizes):
 *   bed height h95: along gravity, the centre coordinate of the particle at which the solids mass
 *     counted from the bottom first reaches 95% (the smallest particle coordinate c with
 *     m(x <= c) >= 0.95 M (1 - 1e-12), "bottom" and "<=" in the sense of gravity; the slack keeps
 *     the round-off of the mass sums from choosing between two particles); exact, found by bisection
 *     on the ordered bit patterns of the coordinates (64 reductions, no gather);
 *   mean height: the mass-weighted mean centre coordinate along gravity (the centre of mass);
 *   mass and count of the particles whose centres (wrapped into periodic boxes, as the frames
 *     store them) lie in a box [lo, hi).
 * All collective; the bisection's sums are per rank in local order, so h95 is exact on any rank
 * count unless a partial mass sum sits within roundoff of 0.95 M. */
#include "dem/dem_impl.h"
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
  /* the smallest key K with m(key <= K) >= frac M lies in [glo, ghi] */
  while (glo < ghi) {
    const uint64_t mid   = glo + (ghi - glo) / 2;
    double         below = 0, all;
    for (PetscInt i = 0; i < dem->p.n; i++)
      if (dem_order_key(up * dem->p.x[3 * i + axis]) <= mid) below += dem_mass_of(dem, i);
    PetscCallMPI(MPI_Allreduce(&below, &all, 1, MPI_DOUBLE, MPI_SUM, dem->comm));
    if (all >= frac * tot[0] * (1 - 1e-12)) ghi = mid; /* slack: with equal masses the count reaching frac M is exact, not its round-off */
    else glo = mid + 1;
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
