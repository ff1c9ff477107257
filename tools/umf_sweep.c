/* U_mf from a pressure-drop sweep, as an experimentalist reads it (driven by tools/umf_sweep;
 * build: make build/tools/umf_sweep). One coupled run of the options given (the bed of
 * cases/fluidized_bed/umf_sweep.opts: a simple cubic lattice standing between frictionless side
 * walls on the inlet face) with the inlet ramped linearly (-fluid_bc_zlo_velocity_table,
 * -fluid_inlet_interpolation linear).
 * Every fluid step records the inlet's superficial velocity U and the pressure drop across the
 * column, dp = p(z = 0) - p(top cell), p(z = 0) the inlet face's pressure (FluidFacePressure:
 * the two lowest centres' linear extrapolation plus the drag the beads leave on the inlet's face
 * points; the bed starts on the inlet face, so the half cell below the first centre holds bed
 * whatever the cell size; -umf_extrapolate: the extrapolation alone, as before). The packed branch, the steps with U in -umf_fit lo,hi times the drag
 * law's prediction U_mf(eps_ref) (CplGetMinFluidization at -umf_eps, default 1 - pi/6), is
 * fitted by least squares to dp = a U + b U^2 (Ergun's form); U_mf is where that fit reaches the
 * bed's buoyant weight per area W = N (pi d^3/6)(rho_p - rho_f) g / A (-dem_radius,
 * -dem_density, -fluid_density, -dem_gravity; the column's cross-section A from -domain_lo/hi).
 * The plateau is the mean dp/W over the steps with U above 1.3 times the prediction.
 * Prints rows "U dp/W" every -umf_print steps and one line "result: key=value ...". */
#include "coupling/coupling.h"
#include "dem/dem.h"

typedef struct {
  PetscReal *u, *dp;
  PetscInt   n, cap;
} Sweep;

