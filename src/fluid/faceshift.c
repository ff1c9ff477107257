/* The pressure on a bounded face (wall or inlet) where particles deposit drag.
 *
 * A face point on a non-periodic boundary carries no momentum equation: its velocity is the
 * boundary's. The drag the coupling deposits there, D_b = beta (u - u_s) - f (force per unit of
 * the face's momentum control volume; f the explicit source deposited there: the reaction of the
 * particles' pressure-gradient force with -cpl_form A, else 0), is felt by no interior equation:
 * the half cell between the face and the first row of centres holds it. That half cell's momentum balance gives the face's
 * pressure (axis d, cell side h, centres 1 and 2 counted from the face, s = +1 on the low side,
 * -1 on the high one):
 *   p_b = p_1 + s h (D_b + R / 2),   R = s (p_1 - p_2) / h - D_1,
 * R being the rest of the first interior face's balance (inertia, viscous stress, sources) taken
 * as the same over the half cell. Hence
 *   p_b = 1.5 p_1 - 0.5 p_2 + s h (D_b - D_1 / 2):
 * the linear extrapolation of the centres (exact for a linear pressure: a fluid alone, or a
 * uniform bed) plus the drag's shift. Over a bed this makes the pressure drop from the inlet face
 * equal the drag the gas carries, per unit of its open area, whatever the height of the first
 * cell: beads resting on the floor deposit part of their drag on the inlet's face points, which
 * the extrapolation of the centres sees only when the bed is uniform across the first two rows.
 * Inside the half cell the shift falls linearly to 0 at the first centre.
 *
 * The shifts of every bounded face point (inlets and walls; 0 at outlets, whose pressure is set)
 * are gathered on every rank (one owner a slot, summed: bitwise the same on any rank count) and
 * kept until u, beta or u_s change. Without drag (beta = 0 everywhere, a fluid alone) nothing is
 * stored and nothing is added. */
#include "fluid/fluid_impl.h"
#include <petsc/private/petscimpl.h> /* PetscObjectStateGet: recompute only when u, beta or u_s changed */

/* The shift at boundary face point q (global indices, q[d] = 0 or N[d]) of side s, owned. */
static inline PetscReal fluid_face_shift(const FluidGrid *g, int d, int s, const PetscScalar ****u, const PetscScalar ****b, const PetscScalar ****us, const PetscScalar ****src, const PetscInt q[3])
{
  PetscInt  r[3] = {q[0], q[1], q[2]};
  PetscReal db, d1;

  r[d] += s ? -1 : 1; /* the first interior face point: owned, a rank holds >= 2 cells */
  db = PetscRealPart(b[q[2]][q[1]][q[0]][d] * (u[q[2]][q[1]][q[0]][d] - us[q[2]][q[1]][q[0]][d]) - src[q[2]][q[1]][q[0]][d]);
  d1 = PetscRealPart(b[r[2]][r[1]][r[0]][d] * (u[r[2]][r[1]][r[0]][d] - us[r[2]][r[1]][r[0]][d]));
  return (s ? -1 : 1) * g->h[d] * (db - 0.5 * d1);
}

