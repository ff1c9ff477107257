/* One run of a trade-off reference problem (driven by tools/tradeoff; build: make
 * build/tools/tradeoff_run). Prints one line "result: key=value ..." that tools/tradeoff parses.
 * Errors stop with one line "sable: error: ..." and exit status 1, as bin/sable does.
 *  -tr_problem impact: two spheres (or a sphere and the plane z = 0 with -tr_wall) approach at
 *     -tr_v each, no gravity, no friction; dt = -tr_dt_tc x the contact time Tc that the contact
 *     law itself predicts (DemGetContactFigures: linear pi / sqrt(kn/m* - (gn/2)^2); Hertz from
 *     the reduced Hertz impact equation with its calibrated damping, checked against the closed
 *     form 2.8683 (m*^2/(R* E*^2 v))^(1/5) at e = 1 by tests/dem/test_impact.c). References: the set
 *     restitution -dem_restitution and that Tc. Contact start and end are located by linear
 *     interpolation of the overlap between steps; the restitution is the ratio of the normal
 *     relative velocities after and before. All -dem_ options pass through.
 *  -tr_problem bed: a frozen bed (simple cubic lattice from the -dem_lattice options; with
 *     -tr_bcc the body centres of that lattice are added), run -tr_steps fluid steps; dp/L
 *     between the heights -tr_probe z0,z1 against the drag law's prediction n K U/eps at the
 *     nominal porosity -tr_eps_ref (and at the porosity the grid measured between the probes,
 *     and Ergun's). Every step checks that the fluid velocity stays finite (a NaN stops the
 *     run with a message instead of reaching an output file). All -fluid_/-cpl_ options pass
 *     through. */
#include "coupling/coupling.h"
#include "dem/dem.h"

static PetscErrorCode OneLineError(MPI_Comm comm, int line, const char *func, const char *file, PetscErrorCode n, PetscErrorType p, const char *mess, void *ctx)
{
  (void)comm, (void)line, (void)func, (void)file, (void)ctx;
  if (p == PETSC_ERROR_INITIAL) fprintf(stderr, "sable: error: %s\n", mess ? mess : "unknown error"), fflush(stderr);
  return n;
}

/* the particle with this id (the DEM re-sorts its arrays) */
static PetscErrorCode GetById(Dem dem, PetscInt id, DemParticle *p)
{
  PetscInt n;

  PetscFunctionBeginUser;
  PetscCall(DemGetLocalCount(dem, &n));
  for (PetscInt i = 0; i < n; i++) {
    PetscCall(DemGetParticle(dem, i, p));
    if (p->id == id) PetscFunctionReturn(PETSC_SUCCESS);
  }
  SETERRQ(PETSC_COMM_SELF, PETSC_ERR_PLIB, "particle %" PetscInt_FMT " not found", id);
}

