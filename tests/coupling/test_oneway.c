/* One-way coupling (-cpl_mode oneway): a single glass sphere (d = 1 mm, rho_p = 2500 kg/m^3)
 * released at rest in water-like fluid (rho_f = 1000) that flows upward at U0 through a column
 * periodic across, inlet below and outlet above, started uniform (-cpl_init_fluid uniform). The
 * fluid is single phase, so it stays u = U0 everywhere and the particle obeys
 *   m dv/dt = (m - rho_f V) g + K(Re) (U0 - v),  K = 3 pi mu d F(Re),  Re = rho_f d |U0 - v| / mu,
 * whose solution is the reference at every coupling step:
 *  1. Stokes: mu = 1 Pa s, Re_t 8e-4. The default law (Beetstra) at porosity 1 has F = 1 +
 *     0.1446 Re^1.157 + ... -> 1 (4e-5 at Re_t); Stokes' F = 1 gives the exact exponential
 *     v = v_t + (v0 - v_t) exp(-t/tau), tau = m / (3 pi mu d), v_t = U0 + (m - rho_f V) g tau / m.
 *     (Di Felice's Stokes limit is F = 0.96, 4% off: not the law compared here.)
 *  2. Schiller-Naumann (-cpl_drag schiller), mu = 0.01 Pa s, Re_t 5.5 (F = 1.5 at the end): the
 *     ODE has no closed form in t; the reference is a classical RK4 quadrature written here, with
 *     steps of tau/4000 (halving them changes it by < 1e-12 of the velocity change).
 * Error measure: max over the steps of |v - v_ref| / |v_t - v0| (the velocity change). Bound
 * 0.5%; measured 0.14% (Stokes, dt_dem = tau/70: the DEM's backward-Euler drag half kicks,
 * dem/external.c, are first order in dt_dem/tau) and 0.015% (Schiller-Naumann), on two grids (cells of 1 d and 2.5 d: the answer must not depend on the grid); also the
 * fluid stays U0 to roundoff (nothing reacts on it), and the velocity after 12 (Stokes) or 7
 * (Schiller-Naumann) relaxation times is the law's terminal velocity within 0.5%. */
#include "cpl_common.h"

#define BASE "-domain_lo 0,0,0 -domain_hi 0.01,0.01,0.02 -domain_periodic_x -domain_periodic_y -dem_radius 0.5e-3 -dem_density 2500 -dem_kn 100 -dem_gravity 0,0,-9.81 -dem_lattice 1,1,1 -dem_lattice_spacing 1e-3 -dem_lattice_origin 4.5e-3,4.5e-3,13.5e-3 -fluid_density 1000 -fluid_bc_zlo inlet -fluid_bc_zhi outlet -cpl_mode oneway -cpl_init_fluid uniform -cpl_substeps 5"

typedef struct {
  PetscReal   mu, U0, dt_dem, t_end; /* Pa s, m/s, s, s */
  CplDragLaw  law;
  const char *name, *opt;
} Case;

static const PetscReal d = 1e-3, rp = 2500, rf = 1000, g = -9.81;

/* dv/dt of the ODE at particle velocity v (m/s). */
static PetscReal Accel(const Case *k, PetscReal v)
{
  const PetscReal m = rp * PETSC_PI * d * d * d / 6, V = PETSC_PI * d * d * d / 6;
  const PetscReal re = rf * d * PetscAbsReal(k->U0 - v) / k->mu;
  const PetscReal F  = k->law == CPL_DRAG_SCHILLER ? CplDragFactor(CPL_DRAG_SCHILLER, 1, re) : 1;
  return (m - rf * V) * g / m + 3 * PETSC_PI * k->mu * d * F * (k->U0 - v) / m;
}

/* The reference v(t) from v(t0) = v by RK4 steps of at most h. */
static PetscReal Advance(const Case *k, PetscReal v, PetscReal dt, PetscReal h)
{
  const PetscInt  n = (PetscInt)PetscCeilReal(dt / h - 1e-9);
  const PetscReal s = dt / n;
  for (PetscInt i = 0; i < n; i++) {
    const PetscReal a = Accel(k, v), b = Accel(k, v + 0.5 * s * a), c = Accel(k, v + 0.5 * s * b), e = Accel(k, v + s * c);
    v += s / 6 * (a + 2 * b + 2 * c + e);
  }
  return v;
}

