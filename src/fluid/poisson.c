/* Projection. After the predictor u^ (step.c) the velocity is corrected with the pressure
 * increment phi,
 *   (rho eps_f/dt + beta) (u - u^) = -grad phi,        p^{n+1} = p^n + phi,
 * which keeps the drag sink implicit, and u must satisfy the discrete continuity equation
 *   div(eps_f u) = -(eps^{n+1} - eps^n)/dt.
 * Hence the variable-coefficient Poisson equation
 *   div(c grad phi) = div(eps_f u^) + (eps^{n+1} - eps^n)/dt,   c = eps_f / (rho eps_f/dt + beta),
 * with c = 0 on wall and inlet faces (Neumann) and phi = 0 on outlet faces (Dirichlet, by an odd
 * ghost). The matrix is -div(c grad), symmetric positive (semi-)definite; with no outlet it has
 * the constants as null space, removed from the right-hand side. The same face gradient is used
 * in the matrix and in the correction, so continuity holds to the solver tolerance. KSP prefix
 * -fluid_poisson_ (CG + hypre BoomerAMG, rtol 1e-8 by default); every solve is checked.
 * The matrix changes with eps and beta at every coupled step, but slowly, and hypre's set-up
 * costs about two solves: a preconditioner is kept for up to -fluid_poisson_pc_lag matrix
 * changes (default 20; 0 rebuilds at every change), and rebuilt earlier when a solve needs more
 * than -fluid_poisson_pc_lag_growth (1.5) x the iterations of the first solve after its build,
 * plus one, or when dt changes. The solution is the same to the solver tolerance either way; a
 * solve that fails with a kept preconditioner is repeated with a new one (a warning line, counted
 * in FluidStats). Geometric multigrid (-fluid_poisson_pc_type mg) coarsens the pressure DMDA:
 * its levels are checked against the grid at set-up, and its coarse operators must be Galerkin
 * products (-fluid_poisson_pc_mg_galerkin pmat): only the fine one is assembled.
 * With a vessel (vessel.c, FAVOR) the face coefficients are a_f c, the divergence sums a_f eps_f u
 * and the time derivative has vol_c; a closed cell's row is the identity (phi = 0, same pattern)
 * and the null space without outlet is the open cells' indicator. */
#include "fluid/fluid_impl.h"
#include <petsc/private/petscimpl.h> /* PetscObjectStateGet: rebuild the matrix only when eps, beta or dt changed */

/* Defensive check of a PETSc option: PETSc 3.18's PCSetFromOptions_MG dereferences a level
 * array that it never allocates when -<prefix>pc_mg_levels is 0 or negative (a segfault), so the
 * raw value of name (-fluid_poisson_pc_mg_levels, -fluid_viscous_pc_mg_levels) is checked before
 * KSPSetFromOptions reads it. Collective (every rank reads the same options). */
PetscErrorCode FluidCheckMGLevelsOption(Fluid fl, const char *name)
{
  const char *v;
  char       *end;
  long        L;
  PetscBool   set;

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsFindPair(NULL, NULL, name, &v, &set));
  if (!set) PetscFunctionReturn(PETSC_SUCCESS);
  L = v ? strtol(v, &end, 10) : 0;
  PetscCheck(v && end != v && !*end && L >= 1 && L <= 30, fl->comm, PETSC_ERR_ARG_OUTOFRANGE, "%s %s: the number of multigrid levels must be an integer in [1,30]", name, v ? v : "(no value)");
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. The KSP and its options (-fluid_poisson_), read with the other -fluid_ options so
 * that the unused-option check sees them. */
