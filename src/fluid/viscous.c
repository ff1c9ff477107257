/* Implicit viscous predictor (-fluid_viscous implicit), backward Euler on the component-wise
 * part of 2 mu div(eps D(u)):
 *   (rho eps_f^{n+1}/dt + beta) u^_d - L_d(u^_d) = rhs_d,
 *   L_d(u_d) = d/dx_d (2 mu eps du_d/dx_d) + sum_{e != d} d/dx_e (mu eps_edge du_d/dx_e),
 * while the transpose part d/dx_e (mu eps_edge du_e/dx_d) stays explicit (momentum.c). The three
 * components decouple; the matrix lives on a star-stencil copy of the face DMDA and is
 * symmetric positive definite (CG + Jacobi by default, KSP prefix -fluid_viscous_). Boundary
 * ghosts are the linear relations of bc.c, ghost = alpha u(P) + gamma, folded into the diagonal
 * and the right-hand side; fixed faces (walls, inlets) are known values moved to the right-hand
 * side; their own rows are identities. Removes the viscous time-step limit (not the CFL one). */
#include "fluid/fluid_impl.h"
#include <petsc/private/petscimpl.h> /* PetscObjectStateGet: rebuild only when eps, beta or dt changed */

/* Collective. The KSP and its options (-fluid_viscous_), read with the other -fluid_ options. */
PetscErrorCode FluidViscousCreateKSP(Fluid fl)
{
  PC pc;

  PetscFunctionBeginUser;
  PetscCall(KSPCreate(fl->comm, &fl->vksp));
  PetscCall(KSPSetOptionsPrefix(fl->vksp, "fluid_viscous_"));
  PetscCall(KSPSetType(fl->vksp, KSPCG));
  PetscCall(KSPGetPC(fl->vksp, &pc));
  PetscCall(PCSetType(pc, PCJACOBI));
  PetscCall(KSPSetTolerances(fl->vksp, 1e-10, 1e-50, PETSC_DEFAULT, 1000));
  PetscCall(KSPSetInitialGuessNonzero(fl->vksp, PETSC_TRUE));
  PetscCall(FluidCheckMGLevelsOption(fl, "-fluid_viscous_pc_mg_levels"));
  PetscCall(KSPSetFromOptions(fl->vksp));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. The matrix on a star-stencil copy of the face DMDA. */
PetscErrorCode FluidViscousSetUp(Fluid fl)
{
  const PetscInt *l[3];
  PetscInt        np[3], M[3];
  DMBoundaryType  bt[3];

  PetscFunctionBeginUser;
  PetscCall(DMDAGetInfo(fl->fda, NULL, &M[0], &M[1], &M[2], &np[0], &np[1], &np[2], NULL, NULL, &bt[0], &bt[1], &bt[2], NULL));
  PetscCall(DMDAGetOwnershipRanges(fl->fda, &l[0], &l[1], &l[2]));
  PetscCall(DMDACreate3d(fl->comm, bt[0], bt[1], bt[2], DMDA_STENCIL_STAR, M[0], M[1], M[2], np[0], np[1], np[2], 3, 1, l[0], l[1], l[2], &fl->vda));
  PetscCall(DMSetUp(fl->vda));
  PetscCall(DMCreateMatrix(fl->vda, &fl->V));
  PetscCall(VecDuplicate(fl->u, &fl->vbc));
  PetscCall(VecDuplicate(fl->u, &fl->phiu));
  fl->dt_vmat = -1;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Ghost of component d across side s of axis e, for an active point next to it:
 * ghost = alpha u(P) + gamma (bc.c). */
static void FluidGhostRelation(Fluid fl, int d, int e, int s, PetscScalar *alpha, PetscScalar *gamma)
{
  const FluidBC *bc = &fl->bc[e][s];
  *gamma            = 0;
  if (d == e) {
    *alpha = 1;
    return;
  } /* only an outlet face has a ghost normal neighbour */
  switch (bc->type) {
  case FLUID_BC_WALL:
    *alpha = -1;
    break;
  case FLUID_BC_INLET:
    *alpha = -1;
    *gamma = 2 * bc->vel[d];
    break;
  default:
    *alpha = 1;
    break;
  }
}

/* Value of the fixed normal face of axis d on side s, cb the local offset of the cell next to it
 * (wall 0, inlet U_n / eps_f at the new level's porosity, as bc.c fills it). */
static PetscScalar FluidFixedValue(Fluid fl, const PetscScalar *eps, PetscInt cb, int d, int s)
{
  const FluidGrid *g = &fl->g;
  if (fl->bc[d][s].type != FLUID_BC_INLET) return 0;
  return fl->bc[d][s].vel[d] / (0.5 * (eps[cb] + eps[cb + (s ? 1 : -1) * g->cs[d]]));
}

/* One row of the matrix (and its boundary right-hand side) for component d at point idx. */
static PetscErrorCode FluidViscousRow(Fluid fl, PetscReal dt, const PetscScalar *eps, const PetscScalar *beta, const PetscInt idx[3], PetscInt f, PetscInt c, PetscInt o, int d, PetscScalar *vbc)
{
  const FluidGrid *g   = &fl->g;
  MatStencil       row = {.k = idx[2], .j = idx[1], .i = idx[0], .c = d}, col[7];
  PetscScalar      v[7];
  PetscInt         n = 1;

  PetscFunctionBeginUser;
  (void)f;
  col[0]     = row;
  vbc[o + d] = 0;
  if (!FluidFaceActive(fl, d, idx)) {
    v[0] = 1;
    PetscCall(MatSetValuesStencil(fl->V, 1, &row, 1, col, v, ADD_VALUES));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  v[0] = fl->rho * 0.5 * (eps[c] + eps[c - g->cs[d]]) / dt + beta[o + d];
  for (int e = 0; e < 3; e++)
    for (int s = 0; s < 2; s++) {
      const PetscInt cd = g->cs[d], ce = g->cs[e], nb = idx[e] + (s ? 1 : -1);
      PetscScalar    k;
      if (e == d) k = 2 * fl->mu * eps[s ? c : c - cd] / (g->h[d] * g->h[d]);
      else {
        const PetscInt cq = s ? c + ce : c;
        k                 = fl->mu * 0.25 * (eps[cq] + eps[cq - cd] + eps[cq - ce] + eps[cq - cd - ce]) / (g->h[e] * g->h[e]);
      }
      v[0] += k;
      const PetscInt top = (e == d) ? g->N[e] : g->N[e] - 1; /* last in-domain index */
      if (FluidPeriodic(fl, e) || (nb >= 0 && nb <= top && (e != d || (nb > 0 && nb < g->N[e]) || fl->bc[e][nb ? 1 : 0].type == FLUID_BC_OUTLET))) {
        col[n] = row;
        if (e == 0) col[n].i = nb;
        if (e == 1) col[n].j = nb;
        if (e == 2) col[n].k = nb;
        v[n++] = -k;
      } else if (nb >= 0 && nb <= top) vbc[o + d] += k * FluidFixedValue(fl, eps, nb ? c : c - cd, d, nb ? 1 : 0); /* fixed face */
      else {
        PetscScalar alpha, gamma;
        FluidGhostRelation(fl, d, e, s, &alpha, &gamma);
        v[0] -= k * alpha;
        vbc[o + d] += k * gamma;
      }
    }
  PetscCall(MatSetValuesStencil(fl->V, 1, &row, n, col, v, ADD_VALUES)); /* ADD: with two cells on a periodic axis both neighbours are one point */
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode FluidViscousAssemble(Fluid fl, PetscReal dt)
{
  const FluidGrid   *g = &fl->g;
  const PetscScalar *eps, *beta;
  PetscScalar       *vbc;
  PetscInt           idx[3], f, c, o;

  PetscFunctionBeginUser;
  PetscCall(MatZeroEntries(fl->V));
  PetscCall(VecGetArrayRead(fl->epsloc, &eps));
  PetscCall(VecGetArrayRead(fl->beta, &beta));
  PetscCall(VecGetArray(fl->vbc, &vbc));
  FLUID_FOR_OWNED_FACES(g, idx, f, c, o)
  for (int d = 0; d < 3; d++) PetscCall(FluidViscousRow(fl, dt, eps, beta, idx, f, c, o, d, vbc));
  PetscCall(VecRestoreArray(fl->vbc, &vbc));
  PetscCall(VecRestoreArrayRead(fl->beta, &beta));
  PetscCall(VecRestoreArrayRead(fl->epsloc, &eps));
  PetscCall(MatAssemblyBegin(fl->V, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(fl->V, MAT_FINAL_ASSEMBLY));
  PetscCall(KSPSetOperators(fl->vksp, fl->V, fl->V));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. Solves for uhat in place: on entry uhat holds the predictor right-hand side. */
PetscErrorCode FluidViscousSolve(Fluid fl, PetscReal dt, Vec rhs, Vec uhat)
{
  PetscObjectState   se, sb;
  KSPConvergedReason reason;
  PetscInt           its;
  PetscReal          rnorm;

  PetscFunctionBeginUser;
  PetscCall(PetscObjectStateGet((PetscObject)fl->eps, &se));
  PetscCall(PetscObjectStateGet((PetscObject)fl->beta, &sb));
  if (se != fl->veps_state || sb != fl->vbeta_state || dt != fl->dt_vmat) {
    PetscCall(FluidViscousAssemble(fl, dt));
    fl->veps_state  = se;
    fl->vbeta_state = sb;
    fl->dt_vmat     = dt;
  }
  PetscCall(VecAXPY(rhs, 1.0, fl->vbc));
  PetscCall(VecCopy(fl->u, fl->phiu)); /* initial guess: the old velocity */
  PetscCall(KSPSolve(fl->vksp, rhs, fl->phiu));
  PetscCall(KSPGetConvergedReason(fl->vksp, &reason));
  PetscCall(KSPGetIterationNumber(fl->vksp, &its));
  PetscCall(KSPGetResidualNorm(fl->vksp, &rnorm));
  PetscCheck(reason > 0, fl->comm, PETSC_ERR_NOT_CONVERGED, "fluid implicit viscous solve failed: %s after %d iterations, residual %g; try -fluid_viscous_ksp_max_it or -fluid_viscous_pc_type", KSPConvergedReasons[reason], (int)its, (double)rnorm);
  PetscCall(VecCopy(fl->phiu, uhat));
  PetscFunctionReturn(PETSC_SUCCESS);
}
