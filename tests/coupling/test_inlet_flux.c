/* The inlet's velocity is the superficial one: a bed resting on the inlet gets the gas it asks
 * for. A disordered bed (test_packed's: lattice of spacing 1.2 d, jittered, porosity ~0.7 varying
 * column to column) stands on the inlet face (its first cell layer holds solids) in the packed_bed
 * column (bi-periodic sides, U = 1 from below, outlet above; dimensionless, mu = 0.1).
 * Volume balance of the fluid, Q the volume flux eps_f u_f A through a boundary:
 *   1. frozen bed, after 30 steps: Q_in / (U A) - 1 at roundoff (each inlet face carries U_n),
 *      Q_out / (U A) - 1 at the Poisson tolerance (continuity through the bed);
 *   2. the bed free to move (it rises and expands at U = 1.5): over each of 20 steps the fluid
 *      volume changes by (Q_in - Q_out) dt, to the Poisson tolerance; Q_in = U A at every step
 *      while the porosity of the inlet layer changes.
 * Before the first step the inlet face already carries U (the monitors' and the bed line's
 * superficial velocity, CplGetLayer). The first layer's mean porosity is checked below 0.9 (the
 * checks are about solids at the inlet).
 * Run on 1 and 2 ranks (2: the inlet and the outlet on different ranks). Scene: packed_bed.opts. */
/* ranks: 1 2 */
#include "cpl_common.h"

#define BED "-dem_lattice 3,3,15 -dem_lattice_spacing 1.2 -dem_lattice_origin 0,0,0 -dem_lattice_jitter 1 -dem_seed 7 -da_grid_x 3 -da_grid_y 3 -da_grid_z 20 -domain_hi 3.6,3.6,24 -fluid_viscosity 0.1"

/* Volume fluxes through the inlet (z = 0) and outlet (z = top) faces and the fluid volume. */
static PetscErrorCode Fluxes(Fluid fl, const Domain *dom, PetscReal *qin, PetscReal *qout, PetscReal *vol)
{
  DM                   cda, fda;
  Vec                  u, eps;
  const PetscScalar ***e, ****v;
  PetscInt             xs[3], xm[3], N[3];
  PetscReal            loc[3] = {0, 0, 0}, glob[3];
  const PetscReal      A      = dom->h[0] * dom->h[1];

  PetscFunctionBeginUser;
  PetscCall(FluidGetDMs(fl, &cda, &fda));
  PetscCall(FluidGetVelocity(fl, &u));
  PetscCall(FluidGetPorosity(fl, &eps));
  PetscCall(DMDAGetInfo(cda, NULL, &N[0], &N[1], &N[2], NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL));
  PetscCall(DMDAGetCorners(cda, &xs[0], &xs[1], &xs[2], &xm[0], &xm[1], &xm[2]));
  PetscCall(DMDAVecGetArrayRead(cda, eps, &e));
  PetscCall(DMDAVecGetArrayDOFRead(fda, u, &v));
  for (PetscInt k = xs[2]; k < xs[2] + xm[2]; k++)
    for (PetscInt j = xs[1]; j < xs[1] + xm[1]; j++)
      for (PetscInt i = xs[0]; i < xs[0] + xm[0]; i++) {
        loc[2] += e[k][j][i] * A * dom->h[2];
        if (k == 0) loc[0] += e[k][j][i] * v[k][j][i][2] * A;            /* eps_f on a domain face: the cell's */
        if (k == N[2] - 1) loc[1] += e[k][j][i] * v[k + 1][j][i][2] * A; /* the last rank owns face N */
      }
  PetscCall(DMDAVecRestoreArrayDOFRead(fda, u, &v));
  PetscCall(DMDAVecRestoreArrayRead(cda, eps, &e));
  PetscCallMPI(MPIU_Allreduce(loc, glob, 3, MPIU_REAL, MPIU_SUM, PETSC_COMM_WORLD));
  *qin  = glob[0];
  *qout = glob[1];
  *vol  = glob[2];
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  TestCpl   t;
  CplStats  st;
  PetscReal qin, qout, vol, vol0, zc, p, e0, u0, area;

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(TestCplCreateScene("packed_bed.opts", BED, NULL, &t));
  area = 3.6 * 3.6;
  PetscCall(CplGetLayer(t.cpl, 2, 0.0, &zc, &p, &e0, &u0));
  PetscCall(TestCplRun(&t, 30, &st));
  PetscCall(Fluxes(t.fl, &t.dom, &qin, &qout, &vol));
  CheckDetail("inlet layer porosity %.4f", (double)e0);
  PetscCall(CheckBelow("frozen bed: mean porosity of the inlet's cell layer", e0, 0.9));
  PetscCall(CheckCloseAbs("before the first step: superficial velocity through the inlet face (CplGetLayer) - U", u0 - 1, 0, 1e-13));
  PetscCall(CheckCloseAbs("frozen bed on the inlet: inflow / (U A) - 1", qin / area - 1, 0, 1e-13));
  PetscCall(CheckCloseAbs("frozen bed on the inlet: outflow / (U A) - 1", qout / area - 1, 0, 1e-6));
  PetscCall(TestCplDestroy(&t));

  PetscCall(TestCplCreateScene("packed_bed.opts", BED " -dem_frozen 0 -fluid_bc_zlo_velocity 0,0,1.5 -fluid_dt 0.01 -cpl_substeps 10", NULL, &t));
  {
    PetscReal in_err = 0, bal_err = 0, emin = 1, emax = 0;
    PetscCall(Fluxes(t.fl, &t.dom, &qin, &qout, &vol0));
    for (int s = 0; s < 20; s++) {
      PetscCall(CplStep(t.cpl, &st));
      PetscCall(Fluxes(t.fl, &t.dom, &qin, &qout, &vol));
      PetscCall(CplGetLayer(t.cpl, 2, 0.0, &zc, &p, &e0, &u0));
      emin    = PetscMin(emin, e0);
      emax    = PetscMax(emax, e0);
      in_err  = PetscMax(in_err, PetscAbsReal(qin / (1.5 * area) - 1));
      bal_err = PetscMax(bal_err, PetscAbsReal((vol - vol0) / 0.01 - (qin - qout)) / (1.5 * area));
      vol0    = vol;
    }
    CheckDetail("inlet layer porosity %.6f to %.6f over the steps", (double)emin, (double)emax);
    PetscCall(CheckBelow("moving bed: 1e-3 over the range of the inlet layer's porosity (it changes)", 1e-3 / (emax - emin), 1));
    PetscCall(CheckBelow("moving bed on the inlet: max over steps |inflow / (U A) - 1|", in_err, 1e-13));
    PetscCall(CheckBelow("moving bed: max over steps |dV/dt - (Q_in - Q_out)| / (U A)", bal_err, 1e-6));
  }
  PetscCall(TestCplDestroy(&t));
  PetscCall(PetscFinalize());
  return check_failures ? 1 : 0;
}
