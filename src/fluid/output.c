/* Fluid output: porosity eps, pressure p and the cell-centred velocity (the mean of the two
 * face values of each component) of the owned cells, written as fluid fields of the open
 * frame (io.h) when it takes fluid fields (-io_fluid_interval, -io_fields). The cell-centred velocity is also what the drivers' time averages sample. */
#include "fluid/fluid_impl.h"

PetscErrorCode FluidGetCellVelocity(Fluid fl, PetscReal *vel)
{
  const FluidGrid   *g = &fl->g;
  const PetscScalar *u;
  PetscInt           idx[3], c, o;

  PetscFunctionBeginUser;
  PetscCall(FluidLocalPorosityOld(fl, PETSC_FALSE));
  PetscCall(FluidLocalVelocity(fl, fl->fld.u, fl->fld.uloc, fl->fld.epsoldloc));
  PetscCall(VecGetArrayRead(fl->fld.uloc, &u));
  FLUID_FOR_OWNED_CELLS(g, idx, c, o)
  {
    const PetscInt f = FluidFaceOff(g, idx[0], idx[1], idx[2]);
    for (int d = 0; d < 3; d++) vel[3 * o + d] = 0.5 * (u[f + d] + u[f + g->fs[d] + d]);
  }
  PetscCall(VecRestoreArrayRead(fl->fld.uloc, &u));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FluidWriteOutput(Fluid fl, Io io)
{
  const FluidGrid   *g = &fl->g;
  const PetscScalar *e, *p;
  PetscReal         *vel;
  PetscInt           n = g->xm[0] * g->xm[1] * g->xm[2];
  PetscBool          want;

  PetscFunctionBeginUser;
  PetscCall(IoFrameWants(io, "fluid", NULL, &want)); /* not at this frame's time (-io_fluid_interval) */
  if (!want) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(IoSetFluidMesh(io, g->lo, g->h, g->N));
  PetscCall(PetscMalloc1(3 * n, &vel));
  PetscCall(FluidGetCellVelocity(fl, vel));
  PetscCall(VecGetArrayRead(fl->fld.eps, &e));
  PetscCall(VecGetArrayRead(fl->fld.p, &p));
  PetscCall(IoWriteField(io, "eps", 1, g->xs, g->xm, e));
  PetscCall(IoWriteField(io, "p", 1, g->xs, g->xm, p));
  PetscCall(IoWriteField(io, "velocity", 3, g->xs, g->xm, vel));
  if (fl->ves.cut) { /* the vessel's open-volume fraction: clip at 0.5 */
    const PetscScalar *v;
    PetscCall(VecGetArrayRead(fl->ves.vol, &v));
    PetscCall(IoWriteField(io, "vessel", 1, g->xs, g->xm, v));
    PetscCall(VecRestoreArrayRead(fl->ves.vol, &v));
  }
  PetscCall(VecRestoreArrayRead(fl->fld.p, &p));
  PetscCall(VecRestoreArrayRead(fl->fld.eps, &e));
  PetscCall(PetscFree(vel));
  PetscFunctionReturn(PETSC_SUCCESS);
}
