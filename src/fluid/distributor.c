/* A distributor plate (-fluid_distributor z0,phi[,Cd]): a perforated plate across the grid on
 * the z-faces of the layer nearest z0, of open-area fraction phi, whose pressure drop follows
 * the orifice law of gas distributors (Kunii & Levenspiel, Fluidization Engineering, 2nd ed.,
 * Butterworth-Heinemann 1991, ch. 4, the orifice equation of distributor design):
 *   U_or = Cd sqrt(2 dp / rho),   U = phi U_or   =>   dp = (rho / 2) (U / (Cd phi))^2,
 * U the superficial velocity through the plate, Cd the orifice coefficient (0.6 for sharp-edged
 * holes in a thin plate at high Reynolds numbers, as the book gives it). On the plate's faces the law is an implicit
 * resistance beta_p u (N/m^3) over the face's control volume of height h_z:
 *   beta_p = rho eps_f^2 |u^n| / (2 h_z (Cd phi)^2),
 * linearised with the previous velocity u^n, so that h_z beta_p u = dp exactly in a steady flow.
 * It adds to beta in the predictor and the Poisson coefficient (FluidBetaOfSolve), not to the
 * drag's beta u_s term: the plate stands still. Limits: z-faces only; with -fluid_viscous implicit
 * the steady dp is reached after a short transient (src/fluid/README.md, Limits). */
#include "fluid/fluid_impl.h"
#include <petsc/private/petscimpl.h> /* PetscObjectStateGet */

PetscErrorCode FluidSetFromOptionsDistributor(Fluid fl)
{
  PetscReal v[3] = {0, 0, 0.6};
  PetscInt  n    = 3;
  PetscBool set;

  PetscFunctionBeginUser;
  PetscOptionsBegin(fl->comm, NULL, "Fluid distributor plate", NULL);
  PetscCall(SableOptionsRealArray("-fluid_distributor", "A perforated plate across the grid: height z0 (m, the nearest z-face layer), open-area fraction phi in (0,1], orifice coefficient Cd in (0,1] (default 0.6); dp = rho/2 (U/(Cd phi))^2", "m, -, -", v, 0, &n, &set));
  PetscOptionsEnd();
  fl->plate.on = PETSC_FALSE;
  if (!set) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCheck(n == 2 || n == 3, fl->comm, PETSC_ERR_ARG_SIZ, "-fluid_distributor takes z0,phi[,Cd]; got %d values", (int)n);
  if (n == 2) v[2] = 0.6;
  const PetscReal h = fl->dom->h[2], lo = fl->dom->lo[2];
  const PetscInt  N = fl->dom->cells[2], k0 = (PetscInt)PetscFloorReal((v[0] - lo) / h + 0.5);
  PetscCheck(v[1] > 0 && v[1] <= 1, fl->comm, PETSC_ERR_ARG_OUTOFRANGE, "-fluid_distributor: open-area fraction %g must be in (0,1]", (double)v[1]);
  PetscCheck(v[2] > 0 && v[2] <= 1, fl->comm, PETSC_ERR_ARG_OUTOFRANGE, "-fluid_distributor: orifice coefficient %g must be in (0,1]", (double)v[2]);
  PetscCheck(k0 >= 1 && k0 <= N - 1, fl->comm, PETSC_ERR_ARG_OUTOFRANGE, "-fluid_distributor: height %g m must lie inside the domain, its nearest z-face layer in [1,%d] (got %d)", (double)v[0], (int)N - 1, (int)k0);
  fl->plate.on  = PETSC_TRUE;
  fl->plate.k0  = k0;
  fl->plate.phi = v[1];
  fl->plate.cd  = v[2];
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. beff = beta + the vessel's film friction (vessel.c) + beta_p at u^n (fl->u) and
 * eps^{n+1} (epsloc, current). Without a plate beff changes only with beta: it is remade only
 * when beta's state moved (else the Poisson matrix, keyed on beff's state, would be rebuilt
 * every step of a fluid alone in a vessel). */
PetscErrorCode FluidResistanceUpdate(Fluid fl)
{
  const FluidGrid   *g = &fl->g;
  const PetscScalar *u, *eps;
  PetscScalar       *b;
  PetscInt           idx[3], f, c, o;
  PetscObjectState   sb;

  PetscFunctionBeginUser;
  PetscCall(PetscObjectStateGet((PetscObject)fl->fld.beta, &sb));
  if (!fl->plate.on && fl->plate.beff && sb == fl->plate.beta_state) PetscFunctionReturn(PETSC_SUCCESS);
  if (!fl->plate.beff) PetscCall(VecDuplicate(fl->fld.beta, &fl->plate.beff)); /* first use, or a new layout */
  PetscCall(VecCopy(fl->fld.beta, fl->plate.beff));
  if (fl->ves.film) PetscCall(VecAXPY(fl->plate.beff, 1.0, fl->ves.film));
  fl->plate.beta_state = sb;
  if (!fl->plate.on) PetscFunctionReturn(PETSC_SUCCESS);
  const PetscReal k = fl->prop.rho / (2 * g->h[2] * PetscSqr(fl->plate.cd * fl->plate.phi));
  PetscCall(VecGetArrayRead(fl->fld.u, &u));
  PetscCall(VecGetArrayRead(fl->fld.epsloc, &eps));
  PetscCall(VecGetArray(fl->plate.beff, &b));
  FLUID_FOR_OWNED_FACES(g, idx, f, c, o)
  {
    if (idx[2] != fl->plate.k0 || !FluidFaceActive(fl, 2, idx)) continue;
    const PetscScalar ef = 0.5 * (eps[c] + eps[c - g->cs[2]]);
    b[o + 2] += k * ef * ef * PetscAbsScalar(u[o + 2]);
  }
  PetscCall(VecRestoreArray(fl->plate.beff, &b));
  PetscCall(VecRestoreArrayRead(fl->fld.epsloc, &eps));
  PetscCall(VecRestoreArrayRead(fl->fld.u, &u));
  PetscFunctionReturn(PETSC_SUCCESS);
}
