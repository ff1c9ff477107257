/* Run-out of a granular column collapse (cases/dam_break), measured as in Grains3D Part II §4.2.2:
 * the deposit length L_inf is the smallest X beyond the gate where the solid fraction phi(X) of
 * a control box d x W x d, centred at (X, W/2, d/2), is at most phi_min = 0.1; the column height
 * H is, likewise, the smallest height Z where the box L x W x d centred at (L/2, W/2, Z) has
 * phi <= phi_min. Solid fraction = (particles whose centre is in the box) x V_p / box volume,
 * V_p = pi d^3 / 6 with d the volume-equivalent diameter. Prints a = H/L and (L_inf - L)/L with
 * the Lube et al. (2005) correlation 1.9 a^(2/3) beside it.
 * Options: -runout_initial FILE (the filled column), -runout_final FILE (the deposit),
 * -runout_gate L (m), -runout_width W (m), -runout_d d (m), -runout_phi_min (default 0.1). */
#include "io/io.h"

static PetscReal Fraction(const PetscReal *x, PetscInt n, const PetscReal lo[3], const PetscReal hi[3], PetscReal vp)
{
  PetscInt c = 0;
  for (PetscInt i = 0; i < n; i++) {
    PetscBool in = PETSC_TRUE;
    for (int k = 0; k < 3; k++) in = (PetscBool)(in && x[3 * i + k] >= lo[k] && x[3 * i + k] < hi[k]);
    c += in;
  }
  return c * vp / ((hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2]));
}

int main(int argc, char **argv)
{
  char      fi[PETSC_MAX_PATH_LEN] = "", ff[PETSC_MAX_PATH_LEN] = "";
  PetscReal L = 0, W = 0, d = 0, phimin = 0.1, *xi, *xf, H = 0, Linf = 0;
  PetscInt  ni, nf, nc;

  PetscCall(PetscInitialize(&argc, &argv, NULL, "column_runout: run-out of a granular column collapse\n"));
  PetscOptionsBegin(PETSC_COMM_WORLD, NULL, "column run-out", NULL);
  PetscCall(PetscOptionsString("-runout_initial", "HDF5 frame of the filled column", NULL, fi, fi, sizeof fi, NULL));
  PetscCall(PetscOptionsString("-runout_final", "HDF5 frame of the deposit", NULL, ff, ff, sizeof ff, NULL));
  PetscCall(PetscOptionsReal("-runout_gate", "Column length L = gate position (m)", NULL, L, &L, NULL));
  PetscCall(PetscOptionsReal("-runout_width", "Channel width W (m)", NULL, W, &W, NULL));
  PetscCall(PetscOptionsReal("-runout_d", "Volume-equivalent particle diameter (m)", NULL, d, &d, NULL));
  PetscCall(PetscOptionsReal("-runout_phi_min", "Solid fraction that ends the deposit", NULL, phimin, &phimin, NULL));
  PetscOptionsEnd();
  PetscCheck(fi[0] && ff[0], PETSC_COMM_WORLD, PETSC_ERR_ARG_WRONG, "-runout_initial and -runout_final are required");
  PetscCheck(L > 0 && W > 0 && d > 0, PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE, "-runout_gate %g, -runout_width %g and -runout_d %g must be > 0 (m)", (double)L, (double)W, (double)d);
  PetscCheck(phimin > 0 && phimin < 1, PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE, "-runout_phi_min %g must be in (0,1)", (double)phimin);
  PetscCall(IoReadDataset(fi, "/particles/position", &ni, &nc, &xi));
  PetscCall(IoReadDataset(ff, "/particles/position", &nf, &nc, &xf));
  const PetscReal vp = PETSC_PI * d * d * d / 6;
  for (PetscReal z = 0.5 * d;; z += 0.05 * d) {
    const PetscReal lo[3] = {0, 0, z - 0.5 * d}, hi[3] = {L, W, z + 0.5 * d};
    if (Fraction(xi, ni, lo, hi, vp) <= phimin) {
      H = z;
      break;
    }
  }
  for (PetscReal X = L;; X += 0.05 * d) {
    const PetscReal lo[3] = {X - 0.5 * d, 0, 0}, hi[3] = {X + 0.5 * d, W, d};
    if (Fraction(xf, nf, lo, hi, vp) <= phimin) {
      Linf = X;
      break;
    }
  }
  const PetscReal a = H / L;
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "column: %" PetscInt_FMT " particles, L = %.4f m, H = %.4f m, aspect ratio a = H/L = %.3f\n", ni, (double)L, (double)H, (double)a));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "deposit: L_inf = %.4f m (phi <= %g), run-out (L_inf - L)/L = %.3f; Lube et al. 1.9 a^(2/3) = %.3f\n", (double)Linf, (double)phimin, (double)((Linf - L) / L), (double)(1.9 * PetscPowReal(a, 2.0 / 3.0))));
  PetscCall(PetscFree(xi));
  PetscCall(PetscFree(xf));
  PetscCall(PetscFinalize());
  return 0;
}
