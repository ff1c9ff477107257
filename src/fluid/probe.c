/* Probes of the fluid: the cell-centred pressure at a point x by trilinear interpolation
 * between the eight cell centres around it. Along a wall, inlet or outlet axis the pressure at a
 * point within half a cell of the boundary is extrapolated linearly from the two nearest centre
 * rows (on the face itself 1.5 p1 - 0.5 p2: second order, exact for a linear pressure), plus at
 * a wall or inlet the drag's shift (faceshift.c; the averages too: near such a face they are not
 * the frames' interpolant alone), the porosity and velocity take the nearest row's value; along a periodic axis the centres wrap. The rank that owns the cell holding x interpolates from
 * its ghosted copy (the DMDA's stencil is at least one cell wide); the others add 0.
 * Averages (FluidAverageFields) of the same interpolant f of the cell-centred pressure, porosity
 * and velocity (the frames' fields), exact, with no sampling parameter:
 *   over a segment: f restricted to the segment is a cubic polynomial of the arc length between
 *     the points where the segment crosses a plane of cell centres, so two Gauss-Legendre points
 *     on each such piece integrate it exactly;
 *   over an axis-aligned box (a rectangle: a box flat along its normal): f is a product of
 *     piecewise-linear functions of each axis, integrated exactly axis by axis; over a whole
 *     cross-section this is the plain mean of the cells' values, interpolated linearly between
 *     the two layers of centres around the plane.
 * Each term (a weight times a cell's value) is computed by the rank owning the cell into its own
 * slot of a buffer; the buffer is summed over ranks (one non-zero per slot, so exactly) and then
 * in a fixed order: the averages are bitwise the same on any rank count. */
#include "fluid/fluid_impl.h"

/* Lower centre index and weight of the upper one along axis d for coordinate x; beyond the end
 * centres of a bounded axis the nearest one (w = 0), or with extrapolate the line through the
 * two last (w < 0 or > 1). */
static void FluidProbeAxisX(const Fluid fl, int d, PetscReal x, PetscBool extrapolate, PetscInt *i0, PetscReal *w)
{
  const PetscInt  n = fl->g.N[d];
  const PetscReal s = (x - fl->g.lo[d]) / fl->g.h[d] - 0.5; /* in centre units */
  PetscInt        i = (PetscInt)PetscFloorReal(s);

  *w = s - (PetscReal)i;
  if (!fl->dom->periodic[d]) {
    if (extrapolate && n >= 2 && (i < 0 || i >= n - 1)) {
      *i0 = i < 0 ? 0 : n - 2;
      *w  = s - (PetscReal)*i0;
    } else if (i < 0) *i0 = 0, *w = 0;
    else if (i >= n - 1) *i0 = n - 1, *w = 0;
    else *i0 = i;
  } else *i0 = i; /* the ghosts hold i = -1 and i = n */
}

/* Global cell index along axis d: periodic indices wrapped into [0, N). */
static inline PetscInt FluidWrapIndex(const Fluid fl, int d, PetscInt i)
{
  const PetscInt n = fl->g.N[d];
  return fl->dom->periodic[d] ? ((i % n) + n) % n : i;
}

/* The drag's shift of the pressure at point x (faceshift.c): over every bounded face within half
 * a cell of x, the face's shifts interpolated along its axes, times the share along its normal. */
static PetscReal FluidProbeShift(const Fluid fl, const PetscReal x[3])
{
  PetscReal v = 0;

  if (!fl->fshift.any) return 0;
  for (int d = 0; d < 3; d++)
    for (int s = 0; s < 2; s++) {
      const PetscReal share = FluidFaceShiftAxisShare(fl, d, s, x[d], x[d]);
      const int       a = (d + 1) % 3, c = (d + 2) % 3;
      PetscInt        ia, ic;
      PetscReal       wa, wc;
      if (share == 0) continue;
      FluidProbeAxisX(fl, a, x[a], PETSC_FALSE, &ia, &wa);
      FluidProbeAxisX(fl, c, x[c], PETSC_FALSE, &ic, &wc);
      for (int k = 0; k < 4; k++) {
        const int       ba = k & 1, bc = k >> 1;
        const PetscReal wt = (ba ? wa : 1 - wa) * (bc ? wc : 1 - wc);
        if (wt != 0) v += share * wt * FluidFaceShiftPoint(fl, d, s, FluidWrapIndex(fl, a, ia + ba) + fl->g.N[a] * FluidWrapIndex(fl, c, ic + bc));
      }
    }
  return v;
}

