/* Fluid fields from analytic functions: porosity at cell centres, velocity at face centres
 * (component d at the centre of the lower d-face), and the error of the face velocity against
 * an analytic field. For initial conditions, cases and verification tests. Coordinates in m. */
#include "fluid/fluid_impl.h"

PetscErrorCode FluidSetPorosityFunction(Fluid fl, FluidScalarFn fn, void *ctx)
{
  const FluidGrid *g = &fl->g;
  PetscScalar     *e;
  PetscInt         idx[3], c, o;

  PetscFunctionBeginUser;
  PetscCall(VecGetArray(fl->fld.eps, &e));
  FLUID_FOR_OWNED_CELLS(g, idx, c, o)
  {
    PetscReal x[3];
    for (int d = 0; d < 3; d++) x[d] = g->lo[d] + (idx[d] + 0.5) * g->h[d];
    e[o] = fn(x, ctx);
  }
  PetscCall(VecRestoreArray(fl->fld.eps, &e));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static void FluidFaceCentre(const FluidGrid *g, const PetscInt idx[3], int d, PetscReal x[3])
{
  for (int e = 0; e < 3; e++) x[e] = g->lo[e] + (idx[e] + (e == d ? 0.0 : 0.5)) * g->h[e];
}

PetscErrorCode FluidSetVelocityFunction(Fluid fl, FluidVectorFn fn, void *ctx)
{
  const FluidGrid *g = &fl->g;
  PetscScalar     *u;
  PetscInt         idx[3], f, c, o;

  PetscFunctionBeginUser;
  PetscCall(VecGetArray(fl->fld.u, &u));
  FLUID_FOR_OWNED_FACES(g, idx, f, c, o)
  for (int d = 0; d < 3; d++) {
    PetscReal x[3], v[3];
    FluidFaceCentre(g, idx, d, x);
    fn(x, v, ctx);
    u[o + d] = v[d];
  }
  if (fl->ves.cut) { /* a vessel's closed faces hold 0: no gas through the solid */
    const PetscScalar *a;
    PetscInt           n;
    PetscCall(VecGetLocalSize(fl->fld.u, &n));
    PetscCall(VecGetArrayRead(fl->ves.area, &a));
    for (PetscInt i = 0; i < n; i++)
      if (a[i] == 0) u[i] = 0;
    PetscCall(VecRestoreArrayRead(fl->ves.area, &a));
  }
  PetscCall(VecRestoreArray(fl->fld.u, &u));
  PetscCall(FluidBoundaryFaceValues(fl, fl->fld.u));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FluidVelocityError(Fluid fl, FluidVectorFn fn, void *ctx, PetscReal *l2, PetscReal *linf)
{
  const FluidGrid   *g = &fl->g;
  const PetscScalar *u;
  PetscInt           idx[3], f, c, o, n = 0, ng;
  PetscReal          s2 = 0, mx = 0, loc[2], glob[2];

  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(fl->fld.u, &u));
  FLUID_FOR_OWNED_FACES(g, idx, f, c, o)
  for (int d = 0; d < 3; d++) {
    PetscReal x[3], v[3], err;
    for (int e = 0; e < 3; e++)
      if (!FluidPeriodic(fl, e) && e != d && idx[e] == g->N[e]) goto skip; /* unused extra point */
    FluidFaceCentre(g, idx, d, x);
    fn(x, v, ctx);
    err = PetscAbsReal(PetscRealPart(u[o + d]) - v[d]);
    s2 += err * err;
    mx = PetscMax(mx, err);
    n++;
  skip:;
  }
  PetscCall(VecRestoreArrayRead(fl->fld.u, &u));
  loc[0] = s2;
  loc[1] = (PetscReal)n;
  PetscCall(MPIU_Allreduce(loc, glob, 2, MPIU_REAL, MPIU_SUM, fl->comm));
  PetscCall(MPIU_Allreduce(&mx, linf, 1, MPIU_REAL, MPIU_MAX, fl->comm));
  ng  = (PetscInt)glob[1];
  *l2 = PetscSqrtReal(glob[0] / ng);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FluidCellsToFaces(Fluid fl, Vec cell[3], Vec face)
{
  const FluidGrid *g = &fl->g;
  PetscScalar     *out;
  Vec              loc;
  PetscInt         idx[3], f, c, o;

  PetscFunctionBeginUser;
  PetscCall(DMGetLocalVector(fl->g.cda, &loc));
  PetscCall(VecGetArray(face, &out));
  for (int d = 0; d < 3; d++) {
    const PetscScalar *a;
    PetscCall(FluidLocalCell(fl, cell[d], loc, PETSC_FALSE, 0.0));
    PetscCall(VecGetArrayRead(loc, &a));
    FLUID_FOR_OWNED_FACES(g, idx, f, c, o)
    out[o + d] = 0.5 * (a[c] + a[c - g->cs[d]]);
    PetscCall(VecRestoreArrayRead(loc, &a));
  }
  PetscCall(VecRestoreArray(face, &out));
  PetscCall(DMRestoreLocalVector(fl->g.cda, &loc));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The pressure-gradient field for the pressure-gradient form's force on the particles: the
 * momentum equation's own face gradient at the active faces; a wall or inlet face point (no
 * equation) takes its first interior neighbour's, the half cell next to the face then pushes
 * the particles as the cell above it does; unused and closed face points 0. */
PetscErrorCode FluidGetPressureGradient(Fluid fl, Vec gv)
{
  const FluidGrid   *g = &fl->g;
  const PetscScalar *p;
  PetscScalar       *gp;
  PetscInt           idx[3], f, c, o;

  PetscFunctionBeginUser;
  PetscCall(FluidLocalCell(fl, fl->fld.p, fl->fld.ploc, FLUID_GHOST_PRESSURE, fl->bc.p_out));
  PetscCall(VecGetArrayRead(fl->fld.ploc, &p));
  PetscCall(VecGetArray(gv, &gp));
  FLUID_FOR_OWNED_FACES(g, idx, f, c, o)
  for (int d = 0; d < 3; d++) {
    PetscInt cc = c, on = 1;
    gp[o + d] = 0;
    if (!FluidFaceActive(fl, d, idx)) { /* a wall or inlet point on a bounded side: its neighbour's */
      on = 0;
      for (int e = 0; e < 3; e++)
        if (!FluidPeriodic(fl, e) && e != d && idx[e] == g->N[e]) on = -1; /* an unused point */
      if (on == 0 && !FluidPeriodic(fl, d) && (idx[d] == 0 || idx[d] == g->N[d]) && (!fl->ves.aloc || fl->ves.aloc[f + d] > 0)) {
        cc = idx[d] == 0 ? c + g->cs[d] : c - g->cs[d];
        on = 1;
      }
    }
    if (on == 1) gp[o + d] = (p[cc] - p[cc - g->cs[d]]) / g->h[d] + fl->prop.dpdx[d];
  }
  PetscCall(VecRestoreArray(gv, &gp));
  PetscCall(VecRestoreArrayRead(fl->fld.ploc, &p));
  PetscFunctionReturn(PETSC_SUCCESS);
}