static PetscErrorCode FluidFaceShiftCompute(Fluid fl)
{
  FluidFaceShift       *fs = &fl->fshift;
  const FluidGrid      *g  = &fl->g;
  PetscObjectState      st[4];
  PetscReal             bmax;
  PetscBool             changed;
  const PetscScalar ****u, ****b, ****us, ****src;

  PetscFunctionBeginUser;
  PetscCall(PetscObjectStateGet((PetscObject)fl->fld.u, &st[0]));
  PetscCall(PetscObjectStateGet((PetscObject)fl->fld.beta, &st[1]));
  PetscCall(PetscObjectStateGet((PetscObject)fl->fld.us, &st[2]));
  PetscCall(PetscObjectStateGet((PetscObject)fl->fld.src, &st[3]));
  changed = (PetscBool) !(fs->valid && st[0] == fs->st[0] && st[1] == fs->st[1] && st[2] == fs->st[2] && st[3] == fs->st[3]);
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &changed, 1, MPIU_BOOL, MPI_LOR, fl->comm)); /* one decision on every rank: the states are per rank */
  if (!changed) PetscFunctionReturn(PETSC_SUCCESS);
  for (int k = 0; k < 4; k++) fs->st[k] = st[k];
  fs->valid = PETSC_TRUE;
  PetscCall(VecNorm(fl->fld.beta, NORM_INFINITY, &bmax));
  fs->any = (PetscBool)(bmax > 0);
  if (!fs->any) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(DMDAVecGetArrayDOFRead(g->fda, fl->fld.u, &u));
  PetscCall(DMDAVecGetArrayDOFRead(g->fda, fl->fld.beta, &b));
  PetscCall(DMDAVecGetArrayDOFRead(g->fda, fl->fld.us, &us));
  PetscCall(DMDAVecGetArrayDOFRead(g->fda, fl->fld.src, &src));
  for (int d = 0; d < 3; d++) {
    const int      a = (d + 1) % 3, c = (d + 2) % 3;
    const PetscInt n = g->N[a] * g->N[c];
    if (FluidPeriodic(fl, d)) continue;
    for (int s = 0; s < 2; s++) {
      const FluidBC *bc = &fl->bc.face[d][s];
      PetscReal     *loc;
      PetscInt       q[3];
      if (!fs->dp[d][s]) PetscCall(PetscMalloc1(n, &fs->dp[d][s]));
      PetscCall(PetscCalloc1(n, &loc));
      q[d] = s ? g->N[d] : 0;
      if (s ? g->xs[d] + g->xm[d] == g->N[d] : g->xs[d] == 0)
        for (q[c] = g->xs[c]; q[c] < g->xs[c] + g->xm[c]; q[c]++)
          for (q[a] = g->xs[a]; q[a] < g->xs[a] + g->xm[a]; q[a]++) {
            const PetscInt    m    = q[a] + g->N[a] * q[c];
            const FluidBCType type = bc->pkind && bc->pkind[m] ? (FluidBCType)bc->pkind[m] : bc->type;
            if (type != FLUID_BC_OUTLET) loc[m] = fluid_face_shift(g, d, s, u, b, us, src, q);
          }
      PetscCallMPI(MPIU_Allreduce(loc, fs->dp[d][s], (PetscMPIInt)n, MPIU_REAL, MPIU_SUM, fl->comm));
      PetscCall(PetscFree(loc));
    }
  }
  PetscCall(DMDAVecRestoreArrayDOFRead(g->fda, fl->fld.src, &src));
  PetscCall(DMDAVecRestoreArrayDOFRead(g->fda, fl->fld.us, &us));
  PetscCall(DMDAVecRestoreArrayDOFRead(g->fda, fl->fld.beta, &b));
  PetscCall(DMDAVecRestoreArrayDOFRead(g->fda, fl->fld.u, &u));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. The mean pressure over the open part of the boundary face (d, s), weighted by the
 * open area a_f h_a h_b: the set pressure at its outlet points, elsewhere 1.5 p_1 - 0.5 p_2 plus
 * the drag's shift. Local sums and one reduction (the shifts of other faces are not gathered). */