static PetscErrorCode SweepAdd(Sweep *s, PetscReal u, PetscReal dp)
{
  PetscFunctionBeginUser;
  if (s->n == s->cap) {
    s->cap = PetscMax(1024, 2 * s->cap);
    PetscCall(PetscRealloc(s->cap * sizeof(PetscReal), &s->u));
    PetscCall(PetscRealloc(s->cap * sizeof(PetscReal), &s->dp));
  }
  s->u[s->n]  = u;
  s->dp[s->n] = dp;
  s->n++;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Least squares dp = a U + b U^2 over the points with lo <= U <= hi; U where it reaches W. */
static PetscReal SweepKnee(const Sweep *s, PetscReal lo, PetscReal hi, PetscReal W, PetscInt *npts)
{
  PetscReal s22 = 0, s23 = 0, s33 = 0, s1 = 0, s2 = 0, det, a, b;
  *npts = 0;
  for (PetscInt i = 0; i < s->n; i++) {
    const PetscReal u = s->u[i], d = s->dp[i];
    if (u < lo || u > hi) continue;
    s22 += u * u;
    s23 += u * u * u;
    s33 += u * u * u * u;
    s1 += d * u;
    s2 += d * u * u;
    (*npts)++;
  }
  det = s22 * s33 - s23 * s23;
  a   = (s1 * s33 - s2 * s23) / det;
  b   = (s22 * s2 - s23 * s1) / det;
  return b != 0 ? (-a + PetscSqrtReal(a * a + 4 * b * W)) / (2 * b) : W / a;
}

static PetscErrorCode BuoyantWeightPerArea(Dem dem, PetscReal *W)
{
  PetscReal r = 0.5, rp = 1000, rf = 1000, g[3] = {0, 0, -9.81}, lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
  PetscInt  n, N, three = 3;

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-dem_radius", &r, NULL));
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-dem_density", &rp, NULL));
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-fluid_density", &rf, NULL));
  PetscCall(PetscOptionsGetRealArray(NULL, NULL, "-dem_gravity", g, &three, NULL));
  three = 3;
  PetscCall(PetscOptionsGetRealArray(NULL, NULL, "-domain_lo", lo, &three, NULL));
  three = 3;
  PetscCall(PetscOptionsGetRealArray(NULL, NULL, "-domain_hi", hi, &three, NULL));
  PetscCall(DemGetLocalCount(dem, &n));
  PetscCallMPI(MPIU_Allreduce(&n, &N, 1, MPIU_INT, MPI_SUM, PETSC_COMM_WORLD));
  *W = N * (4.0 / 3.0) * PETSC_PI * r * r * r * (rp - rf) * PetscAbsReal(g[2]) / ((hi[0] - lo[0]) * (hi[1] - lo[1]));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  Domain          dom;
  Dem             dem;
  Fluid           fl;
  Cpl             cpl;
  CplStats        st;
  CplFluidization f;
  Sweep           sw     = {0};
  PetscReal       fit[2] = {0.3, 0.7}, eps_ref = 1 - PETSC_PI / 6, t_end = 100, t = 0, W = 0, h, top, plateau = 0;
  PetscBool       face = PETSC_TRUE;
  PetscInt        nfit = 2, print = 200, step = 0, np = 0, npl = 0;

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(PetscOptionsGetRealArray(NULL, NULL, "-umf_fit", fit, &nfit, NULL));
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-umf_eps", &eps_ref, NULL));
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-umf_print", &print, NULL));
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-cpl_t_end", &t_end, NULL));
  {
    PetscBool extrapolate = PETSC_FALSE;
    PetscCall(PetscOptionsGetBool(NULL, NULL, "-umf_extrapolate", &extrapolate, NULL));
    face = (PetscBool)!extrapolate;
  }
  PetscCall(DomainCreate(PETSC_COMM_WORLD, 1.0, 1, &dom));
  PetscCall(DemCreate(&dom, &dem));
  PetscCall(DemSetFromOptions(dem));
  PetscCall(DemExternalSetFromOptions(dem));
  PetscCall(FluidCreate(&dom, &fl));
  PetscCall(FluidSetFromOptions(fl));
  PetscCall(CplCreate(&dom, dem, fl, &cpl));
  PetscCall(CplSetFromOptions(cpl));
  PetscCall(DemSetUp(dem));
  PetscCall(FluidSetUp(fl));
  PetscCall(CplSetUp(cpl));
  PetscCall(BuoyantWeightPerArea(dem, &W));
  {
    PetscReal d32, rhop;
    PetscCall(CplGetBedDiameter(cpl, &d32, &rhop));
    PetscCall(CplGetMinFluidization(cpl, eps_ref, d32, rhop, &f));
  }
  h   = dom.h[2];
  top = dom.hi[2] - 0.5 * h;
  while (t < t_end - 1e-9) {
    PetscReal p0, p1, pt, e, u, U[3];
    PetscInt  ninlet;
    PetscCall(CplStep(cpl, &st));
    PetscCall(CplGetTime(cpl, &t, NULL));
    PetscCall(FluidGetInletVelocity(fl, U, &ninlet));
    PetscCall(CplGetLayer(cpl, 2, top, NULL, &pt, &e, &u));
    if (face) PetscCall(FluidFacePressure(fl, 2, 0, &p0)); /* the inlet face's pressure, the drag left on it included */
    else {
      PetscCall(CplGetLayer(cpl, 2, dom.lo[2] + 0.5 * h, NULL, &p0, &e, &u));
      PetscCall(CplGetLayer(cpl, 2, dom.lo[2] + 1.5 * h, NULL, &p1, &e, &u));
      p0 += 0.5 * (p0 - p1);
    }
    const PetscReal dp = p0 - pt;
    PetscCall(SweepAdd(&sw, U[2], dp));
    if (U[2] > 1.3 * f.umf) {
      plateau += dp / W;
      npl++;
    }
    if (print > 0 && ++step % print == 0) PetscCall(PetscPrintf(PETSC_COMM_WORLD, "t %.4g U %.5g dp/W %.5f\n", (double)t, (double)U[2], (double)(dp / W)));
  }
  const PetscReal umf = SweepKnee(&sw, fit[0] * f.umf, fit[1] * f.umf, W, &np);
  PetscCheck(np >= 2, PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE, "umf_sweep: %d fluid steps with U in -umf_fit %g,%g x %g: the packed branch needs at least 2; ramp the inlet through that range before -cpl_t_end %g", (int)np, (double)fit[0], (double)fit[1], (double)f.umf, (double)t_end);
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "result: h=%.6g umf=%.6g pred=%.6g ratio=%.5f W=%.6g fit_points=%d plateau=%.5f\n", (double)h, (double)umf, (double)f.umf, (double)(umf / f.umf), (double)W, (int)np, (double)(npl ? plateau / npl : 0)));
  PetscCall(PetscFree(sw.u));
  PetscCall(PetscFree(sw.dp));
  PetscCall(CplDestroy(&cpl));
  PetscCall(FluidDestroy(&fl));
  PetscCall(DemDestroy(&dem));
  PetscCall(DomainDestroy(&dom));
  PetscCall(PetscFinalize());
  return 0;
}
