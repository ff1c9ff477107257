/* Terminal velocity of a single sphere on coarse grids with the self corrections on
 * (-cpl_self_porosity -cpl_self_velocity). Dimensionless: d = 1, rho_f = 1, rho_p = 2, g = 1,
 * mu = (18 Re F(Re))^-1/2 with F Schiller-Naumann's 1 + 0.15 Re^0.687, so that the law's terminal
 * Reynolds number is Re. The sphere is held (put back after every coupling step, its velocity
 * free) at a fixed place in the cell (the centre, the centre of an x face, a corner) in a column
 * 32 d wide, periodic across, fed from an inlet 16 d below at the law's terminal velocity u_t and
 * started uniform: Galilean-equivalent to settling in still fluid, without the drift through the
 * cell. Its velocity relaxes to v; the slip u_t - v is its terminal velocity relative to the
 * undisturbed fluid. Reference: the law's own u_t (Schiller-Naumann, eps = 1: the
 * 3 pi mu d F u_t = (rho_p - rho_f) V g root by bisection); bound 2% at every place. Without the
 * correction the same slip is 5% off at 4 d cells, Re 10 (the sphere's drag slows the fluid of
 * its cell): a check shows it, so the bound discriminates. Relaxation length T = 20 tau +
 * 10 min(l^2/nu, l/u_t), l = 2 h (tau = m / K); coupling step min(tau, h / 2u_t, T / 200); the run
 * stops at 3/5 of T, where the slip is steady (the last fifth's mean moves by at most 0.16% of
 * u_t from 3/5 of T to T at every case here, the slowest the 1 d cells: 0.02-0.04%; a check
 * bounds the change from the run's fourth fifth to its last by 0.5% of u_t, measured 0.25%). Cells of 8,
 * 4 and 2 d at Re 10 and 100; centred on a z face (the whole force on one face) at 8 d, and at
 * 2 d with a kernel side of two cells
 * (-cpl_kernel_scale 4.96: -0.22% Re 10, -0.15% Re 100): with any side up to one cell the
 * response over-corrects there, -2.0% at 4 d Re 10 and -4.6% at 2 d Re 100 (doc/validation.md).
 * Cells of 1 d with -cpl_kernel_scale 2 at a
 * corner (its worst place, -1.3% Re 10, -1.6% Re 100); with the default kernel a 1 d cell
 * centre has G K > 1 (the grid's response to the particle's own drag exceeds its slip: +63%),
 * which the coupling must report as capped. Re 0.1 is not
 * here: its self-disturbance is well corrected (-3.3% at 2, 4, 8 d at every place, the same
 * offset uncorrected vs the unbounded-grid response) but that offset is the column's own: the
 * slip moves by -3.4%, -1.3%, -0.50%, -0.25% in columns 32, 64, 128, 256 d wide (1.5x as tall;
 * 8 d cells, centre), so walls fall under a quarter of the bound only at 128 d, where 8 and 4 d
 * cells are within 1% at four places (doc/validation.md) but a run takes 12-18 s (8 d) and
 * 133-221 s (4 d) a place: coupling/test_terminal_re01.sh runs the 8 d centre. */
#include "cpl_common.h"

typedef struct {
  PetscReal re, h, off[3];
  PetscBool correct;
  PetscReal kscale; /* -cpl_kernel_scale; 0: the default */
  PetscInt  steps;  /* coupling steps; 0: the full run */
} Case;

static PetscReal Terminal(PetscReal mu)
{
  PetscReal lo = 0, hi = 100;
  for (int it = 0; it < 200; it++) {
    const PetscReal v = 0.5 * (lo + hi);
    if (3 * PETSC_PI * mu * CplDragFactor(CPL_DRAG_SCHILLER, 1, v / mu) * v > PETSC_PI / 6) hi = v;
    else lo = v;
  }
  return 0.5 * (lo + hi);
}

/* The held sphere's mean slip over the last fifth of the run, over u_t, minus one, and the
 * particle-steps whose self correction hit its cap. */
