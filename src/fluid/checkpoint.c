/* Exact checkpoints of the fluid: everything a step reads from the previous one, so that a run
 * stopped and continued ends bitwise where the uninterrupted run does. Fields (datasets
 * fluid/<name>): velocity u, pressure p, porosity eps and its previous value eps_old, the last
 * pressure increment phi, the drag coefficient beta, solid velocity us and momentum source src
 * (set by the coupling before each step, kept for a fluid run on its own), the advection term
 * of the previous step adv_old (Adams-Bashforth), and the porosity and drag coefficient the
 * kept Poisson preconditioner was built from (eps_pc, beta_pc): hypre's set-up is rebuilt from
 * that same matrix at restart (poisson.c), a fresh one from today's matrix would change the
 * iterates at round-off. Counters (fluid/state): the clock, the last step, the step count and
 * the preconditioner's lag counters; fluid/inlet: per face the row its table reached and the
 * velocity it holds. Fields are stored in the natural ordering of their DMDA: each rank's
 * natural block is a contiguous range written as its rows, so the file holds the whole field in
 * natural order and a run on any rank count reads its own range back. */
#include "fluid/fluid_impl.h"
#include <petsc/private/petscimpl.h> /* PetscObjectStateGet: whether the Poisson matrix is current */

#define FLUID_CKPT_NSTATE 11 /* see FluidCkptState */

