/* The vessel: FAVOR (fractional area-volume obstacle representation; Hirt & Sicilian, "A porosity
 * technique for the definition of obstacles in rectangular cell meshes", 4th Int. Conf. Numer.
 * Ship Hydrodynamics, 1985) on the staggered grid. A level function phi (> 0 gas, < 0 solid, not
 * necessarily a distance) gives at set-up
 *   - the open-volume fraction of each cell and the open-area fraction of each face: a cell (face)
 *     whose centre and corners share a sign with |phi(centre)| > 2 L r (r its half diagonal, L
 *     the largest slope of phi from the centre to a corner) is classified at once; any other is
 *     sampled on a 4 x 4 sub-grid with phi linear on two triangles per sub-square (exact for a
 *     plane wall); a cell's volume is the mean of 4 such cross-sections. Fractions below 1e-3
 *     count as closed, and so does a cell without an active face (its volume becomes 0). A face
 *     whose centre lies in the solid keeps its sampled fraction: its momentum control volume is
 *     a_f V_cell (the coupling's too), so the open area sum a_f h^2 of a layer, not a count of
 *     faces, carries the pressure drop;
 *   - for every active face dof and axis e, side s, whose neighbour dof along e is closed or has
 *     its centre in the solid, or whose own centre is in the solid (a wall link: the two values
 *     do not see each other, the matrix stays symmetric): the distance theta h_e along that grid
 *     line to the wall (Illinois regula falsi on phi; theta = 1 when the closed neighbour's centre
 *     is itself in the gas, theta_min when the face's own centre is in the solid: its velocity,
 *     the mean over an open sliver along the wall, is held near 0 by the wall), clamped below at
 *     -fluid_vessel_theta_min (0.05). The viscous term (momentum.c, viscous.c) replaces the
 *     neighbour by the linear extrapolation through the wall value, u_Q = u_P (1 - 1/theta), so
 *     the flux to the wall is mu (0 - u_P)/(theta h): the symmetric second-order treatment of
 *     Gibou, Fedkiw, Cheng & Kang, J. Comput. Phys. 176 (2002) 205, doi:10.1006/jcph.2001.6977.
 *     With -fluid_vessel_wall slip the flux to the wall is 0 instead (zero normal derivative);
 *   - for a face whose own centre is in the solid (no-slip), the friction of its open sliver as a
 *     film of width w = a_f h (h the face's mean side) along one no-slip wall, 3 mu / w^2 (the
 *     mean velocity of such a film is G w^2 / (3 mu)), kept in film: an implicit sink added to
 *     beta (FluidBetaOfSolve). The wall link alone (at theta_min) left the slivers, free of
 *     particles, nearly free of friction, and the gas ran up them past a bed.
 * Nothing is kept when the vessel cuts no cell or face: the box code runs unchanged. */
#include "fluid/fluid_impl.h"

#define FLUID_VESSEL_CLOSED 1e-3 /* fractions below: closed */
#define FLUID_VESSEL_SUB    4    /* sub-squares per face side, cross-sections per cell */

static const char *const FluidVesselWallNames[] = {"noslip", "slip", "FluidVesselWall", "FLUID_VESSEL_", NULL};

