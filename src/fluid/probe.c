/* Point probes of the fluid: the cell-centred pressure at a point x by trilinear interpolation
 * between the eight cell centres around it. Along a wall, inlet or outlet axis a point within
 * half a cell of the boundary takes the value of the nearest centre row (no extrapolation);
 * along a periodic axis the centres wrap. The rank that owns the cell holding x interpolates from
 * its ghosted copy (the DMDA's stencil is at least one cell wide); the others add 0. */
#include "fluid/fluid_impl.h"

/* Lower centre index and weight of the upper one along axis d for coordinate x. */
static void FluidProbeAxis(const Fluid fl, int d, PetscReal x, PetscInt *i0, PetscReal *w)
{
  const PetscInt  n = fl->g.N[d];
  const PetscReal s = (x - fl->g.lo[d]) / fl->g.h[d] - 0.5; /* in centre units */
  PetscInt        i = (PetscInt)PetscFloorReal(s);

  *w = s - (PetscReal)i;
  if (!fl->dom->periodic[d]) {
    if (i < 0) *i0 = 0, *w = 0;
    else if (i >= n - 1) *i0 = n - 1, *w = 0;
    else *i0 = i;
  } else *i0 = i; /* the ghosts hold i = -1 and i = n */
}

PetscErrorCode FluidProbePressure(Fluid fl, const PetscReal x[3], PetscReal *p)
{
  PetscInt  own[3], i0[3];
  PetscReal w[3], v = 0;
  PetscBool mine = PETSC_TRUE;
  Vec       loc;

  PetscFunctionBeginUser;
  for (int d = 0; d < 3; d++) {
    PetscCheck(x[d] >= fl->dom->lo[d] && x[d] <= fl->dom->hi[d], fl->comm, PETSC_ERR_ARG_OUTOFRANGE, "probe (%g, %g, %g) lies outside the domain (m)", (double)x[0], (double)x[1], (double)x[2]);
    own[d] = PetscMin((PetscInt)PetscFloorReal((x[d] - fl->g.lo[d]) / fl->g.h[d]), fl->g.N[d] - 1);
    mine   = (PetscBool)(mine && own[d] >= fl->g.xs[d] && own[d] < fl->g.xs[d] + fl->g.xm[d]);
    FluidProbeAxis(fl, d, x[d], &i0[d], &w[d]);
  }
  PetscCall(DMGetLocalVector(fl->cda, &loc));
  PetscCall(DMGlobalToLocal(fl->cda, fl->p, INSERT_VALUES, loc));
  if (mine) {
    PetscScalar ***a;
    PetscCall(DMDAVecGetArrayRead(fl->cda, loc, &a));
    for (int c = 0; c < 8; c++) {
      const int       b[3] = {c & 1, (c >> 1) & 1, (c >> 2) & 1};
      const PetscReal wt   = (b[0] ? w[0] : 1 - w[0]) * (b[1] ? w[1] : 1 - w[1]) * (b[2] ? w[2] : 1 - w[2]);
      if (wt != 0) v += wt * PetscRealPart(a[i0[2] + b[2]][i0[1] + b[1]][i0[0] + b[0]]);
    }
    PetscCall(DMDAVecRestoreArrayRead(fl->cda, loc, &a));
  }
  PetscCall(DMRestoreLocalVector(fl->cda, &loc));
  PetscCallMPI(MPI_Allreduce(&v, p, 1, MPIU_REAL, MPI_SUM, fl->comm));
  PetscFunctionReturn(PETSC_SUCCESS);
}