/* The largest change of the mean slip from the run's fourth fifth to its last (of u_t), over the
 * runs to their length: the runs stop at 3/5 of T because the slip is steady there. */
static PetscReal max_drift = 0;

static PetscErrorCode HeldError(const Case *k, PetscReal *err, PetscInt *capped)
{
  const PetscReal mu = 1 / PetscSqrtReal(18 * k->re * CplDragFactor(CPL_DRAG_SCHILLER, 1, k->re)), ut = Terminal(mu);
  const PetscReal tau = 2.0 / (18 * mu * CplDragFactor(CPL_DRAG_SCHILLER, 1, k->re)), l = 2 * k->h;
  const PetscReal tend = 20 * tau + 10 * PetscMin(l * l / mu, l / ut), dt = PetscMin(PetscMin(tau, 0.5 * k->h / ut), tend / 200);
  const PetscInt  nx = (PetscInt)(32 / k->h + 0.5), nz = (PetscInt)(48 / k->h + 0.5), n = k->steps > 0 ? k->steps : 3 * (PetscInt)(tend / dt + 0.5) / 5;
  PetscReal       x0[3], slip = 0, prev = 0;
  char            opts[2048], ks[64] = "";
  TestCpl         t;
  CplStats        st;
  DemParticle     p = {0};

  PetscFunctionBeginUser;
  if (k->kscale > 0) PetscCall(PetscSNPrintf(ks, sizeof ks, "-cpl_kernel_scale %g", (double)k->kscale));
  x0[0] = (nx / 2 + k->off[0]) * k->h;
  x0[1] = (nx / 2 + k->off[1]) * k->h;
  x0[2] = (PetscFloorReal(nz / 3.0) + k->off[2]) * k->h;
  PetscCall(PetscSNPrintf(opts, sizeof opts, "-domain_lo 0,0,0 -domain_hi %g,%g,%g -domain_periodic_x -domain_periodic_y -da_grid_x %d -da_grid_y %d -da_grid_z %d -dem_radius 0.5 -dem_density 2 -dem_kn 1e-2 -dem_gravity 0,0,-1 -dem_lattice 1,1,1 -dem_lattice_spacing 1 -dem_lattice_origin %.17g,%.17g,%.17g -fluid_density 1 -fluid_viscosity %.17g -fluid_viscous implicit -fluid_bc_zlo inlet -fluid_bc_zlo_velocity 0,0,%.17g -fluid_bc_zhi outlet -cpl_init_fluid uniform -cpl_relaxation_ratio_max 10 -cpl_drag schiller -dem_dt %.17g -cpl_substeps 10 %s %s",
                          (double)(nx * k->h), (double)(nx * k->h), (double)(nz * k->h), (int)nx, (int)nx, (int)nz, (double)x0[0], (double)x0[1], (double)x0[2], (double)mu, (double)ut, (double)(dt / 10), k->correct ? "-cpl_self_porosity -cpl_self_velocity" : "", ks));
  PetscCall(TestCplCreate(opts, &t));
  for (PetscInt s = 0; s < n; s++) {
    PetscCall(CplStep(t.cpl, &st));
    PetscCall(DemGetParticle(t.dem, 0, &p)); /* one rank: the particle is local */
    for (int e = 0; e < 3; e++) p.x[e] = x0[e];
    PetscCall(DemSetParticle(t.dem, 0, &p));
    if (s >= 4 * n / 5) slip += (ut - p.v[2]) / (n - 4 * n / 5);
    else if (s >= 3 * n / 5) prev += (ut - p.v[2]) / (4 * n / 5 - 3 * n / 5);
  }
  *err = slip / ut - 1;
  if (k->steps == 0) max_drift = PetscMax(max_drift, PetscAbsReal(slip - prev) / ut);
  PetscCall(CplGetSelfCappedCount(t.cpl, capped));
  PetscCall(TestCplDestroy(&t));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  static const char     *place[3]  = {"centre", "x-face centre", "corner"};
  static const PetscReal off[3][3] = {{0.5, 0.5, 0.5}, {0, 0.5, 0.5}, {0, 0, 0}};
  static const PetscReal res[2] = {10, 100}, hs[2] = {8, 4};
  PetscReal              err;
  PetscInt               capped;

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  for (int r = 0; r < 2; r++)
    for (int c = 0; c < 2; c++)
      for (int q = 0; q < 3; q++) {
        Case k = {res[r], hs[c], {off[q][0], off[q][1], off[q][2]}, PETSC_TRUE, 0, 0};
        PetscCall(HeldError(&k, &err, &capped));
        PetscCall(CheckBelow(CheckName("Re %g, cells of %g d, %s: |terminal slip / Schiller-Naumann's u_t - 1|", (double)k.re, (double)k.h, place[q]), PetscAbsReal(err), 0.02));
      }
  for (int r = 0; r < 2; r++) { /* centred above a z face: the whole force on one face, the model's worst place */
    Case k = {res[r], 8, {0.5, 0.5, 0}, PETSC_TRUE, 0, 0};
    PetscCall(HeldError(&k, &err, &capped));
    PetscCall(CheckBelow(CheckName("Re %g, cells of 8 d, centred on a z face: |terminal slip / Schiller-Naumann's u_t - 1|", (double)k.re), PetscAbsReal(err), 0.02));
  }
  for (int r = 0; r < 2; r++)
    for (int q = 0; q < 3; q++) { /* 2 d cells: the stencil shares the force among 1 to 8 faces */
      Case k = {res[r], 2, {off[q][0], off[q][1], off[q][2]}, PETSC_TRUE, 0, 0};
      PetscCall(HeldError(&k, &err, &capped));
      PetscCall(CheckBelow(CheckName("Re %g, cells of 2 d, %s: |terminal slip / Schiller-Naumann's u_t - 1|", (double)k.re, place[q]), PetscAbsReal(err), 0.02));
    }
  for (int r = 0; r < 2; r++) { /* 2 d cells centred on a z face, kernel side two cells (3.998 d): the force on three face layers */
    Case k = {res[r], 2, {0.5, 0.5, 0}, PETSC_TRUE, 4.96, 0};
    PetscCall(HeldError(&k, &err, &capped));
    PetscCall(CheckBelow(CheckName("Re %g, cells of 2 d, kernel scale 4.96, centred on a z face: |terminal slip / Schiller-Naumann's u_t - 1|", (double)k.re), PetscAbsReal(err), 0.02));
  }
  for (int r = 0; r < 2; r++) { /* 1 d cells, the worst place of the wider kernel (side 1.6 d) */
    Case k = {res[r], 1, {0, 0, 0}, PETSC_TRUE, 2, 0};
    PetscCall(HeldError(&k, &err, &capped));
    PetscCall(CheckBelow(CheckName("Re %g, cells of 1 d, kernel scale 2, corner: |terminal slip / Schiller-Naumann's u_t - 1|", (double)k.re), PetscAbsReal(err), 0.02));
  }
  { /* 1 d cells, kernel scale 1: G K >= 1 (the grid's own response exceeds the slip), reported */
    Case k = {10, 1, {0.5, 0.5, 0.5}, PETSC_TRUE, 0, 3};
    PetscCall(HeldError(&k, &err, &capped));
    PetscCall(CheckAbove("Re 10, cells of 1 d, kernel scale 1, centre: particle-steps the self correction reports capped (of 3)", (PetscReal)capped, 0.5));
  }
  {
    Case k = {10, 4, {0.5, 0.5, 0.5}, PETSC_FALSE, 0, 0};
    PetscCall(HeldError(&k, &err, &capped));
    PetscCall(CheckAbove("uncorrected, Re 10, cells of 4 d, centre: the self-induced slip the correction removes, slip / u_t - 1", err, 0.02));
  }
  PetscCall(CheckBelow("every run to its length: the mean slip of its last fifth against its fourth, |change| / u_t (steady: a quarter of the 2% bound)", max_drift, 0.005));
  PetscCall(PetscFinalize());
  return check_failures ? 1 : 0;
}