static PetscErrorCode Impact(void)
{
  PetscReal      dt_tc = 0.02, v = 0.5, r = 0.005, tc = 0, e = 0, dt, t_in = -1, t_out = -1, dprev = -1, e_meas = 0, vrel0, eset;
  PetscBool      wall  = PETSC_FALSE;
  PetscInt       steps = 0, contact_steps = 0;
  PetscLogDouble t0, t1;
  char           buf[64];

  PetscFunctionBeginUser;
  PetscOptionsBegin(PETSC_COMM_WORLD, NULL, "impact problem", NULL);
  PetscCall(PetscOptionsReal("-tr_dt_tc", "Time step over the contact time", NULL, dt_tc, &dt_tc, NULL));
  PetscCall(PetscOptionsReal("-tr_v", "Approach speed of each sphere (m/s)", NULL, v, &v, NULL));
  PetscCall(PetscOptionsBool("-tr_wall", "Sphere against the plane z = 0 instead of two spheres", NULL, wall, &wall, NULL));
  PetscOptionsEnd();
  PetscCheck(dt_tc > 0 && dt_tc <= 1, PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE, "-tr_dt_tc %g must be in (0,1]", (double)dt_tc);
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-dem_radius", &r, NULL));
  vrel0 = wall ? v : 2 * v;
  PetscCall(PetscSNPrintf(buf, sizeof buf, "%.17g", (double)vrel0));
  PetscCall(PetscOptionsSetValue(NULL, "-dem_impact_velocity", buf));
  PetscCall(PetscOptionsSetValue(NULL, "-dem_dt_max_fraction", "1"));
  PetscCall(PetscOptionsSetValue(NULL, "-dem_gravity", "0,0,0"));
  PetscCall(PetscOptionsSetValue(NULL, "-dem_friction", "0"));
  if (wall) PetscCall(PetscOptionsSetValue(NULL, "-dem_plane_0", "0,0,0,0,0,1"));
  PetscCall(PetscSNPrintf(buf, sizeof buf, "%g,%g,%g", -10 * r, -10 * r, -10 * r));
  PetscCall(PetscOptionsSetValue(NULL, "-domain_lo", buf));
  PetscCall(PetscSNPrintf(buf, sizeof buf, "%g,%g,%g", 10 * r, 10 * r, 10 * r));
  PetscCall(PetscOptionsSetValue(NULL, "-domain_hi", buf));
  for (int pass = 0; pass < 2; pass++) { /* pass 0 only asks the law for Tc */
    Domain dom;
    Dem    dem;
    PetscCall(PetscSNPrintf(buf, sizeof buf, "%.17g", pass ? (double)(dt_tc * tc) : 1e-9));
    PetscCall(PetscOptionsSetValue(NULL, "-dem_dt", buf));
    PetscCall(DomainCreate(PETSC_COMM_WORLD, 20 * r, 1, &dom));
    PetscCall(DemCreate(&dom, &dem));
    PetscCall(DemSetFromOptions(dem));
    DemParticle a = {.id = 0, .shape = 0, .x = {0, 0, (wall ? 1.02 : 1.01) * r}, .v = {0, 0, -v}, .q = {1, 0, 0, 0}};
    DemParticle b = {.id = 1, .shape = 0, .x = {0, 0, -1.01 * r}, .v = {0, 0, v}, .q = {1, 0, 0, 0}};
    PetscCall(DemAddParticle(dem, &a));
    if (!wall) PetscCall(DemAddParticle(dem, &b));
    PetscCall(DemSetUp(dem));
    if (pass == 0) {
      PetscCall(DemGetContactFigures(dem, 0, wall ? -1 : 0, vrel0, &tc, &eset));
      PetscCall(DemDestroy(&dem));
      PetscCall(DomainDestroy(&dom));
      continue;
    }
    dt = dt_tc * tc;
    PetscCall(PetscTime(&t0));
    for (; steps < 10000000 && t_out < 0; steps++) {
      DemParticle pa = {0}, pb = b;
      PetscReal   t, delta;
      PetscCall(GetById(dem, 0, &pa));
      if (!wall) PetscCall(GetById(dem, 1, &pb));
      delta = wall ? r - pa.x[2] : 2 * r - PetscAbsReal(pa.x[2] - pb.x[2]);
      PetscCall(DemGetTime(dem, &t, NULL));
      if (dprev <= 0 && delta > 0 && t_in < 0) t_in = t - dt * delta / (delta - dprev);
      if (delta > 0) contact_steps++;
      if (dprev > 0 && delta <= 0 && t_in >= 0) {
        t_out  = t - dt * delta / (delta - dprev);
        e_meas = (wall ? pa.v[2] : pa.v[2] - pb.v[2]) / vrel0;
      }
      PetscCheck(PetscIsNormalReal(delta) || delta == 0, PETSC_COMM_WORLD, PETSC_ERR_FP, "impact: overlap not finite at step %" PetscInt_FMT, steps);
      dprev = delta;
      PetscCall(DemStep(dem));
    }
    PetscCall(PetscTime(&t1));
    PetscCheck(t_out > 0, PETSC_COMM_WORLD, PETSC_ERR_CONV_FAILED, "impact: the spheres did not separate within %" PetscInt_FMT " steps", steps);
    PetscCall(DemDestroy(&dem));
    PetscCall(DomainDestroy(&dom));
  }
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-dem_restitution", &e, NULL));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "result: e_set=%.10g e_meas=%.10g err_e=%.6e tc_ref=%.10g tc_meas=%.10g err_tc=%.6e steps=%" PetscInt_FMT " contact_steps=%" PetscInt_FMT " particles=%d wall_s=%.6g us_per_pstep=%.6g iterations=0\n", (double)e, (double)e_meas, (double)(PetscAbsReal(e_meas - e) / e), (double)tc, (double)(t_out - t_in), (double)(PetscAbsReal(t_out - t_in - tc) / tc), steps, contact_steps, wall ? 1 : 2, t1 - t0, 1e6 * (t1 - t0) / (steps * (wall ? 1.0 : 2.0))));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* the body centres of the -dem_lattice cells (a body-centred cubic bed with the lattice sites) */
static PetscErrorCode AddBodyCentres(Dem dem)
{
  PetscInt  n[3] = {1, 1, 1}, nn = 3, nlocal;
  PetscReal a = 1, o[3] = {0, 0, 0}, lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsGetIntArray(NULL, NULL, "-dem_lattice", n, &nn, NULL));
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-dem_lattice_spacing", &a, NULL));
  nn = 3;
  PetscCall(PetscOptionsGetRealArray(NULL, NULL, "-dem_lattice_origin", o, &nn, NULL));
  nn = 3;
  PetscCall(PetscOptionsGetRealArray(NULL, NULL, "-domain_lo", lo, &nn, NULL));
  nn = 3;
  PetscCall(PetscOptionsGetRealArray(NULL, NULL, "-domain_hi", hi, &nn, NULL));
  PetscCall(DemGetLocalCount(dem, &nlocal));
  for (PetscInt k = 0; k < n[2] - 1; k++)
    for (PetscInt j = 0; j < n[1]; j++)
      for (PetscInt i = 0; i < n[0]; i++) {
        DemParticle p = {0};
        PetscCall(PetscMemzero(&p, sizeof p));
        p.id   = 1000000 + i + n[0] * (j + n[1] * k);
        p.q[0] = 1;
        p.x[0] = o[0] + (i + 1.0) * a; /* lattice sites are o + (i + 1/2) a */
        p.x[1] = o[1] + (j + 1.0) * a;
        p.x[2] = o[2] + (k + 1.0) * a;
        if (p.x[0] >= hi[0]) p.x[0] -= hi[0] - lo[0]; /* periodic sides */
        if (p.x[1] >= hi[1]) p.x[1] -= hi[1] - lo[1];
        PetscCall(DemAddParticle(dem, &p));
      }
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscReal Ergun(PetscReal eps, PetscReal U, PetscReal mu, PetscReal rho)
{
  const PetscReal e3 = eps * eps * eps;
  return 150 * mu * PetscSqr(1 - eps) * U / e3 + 1.75 * rho * (1 - eps) * U * U / e3;
}

static PetscErrorCode Bed(void)
{
  Domain         dom;
  Dem            dem;
  Fluid          fl;
  Cpl            cpl;
  CplStats       st;
  Vec            u;
  PetscBool      bcc    = PETSC_FALSE;
  PetscInt       nsteps = 60, nz = 2, its = 0, np;
  PetscReal      probe[2] = {8.5, 15.5}, eps_ref = 1 - PETSC_PI / 6, mu = 0.1, rho = 1, umax = 0;
  PetscReal      p0, p1, e0, e1, u0, u1, z0, z1, eps, dpdl;
  PetscLogDouble t0, t1;

  PetscFunctionBeginUser;
  PetscOptionsBegin(PETSC_COMM_WORLD, NULL, "frozen bed problem", NULL);
  PetscCall(PetscOptionsBool("-tr_bcc", "Add the body centres of the lattice cells", NULL, bcc, &bcc, NULL));
  PetscCall(PetscOptionsInt("-tr_steps", "Fluid steps", NULL, nsteps, &nsteps, NULL));
  PetscCall(PetscOptionsRealArray("-tr_probe", "Heights z0,z1 of the dp/L probes", NULL, probe, &nz, NULL));
  PetscCall(PetscOptionsReal("-tr_eps_ref", "Nominal bed porosity of the reference", NULL, eps_ref, &eps_ref, NULL));
  PetscOptionsEnd();
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-fluid_viscosity", &mu, NULL));
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-fluid_density", &rho, NULL));
  PetscCall(DomainCreate(PETSC_COMM_WORLD, 1.0, 1, &dom));
  PetscCall(DemCreate(&dom, &dem));
  PetscCall(DemSetFromOptions(dem));
  PetscCall(DemExternalSetFromOptions(dem));
  PetscCall(FluidCreate(&dom, &fl));
  PetscCall(FluidSetFromOptions(fl));
  PetscCall(CplCreate(&dom, dem, fl, &cpl));
  PetscCall(CplSetFromOptions(cpl));
  if (bcc) PetscCall(AddBodyCentres(dem));
  PetscCall(SableCheckOptionsUsed(PETSC_COMM_WORLD));
  PetscCall(DemSetUp(dem));
  PetscCall(FluidSetUp(fl));
  PetscCall(CplSetUp(cpl));
  PetscCall(FluidGetVelocity(fl, &u));
  PetscCall(PetscTime(&t0));
  for (PetscInt s = 0; s < nsteps; s++) {
    PetscReal un;
    PetscCall(CplStep(cpl, &st));
    its += st.fluid.poisson_its;
    PetscCall(VecNorm(u, NORM_INFINITY, &un));
    PetscCheck(PetscIsNormalReal(un) || un == 0, PETSC_COMM_WORLD, PETSC_ERR_FP, "fluid velocity not finite at step %" PetscInt_FMT ": lower -fluid_dt", s);
    umax = PetscMax(umax, un);
  }
  PetscCall(PetscTime(&t1));
  PetscCall(CplGetLayer(cpl, 2, probe[0], &z0, &p0, &e0, &u0));
  PetscCall(CplGetLayer(cpl, 2, probe[1], &z1, &p1, &e1, &u1));
  PetscCall(CplMeanPorosity(cpl, 2, z0, z1, &eps));
  PetscCall(DemGetLocalCount(dem, &np));
  dpdl = (p0 - p1) / (z1 - z0);
  {
    const PetscReal pred  = CplPackedBedGradient(CPL_DRAG_BEETSTRA, eps_ref, u0, 1, rho, mu);
    const PetscReal grid  = CplPackedBedGradient(CPL_DRAG_BEETSTRA, eps, u0, 1, rho, mu);
    const PetscReal scale = pred > 0 ? pred : 1; /* empty column: relative to 1 Pa/m */
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "result: dpdl=%.10g eps_ref=%.10g eps_grid=%.10g usup=%.10g pred=%.10g pred_grid=%.10g ergun=%.10g err=%.6e err_grid=%.6e umax=%.6g particles=%" PetscInt_FMT " steps=%" PetscInt_FMT " wall_s=%.6g us_per_pstep=%.6g iterations=%" PetscInt_FMT "\n", (double)dpdl, (double)eps_ref, (double)eps, (double)u0, (double)pred, (double)grid, (double)Ergun(eps_ref, u0, mu, rho), (double)(PetscAbsReal(dpdl - pred) / scale), (double)(grid > 0 ? PetscAbsReal(dpdl / grid - 1) : PetscAbsReal(dpdl)), (double)umax, np, nsteps, t1 - t0, np ? 1e6 * (t1 - t0) / (nsteps * (double)np) : 0.0, its));
  }
  PetscCall(CplDestroy(&cpl));
  PetscCall(FluidDestroy(&fl));
  PetscCall(DemDestroy(&dem));
  PetscCall(DomainDestroy(&dom));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  char           problem[32] = "impact";
  PetscBool      bed;
  PetscErrorCode ierr;

  PetscCall(PetscInitialize(&argc, &argv, NULL, "tradeoff_run: one run of a trade-off reference problem\n"));
  PetscCall(PetscPushErrorHandler(OneLineError, NULL));
  ierr = PetscOptionsGetString(NULL, NULL, "-tr_problem", problem, sizeof problem, NULL);
  if (!ierr) {
    PetscCall(PetscStrcmp(problem, "bed", &bed));
    ierr = bed ? Bed() : Impact();
  }
  if (ierr) {
    PetscFinalize();
    return 1;
  }
  PetscCall(PetscPopErrorHandler());
  PetscCall(PetscFinalize());
  return 0;
}
