/* Particle size distributions (psd.h): the law of a source's DIAMETER (m) and its sampling by
 * inversion of the number-weighted cumulative distribution F at a uniform u in [0,1), so that
 * a sample depends on u alone (no state: the same particle gets the same size on any rank count).
 *   table      d_i with number fractions p_i, or mass fractions w_i turned into number
 *              fractions p_i ∝ w_i / d_i^3; sorted by diameter; the sample is the first d_i
 *              whose cumulative fraction exceeds u. Entries outside the cut-offs are dropped.
 *   normal     F(d) = Phi((d - m) / s), given by the number-weighted mean m and std s;
 *   lognormal  F(d) = Phi((ln d - mu) / sigma), sigma^2 = ln(1 + s^2/m^2), mu = ln m - sigma^2/2;
 *   uniform    F(d) = (d - min) / (max - min).
 * m and s describe the law before it is cut: the law sampled is the one truncated to [min, max],
 * d = F^-1(F(min) + u (F(max) - F(min))). Without cut-offs a normal or lognormal is cut at the
 * quantiles 1e-6 and 1 - 1e-6 of its law (a largest size is needed: it sets the neighbour cells),
 * and a normal at no less than a tenth of its mean (a diameter must be > 0). With N classes u is
 * first snapped to the middle of its equal-number bin, (floor(u N) + 1/2) / N: the samples take N
 * diameters, each the median of its bin. Phi^-1 is our own: Acklam's rational approximation
 * (relative error 1.2e-9) refined by two Halley steps on erfc, to ~1e-15. */
#include "psd.h"
#include "sable.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The options of a distribution under each prefix that reads one, as printf patterns of the
 * prefix's index, written out whole so that grep and tools/gen-options.sh find them: the
 * unknown-option check's suggestions, and the word (kind) and integer (classes) value checks,
 * which match an indexed name with its pattern (sable.c). A new reader of distributions adds a
 * row to each table. */
static const char *const DemPsdWordOptions[]    = {"-dem_insert_%d_psd"};
static const char *const DemPsdIntOptions[]     = {"-dem_insert_%d_psd_classes"};
static const char *const DemPsdRealOptions[][6] = {{"-dem_insert_%d_psd_diameters", "-dem_insert_%d_psd_fractions", "-dem_insert_%d_psd_mean", "-dem_insert_%d_psd_std", "-dem_insert_%d_psd_min", "-dem_insert_%d_psd_max"}};
static const char *const DemPsdKindNames[]      = {"single", "number", "mass", "normal", "lognormal", "uniform"};

enum {
  PSD_DIAMETERS,
  PSD_FRACTIONS,
  PSD_MEAN,
  PSD_STD,
  PSD_MIN,
  PSD_MAX,
  PSD_KIND,
  PSD_CLASSES,
  PSD_NOPT
};

/* The probability of a law's default tails left out (each side) when no cut-off is given. */
#define DEM_PSD_TAIL 1e-6
/* The least probability a cut law may keep. */
#define DEM_PSD_PMIN 1e-12

static double dem_psd_cdf(double z)
{
  return 0.5 * erfc(-z / sqrt(2.0));
}

/* Phi^-1(p) for 0 < p <= 1/2: Acklam's rational first guess, then Halley steps on
 * e = Phi(x) - p, computed as erfc of a positive argument (no cancellation in the tail). */