PetscErrorCode FluidProbePressure(Fluid fl, const PetscReal x[3], PetscReal *p)
{
  PetscInt  own[3], i0[3];
  PetscReal w[3], v = 0;
  PetscBool mine = PETSC_TRUE, any;
  Vec       loc;

  PetscFunctionBeginUser;
  for (int d = 0; d < 3; d++) {
    PetscCheck(x[d] >= fl->dom->lo[d] && x[d] <= fl->dom->hi[d], fl->comm, PETSC_ERR_ARG_OUTOFRANGE, "probe (%g, %g, %g) lies outside the domain (m)", (double)x[0], (double)x[1], (double)x[2]);
    own[d] = PetscMin((PetscInt)PetscFloorReal((x[d] - fl->g.lo[d]) / fl->g.h[d]), fl->g.N[d] - 1);
    mine   = (PetscBool)(mine && own[d] >= fl->g.xs[d] && own[d] < fl->g.xs[d] + fl->g.xm[d]);
    FluidProbeAxisX(fl, d, x[d], PETSC_TRUE, &i0[d], &w[d]); /* the owner holds both rows: >= 2 cells per rank */
  }
  PetscCall(DMGetLocalVector(fl->g.cda, &loc));
  PetscCall(DMGlobalToLocal(fl->g.cda, fl->fld.p, INSERT_VALUES, loc));
  if (mine) {
    PetscScalar ***a;
    PetscCall(DMDAVecGetArrayRead(fl->g.cda, loc, &a));
    for (int c = 0; c < 8; c++) {
      const int       b[3] = {c & 1, (c >> 1) & 1, (c >> 2) & 1};
      const PetscReal wt   = (b[0] ? w[0] : 1 - w[0]) * (b[1] ? w[1] : 1 - w[1]) * (b[2] ? w[2] : 1 - w[2]);
      if (wt != 0) v += wt * PetscRealPart(a[i0[2] + b[2]][i0[1] + b[1]][i0[0] + b[0]]);
    }
    PetscCall(DMDAVecRestoreArrayRead(fl->g.cda, loc, &a));
  }
  PetscCall(DMRestoreLocalVector(fl->g.cda, &loc));
  PetscCallMPI(MPI_Allreduce(&v, p, 1, MPIU_REAL, MPI_SUM, fl->comm));
  PetscCall(FluidFaceShiftUpdate(fl, &any));
  if (any) *p += FluidProbeShift(fl, x);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The owned-cell offset of global cell (i, j, k), -1 when another rank owns it. */
static inline PetscInt FluidOwnedOffset(const Fluid fl, const PetscInt c[3])
{
  const FluidGrid *g = &fl->g;
  for (int d = 0; d < 3; d++)
    if (c[d] < g->xs[d] || c[d] >= g->xs[d] + g->xm[d]) return -1;
  return ((c[2] - g->xs[2]) * g->xm[1] + (c[1] - g->xs[1])) * g->xm[0] + (c[0] - g->xs[0]);
}

/* The owned fields at owned-cell offset o: p, eps, u (3). */
typedef struct {
  const PetscScalar *p, *eps;
  const PetscReal   *vel; /* NULL: not asked for */
} FluidCellFields;

static inline void FluidCellValues(const FluidCellFields *f, PetscInt o, PetscReal wp, PetscReal w, PetscReal *out)
{
  out[0] += wp * PetscRealPart(f->p[o]);
  if (w == 0) return;
  out[1] += w * PetscRealPart(f->eps[o]);
  for (int d = 0; d < 3; d++) out[2 + d] += f->vel ? w * f->vel[3 * o + d] : 0;
}

/* Weights W[0..N-1] of the cell centres along axis d whose sum with the centres' values is the
 * average over [a, b] of the piecewise-linear interpolant (clamped to the end centres along a
 * non-periodic axis, wrapped along a periodic one); a point when a == b. */
static void FluidAxisWeights(const Fluid fl, int d, PetscReal a, PetscReal b, PetscBool extrapolate, PetscReal *W)
{
  const PetscInt  n  = fl->g.N[d];
  const PetscReal sa = (a - fl->g.lo[d]) / fl->g.h[d] - 0.5, sb = (b - fl->g.lo[d]) / fl->g.h[d] - 0.5;

  for (PetscInt i = 0; i < n; i++) W[i] = 0;
  if (b <= a) {
    PetscInt  i0;
    PetscReal w;
    FluidProbeAxisX(fl, d, a, extrapolate, &i0, &w);
    W[FluidWrapIndex(fl, d, i0)] += 1 - w;
    if (w != 0) W[FluidWrapIndex(fl, d, i0 + 1)] += w;
    return;
  }
  for (PetscInt i = (PetscInt)PetscFloorReal(sa); i < sb; i++) {
    const PetscReal u = PetscMax(sa, (PetscReal)i) - i, v = PetscMin(sb, (PetscReal)(i + 1)) - i; /* the piece, relative to centre i */
    const PetscReal up = 0.5 * (v * v - u * u), len = v - u;                                      /* integrals of (s - i) and of 1 */
    if (extrapolate && !fl->dom->periodic[d] && n >= 2 && (i < 0 || i >= n - 1)) {                /* the line through the two last centres */
      const PetscInt  ie = i < 0 ? 0 : n - 2;
      const PetscReal ue = u + (i - ie), ve = v + (i - ie), upe = 0.5 * (ve * ve - ue * ue);
      W[ie] += len - upe;
      W[ie + 1] += upe;
    } else if (!fl->dom->periodic[d] && i < 0) W[0] += len;
    else if (!fl->dom->periodic[d] && i >= n - 1) W[n - 1] += len;
    else {
      W[FluidWrapIndex(fl, d, i)] += len - up;
      W[FluidWrapIndex(fl, d, i + 1)] += up;
    }
  }
  for (PetscInt i = 0; i < n; i++) W[i] /= sb - sa;
}

/* The average over a box (flat along some axes; cut to the domain) into avg[5]. */
static PetscErrorCode FluidAverageBox(Fluid fl, const FluidSpan *sp, const FluidCellFields *f, PetscReal avg[5])
{
  PetscReal *W[3], *Wp[3], *loc, *all;
  PetscReal  ab[3][2];
  PetscInt   lo[3], hi[3], m[3], nslot, c[3];

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc3(fl->g.N[0], &W[0], fl->g.N[1], &W[1], fl->g.N[2], &W[2]));
  PetscCall(PetscMalloc3(fl->g.N[0], &Wp[0], fl->g.N[1], &Wp[1], fl->g.N[2], &Wp[2]));
  for (int d = 0; d < 3; d++) {
    const PetscReal a = sp->a[d] < sp->b[d] ? PetscMax(sp->a[d], fl->dom->lo[d]) : sp->a[d], b = sp->a[d] < sp->b[d] ? PetscMin(sp->b[d], fl->dom->hi[d]) : sp->b[d];
    ab[d][0] = a, ab[d][1] = b;
    FluidAxisWeights(fl, d, a, b, PETSC_FALSE, W[d]);
    FluidAxisWeights(fl, d, a, b, PETSC_TRUE, Wp[d]); /* the pressure's */
    for (lo[d] = 0; W[d][lo[d]] == 0 && Wp[d][lo[d]] == 0; lo[d]++) { }
    for (hi[d] = fl->g.N[d] - 1; W[d][hi[d]] == 0 && Wp[d][hi[d]] == 0; hi[d]--) { }
    m[d] = hi[d] - lo[d] + 1;
  }
  nslot = m[0] * m[1] * m[2];
  PetscCall(PetscCalloc2(5 * nslot, &loc, 5 * nslot, &all));
  for (c[2] = lo[2]; c[2] <= hi[2]; c[2]++)
    for (c[1] = lo[1]; c[1] <= hi[1]; c[1]++)
      for (c[0] = lo[0]; c[0] <= hi[0]; c[0]++) {
        const PetscInt  o = FluidOwnedOffset(fl, c), slot = ((c[2] - lo[2]) * m[1] + (c[1] - lo[1])) * m[0] + (c[0] - lo[0]);
        const PetscReal w = W[0][c[0]] * W[1][c[1]] * W[2][c[2]], wp = Wp[0][c[0]] * Wp[1][c[1]] * Wp[2][c[2]];
        if (o >= 0 && (w != 0 || wp != 0)) FluidCellValues(f, o, wp, w, loc + 5 * slot);
      }
  PetscCallMPI(MPI_Allreduce(loc, all, (PetscMPIInt)(5 * nslot), MPIU_REAL, MPI_SUM, fl->comm));
  for (int q = 0; q < 5; q++) avg[q] = 0;
  for (PetscInt k = 0; k < nslot; k++)
    for (int q = 0; q < 5; q++) avg[q] += all[5 * k + q];
  for (int d = 0; d < 3 && fl->fshift.any; d++) /* the drag's shift near bounded faces (faceshift.c) */
    for (int s = 0; s < 2; s++) {
      const PetscReal share = FluidFaceShiftAxisShare(fl, d, s, ab[d][0], ab[d][1]);
      if (share != 0) avg[0] += share * FluidFaceShiftAt(fl, d, s, W[(d + 1) % 3], W[(d + 2) % 3]);
    }
  PetscCall(PetscFree2(loc, all));
  PetscCall(PetscFree3(W[0], W[1], W[2]));
  PetscCall(PetscFree3(Wp[0], Wp[1], Wp[2]));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The average over the segment a -> b into avg[5]. */
static PetscErrorCode FluidAverageSegment(Fluid fl, const FluidSpan *sp, const FluidCellFields *f, PetscReal avg[5])
{
  const PetscReal g = 0.5 / PetscSqrtReal(3.0);
  PetscReal      *tau, *loc, *all;
  PetscInt        nt = 0, cap = 2, npt;

  PetscFunctionBeginUser;
  for (int d = 0; d < 3; d++) cap += (PetscInt)(PetscAbsReal(sp->b[d] - sp->a[d]) / fl->g.h[d]) + 2;
  PetscCall(PetscMalloc1(cap, &tau));
  tau[nt++] = 0;
  tau[nt++] = 1;
  for (int d = 0; d < 3; d++) { /* where the segment crosses a plane of centres of axis d */
    const PetscReal s0 = (sp->a[d] - fl->g.lo[d]) / fl->g.h[d] - 0.5, s1 = (sp->b[d] - fl->g.lo[d]) / fl->g.h[d] - 0.5;
    if (s1 == s0) continue;
    for (PetscInt i = (PetscInt)PetscCeilReal(PetscMin(s0, s1)); i <= PetscMax(s0, s1); i++) {
      const PetscReal t = (i - s0) / (s1 - s0);
      if (t > 0 && t < 1 && nt < cap) tau[nt++] = t;
    }
  }
  PetscCall(PetscSortReal(nt, tau));
  npt = 2 * (nt - 1);
  PetscCall(PetscCalloc2(16 * 5 * npt, &loc, 16 * 5 * npt, &all));
  for (PetscInt k = 0; k + 1 < nt; k++)
    for (int e = 0; e < 2; e++) {
      const PetscInt  q = 2 * k + e;
      const PetscReal t = 0.5 * (tau[k] + tau[k + 1]) + (e ? g : -g) * (tau[k + 1] - tau[k]), gw = 0.5 * (tau[k + 1] - tau[k]);
      for (int x = 0; x < 2; x++) { /* the pressure's weights (extrapolated near a bounded side), then the others' */
        PetscInt  i0[3];
        PetscReal w[3];
        for (int d = 0; d < 3; d++) FluidProbeAxisX(fl, d, sp->a[d] + t * (sp->b[d] - sp->a[d]), (PetscBool)(x == 0), &i0[d], &w[d]);
        for (int c = 0; c < 8; c++) {
          const int       b[3] = {c & 1, (c >> 1) & 1, (c >> 2) & 1};
          const PetscReal wt   = gw * (b[0] ? w[0] : 1 - w[0]) * (b[1] ? w[1] : 1 - w[1]) * (b[2] ? w[2] : 1 - w[2]);
          PetscInt        cell[3], o;
          if (wt == 0) continue;
          for (int d = 0; d < 3; d++) cell[d] = FluidWrapIndex(fl, d, i0[d] + b[d]);
          o = FluidOwnedOffset(fl, cell);
          if (o >= 0) FluidCellValues(f, o, x == 0 ? wt : 0, x == 0 ? 0 : wt, loc + 5 * (16 * q + 8 * x + c));
        }
      }
    }
  PetscCallMPI(MPI_Allreduce(loc, all, (PetscMPIInt)(16 * 5 * npt), MPIU_REAL, MPI_SUM, fl->comm));
  for (int q = 0; q < 5; q++) avg[q] = 0;
  for (PetscInt k = 0; k < 16 * npt; k++)
    for (int q = 0; q < 5; q++) avg[q] += all[5 * k + q];
  for (PetscInt k = 0; k + 1 < nt && fl->fshift.any; k++) /* the drag's shift near bounded faces (faceshift.c) */
    for (int e = 0; e < 2; e++) {
      const PetscReal t = 0.5 * (tau[k] + tau[k + 1]) + (e ? g : -g) * (tau[k + 1] - tau[k]), gw = 0.5 * (tau[k + 1] - tau[k]);
      PetscReal       x[3];
      for (int d = 0; d < 3; d++) x[d] = sp->a[d] + t * (sp->b[d] - sp->a[d]);
      avg[0] += gw * FluidProbeShift(fl, x);
    }
  PetscCall(PetscFree2(loc, all));
  PetscCall(PetscFree(tau));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FluidAverageFields(Fluid fl, PetscInt n, const FluidSpan *sp, PetscBool velocity, PetscReal *avg)
{
  FluidCellFields f   = {NULL, NULL, NULL};
  PetscReal      *vel = NULL;
  PetscBool       any;

  PetscFunctionBeginUser;
  if (!n) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(FluidFaceShiftUpdate(fl, &any));
  for (PetscInt s = 0; s < n; s++)
    for (int d = 0; d < 3; d++) { /* a segment within the domain; a box's flat axes within it, its others cut to it */
      const PetscBool in  = (PetscBool)(sp[s].a[d] >= fl->dom->lo[d] && sp[s].a[d] <= fl->dom->hi[d] && sp[s].b[d] >= fl->dom->lo[d] && sp[s].b[d] <= fl->dom->hi[d]);
      const PetscBool cut = (PetscBool)(!sp[s].line && sp[s].a[d] < sp[s].b[d] && sp[s].a[d] < fl->dom->hi[d] && sp[s].b[d] > fl->dom->lo[d]);
      PetscCheck(in || cut, fl->comm, PETSC_ERR_ARG_OUTOFRANGE, "%s: (%g, %g, %g) to (%g, %g, %g) %s the domain [%g, %g] x [%g, %g] x [%g, %g] (m)", sp[s].name, (double)sp[s].a[0], (double)sp[s].a[1], (double)sp[s].a[2], (double)sp[s].b[0], (double)sp[s].b[1], (double)sp[s].b[2], sp[s].line ? "leaves" : "lies outside", (double)fl->dom->lo[0], (double)fl->dom->hi[0], (double)fl->dom->lo[1], (double)fl->dom->hi[1], (double)fl->dom->lo[2], (double)fl->dom->hi[2]);
    }
  if (velocity) {
    PetscCall(PetscMalloc1(3 * fl->g.xm[0] * fl->g.xm[1] * fl->g.xm[2], &vel));
    PetscCall(FluidGetCellVelocity(fl, vel));
  }
  f.vel = vel;
  PetscCall(VecGetArrayRead(fl->fld.p, &f.p));
  PetscCall(VecGetArrayRead(fl->fld.eps, &f.eps));
  for (PetscInt s = 0; s < n; s++) {
    if (sp[s].line) PetscCall(FluidAverageSegment(fl, &sp[s], &f, avg + 5 * s));
    else PetscCall(FluidAverageBox(fl, &sp[s], &f, avg + 5 * s));
  }
  PetscCall(VecRestoreArrayRead(fl->fld.eps, &f.eps));
  PetscCall(VecRestoreArrayRead(fl->fld.p, &f.p));
  PetscCall(PetscFree(vel));
  PetscFunctionReturn(PETSC_SUCCESS);
}
