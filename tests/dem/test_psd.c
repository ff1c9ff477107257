/* Size distributions (src/dem/psd.c) against the distributions themselves. For each law set
 * through the options (a table by number, a table by mass with an entry dropped by a cut-off, a
 * cut lognormal, a cut normal, the far tail of a normal, a uniform), N = 100,000 diameters are
 * drawn as a source draws them, d = DemPsdSample(u) with u a splitmix64 hash of the particle's
 * index, and their number- and mass-weighted mean, standard deviation, d10, d50 and d90 are
 * compared with the exact values of the set (cut) law, computed here from its own closed forms
 * (partial moments of the truncated normal and lognormal; sums for a table), within 3 standard
 * errors of the law: sigma/sqrt(N) for a mean, the delta method for a standard deviation and for
 * the mass-weighted (ratio) estimators, sqrt(p(1-p)/N)/f(d_p) for a quantile (its mass-weighted
 * form for mass quantiles). A table's quantiles are atoms: the sample's must be the table's exact
 * one; its fractions are checked as set, by number or BY MASS; the mass table sampled as if by
 * number must fail that check. Also: the normal quantile against 20-digit values, the mean of d^3
 * (kg/s rates), the range, the default cut-offs (1e-6 tails), classes (bin medians).
 * With arguments, the program only reads them as a source's distribution (-dem_insert_0_psd ...)
 * and prints it, or one error line: the bad-input test, test_psd_badinput.sh. */
#include "check.h"
#include "dem/psd.h"
#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#define NS 100000

/* splitmix64 of (seed, index): a uniform double in [0,1), as a source hashes its particles. */
static double Uniform(uint64_t seed, uint64_t i)
{
  uint64_t z = seed * 0x9E3779B97F4A7C15ULL + i * 0xBF58476D1CE4E5B9ULL;
  z          = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z          = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  z ^= z >> 31;
  return (double)(z >> 11) * (1.0 / 9007199254740992.0);
}

/* The reference law: a table (number probabilities p), or a normal (m, s), lognormal (mu, sg of
 * ln d) or uniform law cut to [a, b]. */
typedef enum {
  TABLE,
  NORMAL,
  LOGNORMAL,
  UNIFORM
} LawKind;
typedef struct {
  LawKind kind;
  double  a, b, m, s;
  int     n;
  double  d[8], p[8];
} Law;

static double Phi(double z)
{
  return 0.5 * erfc(-z / sqrt(2.0));
}
static double PhiBetween(double al, double be)
{
  return al > 0 ? Phi(-al) - Phi(-be) : Phi(be) - Phi(al);
}

/* E[d^k 1{d <= x}] of the law, k <= 12. */
static double Partial(const Law *L, int k, double x)
{
  double r = 0;

  if (L->kind == TABLE) {
    for (int i = 0; i < L->n; i++)
      if (L->d[i] <= x) r += L->p[i] * pow(L->d[i], k);
    return r;
  }
  if (x <= L->a) return 0;
  x = fmin(x, L->b);
  if (L->kind == UNIFORM) return (pow(x, k + 1) - pow(L->a, k + 1)) / ((k + 1) * (L->b - L->a));
  if (L->kind == LOGNORMAL) {
    const double al = (log(L->a) - L->m) / L->s, be = (log(L->b) - L->m) / L->s, xi = (log(x) - L->m) / L->s;
    return exp(k * L->m + 0.5 * k * k * L->s * L->s) * PhiBetween(al - k * L->s, xi - k * L->s) / PhiBetween(al, be);
  }
  { /* normal: d = m + s y, int y^j phi(y) dy over [al, xi] by I_j = (j-1) I_{j-2} + al^{j-1} phi(al) - xi^{j-1} phi(xi) */
    const double al = (L->a - L->m) / L->s, be = (L->b - L->m) / L->s, xi = (x - L->m) / L->s;
    const double fa = exp(-0.5 * al * al) / sqrt(2 * PETSC_PI), fx = exp(-0.5 * xi * xi) / sqrt(2 * PETSC_PI);
    double       In[13], binom                                     = 1;
    In[0] = PhiBetween(al, xi);
    In[1] = fa - fx;
    for (int j = 2; j <= k; j++) In[j] = (j - 1) * In[j - 2] + pow(al, j - 1) * fa - pow(xi, j - 1) * fx;
    for (int j = 0; j <= k; j++) {
      r += binom * pow(L->m, k - j) * pow(L->s, j) * In[j];
      binom = binom * (k - j) / (j + 1);
    }
    return r / PhiBetween(al, be);
  }
}

