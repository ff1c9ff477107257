/* Exact checkpoints of the coupling: what a coupling step reads from the previous one. That is
 * the momentum owed to the fluid (cpl/owed, a face field in the grid's natural ordering, given
 * back as the next step's source) and the clock and counters (cpl/state: time, step, porosity
 * cells clipped so far, the solid volume of the last projection, and the smallest porosity of
 * the writer's set-up, kept in the layout but not read back: a restart's pre-flight checks the
 * bed it restores) and, with -cpl_filter_width, the mean diameter the filter's width
 * was set from (cpl/filter_diameter: the particles of the restart are not those of the start), and
 * with -cpl_porosity_width likewise its mean diameter (cpl/porosity_diameter). Everything else a step uses is computed afresh from the particles
 * at its start (the drag at the particles, the cached kernel stencils, the face fields); the
 * per-particle drag arrays live in the DEM and are its checkpoint's (dem/ext_..., external.c). */
#include "coupling/coupling_impl.h"

#define CPL_CKPT_NSTATE 5

PetscErrorCode CplCheckpointWrite(Cpl cpl, IoCkpt ck)
{
  const PetscReal s[CPL_CKPT_NSTATE] = {cpl->clock.t, (PetscReal)cpl->clock.step, (PetscReal)cpl->diag.clipped_total, cpl->diag.solid_grid, cpl->diag.eps_min0};

  PetscFunctionBeginUser;
  PetscCall(FluidCheckpointWriteVec(ck, "cpl/owed", cpl->ex.owed));
  PetscCall(IoCkptWriteShared(ck, "cpl/state", IO_CKPT_REAL, CPL_CKPT_NSTATE, s));
  if (cpl->filt.n > 0) PetscCall(IoCkptWriteShared(ck, "cpl/filter_diameter", IO_CKPT_REAL, 1, &cpl->filt.d));
  if (cpl->pw.width > 0) PetscCall(IoCkptWriteShared(ck, "cpl/porosity_diameter", IO_CKPT_REAL, 1, &cpl->pw.d));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The mean diameter a width option (name, value) was set from, dataset ds: one line if the
 * checkpoint was written without the option. */
static PetscErrorCode CplReadDiameter(Cpl cpl, IoCkpt ck, const char *ds, const char *name, PetscReal value, PetscReal *d)
{
  PetscBool has;

  PetscFunctionBeginUser;
  PetscCall(IoCkptHas(ck, ds, &has));
  PetscCheck(has, cpl->comm, PETSC_ERR_FILE_UNEXPECTED, "%s %g: the checkpoint was written without it; restart without %s", name, (double)value, name);
  PetscCall(IoCkptReadShared(ck, ds, IO_CKPT_REAL, 1, d));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CplCheckpointRead(Cpl cpl, IoCkpt ck)
{
  PetscReal s[CPL_CKPT_NSTATE];

  PetscFunctionBeginUser;
  PetscCheck(cpl->ex.owed, cpl->comm, PETSC_ERR_ORDER, "call CplSetUp before CplCheckpointRead");
  PetscCall(FluidCheckpointReadVec(ck, "cpl/owed", cpl->ex.owed));
  PetscCall(IoCkptReadShared(ck, "cpl/state", IO_CKPT_REAL, CPL_CKPT_NSTATE, s));
  cpl->clock.t            = s[0];
  cpl->clock.step         = (PetscInt)s[1];
  cpl->diag.clipped_total = (PetscInt)s[2];
  cpl->diag.solid_grid    = s[3]; /* s[4], the writer's start porosity, is not read back: the restart's
                                  pre-flight is of the restored bed (CplSetUp's projection) */
  if (cpl->filt.n > 0) {          /* the filter's width from the mean diameter at the run's start */
    PetscReal d;
    PetscCall(CplReadDiameter(cpl, ck, "cpl/filter_diameter", "-cpl_filter_width", cpl->filt.width, &d));
    PetscCall(CplFilterSetUp(cpl, d));
  }
  if (cpl->pw.width > 0) { /* the same for the drag's porosity width */
    PetscReal d;
    PetscCall(CplReadDiameter(cpl, ck, "cpl/porosity_diameter", "-cpl_porosity_width", cpl->pw.width, &d));
    PetscCall(CplSmoothSetUp(cpl, d));
  }
  CplInvalidateStencils(cpl);
  PetscFunctionReturn(PETSC_SUCCESS);
}