static double dem_psd_lower_quantile(double p)
{
  static const double a[] = {-3.969683028665376e+01, 2.209460984245205e+02, -2.759285104469687e+02, 1.383577518672690e+02, -3.066479806614716e+01, 2.506628277459239e+00};
  static const double b[] = {-5.447609879822406e+01, 1.615858368580409e+02, -1.556989798598866e+02, 6.680131188771972e+01, -1.328068155288572e+01};
  static const double c[] = {-7.784894002430293e-03, -3.223964580411365e-01, -2.400758277161838e+00, -2.549732539343734e+00, 4.374664141464968e+00, 2.938163982698783e+00};
  static const double d[] = {7.784695709041462e-03, 3.224671290700398e-01, 2.445134137142996e+00, 3.754408661907416e+00};
  double              x;

  if (p < 0.02425) {
    const double q = sqrt(-2 * log(p));
    x              = (((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) / ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1);
  } else {
    const double q = p - 0.5, r = q * q;
    x = (((((a[0] * r + a[1]) * r + a[2]) * r + a[3]) * r + a[4]) * r + a[5]) * q / (((((b[0] * r + b[1]) * r + b[2]) * r + b[3]) * r + b[4]) * r + 1);
  }
  for (int k = 0; k < 2; k++) {
    const double e = dem_psd_cdf(x) - p, u = e * sqrt(2 * PETSC_PI) * exp(0.5 * x * x);
    x -= u / (1 + 0.5 * x * u);
  }
  return x;
}

double DemPsdNormalQuantile(double p)
{
  if (p <= 0) return -INFINITY;
  if (p >= 1) return INFINITY;
  return p > 0.5 ? -dem_psd_lower_quantile(1 - p) : dem_psd_lower_quantile(p); /* 1 - p is exact */
}

/* The quantile of the cut continuous law at u in [0,1). */
static double dem_psd_quantile(const DemPsd *psd, double u)
{
  double d, z;

  if (psd->kind == DEM_PSD_UNIFORM) d = psd->dmin + u * (psd->dmax - psd->dmin);
  else {
    /* a window above the median is sampled by its upper-tail probabilities: no cancellation */
    z = psd->plo > 0.5 ? -DemPsdNormalQuantile(psd->qlo - u * (psd->qlo - psd->qhi)) : DemPsdNormalQuantile(psd->plo + u * (psd->phi - psd->plo));
    d = psd->kind == DEM_PSD_NORMAL ? psd->mu + psd->sigma * z : exp(psd->mu + psd->sigma * z);
  }
  return PetscMin(PetscMax(d, psd->dmin), psd->dmax); /* round-off never leaves [min, max] */
}

double DemPsdSample(const DemPsd *psd, double u)
{
  PetscInt lo = 0, hi = psd->ntab - 1;

  switch (psd->kind) {
  case DEM_PSD_SINGLE:
    return psd->mean;
  case DEM_PSD_NUMBER:
  case DEM_PSD_MASS:
    while (lo < hi) { /* the first entry whose cumulative fraction exceeds u */
      const PetscInt mid = (lo + hi) / 2;
      if (u < psd->cum[mid]) hi = mid;
      else lo = mid + 1;
    }
    return psd->d[lo];
  default:
    if (psd->classes > 0) {
      const PetscInt j = PetscMin((PetscInt)(u * psd->classes), psd->classes - 1);
      u                = (j + 0.5) / psd->classes;
    }
    return dem_psd_quantile(psd, u);
  }
}

void DemPsdRange(const DemPsd *psd, double *dmin, double *dmax)
{
  switch (psd->kind) {
  case DEM_PSD_SINGLE:
    *dmin = *dmax = psd->mean;
    break;
  case DEM_PSD_NUMBER:
  case DEM_PSD_MASS:
    *dmin = psd->d[0];
    *dmax = psd->d[psd->ntab - 1];
    break;
  default:
    *dmin = psd->classes > 0 ? DemPsdSample(psd, 0) : psd->dmin;
    *dmax = psd->classes > 0 ? DemPsdSample(psd, 1 - 0.5 / psd->classes) : psd->dmax;
  }
}

/* int_al^be y^k phi(y) dy for k = 0..3 (the standard normal's partial moments; the recursion
 * I_k = (k-1) I_{k-2} + al^{k-1} phi(al) - be^{k-1} phi(be)). */
static void dem_psd_normal_partial(double al, double be, double pm[4])
{
  const double fa = exp(-0.5 * al * al) / sqrt(2 * PETSC_PI), fb = exp(-0.5 * be * be) / sqrt(2 * PETSC_PI);

  pm[0] = al > 0 ? dem_psd_cdf(-al) - dem_psd_cdf(-be) : dem_psd_cdf(be) - dem_psd_cdf(al);
  pm[1] = fa - fb;
  pm[2] = pm[0] + al * fa - be * fb;
  pm[3] = 2 * pm[1] + al * al * fa - be * be * fb;
}

double DemPsdMeanCube(const DemPsd *psd)
{
  double s = 0;

  if (psd->kind == DEM_PSD_SINGLE) return psd->mean * psd->mean * psd->mean;
  if (psd->kind == DEM_PSD_NUMBER || psd->kind == DEM_PSD_MASS) {
    for (PetscInt i = 0; i < psd->ntab; i++) s += (psd->cum[i] - (i ? psd->cum[i - 1] : 0)) * psd->d[i] * psd->d[i] * psd->d[i];
    return s;
  }
  if (psd->classes > 0) {
    for (PetscInt j = 0; j < psd->classes; j++) s += pow(dem_psd_quantile(psd, (j + 0.5) / psd->classes), 3);
    return s / psd->classes;
  }
  if (psd->kind == DEM_PSD_UNIFORM) {
    const double a = psd->dmin, b = psd->dmax;
    return (a + b) * (a * a + b * b) / 4; /* (b^4 - a^4) / (4 (b - a)) */
  }
  {
    const double al = (psd->kind == DEM_PSD_NORMAL ? psd->dmin : log(psd->dmin)) - psd->mu, be = (psd->kind == DEM_PSD_NORMAL ? psd->dmax : log(psd->dmax)) - psd->mu;
    const double m = psd->mu, sg = psd->sigma;
    double       pm[4];
    if (psd->kind == DEM_PSD_LOGNORMAL) { /* E[e^{3 ln d}] of the cut law: the law shifted by 3 sigma */
      double J[4];
      dem_psd_normal_partial(al / sg - 3 * sg, be / sg - 3 * sg, J);
      dem_psd_normal_partial(al / sg, be / sg, pm);
      return exp(3 * m + 4.5 * sg * sg) * J[0] / pm[0];
    }
    dem_psd_normal_partial(al / sg, be / sg, pm);
    return (m * m * m * pm[0] + 3 * m * m * sg * pm[1] + 3 * m * sg * sg * pm[2] + sg * sg * sg * pm[3]) / pm[0];
  }
}

/* The option names under prefix (-dem_insert_3 gives -dem_insert_3_psd_mean, ...), from the
 * row of the tables above whose pattern the prefix fits. */
static PetscErrorCode DemPsdOptionNames(const char *prefix, char names[PSD_NOPT][64])
{
  const char *us  = strrchr(prefix, '_');
  int         idx = -1;
  char        kind[64];

  PetscFunctionBeginUser;
  if (us && us[1] && strspn(us + 1, "0123456789") == strlen(us + 1)) idx = atoi(us + 1);
  PetscCall(PetscSNPrintf(kind, sizeof kind, "%s_psd", prefix));
  for (size_t r = 0; r < sizeof DemPsdWordOptions / sizeof DemPsdWordOptions[0]; r++) {
    PetscCall(PetscSNPrintf(names[PSD_KIND], sizeof names[0], DemPsdWordOptions[r], idx));
    if (idx < 0 || strcmp(names[PSD_KIND], kind)) continue;
    PetscCall(PetscSNPrintf(names[PSD_CLASSES], sizeof names[0], DemPsdIntOptions[r], idx));
    for (int j = 0; j < 6; j++) PetscCall(PetscSNPrintf(names[j], sizeof names[0], DemPsdRealOptions[r][j], idx));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  SETERRQ(PETSC_COMM_SELF, PETSC_ERR_PLIB, "size distribution options under %s are not registered: add its row to the option tables of src/dem/psd.c", prefix);
}

/* Whether option j applies to kind. */
static PetscBool DemPsdApplies(DemPsdKind kind, int j)
{
  const PetscBool table = (PetscBool)(kind == DEM_PSD_NUMBER || kind == DEM_PSD_MASS), law = (PetscBool)(kind == DEM_PSD_NORMAL || kind == DEM_PSD_LOGNORMAL);

  switch (j) {
  case PSD_DIAMETERS:
  case PSD_FRACTIONS:
    return table;
  case PSD_MEAN:
    return (PetscBool)(law || kind == DEM_PSD_SINGLE);
  case PSD_STD:
    return law;
  case PSD_CLASSES:
    return (PetscBool)(law || kind == DEM_PSD_UNIFORM);
  default: /* the cut-offs */
    return (PetscBool)(kind != DEM_PSD_SINGLE);
  }
}

/* A table: the entries with a fraction > 0 inside the cut-offs, sorted by diameter, their
 * number fractions (mass fractions / d^3, normalised) and the cumulative ones. On entry d[]
 * holds the nd diameters given, f the nf fractions given. */
static PetscErrorCode DemPsdSetUpTable(MPI_Comm comm, char names[PSD_NOPT][64], PetscInt nd, PetscInt nf, const PetscReal *f, const PetscBool *set, DemPsd *psd)
{
  PetscReal sum = 0, kd[DEM_PSD_MAX_TABLE], kf[DEM_PSD_MAX_TABLE], p = 0, m1 = 0, m2 = 0;
  PetscInt  n = 0;

  PetscFunctionBeginUser;
  PetscCheck(set[PSD_DIAMETERS], comm, PETSC_ERR_ARG_WRONG, "%s %s needs %s d1,d2,... (m) and %s f1,f2,...", names[PSD_KIND], DemPsdKindNames[psd->kind], names[PSD_DIAMETERS], names[PSD_FRACTIONS]);
  PetscCheck(nd > 0, comm, PETSC_ERR_ARG_WRONG, "%s is empty: give at least one diameter (m)", names[PSD_DIAMETERS]);
  PetscCheck(nf == nd, comm, PETSC_ERR_ARG_SIZ, "%s has %d values for the %d diameters of %s: give one fraction per diameter", names[PSD_FRACTIONS], (int)nf, (int)nd, names[PSD_DIAMETERS]);
  for (PetscInt i = 0; i < nd; i++) {
    PetscCheck(psd->d[i] > 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "%s: diameter %d is %g m, must be > 0", names[PSD_DIAMETERS], (int)i + 1, (double)psd->d[i]);
    PetscCheck(f[i] >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "%s: fraction %d is %g, must be >= 0", names[PSD_FRACTIONS], (int)i + 1, (double)f[i]);
    sum += f[i];
  }
  PetscCheck(sum > 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "%s: all %d fractions are 0; at least one must be > 0", names[PSD_FRACTIONS], (int)nf);
  for (PetscInt i = 0; i < nd; i++) { /* keep, in order of diameter (insertion: a few entries) */
    PetscInt k = n++;
    if (f[i] == 0 || (set[PSD_MIN] && psd->d[i] < psd->dmin) || (set[PSD_MAX] && psd->d[i] > psd->dmax)) {
      n--;
      continue;
    }
    for (; k > 0 && kd[k - 1] > psd->d[i]; k--) {
      kd[k] = kd[k - 1];
      kf[k] = kf[k - 1];
    }
    kd[k] = psd->d[i];
    kf[k] = f[i];
  }
  if (!n) {
    char cut[160];
    if (set[PSD_MIN] && set[PSD_MAX]) PetscCall(PetscSNPrintf(cut, sizeof cut, "%s %g m and %s %g m leave", names[PSD_MIN], (double)psd->dmin, names[PSD_MAX], (double)psd->dmax));
    else PetscCall(PetscSNPrintf(cut, sizeof cut, "%s %g m leaves", names[set[PSD_MIN] ? PSD_MIN : PSD_MAX], (double)(set[PSD_MIN] ? psd->dmin : psd->dmax)));
    SETERRQ(comm, PETSC_ERR_ARG_OUTOFRANGE, "%s no diameter of %s with a fraction > 0 inside", cut, names[PSD_DIAMETERS]);
  }
  sum = 0;
  for (PetscInt i = 0; i < n; i++) sum += psd->kind == DEM_PSD_MASS ? kf[i] / (kd[i] * kd[i] * kd[i]) : kf[i];
  psd->ntab = n;
  for (PetscInt i = 0; i < n; i++) {
    const PetscReal pi = (psd->kind == DEM_PSD_MASS ? kf[i] / (kd[i] * kd[i] * kd[i]) : kf[i]) / sum;
    psd->d[i]          = kd[i];
    psd->frac[i]       = kf[i];
    p += pi;
    psd->cum[i] = i == n - 1 ? 1 : p; /* the last is 1 exactly: every u < 1 finds an entry */
    m1 += pi * kd[i];
    m2 += pi * kd[i] * kd[i];
  }
  psd->dmin = kd[0];
  psd->dmax = kd[n - 1];
  psd->mean = m1; /* the table's number-weighted mean and standard deviation, for reports */
  psd->std  = PetscSqrtReal(PetscMax(m2 - m1 * m1, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The probability of the standard normal law between al and be (no cancellation in a tail). */
static double dem_psd_normal_between(double al, double be)
{
  return al > 0 ? dem_psd_cdf(-al) - dem_psd_cdf(-be) : dem_psd_cdf(be) - dem_psd_cdf(al);
}

/* A normal, lognormal or uniform law: its parameters, its cut-offs (given, or the defaults of
 * the file header) and the probabilities F(min), F(max). A std of 0 is a single diameter. */
static PetscErrorCode DemPsdSetUpLaw(MPI_Comm comm, char names[PSD_NOPT][64], const PetscBool *set, DemPsd *psd)
{
  const char *kname = DemPsdKindNames[psd->kind];
  PetscBool   logn  = (PetscBool)(psd->kind == DEM_PSD_LOGNORMAL);
  double      al, be, pin;

  PetscFunctionBeginUser;
  if (psd->kind == DEM_PSD_UNIFORM) {
    PetscCheck(set[PSD_MIN] && set[PSD_MAX], comm, PETSC_ERR_ARG_WRONG, "%s uniform needs %s and %s, the smallest and largest diameter (m)", names[PSD_KIND], names[PSD_MIN], names[PSD_MAX]);
    PetscCheck(psd->dmin < psd->dmax, comm, PETSC_ERR_ARG_OUTOFRANGE, "%s %g m must be below %s %g m", names[PSD_MIN], (double)psd->dmin, names[PSD_MAX], (double)psd->dmax);
    psd->plo  = 0;
    psd->phi  = 1;
    psd->mean = 0.5 * (psd->dmin + psd->dmax);
    psd->std  = (psd->dmax - psd->dmin) / PetscSqrtReal(12.0);
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCheck(set[PSD_MEAN] && set[PSD_STD], comm, PETSC_ERR_ARG_WRONG, "%s %s needs %s and %s, the number-weighted mean and standard deviation of the diameter (m)", names[PSD_KIND], kname, names[PSD_MEAN], names[PSD_STD]);
  if (psd->std == 0) { /* one diameter */
    PetscCheck((!set[PSD_MIN] || psd->mean >= psd->dmin) && (!set[PSD_MAX] || psd->mean <= psd->dmax), comm, PETSC_ERR_ARG_OUTOFRANGE, "%s %g m (with %s 0: one diameter) is outside the cut-offs %s, %s", names[PSD_MEAN], (double)psd->mean, names[PSD_STD], names[PSD_MIN], names[PSD_MAX]);
    psd->kind    = DEM_PSD_SINGLE;
    psd->classes = 0;
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  if (logn) {
    psd->sigma = PetscSqrtReal(log1p(psd->std * psd->std / (psd->mean * psd->mean)));
    psd->mu    = log(psd->mean) - 0.5 * psd->sigma * psd->sigma;
  } else {
    psd->mu    = psd->mean;
    psd->sigma = psd->std;
  }
  if (!set[PSD_MIN]) {
    const double z = DemPsdNormalQuantile(DEM_PSD_TAIL);
    psd->dmin      = logn ? exp(psd->mu + psd->sigma * z) : PetscMax(psd->mean + psd->std * z, 0.1 * psd->mean);
  }
  if (!set[PSD_MAX]) psd->dmax = logn ? exp(psd->mu - psd->sigma * DemPsdNormalQuantile(DEM_PSD_TAIL)) : psd->mean - psd->std * DemPsdNormalQuantile(DEM_PSD_TAIL);
  PetscCheck(psd->dmin < psd->dmax, comm, PETSC_ERR_ARG_OUTOFRANGE, "%s %g m%s must be below %s %g m%s", names[PSD_MIN], (double)psd->dmin, set[PSD_MIN] ? "" : " (default)", names[PSD_MAX], (double)psd->dmax, set[PSD_MAX] ? "" : " (default)");
  al       = ((logn ? log(psd->dmin) : psd->dmin) - psd->mu) / psd->sigma;
  be       = ((logn ? log(psd->dmax) : psd->dmax) - psd->mu) / psd->sigma;
  pin      = dem_psd_normal_between(al, be);
  psd->plo = dem_psd_cdf(al);
  psd->phi = dem_psd_cdf(be);
  psd->qlo = dem_psd_cdf(-al);
  psd->qhi = dem_psd_cdf(-be);
  PetscCheck(pin >= DEM_PSD_PMIN && psd->phi > psd->plo, comm, PETSC_ERR_ARG_OUTOFRANGE, "%s %g m and %s %g m keep a probability of %.3g of the %s law (%s %g m, %s %g m): at least %g; move the cut-offs towards the mean", names[PSD_MIN], (double)psd->dmin, names[PSD_MAX], (double)psd->dmax, pin, kname, names[PSD_MEAN], (double)psd->mean, names[PSD_STD], (double)psd->std, DEM_PSD_PMIN);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemPsdSetFromOptions(PetscOptionItems *PetscOptionsObject, MPI_Comm comm, const char *prefix, PetscReal dflt_d, DemPsd *psd)
{
  char      names[PSD_NOPT][64];
  PetscReal f[DEM_PSD_MAX_TABLE];
  PetscInt  nd = DEM_PSD_MAX_TABLE, nf = DEM_PSD_MAX_TABLE, kind = DEM_PSD_SINGLE;
  PetscBool set[PSD_NOPT], help;

  PetscFunctionBeginUser;
  PetscCall(DemPsdOptionNames(prefix, names));
  PetscCall(PetscMemzero(psd, sizeof *psd));
  PetscCall(SableOptionsEnum(names[PSD_KIND], "Size distribution of the diameter: single, number (table of number fractions), mass (table of mass fractions), normal, lognormal, uniform", DemPsdKindNames, 6, kind, &kind, &set[PSD_KIND]));
  psd->kind = (DemPsdKind)kind;
  PetscCall(SableOptionsRealArray(names[PSD_DIAMETERS], "number, mass: the table's diameters", "m", psd->d, 0, &nd, &set[PSD_DIAMETERS]));
  PetscCall(SableOptionsRealArray(names[PSD_FRACTIONS], "number, mass: the fraction of each diameter, by number or by mass (normalised)", NULL, f, 0, &nf, &set[PSD_FRACTIONS]));
  PetscCall(SableOptionsReal(names[PSD_MEAN], "single: the diameter; normal, lognormal: the number-weighted mean diameter of the law before its cut-offs", "m", "(0,inf)", psd->kind == DEM_PSD_SINGLE ? dflt_d : 0, &psd->mean, &set[PSD_MEAN]));
  PetscCall(SableOptionsReal(names[PSD_STD], "normal, lognormal: the number-weighted standard deviation of the diameter before the cut-offs (0: one diameter)", "m", "[0,inf)", -1, &psd->std, &set[PSD_STD]));
  PetscCall(SableOptionsReal(names[PSD_MIN], "Smallest diameter: the law's lower cut-off (normal: default the larger of mean - 4.75 std and mean/10; lognormal: its 1e-6 quantile; table: smaller entries dropped)", "m", "(0,inf)", 0, &psd->dmin, &set[PSD_MIN]));
  PetscCall(SableOptionsReal(names[PSD_MAX], "Largest diameter: the law's upper cut-off (normal, lognormal: default the 1 - 1e-6 quantile; table: larger entries dropped)", "m", "(0,inf)", 0, &psd->dmax, &set[PSD_MAX]));
  PetscCall(SableOptionsInt(names[PSD_CLASSES], "normal, lognormal, uniform: snap the samples to this many diameters, the medians of equal-number bins (0: every sample its own size)", NULL, "[0,inf)", 0, &psd->classes, &set[PSD_CLASSES]));
  for (int j = 0; j < PSD_NOPT; j++) PetscCheck(!set[j] || j == PSD_KIND || DemPsdApplies(psd->kind, j), comm, PETSC_ERR_ARG_INCOMP, "%s is not an option of %s %s", names[j], names[PSD_KIND], DemPsdKindNames[psd->kind]);
  PetscCheck(!set[PSD_MIN] || !set[PSD_MAX] || psd->dmin < psd->dmax, comm, PETSC_ERR_ARG_OUTOFRANGE, "%s %g m must be below %s %g m", names[PSD_MIN], (double)psd->dmin, names[PSD_MAX], (double)psd->dmax);
  PetscCall(PetscOptionsHasHelp(NULL, &help));
  if (help) { /* -help lists the options: a law not complete yet is no error, and nothing is sampled */
    psd->kind = DEM_PSD_SINGLE;
    psd->mean = psd->dmin = psd->dmax = dflt_d;
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  switch (psd->kind) {
  case DEM_PSD_SINGLE:
    PetscCheck(psd->mean > 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "%s %g m must be > 0 (the diameter of a single-size source)", names[PSD_MEAN], (double)psd->mean);
    psd->dmin = psd->dmax = psd->mean;
    break;
  case DEM_PSD_NUMBER:
  case DEM_PSD_MASS:
    PetscCall(DemPsdSetUpTable(comm, names, nd, nf, f, set, psd));
    break;
  default:
    PetscCall(DemPsdSetUpLaw(comm, names, set, psd));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemPsdDescribe(const DemPsd *psd, char *buf, size_t size)
{
  double lo, hi;

  PetscFunctionBeginUser;
  DemPsdRange(psd, &lo, &hi);
  if (psd->kind == DEM_PSD_SINGLE) PetscCall(PetscSNPrintf(buf, size, "single, diameter %g m", psd->mean));
  else if (psd->kind == DEM_PSD_NUMBER || psd->kind == DEM_PSD_MASS) PetscCall(PetscSNPrintf(buf, size, "table of %d diameters by %s in [%g, %g] m, number-weighted mean %g m, std %g m", (int)psd->ntab, DemPsdKindNames[psd->kind], lo, hi, psd->mean, psd->std));
  else PetscCall(PetscSNPrintf(buf, size, "%s, mean %g m, std %g m, cut to [%g, %g] m (probability kept %.6g)%s", DemPsdKindNames[psd->kind], psd->mean, psd->std, psd->dmin, psd->dmax, psd->plo > 0.5 ? psd->qlo - psd->qhi : psd->phi - psd->plo, psd->classes ? ", in classes" : ""));
  PetscFunctionReturn(PETSC_SUCCESS);
}