static double Moment(const Law *L, int k)
{
  return Partial(L, k, INFINITY);
}

/* The number density of the cut law at x. */
static double Density(const Law *L, double x)
{
  if (L->kind == UNIFORM) return 1 / (L->b - L->a);
  if (L->kind == NORMAL) return exp(-0.5 * pow((x - L->m) / L->s, 2)) / (sqrt(2 * PETSC_PI) * L->s * PhiBetween((L->a - L->m) / L->s, (L->b - L->m) / L->s));
  return exp(-0.5 * pow((log(x) - L->m) / L->s, 2)) / (sqrt(2 * PETSC_PI) * L->s * x * PhiBetween((log(L->a) - L->m) / L->s, (log(L->b) - L->m) / L->s));
}

/* The p-quantile by number (k = 0) or by mass (k = 3): the smallest d with Partial(k, d) >=
 * p Moment(k) (a table's atom; bisection for a continuous law). */
static double Quantile(const Law *L, int k, double p)
{
  const double tot = Moment(L, k);
  double       lo = L->a, hi = L->b;

  if (L->kind == TABLE) {
    for (int i = 0; i < L->n; i++)
      if (Partial(L, k, L->d[i]) >= p * tot) return L->d[i];
    return L->d[L->n - 1];
  }
  for (int it = 0; it < 200; it++) {
    const double mid = 0.5 * (lo + hi);
    if (Partial(L, k, mid) < p * tot) lo = mid;
    else hi = mid;
  }
  return 0.5 * (lo + hi);
}