PetscErrorCode FluidCheckpointWriteVec(IoCkpt ck, const char *name, Vec v)
{
  DM                 da;
  Vec                nat;
  const PetscScalar *a;
  PetscInt           m;

  PetscFunctionBeginUser;
  PetscCall(VecGetDM(v, &da));
  PetscCheck(da, PetscObjectComm((PetscObject)v), PETSC_ERR_ARG_WRONG, "checkpoint dataset %s: the Vec has no DMDA", name);
  PetscCall(DMDACreateNaturalVector(da, &nat));
  PetscCall(DMDAGlobalToNaturalBegin(da, v, INSERT_VALUES, nat));
  PetscCall(DMDAGlobalToNaturalEnd(da, v, INSERT_VALUES, nat));
  PetscCall(VecGetLocalSize(nat, &m));
  PetscCall(VecGetArrayRead(nat, &a));
  PetscCall(IoCkptWriteRows(ck, name, IO_CKPT_REAL, m, a));
  PetscCall(VecRestoreArrayRead(nat, &a));
  PetscCall(VecDestroy(&nat));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FluidCheckpointReadVec(IoCkpt ck, const char *name, Vec v)
{
  DM           da;
  Vec          nat;
  PetscScalar *a;
  PetscInt     N, rs, re;
  long long    tot;
  const char  *path;

  PetscFunctionBeginUser;
  PetscCall(VecGetDM(v, &da));
  PetscCheck(da, PetscObjectComm((PetscObject)v), PETSC_ERR_ARG_WRONG, "checkpoint dataset %s: the Vec has no DMDA", name);
  PetscCall(IoCkptGetPath(ck, &path));
  PetscCall(IoCkptGetSize(ck, name, &tot));
  PetscCall(DMDACreateNaturalVector(da, &nat));
  PetscCall(VecGetSize(nat, &N));
  PetscCheck(tot == N, PetscObjectComm((PetscObject)v), PETSC_ERR_FILE_UNEXPECTED, "-restart %s: the dataset %s has %lld values, this grid needs %" PetscInt_FMT " (the fluid grid differs)", path, name, tot, N);
  PetscCall(VecGetOwnershipRange(nat, &rs, &re));
  PetscCall(VecGetArray(nat, &a));
  PetscCall(IoCkptReadSlabAll(ck, name, IO_CKPT_REAL, rs, re - rs, a));
  PetscCall(VecRestoreArray(nat, &a));
  PetscCall(DMDANaturalToGlobalBegin(da, nat, INSERT_VALUES, v));
  PetscCall(DMDANaturalToGlobalEnd(da, nat, INSERT_VALUES, v));
  PetscCall(VecDestroy(&nat));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The fields, in the order they are stored. */
static void FluidCkptFields(Fluid fl, const char *names[11], Vec vecs[11])
{
  const char *n[11] = {"fluid/p", "fluid/eps", "fluid/eps_old", "fluid/phi", "fluid/eps_pc", "fluid/u", "fluid/beta", "fluid/us", "fluid/src", "fluid/adv_old", "fluid/beta_pc"};
  Vec         v[11] = {fl->fld.p, fl->fld.eps, fl->fld.eps_old, fl->pois.phi, fl->pois.eps_pc, fl->fld.u, fl->fld.beta, fl->fld.us, fl->fld.src, fl->mom.adv_old, fl->pois.beta_pc};
  for (int k = 0; k < 11; k++) {
    names[k] = n[k];
    vecs[k]  = v[k];
  }
}

/* The counters (all stored as reals; the integers are exact). *current: whether the Poisson
 * matrix is that of the current eps, beta and dt_mat (no change since its assembly); the beta of
 * the solve is beff with the vessel's films (it must still be beta's: FluidResistanceUpdate
 * remakes it on reading) and never current with a plate (its resistance follows u^n). */
static PetscErrorCode FluidCkptState(Fluid fl, PetscReal s[FLUID_CKPT_NSTATE], PetscBool get, PetscBool *current)
{
  PetscFunctionBeginUser;
  if (get) {
    PetscObjectState se, sb, sbeta;
    PetscCall(PetscObjectStateGet((PetscObject)fl->fld.eps, &se));
    PetscCall(PetscObjectStateGet((PetscObject)FluidBetaOfSolve(fl), &sb));
    PetscCall(PetscObjectStateGet((PetscObject)fl->fld.beta, &sbeta));
    *current = (PetscBool)(fl->pois.dt_mat > 0 && se == fl->pois.eps_state && sb == fl->pois.beta_state);
    if (fl->plate.on) *current = PETSC_FALSE;
    else if (fl->ves.film) *current = (PetscBool)(*current && fl->plate.beff && fl->plate.beta_state == sbeta);
    const PetscReal v[FLUID_CKPT_NSTATE] = {fl->clock.time, fl->mom.dt_old, (PetscReal)fl->clock.nsteps, fl->pois.dt_pc, (PetscReal)fl->pois.pc_its0, (PetscReal)fl->pois.pc_age, (PetscReal)fl->pois.pc_its_last, (PetscReal)fl->pois.pc_builds, (PetscReal)fl->pois.pc_retries, fl->pois.dt_mat, (PetscReal)*current};
    for (int k = 0; k < FLUID_CKPT_NSTATE; k++) s[k] = v[k];
  } else {
    fl->clock.time       = s[0];
    fl->mom.dt_old       = s[1];
    fl->clock.nsteps     = (PetscInt)s[2];
    fl->pois.dt_pc       = s[3];
    fl->pois.pc_its0     = (PetscInt)s[4];
    fl->pois.pc_age      = (PetscInt)s[5];
    fl->pois.pc_its_last = (PetscInt)s[6];
    fl->pois.pc_builds   = (PetscInt)s[7];
    fl->pois.pc_retries  = (PetscInt)s[8];
    fl->pois.dt_mat      = s[9];
    *current             = (PetscBool)(s[10] != 0);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FluidCheckpointWrite(Fluid fl, IoCkpt ck)
{
  const char *names[11];
  Vec         vecs[11];
  PetscReal   s[FLUID_CKPT_NSTATE], inlet[24];
  PetscBool   current;

  PetscFunctionBeginUser;
  PetscCheck(fl->setup && fl->ckpt, fl->comm, PETSC_ERR_ORDER, "call FluidSetCheckpointing before FluidSetUp to write checkpoints");
  FluidCkptFields(fl, names, vecs);
  for (int k = 0; k < 11; k++) PetscCall(FluidCheckpointWriteVec(ck, names[k], vecs[k]));
  PetscCall(FluidCkptState(fl, s, PETSC_TRUE, &current));
  PetscCall(IoCkptWriteShared(ck, "fluid/state", IO_CKPT_REAL, FLUID_CKPT_NSTATE, s));
  for (int d = 0; d < 3; d++)
    for (int e = 0; e < 2; e++) {
      const FluidBC *bc = &fl->bc.face[d][e];
      PetscReal     *r  = &inlet[4 * (2 * d + e)];
      r[0]              = (PetscReal)bc->row;
      for (int k = 0; k < 3; k++) r[1 + k] = bc->vel[k];
    }
  PetscCall(IoCkptWriteShared(ck, "fluid/inlet", IO_CKPT_REAL, 24, inlet));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FluidCheckpointRead(Fluid fl, IoCkpt ck)
{
  const char *names[11];
  Vec         vecs[11];
  PetscReal   s[FLUID_CKPT_NSTATE], inlet[24];
  PetscBool   current;

  PetscFunctionBeginUser;
  PetscCheck(fl->setup, fl->comm, PETSC_ERR_ORDER, "call FluidSetUp before FluidCheckpointRead");
  if (!fl->pois.eps_pc) { /* the preconditioner is rebuilt from them even if this run writes no checkpoint */
    PetscCall(VecDuplicate(fl->fld.p, &fl->pois.eps_pc));
    PetscCall(VecDuplicate(fl->fld.u, &fl->pois.beta_pc));
    fl->ckpt = PETSC_TRUE;
  }
  FluidCkptFields(fl, names, vecs);
  for (int k = 0; k < 11; k++) PetscCall(FluidCheckpointReadVec(ck, names[k], vecs[k]));
  PetscCall(IoCkptReadShared(ck, "fluid/state", IO_CKPT_REAL, FLUID_CKPT_NSTATE, s));
  PetscCall(FluidCkptState(fl, s, PETSC_FALSE, &current));
  PetscCall(IoCkptReadShared(ck, "fluid/inlet", IO_CKPT_REAL, 24, inlet));
  for (int d = 0; d < 3; d++)
    for (int e = 0; e < 2; e++) {
      FluidBC         *bc = &fl->bc.face[d][e];
      const PetscReal *r  = &inlet[4 * (2 * d + e)];
      if (!bc->ntab) continue; /* a fixed inlet keeps the velocity of its options */
      bc->row = (PetscInt)r[0];
      for (int k = 0; k < 3; k++) bc->vel[k] = r[1 + k];
    }
  if (fl->patch) PetscCall(FluidPatchesAtClock(fl));                       /* the patches' values are functions of the clock */
  fl->vimp.dt_mat = -1;                                                    /* the implicit viscous operator is assembled again at the next step */
  if (fl->ves.film && !fl->plate.on) PetscCall(FluidResistanceUpdate(fl)); /* beff = beta + films, as the matrix had it */
  PetscCall(FluidPoissonRestore(fl, current));
  PetscFunctionReturn(PETSC_SUCCESS);
}
