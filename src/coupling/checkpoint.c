/* Exact checkpoints of the coupling: what a coupling step reads from the previous one. That is
 * the momentum owed to the fluid (cpl/owed, a face field in the grid's natural ordering, given
 * back as the next step's source) and the clock and counters (cpl/state: time, step, porosity
 * cells clipped so far, the solid volume of the last projection, the initial smallest porosity
 * of the pre-flight figures). Everything else a step uses is computed afresh from the particles
 * at its start (the drag at the particles, the cached kernel stencils, the face fields); the
 * per-particle drag arrays live in the DEM and are its checkpoint's (dem/ext_..., external.c). */
#include "coupling/coupling_impl.h"

#define CPL_CKPT_NSTATE 5

PetscErrorCode CplCheckpointWrite(Cpl cpl, IoCkpt ck)
{
  const PetscReal s[CPL_CKPT_NSTATE] = {cpl->t, (PetscReal)cpl->step, (PetscReal)cpl->clipped_total, cpl->solid_grid, cpl->eps_min0};

  PetscFunctionBeginUser;
  PetscCall(FluidCheckpointWriteVec(ck, "cpl/owed", cpl->owed));
  PetscCall(IoCkptWriteShared(ck, "cpl/state", IO_CKPT_REAL, CPL_CKPT_NSTATE, s));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CplCheckpointRead(Cpl cpl, IoCkpt ck)
{
  PetscReal s[CPL_CKPT_NSTATE];

  PetscFunctionBeginUser;
  PetscCheck(cpl->owed, cpl->comm, PETSC_ERR_ORDER, "call CplSetUp before CplCheckpointRead");
  PetscCall(FluidCheckpointReadVec(ck, "cpl/owed", cpl->owed));
  PetscCall(IoCkptReadShared(ck, "cpl/state", IO_CKPT_REAL, CPL_CKPT_NSTATE, s));
  cpl->t             = s[0];
  cpl->step          = (PetscInt)s[1];
  cpl->clipped_total = (PetscInt)s[2];
  cpl->solid_grid    = s[3];
  cpl->eps_min0      = s[4];
  CplInvalidateStencils(cpl);
  PetscFunctionReturn(PETSC_SUCCESS);
}