static int CompareDouble(const void *a, const void *b)
{
  const double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

/* A distribution read from an options string under -dem_insert_0, as a source reads it. */
static PetscErrorCode PsdFromString(const char *opts, DemPsd *psd)
{
  PetscOptions o;

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsCreate(&o));
  PetscCall(PetscOptionsInsertString(o, opts));
  PetscCall(PetscOptionsPush(o));
  PetscOptionsBegin(PETSC_COMM_WORLD, NULL, "Size distribution", NULL);
  PetscCall(DemPsdSetFromOptions(PetscOptionsObject, PETSC_COMM_WORLD, "-dem_insert_0", 1e-3, psd));
  PetscOptionsEnd();
  PetscCall(PetscOptionsPop());
  PetscCall(PetscOptionsDestroy(&o));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* |measured - exact| within 3 standard errors, z printed. */
static PetscErrorCode CheckSE(const char *law, const char *what, double measured, double exact, double se)
{
  PetscFunctionBeginUser;
  CheckDetail("z = %.2f", (measured - exact) / se);
  PetscCall(CheckCloseAbs(CheckName("%s, %s within 3 SE (SE %.3g m)", law, what, se), measured, exact, 3 * se));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The sample's statistics: [0..4] number mean, std, d10, d50, d90; [5..9] the same by mass. d is
 * sorted on return. */
static void SampleStats(double *d, int n, double st[10])
{
  const double p[3] = {0.1, 0.5, 0.9};
  double       s1 = 0, s3 = 0, s4 = 0, v = 0, vm = 0, c = 0;
  int          j = 0;

  qsort(d, n, sizeof d[0], CompareDouble);
  for (int i = 0; i < n; i++) {
    s1 += d[i];
    s3 += d[i] * d[i] * d[i];
    s4 += d[i] * d[i] * d[i] * d[i];
  }
  st[0] = s1 / n;
  st[5] = s4 / s3;
  for (int i = 0; i < n; i++) {
    v += (d[i] - st[0]) * (d[i] - st[0]);
    vm += d[i] * d[i] * d[i] * (d[i] - st[5]) * (d[i] - st[5]);
  }
  st[1] = sqrt(v / n);
  st[6] = sqrt(vm / s3);
  for (int q = 0; q < 3; q++) st[2 + q] = d[(int)ceil(p[q] * n) - 1];
  for (int i = 0; i < n && j < 3; i++) { /* mass quantiles: the first d whose cumulative mass reaches p */
    c += d[i] * d[i] * d[i];
    while (j < 3 && c >= p[j] * s3) st[7 + j++] = d[i];
  }
}

/* The law's exact statistics (as SampleStats) and their standard errors for n samples. */
static void LawStats(const Law *L, int n, double ex[10], double se[10])
{
  const double p[3] = {0.1, 0.5, 0.9};
  double       M[13];

  for (int k = 0; k <= 12; k++) M[k] = Moment(L, k);
  {
    const double var = M[2] - M[1] * M[1], mu4 = M[4] - 4 * M[1] * M[3] + 6 * M[1] * M[1] * M[2] - 3 * pow(M[1], 4);
    ex[0] = M[1];
    ex[1] = sqrt(var);
    se[0] = sqrt(var / n);
    se[1] = sqrt((mu4 - var * var) / (4 * var * n));
  }
  {
    const double A = M[3], B = M[4], C = M[5], R = B / A, v = C / A - R * R;
    const double g[3] = {-C / (A * A) + 2 * B * B / (A * A * A), -2 * B / (A * A), 1 / A};
    double       e2   = 0;
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) e2 += g[i] * g[j] * (M[6 + i + j] - M[3 + i] * M[3 + j]);
    ex[5] = R;
    ex[6] = sqrt(v);
    se[5] = sqrt((M[8] - 2 * R * M[7] + R * R * M[6]) / n) / A;
    se[6] = sqrt(e2 / n) / (2 * ex[6]);
  }
  for (int q = 0; q < 3; q++) {
    ex[2 + q] = Quantile(L, 0, p[q]);
    ex[7 + q] = Quantile(L, 3, p[q]);
    if (L->kind == TABLE) se[2 + q] = se[7 + q] = 0; /* atoms: compared exactly */
    else {
      const double x = ex[7 + q];
      se[2 + q]      = sqrt(p[q] * (1 - p[q]) / n) / Density(L, ex[2 + q]);
      se[7 + q]      = sqrt(((1 - 2 * p[q]) * Partial(L, 6, x) + p[q] * p[q] * M[6]) / n) / (x * x * x * Density(L, x));
    }
  }
}

/* Draws NS diameters of psd and checks their ten statistics against the law L; d receives the
 * samples (sorted). */
static PetscErrorCode CheckLaw(const char *name, const DemPsd *psd, const Law *L, double *d)
{
  const char *what[10] = {"number mean", "number std", "number d10", "number d50", "number d90", "mass mean", "mass std", "mass d10", "mass d50", "mass d90"};
  double      st[10], ex[10], se[10], lo, hi;

  PetscFunctionBeginUser;
  for (int i = 0; i < NS; i++) d[i] = DemPsdSample(psd, Uniform(7, i));
  SampleStats(d, NS, st);
  LawStats(L, NS, ex, se);
  for (int k = 0; k < 10; k++) {
    if (se[k] > 0) PetscCall(CheckSE(name, what[k], st[k], ex[k], se[k]));
    else PetscCall(CheckEqualReal(CheckName("%s, %s is the table's exact atom", name, what[k]), st[k], ex[k]));
  }
  PetscCall(CheckClose(CheckName("%s, mean of d^3 (DemPsdMeanCube)", name), DemPsdMeanCube(psd), Moment(L, 3), 1e-12));
  DemPsdRange(psd, &lo, &hi);
  CheckDetail("samples in [%.6g, %.6g] m", d[0], d[NS - 1]);
  PetscCall(CheckTrue(CheckName("%s, range is the law's [%g, %g] m and holds every sample", name, L->kind == TABLE ? L->d[0] : L->a, L->kind == TABLE ? L->d[L->n - 1] : L->b), (PetscBool)(lo == (L->kind == TABLE ? L->d[0] : L->a) && hi == (L->kind == TABLE ? L->d[L->n - 1] : L->b) && d[0] >= lo && d[NS - 1] <= hi), NULL));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The largest |z| of the table's fractions in the sorted sample d, by number (mass = false) or
 * by mass, against the set fractions f (normalised), each z = (measured - set) / SE. */
static double FractionZ(const Law *L, const double *f, PetscBool mass, const double *d, PetscBool report, const char *name, PetscErrorCode *ierr)
{
  double tot = 0, fsum = 0, M3 = Moment(L, 3), M6 = Moment(L, 6), zmax = 0;

  *ierr = PETSC_SUCCESS;
  for (int i = 0; i < L->n; i++) fsum += f[i];
  for (int i = 0; i < NS; i++) tot += mass ? d[i] * d[i] * d[i] : 1;
  for (int e = 0; e < L->n; e++) {
    const double set = f[e] / fsum, de = L->d[e], pe = L->p[e];
    double       got = 0, se;
    for (int i = 0; i < NS; i++)
      if (d[i] == de) got += mass ? de * de * de : 1;
    got /= tot;
    se   = mass ? sqrt((pow(de, 6) * pe * (1 - 2 * set) + set * set * M6) / NS) / M3 : sqrt(set * (1 - set) / NS);
    zmax = fmax(zmax, fabs(got - set) / se);
    if (report) {
      CheckDetail("z = %.2f", (got - set) / se);
      *ierr = CheckCloseAbs(CheckName("%s, %s fraction of d = %g m within 3 SE (SE %.2g)", name, mass ? "mass" : "number", de, se), got, set, 3 * se);
      if (*ierr) return zmax;
    }
  }
  return zmax;
}

/* The reference table: diameters sorted, number probabilities from the set fractions (by mass:
 * f / d^3, normalised); entries above dmax dropped. */
static void TableLaw(int n, const double *dd, const double *f, PetscBool mass, double dmax, Law *L, double *fk)
{
  double sum = 0;

  L->kind = TABLE;
  L->n    = 0;
  for (int i = 0; i < n; i++) {
    int k;
    if (dd[i] > dmax) continue;
    for (k = L->n++; k > 0 && L->d[k - 1] > dd[i]; k--) {
      L->d[k] = L->d[k - 1];
      fk[k]   = fk[k - 1];
    }
    L->d[k] = dd[i];
    fk[k]   = f[i];
  }
  for (int i = 0; i < L->n; i++) sum += mass ? fk[i] / pow(L->d[i], 3) : fk[i];
  for (int i = 0; i < L->n; i++) L->p[i] = (mass ? fk[i] / pow(L->d[i], 3) : fk[i]) / sum;
}

static PetscErrorCode Tables(double *d)
{
  const double   dn[3] = {1e-3, 0.5e-3, 2e-3}, fn[3] = {0.5, 0.2, 0.3};              /* by number, unsorted */
  const double   dm[4] = {0.5e-3, 1e-3, 2e-3, 4e-3}, fm[4] = {0.15, 0.3, 0.55, 0.2}; /* by mass; 4 mm cut off */
  Law            L;
  double         fk[8], z;
  DemPsd         psd;
  PetscErrorCode ierr;

  PetscFunctionBeginUser;
  PetscCall(PsdFromString("-dem_insert_0_psd number -dem_insert_0_psd_diameters 1e-3,0.5e-3,2e-3 -dem_insert_0_psd_fractions 0.5,0.2,0.3", &psd));
  TableLaw(3, dn, fn, PETSC_FALSE, INFINITY, &L, fk);
  PetscCall(CheckLaw("table by number", &psd, &L, d));
  FractionZ(&L, fk, PETSC_FALSE, d, PETSC_TRUE, "table by number", &ierr);
  PetscCall(ierr);

  PetscCall(PsdFromString("-dem_insert_0_psd mass -dem_insert_0_psd_diameters 0.5e-3,1e-3,2e-3,4e-3 -dem_insert_0_psd_fractions 0.15,0.3,0.55,0.2 -dem_insert_0_psd_max 3e-3", &psd));
  TableLaw(4, dm, fm, PETSC_TRUE, 3e-3, &L, fk);
  PetscCall(CheckLaw("table by mass", &psd, &L, d));
  FractionZ(&L, fk, PETSC_TRUE, d, PETSC_TRUE, "table by mass", &ierr);
  PetscCall(ierr);

  /* the same fractions sampled as number fractions: the mass check must see it */
  PetscCall(PsdFromString("-dem_insert_0_psd number -dem_insert_0_psd_diameters 0.5e-3,1e-3,2e-3 -dem_insert_0_psd_fractions 0.15,0.3,0.55", &psd));
  for (int i = 0; i < NS; i++) d[i] = DemPsdSample(&psd, Uniform(7, i));
  z = FractionZ(&L, fk, PETSC_TRUE, d, PETSC_FALSE, NULL, &ierr);
  PetscCall(CheckAbove("mass fractions sampled as number fractions fail the mass check: largest |z|", z, 3));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode Laws(double *d)
{
  DemPsd psd;
  Law    L = {0};
  double s2;

  PetscFunctionBeginUser;
  PetscCall(PsdFromString("-dem_insert_0_psd lognormal -dem_insert_0_psd_mean 1e-3 -dem_insert_0_psd_std 0.5e-3 -dem_insert_0_psd_min 0.4e-3 -dem_insert_0_psd_max 2.5e-3", &psd));
  s2 = log(1 + 0.25);
  L  = (Law){LOGNORMAL, 0.4e-3, 2.5e-3, log(1e-3) - 0.5 * s2, sqrt(s2), 0, {0}, {0}};
  PetscCall(CheckLaw("lognormal cut to [0.4, 2.5] mm", &psd, &L, d));

  PetscCall(PsdFromString("-dem_insert_0_psd normal -dem_insert_0_psd_mean 1e-3 -dem_insert_0_psd_std 0.25e-3 -dem_insert_0_psd_min 0.5e-3 -dem_insert_0_psd_max 1.6e-3", &psd));
  L = (Law){NORMAL, 0.5e-3, 1.6e-3, 1e-3, 0.25e-3, 0, {0}, {0}};
  PetscCall(CheckLaw("normal cut to [0.5, 1.6] mm", &psd, &L, d));

  /* a window 6 to 7 standard deviations above the mean: sampled by its upper-tail probabilities */
  PetscCall(PsdFromString("-dem_insert_0_psd normal -dem_insert_0_psd_mean 1e-3 -dem_insert_0_psd_std 0.1e-3 -dem_insert_0_psd_min 1.6e-3 -dem_insert_0_psd_max 1.7e-3", &psd));
  L = (Law){NORMAL, 1.6e-3, 1.7e-3, 1e-3, 0.1e-3, 0, {0}, {0}};
  PetscCall(CheckLaw("normal's tail cut to [1.6, 1.7] mm", &psd, &L, d));

  PetscCall(PsdFromString("-dem_insert_0_psd uniform -dem_insert_0_psd_min 0.5e-3 -dem_insert_0_psd_max 1.5e-3", &psd));
  L = (Law){UNIFORM, 0.5e-3, 1.5e-3, 0, 0, 0, {0}, {0}};
  PetscCall(CheckLaw("uniform in [0.5, 1.5] mm", &psd, &L, d));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Classes: N = 5 equal-number bins of the cut lognormal, each sample its bin's median. */
static PetscErrorCode Classes(double *d)
{
  const double s2 = log(1.25);
  const Law    L  = {LOGNORMAL, 0.4e-3, 2.5e-3, log(1e-3) - 0.5 * s2, sqrt(s2), 0, {0}, {0}};
  DemPsd       psd;
  double       err = 0, fz = 0, c3 = 0;
  int          distinct = 1;

  PetscFunctionBeginUser;
  PetscCall(PsdFromString("-dem_insert_0_psd lognormal -dem_insert_0_psd_mean 1e-3 -dem_insert_0_psd_std 0.5e-3 -dem_insert_0_psd_min 0.4e-3 -dem_insert_0_psd_max 2.5e-3 -dem_insert_0_psd_classes 5", &psd));
  for (int i = 0; i < NS; i++) d[i] = DemPsdSample(&psd, Uniform(7, i));
  qsort(d, NS, sizeof d[0], CompareDouble);
  for (int i = 1; i < NS; i++) distinct += d[i] != d[i - 1];
  for (int j = 0; j < 5; j++) {
    const double med = Quantile(&L, 0, (j + 0.5) / 5);
    int          cnt = 0;
    for (int i = 0; i < NS; i++) cnt += fabs(d[i] - med) < 1e-9 * med;
    err = fmax(err, fabs(d[(int)((j + 0.5) / 5 * NS)] - med) / med);
    fz  = fmax(fz, fabs(cnt / (double)NS - 0.2) / sqrt(0.2 * 0.8 / NS));
    c3 += pow(med, 3) / 5;
  }
  PetscCall(CheckEqual("lognormal in 5 classes: distinct diameters", distinct, 5));
  PetscCall(CheckBelow("lognormal in 5 classes: each class the median of its equal-number bin, relative error", err, 1e-12));
  PetscCall(CheckBelow("lognormal in 5 classes: largest |z| of the class fractions (1/5 each)", fz, 3));
  PetscCall(CheckClose("lognormal in 5 classes: mean of d^3 (DemPsdMeanCube)", DemPsdMeanCube(&psd), c3, 1e-12));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The normal quantile against 20-digit values (mpmath, 80 digits), and the default cut-offs:
 * the law's 1e-6 tails, a normal's lower one at least a tenth of its mean. */
static PetscErrorCode QuantileAndDefaults(void)
{
  const double p[]  = {0.975, 0.9, 0.999, 0.3, 1e-10, 1e-20, 1e-300};
  const double x[]  = {1.9599639845400542355, 1.281551565544600467, 3.0902323061678135415, -0.52440051270804078404, -6.3613409024040562047, -9.2623400897984075737, -37.047096299361199237};
  double       emax = 0, lo, hi;
  DemPsd       psd;

  PetscFunctionBeginUser;
  for (size_t k = 0; k < sizeof p / sizeof p[0]; k++) emax = fmax(emax, fabs(DemPsdNormalQuantile(p[k]) - x[k]) / fabs(x[k]));
  PetscCall(CheckBelow("normal quantile at 7 points in [1e-300, 0.999], largest relative error", emax, 1e-14));
  PetscCall(PsdFromString("-dem_insert_0_psd lognormal -dem_insert_0_psd_mean 1e-3 -dem_insert_0_psd_std 0.5e-3", &psd));
  DemPsdRange(&psd, &lo, &hi);
  {
    const double s2 = log(1.25), mu = log(1e-3) - 0.5 * s2;
    CheckDetail("[%.4g, %.4g] m", lo, hi);
    PetscCall(CheckClose("lognormal without cut-offs: law's probability below the default lower cut-off", Phi((log(lo) - mu) / sqrt(s2)), 1e-6, 1e-9));
    PetscCall(CheckClose("lognormal without cut-offs: law's probability above the default upper cut-off", Phi(-(log(hi) - mu) / sqrt(s2)), 1e-6, 1e-9));
  }
  PetscCall(PsdFromString("-dem_insert_0_psd normal -dem_insert_0_psd_mean 1e-3 -dem_insert_0_psd_std 0.5e-3", &psd));
  DemPsdRange(&psd, &lo, &hi);
  PetscCall(CheckClose("wide normal without cut-offs: default lower cut-off is a tenth of the mean", lo, 1e-4, 1e-15));
  PetscCall(CheckClose("wide normal without cut-offs: law's probability above the default upper cut-off", Phi(-(hi - 1e-3) / 0.5e-3), 1e-6, 1e-9));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The bad-input mode: the arguments read as source 0's distribution, checked as sable checks
 * its options; one line, "psd: ..." or "error: ...". */
static PetscErrorCode OneLineError(MPI_Comm comm, int line, const char *func, const char *file, PetscErrorCode n, PetscErrorType p, const char *mess, void *ctx)
{
  (void)comm, (void)line, (void)func, (void)file, (void)ctx;
  if (p == PETSC_ERROR_INITIAL) fprintf(stderr, "error: %s\n", mess);
  return n;
}

static PetscErrorCode OptionsOnly(void)
{
  DemPsd psd;
  char   buf[256];

  PetscFunctionBeginUser;
  PetscCall(SableCheckOptionValues(PETSC_COMM_WORLD));
  PetscOptionsBegin(PETSC_COMM_WORLD, NULL, "Size distribution", NULL);
  PetscCall(DemPsdSetFromOptions(PetscOptionsObject, PETSC_COMM_WORLD, "-dem_insert_0", 1e-3, &psd));
  PetscOptionsEnd();
  PetscCall(SableCheckOptionsUsed(PETSC_COMM_WORLD));
  PetscCall(DemPsdDescribe(&psd, buf, sizeof buf));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "psd: %s\n", buf));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  double *d;

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  if (argc > 1) {
    PetscErrorCode ierr;
    PetscCall(PetscPushErrorHandler(OneLineError, NULL));
    ierr = OptionsOnly();
    PetscCall(PetscPopErrorHandler());
    PetscCall(PetscFinalize());
    return ierr ? 1 : 0;
  }
  PetscCall(PetscMalloc1(NS, &d));
  PetscCall(QuantileAndDefaults());
  PetscCall(Tables(d));
  PetscCall(Laws(d));
  PetscCall(Classes(d));
  PetscCall(PetscFree(d));
  PetscCall(PetscFinalize());
  return check_failures ? 1 : 0;
}