PetscErrorCode FluidPoissonCreateKSP(Fluid fl)
{
  PC pc;

  PetscFunctionBeginUser;
  PetscCall(KSPCreate(fl->comm, &fl->pois.ksp));
  PetscCall(KSPSetOptionsPrefix(fl->pois.ksp, "fluid_poisson_"));
  PetscCall(KSPSetType(fl->pois.ksp, KSPCG));
  PetscCall(KSPGetPC(fl->pois.ksp, &pc));
  PetscCall(PCSetType(pc, PCHYPRE));
  PetscCall(PCHYPRESetType(pc, "boomeramg"));
  PetscCall(KSPSetTolerances(fl->pois.ksp, 1e-8, 1e-50, PETSC_DEFAULT, 500));
  PetscCall(FluidCheckMGLevelsOption(fl, "-fluid_poisson_pc_mg_levels"));
  PetscCall(KSPSetFromOptions(fl->pois.ksp));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Geometric multigrid coarsens the pressure DMDA L - 1 times: a periodic axis halves (N even),
 * a bounded one maps N to (N - 1)/2 + 1 (N odd), and every level keeps >= 2 cells per axis. */
static PetscErrorCode FluidPoissonCheckMG(Fluid fl)
{
  PC         pc;
  PetscBool  mg;
  PetscInt   L;
  const char ax[] = "xyz";

  PetscFunctionBeginUser;
  PetscCall(KSPGetPC(fl->pois.ksp, &pc));
  PetscCall(PetscObjectTypeCompare((PetscObject)pc, PCMG, &mg));
  if (!mg) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PCMGGetLevels(pc, &L));
  for (int d = 0; d < 3; d++) {
    PetscInt n = fl->g.N[d];
    for (PetscInt l = 1; l < L; l++) {
      const PetscBool per = FluidPeriodic(fl, d), ok = (PetscBool)(per ? n % 2 == 0 : n % 2 == 1);
      const PetscInt  nc = per ? n / 2 : (n - 1) / 2 + 1;
      PetscCheck(ok && nc >= 2, fl->comm, PETSC_ERR_ARG_INCOMP, "-fluid_poisson_pc_mg_levels %d: the fluid grid (-da_grid_%c %d) has %d cells along the %s %c axis after %d coarsenings and cannot be coarsened again (a periodic axis needs an even count, a bounded one an odd count, and the coarsest level >= 2 cells); lower the levels or change -da_grid_%c", (int)L, ax[d], (int)fl->g.N[d], (int)n, per ? "periodic" : "bounded", ax[d], (int)(l - 1), ax[d]);
      n = nc;
    }
  }
  if (L > 1) { /* the coarse operators can only be Galerkin products: PETSc's own message asks for DMKSPSetComputeOperators */
    PCMGGalerkinType g;
    PetscCall(PCMGGetGalerkin(pc, &g));
    PetscCheck(g == PC_MG_GALERKIN_PMAT || g == PC_MG_GALERKIN_BOTH, fl->comm, PETSC_ERR_ARG_INCOMP, "-fluid_poisson_pc_type mg with %d levels needs -fluid_poisson_pc_mg_galerkin pmat (or both): Sable assembles the Poisson operator on the fluid grid only", (int)L);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode FluidPoissonPattern(Fluid fl);

PetscErrorCode FluidPoissonSetUp(Fluid fl)
{
  const PetscInt *l[3];
  PetscInt        np[3];
  DMBoundaryType  bt[3];

  PetscFunctionBeginUser;
  PetscCall(DMDAGetInfo(fl->g.cda, NULL, NULL, NULL, NULL, &np[0], &np[1], &np[2], NULL, NULL, &bt[0], &bt[1], &bt[2], NULL));
  PetscCall(DMDAGetOwnershipRanges(fl->g.cda, &l[0], &l[1], &l[2]));
  PetscCall(DMDACreate3d(fl->comm, bt[0], bt[1], bt[2], DMDA_STENCIL_STAR, fl->g.N[0], fl->g.N[1], fl->g.N[2], np[0], np[1], np[2], 1, 1, l[0], l[1], l[2], &fl->pois.pda));
  PetscCall(DMSetUp(fl->pois.pda));
  PetscCall(DMCreateMatrix(fl->pois.pda, &fl->pois.A));
  PetscCall(FluidPoissonPattern(fl));
  PetscCall(KSPSetDM(fl->pois.ksp, fl->pois.pda)); /* for geometric multigrid (-fluid_poisson_pc_type mg); the operators stay ours */
  PetscCall(KSPSetDMActive(fl->pois.ksp, PETSC_FALSE));
  PetscCall(FluidPoissonCheckMG(fl));
  PetscCall(VecDuplicate(fl->fld.u, &fl->pois.coef));
  PetscCall(VecDuplicate(fl->fld.uloc, &fl->pois.coefloc));
  if (fl->pois.singular && fl->ves.cut) { /* closed cells have identity rows: the open cells' indicator */
    PetscCall(MatNullSpaceCreate(fl->comm, PETSC_FALSE, 1, &fl->ves.ind, &fl->pois.nsp));
    PetscCall(MatSetNullSpace(fl->pois.A, fl->pois.nsp));
  } else if (fl->pois.singular) {
    PetscCall(MatNullSpaceCreate(fl->comm, PETSC_TRUE, 0, NULL, &fl->pois.nsp));
    PetscCall(MatSetNullSpace(fl->pois.A, fl->pois.nsp));
  }
  fl->pois.dt_mat  = -1;
  fl->pois.pc_its0 = -1; /* a new matrix: the first solve builds the preconditioner */
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Face coefficients c (0 on fixed faces) into fl->coef and its ghosted copy. */
static PetscErrorCode FluidPoissonCoefficients(Fluid fl, PetscReal dt, const PetscScalar *eps, Vec vbeta)
{
  const FluidGrid   *g = &fl->g;
  PetscInt           idx[3], f, c, o;
  PetscScalar       *cf;
  const PetscScalar *beta;

  PetscFunctionBeginUser;
  PetscCall(VecGetArray(fl->pois.coef, &cf));
  PetscCall(VecGetArrayRead(vbeta, &beta));
  FLUID_FOR_OWNED_FACES(g, idx, f, c, o)
  for (int d = 0; d < 3; d++) {
    const PetscScalar ef = 0.5 * (eps[c] + eps[c - g->cs[d]]);
    cf[o + d]            = FluidFaceActive(fl, d, idx) ? ef / (fl->prop.rho * ef / dt + beta[o + d]) : 0;
  }
  PetscCall(VecRestoreArrayRead(vbeta, &beta));
  PetscCall(VecRestoreArray(fl->pois.coef, &cf));
  PetscCall(DMGlobalToLocal(fl->g.fda, fl->pois.coef, INSERT_VALUES, fl->pois.coefloc));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Whether the row of cell idx couples to its neighbour on side s (0 lower, 1 upper) along d:
 * yes inside the grid and across a periodic side; no across an outlet (its face enters the
 * diagonal) or a wall or inlet face (c = 0 there). */
static inline PetscBool fluid_poisson_neighbour(Fluid fl, const PetscInt idx[3], int d, int s)
{
  return (PetscBool)(FluidPeriodic(fl, d) || (s ? idx[d] < fl->g.N[d] - 1 : idx[d] > 0));
}

/* The matrix's nonzero pattern, once per layout: row by row over the owned cells, the diagonal
 * then the neighbours in the order d = x, y, z, lower before upper, as local (ghosted) indices
 * of the pressure DMDA; PETSc maps them to global ones (a periodic ghost to its owner). */
static PetscErrorCode FluidPoissonPattern(Fluid fl)
{
  const FluidGrid *g = &fl->g;
  PetscInt         gs[3], gm[3], idx[3], c, o, *ci, *cj;
  PetscCount       n = 0;

  PetscFunctionBeginUser;
  PetscCall(DMDAGetGhostCorners(fl->pois.pda, &gs[0], &gs[1], &gs[2], &gm[0], &gm[1], &gm[2]));
  PetscCall(PetscMalloc2(7 * g->xm[0] * g->xm[1] * g->xm[2], &ci, 7 * g->xm[0] * g->xm[1] * g->xm[2], &cj));
  FLUID_FOR_OWNED_CELLS(g, idx, c, o)
  {
    const PetscInt row     = ((idx[2] - gs[2]) * gm[1] + idx[1] - gs[1]) * gm[0] + idx[0] - gs[0];
    const PetscInt step[3] = {1, gm[0], gm[0] * gm[1]};
    ci[n] = row, cj[n++] = row;
    for (int d = 0; d < 3; d++)
      for (int s = 0; s < 2; s++)
        if (fluid_poisson_neighbour(fl, idx, d, s)) ci[n] = row, cj[n++] = row + (s ? step[d] : -step[d]);
  }
  PetscCall(MatSetPreallocationCOOLocal(fl->pois.A, n, ci, cj));
  PetscCall(PetscFree2(ci, cj));
  PetscCall(PetscFree(fl->pois.coo_v));
  PetscCall(PetscMalloc1(n, &fl->pois.coo_v));
  fl->pois.ncoo = n;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The values of -div(c grad) in the pattern's order, set in one call (no search per entry);
 * c from eps (ghosted local array) and the face Vec beta. */
static PetscErrorCode FluidPoissonAssemble(Fluid fl, PetscReal dt, const PetscScalar *eps, Vec beta)
{
  const FluidGrid   *g = &fl->g;
  const PetscScalar *cf;
  PetscScalar       *v = fl->pois.coo_v;
  PetscInt           idx[3], c, o;
  PetscCount         n = 0;

  PetscFunctionBeginUser;
  PetscCall(FluidPoissonCoefficients(fl, dt, eps, beta));
  PetscCall(VecGetArrayRead(fl->pois.coefloc, &cf));
  FLUID_FOR_OWNED_CELLS(g, idx, c, o)
  {
    const PetscInt   f  = FluidFaceOff(g, idx[0], idx[1], idx[2]);
    const PetscCount nd = n++;
    const PetscReal *a  = fl->ves.aloc; /* FAVOR: the face coefficients a_f c */
    v[nd]               = 0;
    if (a && FluidCellClosed(fl, idx)) { /* identity row: phi = 0 */
      v[nd] = 1;
      for (int d = 0; d < 3; d++)
        for (int s = 0; s < 2; s++)
          if (fluid_poisson_neighbour(fl, idx, d, s)) v[n++] = 0;
      continue;
    }
    for (int d = 0; d < 3; d++) {
      const PetscReal   ih2 = 1.0 / (g->h[d] * g->h[d]);
      const PetscScalar cm = a ? a[f + d] * cf[f + d] * ih2 : cf[f + d] * ih2, cp = a ? a[f + g->fs[d] + d] * cf[f + g->fs[d] + d] * ih2 : cf[f + g->fs[d] + d] * ih2;
      v[nd] += cm + cp;
      for (int s = 0; s < 2; s++) {
        const PetscScalar cc = s ? cp : cm;
        if (fluid_poisson_neighbour(fl, idx, d, s)) v[n++] = -cc;
        else v[nd] += cc; /* Dirichlet on an outlet face: ghost phi = -phi (c is 0 on fixed faces) */
      }
    }
  }
  PetscCheck(n == fl->pois.ncoo, PETSC_COMM_SELF, PETSC_ERR_PLIB, "Poisson matrix: %" PetscCount_FMT " values for a pattern of %" PetscCount_FMT, n, fl->pois.ncoo);
  PetscCall(VecRestoreArrayRead(fl->pois.coefloc, &cf));
  PetscCall(MatSetValuesCOO(fl->pois.A, v, INSERT_VALUES));
  PetscCall(KSPSetOperators(fl->pois.ksp, fl->pois.A, fl->pois.A));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* rhs = -(div(eps_f u^) + (eps^{n+1} - eps^n)/dt) on the owned cells. */
static PetscErrorCode FluidPoissonRHS(Fluid fl, PetscReal dt, const PetscScalar *u, const PetscScalar *eps, const PetscScalar *eps0)
{
  const FluidGrid *g = &fl->g;
  PetscScalar     *b;
  PetscInt         idx[3], c, o;

  PetscFunctionBeginUser;
  PetscCall(VecGetArray(fl->pois.rhs, &b));
  if (fl->ves.cut) { /* FAVOR: a_f on the fluxes, vol_c on the time derivative; closed cells 0 */
    FLUID_FOR_OWNED_CELLS(g, idx, c, o)
    b[o] = FluidCellClosed(fl, idx) ? 0 : -(fluid_mass_divergence_favor(g, u, eps, fl->ves.aloc, FluidFaceOff(g, idx[0], idx[1], idx[2]), c) + fl->ves.vloc[c] * (eps[c] - eps0[c]) / dt);
  } else {
    FLUID_FOR_OWNED_CELLS(g, idx, c, o)
    b[o] = -(fluid_mass_divergence(g, u, eps, FluidFaceOff(g, idx[0], idx[1], idx[2]), c) + (eps[c] - eps0[c]) / dt);
  }
  PetscCall(VecRestoreArray(fl->pois.rhs, &b));
  Vec src;
  PetscCall(FluidPatchSource(fl, &src)); /* patches' volume sources S: div(eps_f u) + deps/dt = S */
  if (src) PetscCall(VecAXPY(fl->pois.rhs, 1.0, src));
  if (fl->pois.nsp) PetscCall(MatNullSpaceRemove(fl->pois.nsp, fl->pois.rhs));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* u = u^ - (c/eps_f) grad phi on the active faces; p += phi. */
static PetscErrorCode FluidCorrect(Fluid fl, const PetscScalar *eps)
{
  const FluidGrid   *g = &fl->g;
  const PetscScalar *uh, *cf, *phi;
  PetscScalar       *u;
  PetscInt           idx[3], f, c, o;

  PetscFunctionBeginUser;
  PetscCall(FluidLocalCell(fl, fl->pois.phi, fl->pois.philoc, FLUID_GHOST_INCREMENT, 0.0));
  PetscCall(VecGetArrayRead(fl->mom.uhat, &uh));
  PetscCall(VecGetArrayRead(fl->pois.coef, &cf));
  PetscCall(VecGetArrayRead(fl->pois.philoc, &phi));
  PetscCall(VecGetArray(fl->fld.u, &u));
  FLUID_FOR_OWNED_FACES(g, idx, f, c, o)
  for (int d = 0; d < 3; d++) {
    const PetscScalar ef = 0.5 * (eps[c] + eps[c - g->cs[d]]);
    u[o + d]             = uh[o + d] - (cf[o + d] / ef) * (phi[c] - phi[c - g->cs[d]]) / g->h[d];
  }
  PetscCall(VecRestoreArray(fl->fld.u, &u));
  PetscCall(VecRestoreArrayRead(fl->pois.philoc, &phi));
  PetscCall(VecRestoreArrayRead(fl->pois.coef, &cf));
  PetscCall(VecRestoreArrayRead(fl->mom.uhat, &uh));
  PetscCall(VecAXPY(fl->fld.p, 1.0, fl->pois.phi));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Decides, after the matrix changed, whether the preconditioner is rebuilt (see the header). */
static inline PetscBool fluid_poisson_rebuild_pc(const struct _p_Fluid *fl, PetscReal dt)
{
  if (fl->pois.pc_lag == 0 || fl->pois.pc_its0 < 0 || dt != fl->pois.dt_pc) return PETSC_TRUE;
  if (fl->pois.pc_age >= fl->pois.pc_lag) return PETSC_TRUE;
  return (PetscBool)(fl->pois.pc_its_last > fl->pois.pc_growth * fl->pois.pc_its0 + 1);
}

static PetscErrorCode FluidPoissonSolve(Fluid fl, PetscBool rebuild, KSPConvergedReason *reason, FluidStats *st)
{
  PetscFunctionBeginUser;
  PetscCall(KSPSetReusePreconditioner(fl->pois.ksp, (PetscBool)!rebuild));
  PetscCall(KSPSolve(fl->pois.ksp, fl->pois.rhs, fl->pois.phi));
  PetscCall(KSPGetConvergedReason(fl->pois.ksp, reason));
  PetscCall(KSPGetIterationNumber(fl->pois.ksp, &st->poisson_its));
  PetscCall(KSPGetResidualNorm(fl->pois.ksp, &st->poisson_rnorm));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FluidProject(Fluid fl, PetscReal dt, FluidStats *st)
{
  const PetscScalar *u, *eps, *eps0;
  PetscObjectState   se, sb;
  KSPConvergedReason reason;
  PetscBool          changed = PETSC_FALSE, rebuild = PETSC_FALSE;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(fl->ev.poisson, 0, 0, 0, 0));
  PetscCall(FluidLocalVelocity(fl, fl->mom.uhat, fl->fld.uloc, fl->fld.epsloc)); /* the inlets at the new level's porosity */
  PetscCall(VecGetArrayRead(fl->fld.uloc, &u));
  PetscCall(VecGetArrayRead(fl->fld.epsloc, &eps));
  PetscCall(VecGetArrayRead(fl->fld.epsoldloc, &eps0));
  PetscCall(PetscObjectStateGet((PetscObject)fl->fld.eps, &se));
  PetscCall(PetscObjectStateGet((PetscObject)FluidBetaOfSolve(fl), &sb));
  if (se != fl->pois.eps_state || sb != fl->pois.beta_state || dt != fl->pois.dt_mat) {
    PetscCall(FluidPoissonAssemble(fl, dt, eps, FluidBetaOfSolve(fl)));
    fl->pois.eps_state  = se;
    fl->pois.beta_state = sb;
    fl->pois.dt_mat     = dt;
    changed             = PETSC_TRUE;
    rebuild             = fluid_poisson_rebuild_pc(fl, dt);
  }
  PetscCall(FluidPoissonRHS(fl, dt, u, eps, eps0));
  PetscCall(VecRestoreArrayRead(fl->fld.epsoldloc, &eps0));
  PetscCall(VecRestoreArrayRead(fl->fld.uloc, &u));
  PetscCall(FluidPoissonSolve(fl, rebuild, &reason, st));
  if (reason <= 0 && !rebuild && (changed || fl->pois.pc_age > 0)) { /* a kept preconditioner is never the reason to stop */
    PetscCall(PetscPrintf(fl->comm, "warning: fluid Poisson solve %s after %d iterations with a kept preconditioner; rebuilt and solved again\n", KSPConvergedReasons[reason], (int)st->poisson_its));
    fl->pois.pc_retries++;
    rebuild = PETSC_TRUE;
    PetscCall(FluidPoissonSolve(fl, rebuild, &reason, st));
  }
  PetscCheck(reason > 0, fl->comm, PETSC_ERR_NOT_CONVERGED, "fluid pressure Poisson solve failed: %s after %d iterations, residual %g; try -fluid_poisson_ksp_max_it, -fluid_poisson_ksp_rtol or -fluid_poisson_pc_type", KSPConvergedReasons[reason], (int)st->poisson_its, (double)st->poisson_rnorm);
  if (rebuild) {
    fl->pois.pc_its0 = st->poisson_its;
    fl->pois.pc_age  = 0;
    fl->pois.dt_pc   = dt;
    fl->pois.pc_builds++;
    if (fl->ckpt) { /* what a checkpoint needs to build this preconditioner again */
      PetscCall(VecCopy(fl->fld.eps, fl->pois.eps_pc));
      PetscCall(VecCopy(FluidBetaOfSolve(fl), fl->pois.beta_pc)); /* with a distributor plate, its resistance too */
    }
  } else if (changed) fl->pois.pc_age++;
  fl->pois.pc_its_last   = st->poisson_its;
  st->poisson_pc_builds  = fl->pois.pc_builds;
  st->poisson_pc_retries = fl->pois.pc_retries;
  PetscCall(PetscLogEventEnd(fl->ev.poisson, 0, 0, 0, 0));
  PetscCall(PetscLogEventBegin(fl->ev.correct, 0, 0, 0, 0));
  PetscCall(FluidCorrect(fl, eps));
  PetscCall(VecRestoreArrayRead(fl->fld.epsloc, &eps));
  PetscCall(PetscLogEventEnd(fl->ev.correct, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. After a checkpoint restored the fields and the preconditioner's counters
 * (fluid/checkpoint.c): builds the kept preconditioner again from the matrix it was built from
 * (eps_pc, beta_pc at dt_pc), the same operator hence the same preconditioner as in the
 * interrupted run, then, when the checkpoint's matrix was current, assembles the matrix of the
 * current eps and beta at dt_mat and marks it current. */
PetscErrorCode FluidPoissonRestore(Fluid fl, PetscBool current)
{
  const PetscScalar *eps;

  PetscFunctionBeginUser;
  if (fl->pois.pc_its0 >= 0) {
    PetscCall(FluidLocalCell(fl, fl->pois.eps_pc, fl->fld.epsloc, PETSC_FALSE, 0.0));
    PetscCall(VecGetArrayRead(fl->fld.epsloc, &eps));
    PetscCall(FluidPoissonAssemble(fl, fl->pois.dt_pc, eps, fl->pois.beta_pc));
    PetscCall(VecRestoreArrayRead(fl->fld.epsloc, &eps));
    PetscCall(KSPSetReusePreconditioner(fl->pois.ksp, PETSC_FALSE));
    PetscCall(KSPSetUp(fl->pois.ksp));
  }
  if (!current) {
    fl->pois.dt_mat = -1;
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(FluidLocalCell(fl, fl->fld.eps, fl->fld.epsloc, PETSC_FALSE, 0.0));
  PetscCall(VecGetArrayRead(fl->fld.epsloc, &eps));
  PetscCall(FluidPoissonAssemble(fl, fl->pois.dt_mat, eps, FluidBetaOfSolve(fl))); /* with the vessel's films (beff, remade on reading) */
  PetscCall(VecRestoreArrayRead(fl->fld.epsloc, &eps));
  PetscCall(PetscObjectStateGet((PetscObject)fl->fld.eps, &fl->pois.eps_state));
  PetscCall(PetscObjectStateGet((PetscObject)FluidBetaOfSolve(fl), &fl->pois.beta_state));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective: max over cells of |div(eps_f u) + (eps^{n+1} - eps^n)/dt| for the current u (with
 * a vessel: over the open cells, |sum a_f eps_f u / h + vol_c (eps^{n+1} - eps^n)/dt|). */
PetscErrorCode FluidDivergenceMax(Fluid fl, PetscReal dt, PetscReal *dmax)
{
  const FluidGrid   *g = &fl->g;
  const PetscScalar *u, *eps, *eps0;
  PetscInt           idx[3], c, o;
  PetscReal          m = 0;
  const PetscScalar *S = NULL;
  Vec                src;

  PetscFunctionBeginUser;
  PetscCall(FluidPatchSource(fl, &src));
  if (src) PetscCall(VecGetArrayRead(src, &S));
  PetscCall(FluidLocalVelocity(fl, fl->fld.u, fl->fld.uloc, fl->fld.epsloc));
  PetscCall(VecGetArrayRead(fl->fld.uloc, &u));
  PetscCall(VecGetArrayRead(fl->fld.epsloc, &eps));
  PetscCall(VecGetArrayRead(fl->fld.epsoldloc, &eps0));
  if (fl->ves.cut) {
    FLUID_FOR_OWNED_CELLS(g, idx, c, o)
    if (!FluidCellClosed(fl, idx)) m = PetscMax(m, PetscAbsScalar(fluid_mass_divergence_favor(g, u, eps, fl->ves.aloc, FluidFaceOff(g, idx[0], idx[1], idx[2]), c) + fl->ves.vloc[c] * (eps[c] - eps0[c]) / dt - (S ? S[o] : 0)));
  } else {
    FLUID_FOR_OWNED_CELLS(g, idx, c, o)
    m = PetscMax(m, PetscAbsScalar(fluid_mass_divergence(g, u, eps, FluidFaceOff(g, idx[0], idx[1], idx[2]), c) + (eps[c] - eps0[c]) / dt - (S ? S[o] : 0)));
  }
  if (src) PetscCall(VecRestoreArrayRead(src, &S));
  PetscCall(VecRestoreArrayRead(fl->fld.epsoldloc, &eps0));
  PetscCall(VecRestoreArrayRead(fl->fld.epsloc, &eps));
  PetscCall(VecRestoreArrayRead(fl->fld.uloc, &u));
  PetscCall(MPIU_Allreduce(&m, dmax, 1, MPIU_REAL, MPIU_MAX, fl->comm));
  PetscFunctionReturn(PETSC_SUCCESS);
}
