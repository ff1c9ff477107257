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
  PetscCall(KSPCreate(fl->comm, &fl->vimp.ksp));
  PetscCall(KSPSetOptionsPrefix(fl->vimp.ksp, "fluid_viscous_"));
  PetscCall(KSPSetType(fl->vimp.ksp, KSPCG));
  PetscCall(KSPGetPC(fl->vimp.ksp, &pc));
  PetscCall(PCSetType(pc, PCJACOBI));
  PetscCall(KSPSetTolerances(fl->vimp.ksp, 1e-10, 1e-50, PETSC_DEFAULT, 1000));
  PetscCall(KSPSetInitialGuessNonzero(fl->vimp.ksp, PETSC_TRUE));
  PetscCall(FluidCheckMGLevelsOption(fl, "-fluid_viscous_pc_mg_levels"));
  PetscCall(KSPSetFromOptions(fl->vimp.ksp));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. The matrix on a star-stencil copy of the face DMDA. */
PetscErrorCode FluidViscousSetUp(Fluid fl)
{
  const PetscInt *l[3];
  PetscInt        np[3], M[3];
  DMBoundaryType  bt[3];

  PetscFunctionBeginUser;
  PetscCall(DMDAGetInfo(fl->g.fda, NULL, &M[0], &M[1], &M[2], &np[0], &np[1], &np[2], NULL, NULL, &bt[0], &bt[1], &bt[2], NULL));
  PetscCall(DMDAGetOwnershipRanges(fl->g.fda, &l[0], &l[1], &l[2]));
  PetscCall(DMDACreate3d(fl->comm, bt[0], bt[1], bt[2], DMDA_STENCIL_STAR, M[0], M[1], M[2], np[0], np[1], np[2], 3, 1, l[0], l[1], l[2], &fl->vimp.da));
  PetscCall(DMSetUp(fl->vimp.da));
  PetscCall(DMCreateMatrix(fl->vimp.da, &fl->vimp.V));
  PetscCall(VecDuplicate(fl->fld.u, &fl->vimp.bc));
  PetscCall(VecDuplicate(fl->fld.u, &fl->vimp.phiu));
  fl->vimp.dt_mat = -1;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Ghost of component d across side s of axis e, for an active point next to it:
 * ghost = alpha u(P) + gamma (bc.c). */
static void FluidGhostRelation(Fluid fl, int d, int e, int s, const PetscInt idx[3], PetscScalar *alpha, PetscScalar *gamma)
{
  const FluidBC    *bc    = &fl->bc.face[e][s];
  const FluidBCType type  = fluid_bc_at(fl, e, s, idx); /* a patch's point: its condition, no tangential inflow */
  const PetscBool   patch = (PetscBool)(bc->pkind && bc->pkind[fluid_face_point(fl, e, idx)]);
  *gamma                  = 0;
  if (d == e) {
    *alpha = 1;
    return;
  } /* only an outlet face has a ghost normal neighbour */
  switch (type) {
  case FLUID_BC_WALL:
    *alpha = -1;
    break;
  case FLUID_BC_INLET:
    *alpha = -1;
    *gamma = patch ? 0 : 2 * bc->vel[d];
    break;
  default:
    *alpha = 1;
    break;
  }
}

/* Value of the fixed normal face of axis d on side s, cb the local offset of the cell next to it
 * (wall 0, inlet U_n / eps_f at the new level's porosity, as bc.c fills it). */
static PetscScalar FluidFixedValue(Fluid fl, const PetscScalar *eps, PetscInt cb, int d, int s, const PetscInt idx[3])
{
  const FluidGrid *g  = &fl->g;
  const FluidBC   *bc = &fl->bc.face[d][s];
  if (fluid_bc_at(fl, d, s, idx) != FLUID_BC_INLET) return 0;
  const PetscReal vn = bc->pkind && bc->pkind[fluid_face_point(fl, d, idx)] ? bc->pvn[fluid_face_point(fl, d, idx)] : bc->vel[d];
  return vn / (0.5 * (eps[cb] + eps[cb + (s ? 1 : -1) * g->cs[d]]));
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
    PetscCall(MatSetValuesStencil(fl->vimp.V, 1, &row, 1, col, v, ADD_VALUES));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  v[0] = fl->prop.rho * 0.5 * (eps[c] + eps[c - g->cs[d]]) / dt + beta[o + d];
  for (int e = 0; e < 3; e++)
    for (int s = 0; s < 2; s++) {
      const PetscInt cd = g->cs[d], ce = g->cs[e], nb = idx[e] + (s ? 1 : -1);
      PetscScalar    k;
      if (e == d) k = 2 * fl->prop.mu * eps[s ? c : c - cd] / (g->h[d] * g->h[d]);
      else {
        const PetscInt cq = s ? c + ce : c;
        k                 = fl->prop.mu * 0.25 * (eps[cq] + eps[cq - cd] + eps[cq - ce] + eps[cq - cd - ce]) / (g->h[e] * g->h[e]);
      }
      if (fl->ves.cut) { /* the vessel (momentum.c, FluidViscousAtVessel): the Laplacian part, symmetric; a wall link folds into the diagonal */
        const PetscInt w = fl->ves.wl[o + d];
        if (e == d) k *= 0.5;
        if (w >= 0 && fl->ves.theta[w + 2 * e + s] > 0) {
          if (!fl->ves.slip) v[0] += k / fl->ves.theta[w + 2 * e + s];
          continue;
        }
      }
      v[0] += k;
      const PetscInt top = (e == d) ? g->N[e] : g->N[e] - 1; /* last in-domain index */
      if (FluidPeriodic(fl, e) || (nb >= 0 && nb <= top && (e != d || (nb > 0 && nb < g->N[e]) || fluid_bc_at(fl, e, nb ? 1 : 0, idx) == FLUID_BC_OUTLET))) {
        col[n] = row;
        if (e == 0) col[n].i = nb;
        if (e == 1) col[n].j = nb;
        if (e == 2) col[n].k = nb;
        v[n++] = -k;
      } else if (nb >= 0 && nb <= top) vbc[o + d] += k * FluidFixedValue(fl, eps, nb ? c : c - cd, d, nb ? 1 : 0, idx); /* fixed face */
      else {
        PetscScalar alpha, gamma;
        FluidGhostRelation(fl, d, e, s, idx, &alpha, &gamma);
        v[0] -= k * alpha;
        vbc[o + d] += k * gamma;
      }
    }
  PetscCall(MatSetValuesStencil(fl->vimp.V, 1, &row, n, col, v, ADD_VALUES)); /* ADD: with two cells on a periodic axis both neighbours are one point */
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode FluidViscousAssemble(Fluid fl, PetscReal dt)
{
  const FluidGrid   *g = &fl->g;
  const PetscScalar *eps, *beta;
  PetscScalar       *vbc;
  PetscInt           idx[3], f, c, o;

  PetscFunctionBeginUser;
  PetscCall(MatZeroEntries(fl->vimp.V));
  PetscCall(VecGetArrayRead(fl->fld.epsloc, &eps));
  PetscCall(VecGetArrayRead(FluidBetaOfSolve(fl), &beta)); /* with a distributor plate, its resistance too */
  PetscCall(VecGetArray(fl->vimp.bc, &vbc));
  FLUID_FOR_OWNED_FACES(g, idx, f, c, o)
  for (int d = 0; d < 3; d++) PetscCall(FluidViscousRow(fl, dt, eps, beta, idx, f, c, o, d, vbc));
  PetscCall(VecRestoreArray(fl->vimp.bc, &vbc));
  PetscCall(VecRestoreArrayRead(FluidBetaOfSolve(fl), &beta));
  PetscCall(VecRestoreArrayRead(fl->fld.epsloc, &eps));
  PetscCall(MatAssemblyBegin(fl->vimp.V, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(fl->vimp.V, MAT_FINAL_ASSEMBLY));
  PetscCall(KSPSetOperators(fl->vimp.ksp, fl->vimp.V, fl->vimp.V));
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
  PetscCall(PetscObjectStateGet((PetscObject)fl->fld.eps, &se));
  PetscCall(PetscObjectStateGet((PetscObject)FluidBetaOfSolve(fl), &sb));
  if (se != fl->vimp.eps_state || sb != fl->vimp.beta_state || dt != fl->vimp.dt_mat) {
    PetscCall(FluidViscousAssemble(fl, dt));
    fl->vimp.eps_state  = se;
    fl->vimp.beta_state = sb;
    fl->vimp.dt_mat     = dt;
  }
  PetscCall(VecAXPY(rhs, 1.0, fl->vimp.bc));
  PetscCall(VecCopy(fl->fld.u, fl->vimp.phiu)); /* initial guess: the old velocity */
  PetscCall(KSPSolve(fl->vimp.ksp, rhs, fl->vimp.phiu));
  PetscCall(KSPGetConvergedReason(fl->vimp.ksp, &reason));
  PetscCall(KSPGetIterationNumber(fl->vimp.ksp, &its));
  PetscCall(KSPGetResidualNorm(fl->vimp.ksp, &rnorm));
  PetscCheck(reason > 0, fl->comm, PETSC_ERR_NOT_CONVERGED, "fluid implicit viscous solve failed: %s after %d iterations, residual %g; try -fluid_viscous_ksp_max_it or -fluid_viscous_pc_type", KSPConvergedReasons[reason], (int)its, (double)rnorm);
  PetscCall(VecCopy(fl->vimp.phiu, uhat));
  PetscFunctionReturn(PETSC_SUCCESS);
}