PetscErrorCode FluidFacePressure(Fluid fl, int d, int s, PetscReal *pmean)
{
  const FluidGrid   *g  = &fl->g;
  const FluidBC     *bc = &fl->bc.face[d][s];
  const int          a = (d + 1) % 3, c = (d + 2) % 3;
  PetscReal          loc[2] = {0, 0}, sum[2];
  const PetscScalar *p, *vol = NULL, ****ar = NULL, ****u, ****b, ****us, ****src;
  PetscInt           q[3], c1[3], c2[3];

  PetscFunctionBeginUser;
  PetscCheck(!FluidPeriodic(fl, d) && g->N[d] >= 2, fl->comm, PETSC_ERR_ARG_WRONG, "FluidFacePressure: axis %d is periodic or has one cell", d);
  if (s ? g->xs[d] + g->xm[d] == g->N[d] : g->xs[d] == 0) {
    PetscCall(VecGetArrayRead(fl->fld.p, &p));
    if (fl->ves.cut) PetscCall(DMDAVecGetArrayDOFRead(g->fda, fl->ves.area, &ar));
    if (fl->ves.cut) PetscCall(VecGetArrayRead(fl->ves.vol, &vol));
    PetscCall(DMDAVecGetArrayDOFRead(g->fda, fl->fld.u, &u));
    PetscCall(DMDAVecGetArrayDOFRead(g->fda, fl->fld.beta, &b));
    PetscCall(DMDAVecGetArrayDOFRead(g->fda, fl->fld.us, &us));
    PetscCall(DMDAVecGetArrayDOFRead(g->fda, fl->fld.src, &src));
    q[d] = s ? g->N[d] : 0;
    for (q[c] = g->xs[c]; q[c] < g->xs[c] + g->xm[c]; q[c]++)
      for (q[a] = g->xs[a]; q[a] < g->xs[a] + g->xm[a]; q[a]++) {
        const PetscInt    m    = q[a] + g->N[a] * q[c];
        const FluidBCType type = bc->pkind && bc->pkind[m] ? (FluidBCType)bc->pkind[m] : bc->type;
        PetscReal         w    = g->h[a] * g->h[c], pf;
        for (int e = 0; e < 3; e++) c1[e] = c2[e] = q[e] - g->xs[e];
        c1[d] = s ? g->xm[d] - 1 : 0;
        c2[d] = s ? g->xm[d] - 2 : 1;
        if (ar) w *= PetscRealPart(ar[q[2]][q[1]][q[0]][d]);
        if (w == 0) continue;
        if (type == FLUID_BC_OUTLET) pf = bc->pkind && bc->pkind[m] ? bc->pp[m] : fl->bc.p_out;
        else {
          const PetscInt  o1 = (c1[2] * g->xm[1] + c1[1]) * g->xm[0] + c1[0], o2 = (c2[2] * g->xm[1] + c2[1]) * g->xm[0] + c2[0];
          const PetscBool line = (PetscBool)(!vol || PetscRealPart(vol[o2]) > 0); /* the second centre closed by the vessel: the first alone */
          pf                   = (line ? 1.5 * PetscRealPart(p[o1]) - 0.5 * PetscRealPart(p[o2]) : PetscRealPart(p[o1])) + fluid_face_shift(g, d, s, u, b, us, src, q);
        }
        loc[0] += w * pf;
        loc[1] += w;
      }
    PetscCall(DMDAVecRestoreArrayDOFRead(g->fda, fl->fld.src, &src));
    PetscCall(DMDAVecRestoreArrayDOFRead(g->fda, fl->fld.us, &us));
    PetscCall(DMDAVecRestoreArrayDOFRead(g->fda, fl->fld.beta, &b));
    PetscCall(DMDAVecRestoreArrayDOFRead(g->fda, fl->fld.u, &u));
    if (vol) PetscCall(VecRestoreArrayRead(fl->ves.vol, &vol));
    if (ar) PetscCall(DMDAVecRestoreArrayDOFRead(g->fda, fl->ves.area, &ar));
    PetscCall(VecRestoreArrayRead(fl->fld.p, &p));
  }
  PetscCallMPI(MPIU_Allreduce(loc, sum, 2, MPIU_REAL, MPIU_SUM, fl->comm));
  *pmean = sum[1] > 0 ? sum[0] / sum[1] : 0;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FluidFaceShiftUpdate(Fluid fl, PetscBool *any)
{
  PetscFunctionBeginUser;
  PetscCall(FluidFaceShiftCompute(fl));
  *any = fl->fshift.any;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The shift's share along axis d of the interval [x0, x1] (a point when x1 <= x0), its mean over
 * the interval: 1 on a bounded face, falling linearly to 0 at the first centre; side s. */
PetscReal FluidFaceShiftAxisShare(const Fluid fl, int d, int s, PetscReal x0, PetscReal x1)
{
  const PetscReal h = fl->g.h[d], e = s ? fl->dom->hi[d] : fl->dom->lo[d];
  PetscReal       t0, t1; /* distances from the face, in half cells */

  if (FluidPeriodic(fl, d) || fl->g.N[d] < 2) return 0;
  t0 = PetscAbsReal(x0 - e) / (0.5 * h);
  t1 = PetscAbsReal(x1 - e) / (0.5 * h);
  if (x1 <= x0) return t0 < 1 ? 1 - t0 : 0;
  if (t0 > t1) {
    const PetscReal t = t0;
    t0 = t1, t1 = t;
  }
  if (t0 >= 1) return 0;
  {
    const PetscReal b = PetscMin(t1, 1); /* integral of (1 - t) over [t0, b], over the interval's length */
    return ((b - t0) - 0.5 * (b * b - t0 * t0)) / (t1 - t0);
  }
}

/* The shift on the face (d, s) at tangential weights Wa, Wb (cell-centre weights along the
 * face's axes a = (d + 1) % 3, b = (d + 2) % 3, summing to 1). */
PetscReal FluidFaceShiftAt(const Fluid fl, int d, int s, const PetscReal *Wa, const PetscReal *Wb)
{
  const FluidGrid *g = &fl->g;
  const int        a = (d + 1) % 3, c = (d + 2) % 3;
  const PetscReal *dp = fl->fshift.dp[d][s];
  PetscReal        v  = 0;

  if (!fl->fshift.any || !dp) return 0;
  for (PetscInt j = 0; j < g->N[c]; j++) {
    if (Wb[j] == 0) continue;
    for (PetscInt i = 0; i < g->N[a]; i++)
      if (Wa[i] != 0) v += Wb[j] * Wa[i] * dp[i + g->N[a] * j];
  }
  return v;
}

/* The shift of patch face point m (index along the face's axes) of face (d, s). */
PetscReal FluidFaceShiftPoint(const Fluid fl, int d, int s, PetscInt m)
{
  return fl->fshift.any && fl->fshift.dp[d][s] ? fl->fshift.dp[d][s][m] : 0;
}

PetscErrorCode FluidFaceShiftDestroy(Fluid fl)
{
  PetscFunctionBeginUser;
  for (int d = 0; d < 3; d++)
    for (int s = 0; s < 2; s++) PetscCall(PetscFree(fl->fshift.dp[d][s]));
  fl->fshift.valid = fl->fshift.any = PETSC_FALSE;
  PetscFunctionReturn(PETSC_SUCCESS);
}