PetscErrorCode FluidSetVessel(Fluid fl, FluidLevelFn level, void *ctx)
{
  PetscFunctionBeginUser;
  PetscCheck(!fl->setup, fl->comm, PETSC_ERR_ORDER, "call FluidSetVessel before FluidSetUp");
  fl->ves.level = level;
  fl->ves.ctx   = ctx;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FluidVesselActive(Fluid fl, PetscBool *cut)
{
  PetscFunctionBeginUser;
  PetscCheck(fl->setup, PETSC_COMM_SELF, PETSC_ERR_ORDER, "call FluidSetUp before FluidVesselActive");
  *cut = fl->ves.cut;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FluidGetOpenFractions(Fluid fl, Vec *vol, Vec *area)
{
  PetscFunctionBeginUser;
  PetscCheck(fl->setup, PETSC_COMM_SELF, PETSC_ERR_ORDER, "call FluidSetUp before FluidGetOpenFractions");
  if (vol) *vol = fl->ves.vol;
  if (area) *area = fl->ves.area;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FluidSetFromOptionsVessel(Fluid fl)
{
  PetscInt wall = fl->ves.slip ? 1 : 0;

  PetscFunctionBeginUser;
  if (fl->ves.theta_min == 0) fl->ves.theta_min = 0.05;
  PetscOptionsBegin(fl->comm, NULL, "Fluid vessel (FAVOR)", NULL);
  PetscCall(SableOptionsEnum("-fluid_vessel_wall", "Vessel wall for the viscous term: noslip (u = 0 on the wall, at its distance along each grid line) or slip (zero normal derivative)", FluidVesselWallNames, 2, wall, &wall, NULL));
  PetscCall(SableOptionsReal("-fluid_vessel_theta_min", "Smallest wall distance, in cells, the viscous term uses (closer walls are moved to it): its stiffness is 1/theta", NULL, "(0,1]", fl->ves.theta_min, &fl->ves.theta_min, NULL));
  PetscOptionsEnd();
  fl->ves.slip = (PetscBool)(wall == 1);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FluidVesselDestroy(Fluid fl)
{
  PetscFunctionBeginUser;
  PetscCall(VecDestroy(&fl->ves.vol));
  PetscCall(VecDestroy(&fl->ves.area));
  PetscCall(VecDestroy(&fl->ves.ind));
  PetscCall(PetscFree3(fl->ves.aloc, fl->ves.vloc, fl->ves.full));
  PetscCall(PetscFree(fl->ves.wl));
  PetscCall(PetscFree(fl->ves.theta));
  PetscCall(VecDestroy(&fl->ves.film));
  fl->ves.nlink = 0;
  fl->ves.cut   = PETSC_FALSE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Fraction of a triangle where the linear interpolant of its vertex values is > 0 (exact). */
static inline PetscReal fluid_tri_fraction(PetscReal a, PetscReal b, PetscReal c)
{
  const int np = (a > 0) + (b > 0) + (c > 0);
  PetscReal p, q, r;

  if (np == 3) return 1;
  if (np == 0) return 0;
  if (np == 1) { /* the positive corner's triangle */
    if (a > 0) p = a, q = b, r = c;
    else if (b > 0) p = b, q = a, r = c;
    else p = c, q = a, r = b;
    return (p / (p - q)) * (p / (p - r));
  }
  if (a <= 0) p = a, q = b, r = c; /* one corner in the solid: all but its triangle */
  else if (b <= 0) p = b, q = a, r = c;
  else p = c, q = a, r = b;
  return 1 - (p / (p - q)) * (p / (p - r));
}

/* Open fraction of the rectangle at x0 spanning h[a] along axis a and h[b] along b. */
static PetscReal FluidRectFraction(FluidVessel *v, const PetscReal x0[3], int a, int b, const PetscReal h[3])
{
  const int n = FLUID_VESSEL_SUB;
  PetscReal ph[FLUID_VESSEL_SUB + 1][FLUID_VESSEL_SUB + 1], s = 0;

  for (int i = 0; i <= n; i++)
    for (int j = 0; j <= n; j++) {
      PetscReal x[3] = {x0[0], x0[1], x0[2]};
      x[a] += i * h[a] / n;
      x[b] += j * h[b] / n;
      ph[i][j] = v->level(x, v->ctx);
    }
  for (int i = 0; i < n; i++)
    for (int j = 0; j < n; j++) s += fluid_tri_fraction(ph[i][j], ph[i + 1][j], ph[i + 1][j + 1]) + fluid_tri_fraction(ph[i][j], ph[i + 1][j + 1], ph[i][j + 1]);
  return s / (2 * n * n);
}

/* 1 open, 0 closed, -1 cut or not decided, from the centre value pc and n corner values pk of a
 * box of half diagonal r (the file header's test). */
static int fluid_classify(PetscReal pc, const PetscReal *pk, int n, PetscReal r)
{
  PetscReal L = 0;
  for (int k = 0; k < n; k++) {
    if ((pk[k] > 0) != (pc > 0)) return -1;
    L = PetscMax(L, PetscAbsReal(pk[k] - pc) / r);
  }
  if (PetscAbsReal(pc) > 2 * L * r) return pc > 0 ? 1 : 0;
  return -1;
}

/* Wall position t in (0,1] on the segment xp -> xq, phi(xp) = fp > 0 >= phi(xq) = fq. */
static PetscReal FluidWallDistance(FluidVessel *v, const PetscReal xp[3], const PetscReal xq[3], PetscReal fp, PetscReal fq)
{
  PetscReal t0 = 0, t1 = 1, f0 = fp, f1 = fq, t = 1;
  int       side = 0;

  for (int it = 0; it < 80 && t1 - t0 > 1e-13; it++) {
    PetscReal x[3], ft;
    t = (f1 != f0) ? (t0 * f1 - t1 * f0) / (f1 - f0) : 0.5 * (t0 + t1);
    if (!(t > t0 && t < t1)) t = 0.5 * (t0 + t1);
    for (int k = 0; k < 3; k++) x[k] = xp[k] + t * (xq[k] - xp[k]);
    ft = v->level(x, v->ctx);
    if (ft > 0) {
      t0 = t, f0 = ft;
      if (side == -1) f1 *= 0.5;
      side = -1;
    } else {
      t1 = t, f1 = ft;
      if (side == 1) f0 *= 0.5;
      side = 1;
      if (ft == 0) break;
    }
  }
  return t;
}

static void FluidFaceCentreX(const FluidGrid *g, const PetscInt idx[3], int d, PetscReal x[3])
{
  for (int e = 0; e < 3; e++) x[e] = g->lo[e] + (idx[e] + (e == d ? 0.0 : 0.5)) * g->h[e];
}

/* Whether face point idx of component d exists on the grid (periodic ghosts do). */
static inline PetscBool fluid_face_in_range(Fluid fl, int d, const PetscInt idx[3])
{
  for (int e = 0; e < 3; e++) {
    if (FluidPeriodic(fl, e)) continue;
    if (idx[e] < 0 || idx[e] > (e == d ? fl->g.N[e] : fl->g.N[e] - 1)) return PETSC_FALSE;
  }
  return PETSC_TRUE;
}

/* Whether face point idx of component d lies on an inlet face of the box (a fixed value). */
static inline PetscBool fluid_inlet_face(Fluid fl, int d, const PetscInt idx[3])
{
  if (FluidPeriodic(fl, d)) return PETSC_FALSE;
  if (idx[d] == 0) return (PetscBool)(fl->bc.face[d][0].type == FLUID_BC_INLET);
  if (idx[d] == fl->g.N[d]) return (PetscBool)(fl->bc.face[d][1].type == FLUID_BC_INLET);
  return PETSC_FALSE;
}

/* Open fractions of the owned cells and faces into the global Vecs; *cut: some in-range one < 1. */
static PetscErrorCode FluidVesselFractions(Fluid fl, PetscBool *cut)
{
  FluidVessel *v = &fl->ves;
  FluidGrid   *g = &fl->g;
  PetscInt     nn[3], idx[3], c, f, o;
  PetscReal   *pn, *vol, *area, hd = 0;
  signed char *cls;

  PetscFunctionBeginUser;
  *cut = PETSC_FALSE;
  for (int d = 0; d < 3; d++) nn[d] = g->fxm[d] + 1, hd += 0.25 * g->h[d] * g->h[d];
  hd = PetscSqrtReal(hd);
  PetscCall(PetscMalloc2(nn[0] * nn[1] * nn[2], &pn, g->xm[0] * g->xm[1] * g->xm[2], &cls));
#define NODE(i, j, k) pn[(((k)-g->xs[2]) * nn[1] + (j)-g->xs[1]) * nn[0] + (i)-g->xs[0]]
  for (PetscInt k = g->xs[2]; k < g->xs[2] + nn[2]; k++)
    for (PetscInt j = g->xs[1]; j < g->xs[1] + nn[1]; j++)
      for (PetscInt i = g->xs[0]; i < g->xs[0] + nn[0]; i++) {
        const PetscReal x[3] = {g->lo[0] + i * g->h[0], g->lo[1] + j * g->h[1], g->lo[2] + k * g->h[2]};
        NODE(i, j, k)        = v->level(x, v->ctx);
      }
  PetscCall(VecGetArray(v->vol, &vol));
  FLUID_FOR_OWNED_CELLS(g, idx, c, o)
  {
    PetscReal pk[8], x[3];
    for (int q = 0; q < 8; q++) pk[q] = NODE(idx[0] + (q & 1), idx[1] + ((q >> 1) & 1), idx[2] + ((q >> 2) & 1));
    for (int d = 0; d < 3; d++) x[d] = g->lo[d] + (idx[d] + 0.5) * g->h[d];
    cls[o] = (signed char)fluid_classify(v->level(x, v->ctx), pk, 8, hd);
    if (cls[o] >= 0) vol[o] = cls[o];
    else { /* the mean of cross-sections at the midpoints of FLUID_VESSEL_SUB slabs along z */
      PetscReal s = 0;
      for (int l = 0; l < FLUID_VESSEL_SUB; l++) {
        const PetscReal x0[3] = {g->lo[0] + idx[0] * g->h[0], g->lo[1] + idx[1] * g->h[1], g->lo[2] + (idx[2] + (l + 0.5) / FLUID_VESSEL_SUB) * g->h[2]};
        s += FluidRectFraction(v, x0, 0, 1, g->h);
      }
      vol[o] = s / FLUID_VESSEL_SUB;
      if (vol[o] < FLUID_VESSEL_CLOSED) vol[o] = 0;
    }
    if (vol[o] < 1) *cut = PETSC_TRUE;
  }
  PetscCall(VecRestoreArray(v->vol, &vol));
  PetscCall(VecGetArray(v->area, &area));
  FLUID_FOR_OWNED_FACES(g, idx, f, c, o)
  for (int d = 0; d < 3; d++) {
    const int a = (d + 1) % 3, b = (d + 2) % 3;
    PetscBool owned_cell = PETSC_TRUE;
    if (!fluid_face_in_range(fl, d, idx)) {
      area[o + d] = 0; /* the unused extra point of a tangential component */
      continue;
    }
    for (int e = 0; e < 3; e++)
      if (idx[e] >= g->xs[e] + g->xm[e]) owned_cell = PETSC_FALSE;
    if (owned_cell) { /* the face is the lower d-face of the owned cell idx: classified whole? */
      const PetscInt oc = ((idx[2] - g->xs[2]) * g->xm[1] + idx[1] - g->xs[1]) * g->xm[0] + idx[0] - g->xs[0];
      if (cls[oc] >= 0) {
        area[o + d] = cls[oc];
        if (area[o + d] < 1) *cut = PETSC_TRUE;
        continue;
      }
    }
    {
      PetscInt  q[3] = {idx[0], idx[1], idx[2]};
      PetscReal pk[4], x[3], x0[3], r = 0.5 * PetscSqrtReal(g->h[a] * g->h[a] + g->h[b] * g->h[b]), pc;
      for (int m = 0; m < 4; m++) {
        q[a]  = idx[a] + (m & 1);
        q[b]  = idx[b] + ((m >> 1) & 1);
        pk[m] = NODE(q[0], q[1], q[2]);
      }
      FluidFaceCentreX(g, idx, d, x);
      pc          = v->level(x, v->ctx);
      const int k = fluid_classify(pc, pk, 4, r);
      if (k >= 0) area[o + d] = k;
      else {
        for (int e = 0; e < 3; e++) x0[e] = g->lo[e] + idx[e] * g->h[e];
        area[o + d] = FluidRectFraction(v, x0, a, b, g->h);
        if (area[o + d] < FLUID_VESSEL_CLOSED) area[o + d] = 0;
      }
      if (area[o + d] < 1) *cut = PETSC_TRUE;
    }
  }
#undef NODE
  PetscCall(VecRestoreArray(v->area, &area));
  PetscCall(PetscFree2(pn, cls));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* A ghosted copy of a global Vec as a plain array (outside = the value beyond a bounded axis). */
static PetscErrorCode FluidVesselLocalCopy(DM da, Vec gv, PetscReal outside, PetscReal **out)
{
  Vec                l;
  PetscInt           n;
  const PetscScalar *a;

  PetscFunctionBeginUser;
  PetscCall(DMGetLocalVector(da, &l));
  PetscCall(VecSet(l, outside));
  PetscCall(DMGlobalToLocal(da, gv, INSERT_VALUES, l));
  PetscCall(VecGetLocalSize(l, &n));
  PetscCall(VecGetArrayRead(l, &a));
  for (PetscInt i = 0; i < n; i++) (*out)[i] = PetscRealPart(a[i]);
  PetscCall(VecRestoreArrayRead(l, &a));
  PetscCall(DMRestoreLocalVector(da, &l));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* An inlet face keeps its open area even when its centre lies in the solid (it has no momentum
 * equation, and the inflow is then U_n times the geometric open area, not an O(h) smaller one),
 * unless the cell inside has no active face to pass the gas on: then it is closed. *changed:
 * some owned face was closed here. */
static PetscErrorCode FluidVesselInlets(Fluid fl, PetscBool *changed)
{
  FluidGrid   *g = &fl->g;
  PetscInt     idx[3], f, c, o;
  PetscScalar *area;

  PetscFunctionBeginUser;
  *changed = PETSC_FALSE;
  if (!fl->bc.has_inlet) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(VecGetArray(fl->ves.area, &area));
  FLUID_FOR_OWNED_FACES(g, idx, f, c, o)
  for (int d = 0; d < 3; d++) {
    PetscInt in[3] = {idx[0], idx[1], idx[2]};
    if (!fluid_inlet_face(fl, d, idx) || !fluid_face_in_range(fl, d, idx) || area[o + d] == 0) continue;
    if (idx[d] == g->N[d]) in[d]--;
    if (FluidCellClosed(fl, in)) area[o + d] = 0, *changed = PETSC_TRUE;
  }
  PetscCall(VecRestoreArray(fl->ves.area, &area));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Closed cells (no active face) get volume 0; full cells; the null-space vector. */
static PetscErrorCode FluidVesselCells(Fluid fl)
{
  FluidVessel *v = &fl->ves;
  FluidGrid   *g = &fl->g;
  PetscInt     idx[3], c, o, nopen = 0;
  PetscScalar *vol, *ind;
  Vec          full;
  PetscReal    norm;

  PetscFunctionBeginUser;
  PetscCall(VecDuplicate(v->vol, &v->ind));
  PetscCall(VecDuplicate(v->vol, &full));
  PetscCall(VecGetArray(v->vol, &vol));
  PetscCall(VecGetArray(v->ind, &ind));
  {
    PetscScalar *fu;
    PetscCall(VecGetArray(full, &fu));
    FLUID_FOR_OWNED_CELLS(g, idx, c, o)
    {
      const PetscInt  f      = FluidFaceOff(g, idx[0], idx[1], idx[2]);
      const PetscBool closed = FluidCellClosed(fl, idx);
      if (closed) vol[o] = 0;
      ind[o] = closed ? 0 : 1;
      nopen += closed ? 0 : 1;
      fu[o] = vol[o] == 1 ? 1 : 0;
      for (int d = 0; d < 3; d++)
        if (v->aloc[f + d] != 1 || v->aloc[f + g->fs[d] + d] != 1) fu[o] = 0;
    }
    PetscCall(VecRestoreArray(full, &fu));
  }
  PetscCall(VecRestoreArray(v->ind, &ind));
  PetscCall(VecRestoreArray(v->vol, &vol));
  PetscCallMPI(MPI_Allreduce(&nopen, &v->nopen, 1, MPIU_INT, MPI_SUM, fl->comm));
  PetscCall(VecNorm(v->ind, NORM_2, &norm));
  if (norm > 0) PetscCall(VecScale(v->ind, 1.0 / norm));
  PetscCall(FluidVesselLocalCopy(g->cda, v->vol, 1.0, &v->vloc));
  PetscCall(FluidVesselLocalCopy(g->cda, full, 1.0, &v->full));
  PetscCall(VecDestroy(&full));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The wall links of the active owned face dofs. */
static PetscErrorCode FluidVesselLinks(Fluid fl)
{
  FluidVessel *v = &fl->ves;
  FluidGrid   *g = &fl->g;
  PetscInt     idx[3], f, c, o, n = 0, cap = 0, nfilm = 0, gfilm;
  PetscScalar *film;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(3 * g->fxm[0] * g->fxm[1] * g->fxm[2], &v->wl));
  PetscCall(DMCreateGlobalVector(g->fda, &v->film));
  PetscCall(VecGetArray(v->film, &film));
  FLUID_FOR_OWNED_FACES(g, idx, f, c, o)
  for (int d = 0; d < 3; d++) {
    PetscReal th[6] = {0, 0, 0, 0, 0, 0}, xp[3], fp = 0;
    PetscBool any = PETSC_FALSE, have = PETSC_FALSE;
    v->wl[o + d] = -1;
    if (!FluidFaceActive(fl, d, idx)) continue;
    for (int e = 0; e < 3; e++)
      for (int s = 0; s < 2; s++) {
        PetscInt q[3] = {idx[0], idx[1], idx[2]};
        q[e] += s ? 1 : -1;
        if (!fluid_face_in_range(fl, d, q)) continue;
        const PetscReal aq = v->aloc[f + (s ? 1 : -1) * g->fs[e] + d];
        if (aq == 1 && v->aloc[f + d] == 1) continue; /* both whole: both centres in the gas */
        PetscReal xq[3], fq, t = 1;
        if (!have) {
          FluidFaceCentreX(g, idx, d, xp);
          fp   = v->level(xp, v->ctx);
          have = PETSC_TRUE;
        }
        for (int k = 0; k < 3; k++) xq[k] = xp[k];
        xq[e] += (s ? 1 : -1) * g->h[e];
        fq = v->level(xq, v->ctx);
        if (aq > 0 && fp > 0 && fq > 0) continue; /* an open neighbour in the gas: an ordinary link */
        any = PETSC_TRUE;
        if (fp <= 0) t = 0; /* the face's own velocity point is in the solid: the wall is at it */
        else if (fq <= 0) t = FluidWallDistance(v, xp, xq, fp, fq);
        th[2 * e + s] = PetscMax(t, v->theta_min);
      }
    if (have && fp <= 0 && !v->slip) { /* the open part of the face is a sliver along the wall */
      const PetscReal w = v->aloc[f + d] * PetscSqrtReal(g->h[(d + 1) % 3] * g->h[(d + 2) % 3]);
      film[o + d]       = 3 * fl->prop.mu / (w * w);
      nfilm++;
    }
    if (!any) continue;
    if (n + 6 > cap) {
      PetscReal *nt;
      cap = PetscMax(2 * cap, 600);
      PetscCall(PetscMalloc1(cap, &nt));
      if (n) PetscCall(PetscArraycpy(nt, v->theta, n));
      PetscCall(PetscFree(v->theta));
      v->theta = nt;
    }
    v->wl[o + d] = n;
    for (int k = 0; k < 6; k++) v->theta[n++] = th[k];
  }
  v->nlink = n / 6;
  PetscCall(VecRestoreArray(v->film, &film));
  PetscCallMPI(MPIU_Allreduce(&nfilm, &gfilm, 1, MPIU_INT, MPI_SUM, fl->comm));
  if (!gfilm) PetscCall(VecDestroy(&v->film));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. At set-up and after a redistribution: everything above from the level function. */
PetscErrorCode FluidVesselSetUp(Fluid fl)
{
  FluidVessel *v = &fl->ves;
  PetscBool    cut, gcut;
  PetscInt     nc, nf;

  PetscFunctionBeginUser;
  PetscCall(FluidVesselDestroy(fl));
  if (!v->level) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(DMCreateGlobalVector(fl->g.cda, &v->vol));
  PetscCall(DMCreateGlobalVector(fl->g.fda, &v->area));
  PetscCall(FluidVesselFractions(fl, &cut));
  PetscCallMPI(MPI_Allreduce(&cut, &gcut, 1, MPIU_BOOL, MPI_LOR, fl->comm));
  if (!gcut) {
    PetscCall(FluidVesselDestroy(fl));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  nc = fl->g.gcm[0] * fl->g.gcm[1] * fl->g.gcm[2];
  nf = 3 * fl->g.gfm[0] * fl->g.gfm[1] * fl->g.gfm[2];
  PetscCall(PetscMalloc3(nf, &v->aloc, nc, &v->vloc, nc, &v->full));
  PetscCall(FluidVesselLocalCopy(fl->g.fda, v->area, 0.0, &v->aloc));
  PetscCall(FluidVesselInlets(fl, &cut));
  PetscCallMPI(MPI_Allreduce(&cut, &gcut, 1, MPIU_BOOL, MPI_LOR, fl->comm));
  if (gcut) PetscCall(FluidVesselLocalCopy(fl->g.fda, v->area, 0.0, &v->aloc));
  PetscCall(FluidVesselCells(fl));
  PetscCall(FluidVesselLinks(fl));
  v->cut = PETSC_TRUE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The closed in-range dofs of a ghosted local face array to 0 (inlet faces the vessel closes). */
PetscErrorCode FluidVesselZeroClosed(Fluid fl, PetscScalar *u)
{
  const FluidGrid *g = &fl->g;
  PetscInt         idx[3];

  PetscFunctionBeginUser;
  for (idx[2] = g->gfs[2]; idx[2] < g->gfs[2] + g->gfm[2]; idx[2]++)
    for (idx[1] = g->gfs[1]; idx[1] < g->gfs[1] + g->gfm[1]; idx[1]++)
      for (idx[0] = g->gfs[0]; idx[0] < g->gfs[0] + g->gfm[0]; idx[0]++) {
        const PetscInt f = FluidFaceOff(g, idx[0], idx[1], idx[2]);
        for (int d = 0; d < 3; d++)
          if (fl->ves.aloc[f + d] == 0 && fluid_face_in_range(fl, d, idx)) u[f + d] = 0;
      }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The explicit viscous number of the linked dofs: dt nu sum over the six links of w / h_e^2, w = 1
 * for an open neighbour, 1/(2 theta) for a no-slip wall (the row's diagonal 1/theta, no
 * neighbour: Gershgorin's bound in the units of the box number 2 dt nu sum 1/h^2), 0 for a slip
 * wall, times the porosity ratio of the face's two cells. The largest on this rank, its cell. */
PetscReal FluidVesselViscousNumber(Fluid fl, PetscReal dt, const PetscScalar *eps, PetscInt cell[3])
{
  const FluidGrid *g  = &fl->g;
  const PetscReal  nu = fl->prop.mu / fl->prop.rho;
  PetscInt         idx[3], f, c, o;
  PetscReal        m = -1;

  if (!fl->ves.cut || !fl->ves.nlink) return m;
  FLUID_FOR_OWNED_FACES(g, idx, f, c, o)
  for (int d = 0; d < 3; d++) {
    const PetscInt w = fl->ves.wl[o + d];
    PetscReal      s = 0;
    if (w < 0) continue;
    for (int e = 0; e < 3; e++)
      for (int q = 0; q < 2; q++) {
        const PetscReal th = fl->ves.theta[w + 2 * e + q];
        s += (th == 0 ? 1 : (fl->ves.slip ? 0 : 0.5 / th)) / (g->h[e] * g->h[e]);
      }
    const PetscReal e0 = PetscRealPart(eps[c]), e1 = PetscRealPart(eps[c - g->cs[d]]);
    s *= dt * nu * PetscMax(e0, e1) / PetscMin(e0, e1);
    if (s > m) {
      m = s;
      for (int k = 0; k < 3; k++) cell[k] = idx[k];
    }
  }
  return m;
}