static void Uniform(const PetscReal x[3], PetscReal v[3], void *ctx)
{
  (void)x;
  v[0] = v[1] = 0;
  v[2]        = *(PetscReal *)ctx;
}

/* Terminal velocity of the law: Accel(v_t) = 0 by bisection between U0 - 10 m/s and U0. */
static PetscReal Terminal(const Case *k)
{
  PetscReal lo = k->U0 - 10, hi = k->U0;
  for (int it = 0; it < 200; it++) {
    const PetscReal v = 0.5 * (lo + hi);
    if (Accel(k, v) > 0) lo = v; /* drag still below the weight: v_t lies above */
    else hi = v;
  }
  return 0.5 * (lo + hi);
}

static PetscErrorCode RunCase(const Case *k, PetscInt cells_xy, PetscInt cells_z)
{
  char        opts[1024];
  TestCpl     t;
  CplStats    st;
  DemParticle p   = {0};
  PetscReal   tau = rp * d * d / (18 * k->mu), vt = Terminal(k), v0 = 0, vref = 0, err = 0, dt, time = 0, l2, linf;
  PetscInt    nsteps;

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(opts, sizeof opts, "%s -da_grid_x %d -da_grid_y %d -da_grid_z %d -fluid_viscosity %g -fluid_bc_zlo_velocity 0,0,%g -dem_dt %g %s", BASE, (int)cells_xy, (int)cells_xy, (int)cells_z, (double)k->mu, (double)k->U0, (double)k->dt_dem, k->opt));
  PetscCall(TestCplCreate(opts, &t));
  PetscCall(CplGetTimeStep(t.cpl, &dt));
  nsteps = (PetscInt)(k->t_end / dt + 0.5);
  for (PetscInt s = 0; s < nsteps; s++) {
    PetscCall(CplStep(t.cpl, &st));
    PetscCall(DemGetParticle(t.dem, 0, &p)); /* one rank: the particle is local */
    vref = Advance(k, vref, dt, tau / 4000);
    time += dt;
    err = PetscMax(err, PetscAbsReal(p.v[2] - vref) / PetscAbsReal(vt - v0));
  }
  {
    PetscReal U0 = k->U0;
    PetscCall(FluidVelocityError(t.fl, Uniform, &U0, &l2, &linf));
  }
  CheckDetail("bound 0.5%% of |v_t - v0| = %.4g m/s; %d steps of %.3g s = %.2f tau, Re_t %.3g, cells %.2g d", (double)PetscAbsReal(vt - v0), (int)nsteps, (double)dt, (double)(time / tau), (double)(rf * d * PetscAbsReal(k->U0 - vt) / k->mu), (double)(0.01 / cells_xy / d));
  PetscCall(CheckBelow(CheckName("%s, cells of %.2g d: velocity history vs the law's, max |v - v_ref| / |v_t - v0|", k->name, (double)(0.01 / cells_xy / d)), err, 5e-3));
  PetscCall(CheckClose(CheckName("%s, cells of %.2g d: velocity at the end vs the law's terminal velocity %.5g m/s", k->name, (double)(0.01 / cells_xy / d), (double)vt), p.v[2], vt, 5e-3));
  CheckDetail("bound 1e-10 of U0 = %g m/s", (double)k->U0);
  PetscCall(CheckBelow(CheckName("%s, cells of %.2g d: the fluid is untouched by the particle, max |u - U0| / U0", k->name, (double)(0.01 / cells_xy / d)), linf / k->U0, 1e-10));
  PetscCall(TestCplDestroy(&t));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  const Case cases[2] = {
    {1.0, 5e-4, 2e-6, 1.7e-3, CPL_DRAG_BEETSTRA, "Stokes (Beetstra at Re_p << 1)", ""},
    {1e-2, 2e-2, 2e-5, 0.1, CPL_DRAG_SCHILLER, "Schiller-Naumann", "-cpl_drag schiller"},
  };

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  for (int k = 0; k < 2; k++) {
    PetscCall(RunCase(&cases[k], 10, 20));
    PetscCall(RunCase(&cases[k], 4, 8));
  }
  PetscCall(PetscFinalize());
  return check_failures ? 1 : 0;
}
