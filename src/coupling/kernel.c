/* Cube projection kernel (Bernard et al., as used in Grains3D Part II §4.3). A particle of
 * volume V is a cube of side a = kscale V^(1/3) (kscale = 1: the cube has the particle's volume;
 * a sphere: (pi/6)^(1/3) d) centred on it, of uniform solid density V / a^3. Its exact overlap with a box is a
 * product of 1-D overlaps, so the weights are separable: W(cell) = w0(i) w1(j) w2(k), each 1-D set
 * summing to one (the last weight is one minus the others, so the sum is one to a rounding).
 *   solid fraction of a cell:  sum_p V_p W_pc / V_cell           (porosity = 1 - that)
 *   face field q of component d: sum_p q_p W^d_pf / V_cell, W^d using the face control volume
 *     [x_f - h/2, x_f + h/2] along d and the cell extent along the other axes;
 *   value at a particle: u_p = sum_f W^d_pf u_f  (the transpose of the spreading).
 * Along a non-periodic axis the cube is shifted inside the domain (a particle touching a wall
 * keeps all its volume in the fluid grid); along a periodic axis it wraps, to the image nearest
 * the rank's box (whose ghost cells hold the other side's cells). Each rank spreads its
 * own particles into ghosted local arrays; DMLocalToGlobal with ADD_VALUES sums the parts that
 * fall in a neighbour's cells (so ghost particles, once the DEM has them, are not spread: their
 * owner does it). The stencils are computed once per particle configuration and cached. Units
 * SI. */
#include "coupling/coupling_impl.h"

/* 1-D overlap fractions of the segment [u, u + l] (in units of the interval width, from the
 * first interval's lower end) with the unit intervals [m, m + 1]: PETSC_FALSE if it spans more
 * than 4 (the caller names the limit). il = 1/l. The last weight is one minus the others. */
static inline PetscBool cpl_weights_1d(double u, double l, double il, PetscInt *m0, int *n, double w[4])
{
  const double   e     = u + l;
  const PetscInt first = (PetscInt)PetscFloorReal(u);
  PetscInt       last  = (PetscInt)PetscFloorReal(e);
  double         sum   = 0;

  if (last > first && (double)last >= e) last--; /* the segment ends exactly on a boundary */
  if (last - first >= 4) return PETSC_FALSE;
  *m0 = first;
  *n  = (int)(last - first + 1);
  for (int k = 0; k < *n - 1; k++) {
    const double lo = (double)(first + k), hi = lo + 1;
    w[k] = (PetscMin(e, hi) - PetscMax(u, lo)) * il;
    sum += w[k];
  }
  w[*n - 1] = 1.0 - sum;
  return PETSC_TRUE;
}

/* Kernel side, volume and drag diameter of a shape: the shape's true volume V and its
 * volume-equivalent diameter (a sphere: 4/3 pi r^3 and 2 r), side kscale V^(1/3). */
PetscErrorCode CplKernelSide(Cpl cpl, PetscInt shape, PetscReal *side, PetscReal *vol, PetscReal *diam)
{
  PetscReal v, deq;

  PetscFunctionBeginUser;
  PetscCall(DemGetShapeGeometry(cpl->dem, shape, &v, &deq));
  if (diam) *diam = deq;
  if (vol) *vol = v;
  if (side) *side = cpl->kern.scale * PetscCbrtReal(v);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CplStencilOf(Cpl cpl, const PetscReal x[3], PetscReal side, CplStencil *s)
{
  const Domain *dom = cpl->dom;

  PetscFunctionBeginUser;
  for (int e = 0; e < 3; e++) {
    const double ih = 1.0 / dom->h[e], l = side * ih, il = 1.0 / l;
    double       xc = x[e], a;
    if (dom->periodic[e]) { /* the image nearest this rank's box: a particle that crossed a
                               periodic side since the last rebuild is still ours, on the far side */
      const double mid = 0.5 * (dom->sublo[e] + dom->subhi[e]);
      xc               = dom->lo[e] + (xc - dom->lo[e]) - dom->len[e] * PetscFloorReal((xc - dom->lo[e]) / dom->len[e]);
      if (xc - mid > 0.5 * dom->len[e]) xc -= dom->len[e];
      else if (xc - mid < -0.5 * dom->len[e]) xc += dom->len[e];
    }
    a = xc - 0.5 * side;
    if (!dom->periodic[e]) a = PetscMin(PetscMax(a, dom->lo[e]), dom->hi[e] - side);
    { /* cells from lo, face control volumes from lo - h/2: the same u shifted by a half */
      const double u = (a - dom->lo[e]) * ih;
      PetscCheck(cpl_weights_1d(u, l, il, &s->c0[e], &s->nc[e], s->wc[e]) && cpl_weights_1d(u + 0.5, l, il, &s->f0[e], &s->nf[e], s->wf[e]), PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "cube kernel of side %g spans more than 4 cells of size %g; lower -cpl_kernel_scale", side, dom->h[e]);
    }
    s->zf[e] = 1;
  }
  s->zc = 1;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Ghost box of a DMDA and the check that a stencil fits in it (a particle far outside its
 * rank's box would need migration first). */
typedef struct {
  PetscInt gs[3], gm[3], dof;
} CplBox;

static PetscErrorCode CplBoxOf(DM da, CplBox *b)
{
  PetscFunctionBeginUser;
  PetscCall(DMDAGetGhostCorners(da, &b->gs[0], &b->gs[1], &b->gs[2], &b->gm[0], &b->gm[1], &b->gm[2]));
  PetscCall(DMDAGetInfo(da, NULL, NULL, NULL, NULL, NULL, NULL, NULL, &b->dof, NULL, NULL, NULL, NULL, NULL));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static inline PetscBool cpl_fits(const CplBox *b, const PetscInt first[3], const int n[3], int e)
{
  return (PetscBool)(first[e] >= b->gs[e] && first[e] + n[e] <= b->gs[e] + b->gm[e]);
}

static inline PetscBool cpl_fits_all(const CplBox *b, const PetscInt first[3], const int n[3])
{
  return (PetscBool)(cpl_fits(b, first, n, 0) && cpl_fits(b, first, n, 1) && cpl_fits(b, first, n, 2));
}

/* The error for a stencil that does not fit (cpl_fits_all said so). */
static PetscErrorCode CplCheckFits(const CplBox *b, const PetscInt first[3], const int n[3], PetscInt id)
{
  PetscFunctionBeginUser;
  for (int e = 0; e < 3; e++)
    PetscCheck(cpl_fits(b, first, n, e), PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "particle %" PetscInt_FMT ": its kernel reaches cell %" PetscInt_FMT " on axis %d, beyond this rank's ghost cells [%" PetscInt_FMT ", %" PetscInt_FMT "): the particle left its rank's box (needs particle migration) or the kernel is wider than one cell", id, first[e] < b->gs[e] ? first[e] : first[e] + n[e] - 1, e, b->gs[e], b->gs[e] + b->gm[e]);
  PetscFunctionReturn(PETSC_SUCCESS);
}

static inline PetscInt cpl_off(const CplBox *b, PetscInt i, PetscInt j, PetscInt k)
{
  return ((k - b->gs[2]) * b->gm[1] + (j - b->gs[1])) * b->gm[0] + (i - b->gs[0]);
}

/* The porosity of face (i, j, k) of component d as the fluid takes it, the mean of the two cells
 * it separates (ea: the ghosted cell porosity, box b); on a non-periodic boundary plane the one
 * cell there is. CplStencils checks that both cells are in the ghost box (the last two lines only
 * keep the reads inside it). */
static inline double cpl_face_porosity(const Domain *dom, const CplBox *b, const PetscScalar *ea, int d, PetscInt i, PetscInt j, PetscInt k)
{
  const PetscInt f[3] = {i, j, k};
  PetscInt       hi[3], lo[3];
  for (int e = 0; e < 3; e++) hi[e] = lo[e] = dom->periodic[e] ? f[e] : PetscMin(f[e], dom->cells[e] - 1);
  if (dom->periodic[d] || (f[d] > 0 && f[d] < dom->cells[d])) lo[d] = f[d] - 1; /* face f separates cells f - 1 and f */
  if (lo[d] < b->gs[d]) lo[d] = hi[d];
  if (hi[d] >= b->gs[d] + b->gm[d]) hi[d] = lo[d];
  return 0.5 * (ea[cpl_off(b, hi[0], hi[1], hi[2])] + ea[cpl_off(b, lo[0], lo[1], lo[2])]);
}

/* The axis-d-component view of a stencil: faces along d, cells along the others. */
static void cpl_component(const CplStencil *s, int d, PetscInt first[3], int n[3], const double *w[3])
{
  for (int e = 0; e < 3; e++) {
    first[e] = e == d ? s->f0[e] : s->c0[e];
    n[e]     = e == d ? s->nf[e] : s->nc[e];
    w[e]     = e == d ? s->wf[e] : s->wc[e];
  }
}

/* A vessel cutting the grid (vessel.c): 1 / the open share of the stencil's cells (va: the ghosted
 * open-volume fractions) and of each component's faces (aa: open-area fractions; a face's
 * momentum control volume is a_f V_cell); a kernel with no open cell keeps 1 (counted in lost). */
static void cpl_vessel_shares(const CplBox *bc, const CplBox *bf, const PetscScalar *va, const PetscScalar *aa, CplStencil *st1, PetscInt *lost)
{
  double z = 0;
  for (int k = 0; k < st1->nc[2]; k++)
    for (int j = 0; j < st1->nc[1]; j++)
      for (int i = 0; i < st1->nc[0]; i++) z += st1->wc[2][k] * st1->wc[1][j] * st1->wc[0][i] * va[cpl_off(bc, st1->c0[0] + i, st1->c0[1] + j, st1->c0[2] + k)];
  st1->zc = z > 0 ? 1 / z : 1;
  if (!(z > 0)) (*lost)++;
  for (int d = 0; d < 3; d++) {
    PetscInt      first[3];
    int           n[3];
    const double *w[3];
    cpl_component(st1, d, first, n, w);
    z = 0;
    for (int k = 0; k < n[2]; k++)
      for (int j = 0; j < n[1]; j++)
        for (int i = 0; i < n[0]; i++)
          z += w[2][k] * w[1][j] * w[0][i] * aa[3 * cpl_off(bf, first[0] + i, first[1] + j, first[2] + k) + d];
    st1->zf[d] = z > 0 ? 1 / z : 1;
  }
}

/* The stencils of all local particles, cached while the DEM's state (DemGetState: positions and
 * order) is unchanged and until CplInvalidateStencils (the grids moved); each is checked against
 * the ghost boxes of both grids once, when computed. */
static PetscErrorCode CplStencils(Cpl cpl, const DemArrays *pa, const CplStencil **out)
{
  CplBox   bc, bf;
  PetscInt state;

  PetscFunctionBeginUser;
  PetscCall(DemGetState(cpl->dem, &state));
  if (!cpl->kern.stc_valid || cpl->kern.stc_n != pa->nlocal || cpl->kern.stc_state != state) {
    const PetscScalar *va = NULL, *aa = NULL;
    PetscCall(CplBoxOf(cpl->cda, &bc));
    PetscCall(CplBoxOf(cpl->fda, &bf));
    cpl->ves.lost = 0;
    if (cpl->ves.on) {
      PetscCall(VecGetArrayRead(cpl->ves.vloc, &va));
      PetscCall(VecGetArrayRead(cpl->ves.aloc, &aa));
    }
    if (pa->nlocal > cpl->kern.stc_cap) {
      PetscCall(PetscFree(cpl->kern.stc));
      cpl->kern.stc_cap = PetscMax(pa->nlocal, 2 * cpl->kern.stc_cap);
      PetscCall(PetscMalloc1(cpl->kern.stc_cap, &cpl->kern.stc));
    }
    for (PetscInt p = 0; p < pa->nlocal; p++) {
      CplStencil *st1 = &cpl->kern.stc[p];
      PetscCall(CplStencilOf(cpl, pa->x + 3 * p, CplSideOf(cpl, pa, p), st1));
      if (!cpl_fits_all(&bc, st1->c0, st1->nc)) PetscCall(CplCheckFits(&bc, st1->c0, st1->nc, pa->id[p]));
      if (cpl->pw.width > 0) { /* the superficial velocity reads the cells on both sides of each face */
        PetscInt first[3];
        int      n[3];
        for (int e = 0; e < 3; e++) {
          const PetscBool below = (PetscBool)(cpl->dom->periodic[e] || st1->f0[e] > 0);
          first[e]              = st1->f0[e] - (below ? 1 : 0);
          n[e]                  = st1->nf[e] + (below ? 1 : 0);
          if (!cpl->dom->periodic[e]) n[e] = (int)PetscMin(n[e], cpl->dom->cells[e] - first[e]);
        }
        if (!cpl_fits_all(&bc, first, n)) PetscCall(CplCheckFits(&bc, first, n, pa->id[p]));
      }
      for (int d = 0; d < 3; d++) {
        PetscInt      first[3];
        int           n[3];
        const double *w[3];
        cpl_component(st1, d, first, n, w);
        if (!cpl_fits_all(&bf, first, n)) PetscCall(CplCheckFits(&bf, first, n, pa->id[p]));
      }
      if (va) cpl_vessel_shares(&bc, &bf, va, aa, st1, &cpl->ves.lost);
    }
    if (va) {
      PetscCall(VecRestoreArrayRead(cpl->ves.vloc, &va));
      PetscCall(VecRestoreArrayRead(cpl->ves.aloc, &aa));
    }
    cpl->kern.stc_n     = pa->nlocal;
    cpl->kern.stc_state = state;
    cpl->kern.stc_valid = PETSC_TRUE;
  }
  *out = cpl->kern.stc;
  PetscFunctionReturn(PETSC_SUCCESS);
}

void CplInvalidateStencils(Cpl cpl)
{
  cpl->kern.stc_valid = PETSC_FALSE;
}

/* Adds the solid fraction f W of one particle's stencil to the local cell array a. */
static inline void cpl_spread_cells(const CplBox *b, const CplStencil *st1, double f, PetscScalar *a)
{
  for (int k = 0; k < st1->nc[2]; k++)
    for (int j = 0; j < st1->nc[1]; j++) {
      const double wjk = f * st1->wc[2][k] * st1->wc[1][j];
      PetscInt     o   = cpl_off(b, st1->c0[0], st1->c0[1] + j, st1->c0[2] + k);
      for (int i = 0; i < st1->nc[0]; i++) a[o + i] += wjk * st1->wc[0][i];
    }
}

/* Collective. solid (a global cell Vec) <- the solid fraction of the local particles by the
 * kernel, of all of them (only == NULL) or of those with only[p] == 0, then filtered
 * (-cpl_filter_width, filter.c). */
static PetscErrorCode CplSpreadSolid(Cpl cpl, const PetscReal *only, Vec solid)
{
  DemArrays         pa;
  CplBox            b;
  const CplStencil *stc;
  PetscScalar      *a;

  PetscFunctionBeginUser;
  PetscCall(DemGetArrays(cpl->dem, &pa));
  PetscCall(CplStencils(cpl, &pa, &stc));
  PetscCall(CplBoxOf(cpl->cda, &b));
  PetscCall(VecZeroEntries(cpl->ex.cloc));
  PetscCall(VecGetArray(cpl->ex.cloc, &a));
  if (only) { /* two loops: the every-step one tests nothing; zc is 1 without a vessel */
    for (PetscInt p = 0; p < pa.nlocal; p++)
      if (only[p] == 0) cpl_spread_cells(&b, &stc[p], CplVolumeOf(cpl, &pa, p) / cpl->kern.cell_vol * stc[p].zc, a);
  } else
    for (PetscInt p = 0; p < pa.nlocal; p++) cpl_spread_cells(&b, &stc[p], CplVolumeOf(cpl, &pa, p) / cpl->kern.cell_vol * stc[p].zc, a);
  PetscCall(VecRestoreArray(cpl->ex.cloc, &a));
  PetscCall(VecZeroEntries(solid));
  PetscCall(DMLocalToGlobal(cpl->cda, cpl->ex.cloc, ADD_VALUES, solid));
  if (cpl->ves.on) PetscCall(CplVesselMask(cpl, solid, PETSC_FALSE)); /* closed cells: nothing */
  PetscCall(CplFilter(cpl, solid, PETSC_FALSE));                      /* -cpl_filter_width; nothing when off */
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. Porosity eps^{n+1} of the fluid from the current particle positions: solid
 * fraction by the kernel, eps = 1 - solid, raised to -cpl_porosity_floor where below it. */
PetscErrorCode CplProjectPorosity(Cpl cpl, CplStats *st)
{
  PetscScalar       *e;
  const PetscScalar *s;
  Vec                solid, eps;
  PetscInt           n, clipped = 0, cnt[2];
  PetscReal          emin = 1, sum;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(cpl->ev.project, 0, 0, 0, 0));
  PetscCall(DMGetGlobalVector(cpl->cda, &solid));
  PetscCall(CplSpreadSolid(cpl, NULL, solid));
  if (cpl->ves.on) PetscCall(VecDot(solid, cpl->ves.vol, &sum)); /* the open parts' solid volumes */
  else PetscCall(VecSum(solid, &sum));
  cpl->diag.solid_grid = sum * cpl->kern.cell_vol;
  PetscCall(FluidGetPorosity(cpl->fl, &eps));
  PetscCall(VecGetLocalSize(eps, &n));
  PetscCall(VecGetArrayRead(solid, &s));
  PetscCall(VecGetArray(eps, &e));
  for (PetscInt c = 0; c < n; c++) {
    e[c] = 1.0 - s[c];
    if (e[c] < cpl->drag.eps_floor) {
      e[c] = cpl->drag.eps_floor;
      clipped++;
    }
    emin = PetscMin(emin, e[c]);
  }
  PetscCall(VecRestoreArray(eps, &e));
  PetscCall(VecRestoreArrayRead(solid, &s));
  PetscCall(DMRestoreGlobalVector(cpl->cda, &solid));
  cnt[0] = clipped;
  PetscCall(MPIU_Allreduce(cnt, cnt + 1, 1, MPIU_INT, MPI_SUM, cpl->comm));
  cpl->diag.clipped_total += cnt[1];
  if (cpl->ves.on) PetscCall(CplVesselLost(cpl));
  if (st) {
    st->clipped = cnt[1];
    PetscCall(MPIU_Allreduce(&emin, &st->eps_min, 1, MPIU_REAL, MPIU_MIN, cpl->comm));
  }
  PetscCall(PetscLogEventEnd(cpl->ev.project, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. Particles a source added during the last DEM substeps (their drag coefficient
 * is still the 0 that DemAddParticle gives; every other particle has K > 0 from this step's
 * start) take the place of the fluid they cover: their solid fraction is taken from the previous
 * porosity too (raised to the floor), so (eps - eps_old)/dt in the continuity equation sees only
 * the motion of the particles, not their appearance. Counted as a flux, a particle of volume V
 * appearing in one step would push V/dt of fluid out of its cell (at every batch a pressure
 * spike of about 100 times the weight of the particles present, coupling/test_pour_coupled).
 * The covered fluid leaves the run with its momentum. */
PetscErrorCode CplAdmitNewParticles(Cpl cpl)
{
  DemExternal        ex;
  Vec                solid, old;
  PetscScalar       *e;
  const PetscScalar *s;
  PetscInt           n;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(cpl->ev.project, 0, 0, 0, 0));
  PetscCall(DemGetExternal(cpl->dem, &ex));
  PetscCall(DMGetGlobalVector(cpl->cda, &solid));
  PetscCall(CplSpreadSolid(cpl, ex.k, solid));
  PetscCall(FluidGetPorosityOld(cpl->fl, &old));
  PetscCall(VecGetLocalSize(old, &n));
  PetscCall(VecGetArrayRead(solid, &s));
  PetscCall(VecGetArray(old, &e));
  for (PetscInt c = 0; c < n; c++) e[c] = PetscMax(e[c] - s[c], cpl->drag.eps_floor);
  PetscCall(VecRestoreArray(old, &e));
  PetscCall(VecRestoreArrayRead(solid, &s));
  PetscCall(DMRestoreGlobalVector(cpl->cda, &solid));
  PetscCall(PetscLogEventEnd(cpl->ev.project, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. For each of n <= 3 fields: out (a global face Vec) <- sum_p val_p^d W^d_pf / V_cell
 * per component d, val with 3 values per local particle or one (scalar) used for all three
 * components, then filtered (-cpl_filter_width, filter.c). The fields share one pass over the particles and their stencils; each field is
 * summed in the same order as alone. */
PetscErrorCode CplSpreadFaces(Cpl cpl, PetscInt n, const CplSpread sp[])
{
  DemArrays         pa;
  CplBox            b;
  const CplStencil *stc;
  PetscScalar      *a[3];

  PetscFunctionBeginUser;
  PetscCheck(n >= 1 && n <= 3, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "CplSpreadFaces: %d fields, 1 to 3 supported", (int)n);
  PetscCall(DemGetArrays(cpl->dem, &pa));
  PetscCall(CplStencils(cpl, &pa, &stc));
  PetscCall(CplBoxOf(cpl->fda, &b));
  for (PetscInt s = 0; s < n; s++) {
    PetscCall(VecZeroEntries(cpl->ex.floc[s]));
    PetscCall(VecGetArray(cpl->ex.floc[s], &a[s]));
  }
  for (PetscInt p = 0; p < pa.nlocal; p++) {
    for (int d = 0; d < 3; d++) {
      PetscInt      first[3];
      int           nn[3];
      const double *w[3];
      double        q[3];
      for (PetscInt s = 0; s < n; s++) q[s] = (sp[s].scalar ? sp[s].val[p] : sp[s].val[3 * p + d]) / cpl->kern.cell_vol * stc[p].zf[d];
      cpl_component(&stc[p], d, first, nn, w);
      for (int k = 0; k < nn[2]; k++)
        for (int j = 0; j < nn[1]; j++) {
          PetscInt o = 3 * cpl_off(&b, first[0], first[1] + j, first[2] + k) + d;
          for (PetscInt s = 0; s < n; s++) {
            const double wjk = q[s] * w[2][k] * w[1][j];
            for (int i = 0; i < nn[0]; i++) a[s][o + 3 * i] += wjk * w[0][i];
          }
        }
    }
  }
  for (PetscInt s = 0; s < n; s++) {
    PetscCall(VecRestoreArray(cpl->ex.floc[s], &a[s]));
    PetscCall(VecZeroEntries(sp[s].out));
    PetscCall(DMLocalToGlobal(cpl->fda, cpl->ex.floc[s], ADD_VALUES, sp[s].out));
    if (cpl->ves.on) PetscCall(CplVesselMask(cpl, sp[s].out, PETSC_TRUE)); /* closed faces: nothing */
    PetscCall(CplFilter(cpl, sp[s].out, PETSC_TRUE));                      /* works in floc[0], whose field is summed */
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. Fluid velocity u (3 per local particle, m/s) and porosity eps (1 per particle) at
 * the particles: kernel-weighted averages of the face velocities (boundary faces carry their
 * boundary values) and of the current cell porosity. */
PetscErrorCode CplInterpolate(Cpl cpl, PetscReal *u, PetscReal *eps)
{
  PetscFunctionBeginUser;
  PetscCall(CplInterpolateSelf(cpl, u, eps, NULL, NULL));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode CplInterpolateVessel(Cpl, const DemArrays *, const CplStencil *, const CplBox *, const CplBox *, const PetscScalar *, const PetscScalar *, PetscReal *, PetscReal *);

/* As CplInterpolate; self (may be NULL; 1 per particle) gets the particle's own share of the
 * porosity dip it sees, V_p sum_c W_pc^2 / V_cell (separable: the product over the axes of the
 * sums of the squared 1-D weights), so eps + self is the porosity of the other particles (but
 * for the floor). */
PetscErrorCode CplInterpolateSelf(Cpl cpl, PetscReal *u, PetscReal *eps, PetscReal *self, PetscReal *usup)
{
  DemArrays          pa;
  CplBox             bf, bc;
  Vec                uloc, e;
  const PetscScalar *ua, *ea;
  const CplStencil  *stc;

  PetscFunctionBeginUser;
  PetscCall(DemGetArrays(cpl->dem, &pa));
  PetscCall(CplStencils(cpl, &pa, &stc));
  PetscCall(CplBoxOf(cpl->fda, &bf));
  PetscCall(CplBoxOf(cpl->cda, &bc));
  PetscCall(FluidGetLocalFields(cpl->fl, &uloc, NULL));
  PetscCall(FluidGetPorosity(cpl->fl, &e));
  PetscCall(DMGlobalToLocal(cpl->cda, e, INSERT_VALUES, cpl->ex.cloc));
  PetscCall(VecGetArrayRead(uloc, &ua));
  PetscCall(VecGetArrayRead(cpl->ex.cloc, &ea));
  if (cpl->ves.on) { /* vessel.c: the open cells and faces only, with the deposit's weights */
    PetscCall(CplInterpolateVessel(cpl, &pa, stc, &bc, &bf, ua, ea, u, eps));
    PetscCall(VecRestoreArrayRead(cpl->ex.cloc, &ea));
    PetscCall(VecRestoreArrayRead(uloc, &ua));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  for (PetscInt p = 0; p < pa.nlocal; p++) {
    const CplStencil *st1 = &stc[p];
    double            s   = 0;
    for (int k = 0; k < st1->nc[2]; k++)
      for (int j = 0; j < st1->nc[1]; j++)
        for (int i = 0; i < st1->nc[0]; i++) s += st1->wc[2][k] * st1->wc[1][j] * st1->wc[0][i] * ea[cpl_off(&bc, st1->c0[0] + i, st1->c0[1] + j, st1->c0[2] + k)];
    eps[p] = s;
    if (self) {
      double w2 = CplVolumeOf(cpl, &pa, p) / cpl->kern.cell_vol;
      for (int e = 0; e < 3; e++) {
        double q = 0;
        for (int i = 0; i < st1->nc[e]; i++) q += st1->wc[e][i] * st1->wc[e][i];
        w2 *= q;
      }
      self[p] = w2;
    }
    for (int d = 0; d < 3; d++) {
      PetscInt      first[3];
      int           n[3];
      const double *w[3];
      cpl_component(st1, d, first, n, w);
      s = 0;
      for (int k = 0; k < n[2]; k++)
        for (int j = 0; j < n[1]; j++)
          for (int i = 0; i < n[0]; i++) s += w[2][k] * w[1][j] * w[0][i] * ua[3 * cpl_off(&bf, first[0] + i, first[1] + j, first[2] + k) + d];
      u[3 * p + d] = s;
      if (usup) { /* the superficial velocity: each face's value times its porosity */
        s = 0;
        for (int k = 0; k < n[2]; k++)
          for (int j = 0; j < n[1]; j++)
            for (int i = 0; i < n[0]; i++) {
              const PetscInt f = first[0] + i, g = first[1] + j, h = first[2] + k;
              s += w[2][k] * w[1][j] * w[0][i] * ua[3 * cpl_off(&bf, f, g, h) + d] * cpl_face_porosity(cpl->dom, &bc, ea, d, f, g, h);
            }
        usup[3 * p + d] = s;
      }
    }
  }
  PetscCall(VecRestoreArrayRead(cpl->ex.cloc, &ea));
  PetscCall(VecRestoreArrayRead(uloc, &ua));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* CplInterpolateSelf in a vessel that cuts the grid (no self share, no superficial velocity:
 * vessel.c refuses what needs them): eps_p = zc sum_c W_pc vol_c eps_c and u_p = zf sum_f
 * W_pf a_f u_f, the transpose of the deposit. */
static PetscErrorCode CplInterpolateVessel(Cpl cpl, const DemArrays *pa, const CplStencil *stc, const CplBox *bc, const CplBox *bf, const PetscScalar *ua, const PetscScalar *ea, PetscReal *u, PetscReal *eps)
{
  const PetscScalar *va, *aa;

  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(cpl->ves.vloc, &va));
  PetscCall(VecGetArrayRead(cpl->ves.aloc, &aa));
  for (PetscInt p = 0; p < pa->nlocal; p++) {
    const CplStencil *st1 = &stc[p];
    double            s   = 0;
    for (int k = 0; k < st1->nc[2]; k++)
      for (int j = 0; j < st1->nc[1]; j++)
        for (int i = 0; i < st1->nc[0]; i++) {
          const PetscInt o = cpl_off(bc, st1->c0[0] + i, st1->c0[1] + j, st1->c0[2] + k);
          s += st1->wc[2][k] * st1->wc[1][j] * st1->wc[0][i] * va[o] * ea[o];
        }
    eps[p] = s * st1->zc;
    for (int d = 0; d < 3; d++) {
      PetscInt      first[3];
      int           n[3];
      const double *w[3];
      cpl_component(st1, d, first, n, w);
      s = 0;
      for (int k = 0; k < n[2]; k++)
        for (int j = 0; j < n[1]; j++)
          for (int i = 0; i < n[0]; i++) {
            const PetscInt o = 3 * cpl_off(bf, first[0] + i, first[1] + j, first[2] + k) + d;
            s += w[2][k] * w[1][j] * w[0][i] * aa[o] * ua[o];
          }
      u[3 * p + d] = s * st1->zf[d];
    }
  }
  PetscCall(VecRestoreArrayRead(cpl->ves.vloc, &va));
  PetscCall(VecRestoreArrayRead(cpl->ves.aloc, &aa));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Not collective. A face field at the particles (3 per local particle) from its ghosted local
 * copy floc: the velocity's weights, sum_f W_pf a_f g_f zf in a vessel that cuts the grid (the
 * transpose of the deposit, closed faces weigh nothing). */
PetscErrorCode CplInterpolateFaces(Cpl cpl, Vec floc, PetscReal *out)
{
  DemArrays          pa;
  CplBox             bf;
  const CplStencil  *stc;
  const PetscScalar *ga, *aa = NULL;

  PetscFunctionBeginUser;
  PetscCall(DemGetArrays(cpl->dem, &pa));
  PetscCall(CplStencils(cpl, &pa, &stc));
  PetscCall(CplBoxOf(cpl->fda, &bf));
  PetscCall(VecGetArrayRead(floc, &ga));
  if (cpl->ves.on) PetscCall(VecGetArrayRead(cpl->ves.aloc, &aa));
  for (PetscInt p = 0; p < pa.nlocal; p++)
    for (int d = 0; d < 3; d++) {
      PetscInt      first[3];
      int           n[3];
      const double *w[3];
      double        s = 0;
      cpl_component(&stc[p], d, first, n, w);
      for (int k = 0; k < n[2]; k++)
        for (int j = 0; j < n[1]; j++)
          for (int i = 0; i < n[0]; i++) {
            const PetscInt o = 3 * cpl_off(&bf, first[0] + i, first[1] + j, first[2] + k) + d;
            s += w[2][k] * w[1][j] * w[0][i] * (aa ? aa[o] * ga[o] : ga[o]);
          }
      out[3 * p + d] = aa ? s * stc[p].zf[d] : s;
    }
  if (aa) PetscCall(VecRestoreArrayRead(cpl->ves.aloc, &aa));
  PetscCall(VecRestoreArrayRead(floc, &ga));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. beta (a global face Vec) times the face porosity the fluid uses (the fluid's
 * current cell porosity, cpl_face_porosity), at every owned face. */
PetscErrorCode CplFacePorosityScale(Cpl cpl, Vec beta)
{
  CplBox             bc;
  Vec                e;
  PetscScalar       *b;
  const PetscScalar *ea;
  PetscInt           xs[3], xm[3], idx[3], c = 0;

  PetscFunctionBeginUser;
  PetscCall(CplBoxOf(cpl->cda, &bc));
  PetscCall(FluidGetPorosity(cpl->fl, &e));
  PetscCall(DMGlobalToLocal(cpl->cda, e, INSERT_VALUES, cpl->ex.cloc));
  PetscCall(DMDAGetCorners(cpl->fda, &xs[0], &xs[1], &xs[2], &xm[0], &xm[1], &xm[2]));
  PetscCall(VecGetArrayRead(cpl->ex.cloc, &ea));
  PetscCall(VecGetArray(beta, &b));
  for (idx[2] = xs[2]; idx[2] < xs[2] + xm[2]; idx[2]++)
    for (idx[1] = xs[1]; idx[1] < xs[1] + xm[1]; idx[1]++)
      for (idx[0] = xs[0]; idx[0] < xs[0] + xm[0]; idx[0]++, c += 3)
        for (int d = 0; d < 3; d++)
          if (b[c + d] != 0) b[c + d] *= cpl_face_porosity(cpl->dom, &bc, ea, d, idx[0], idx[1], idx[2]);
  PetscCall(VecRestoreArray(beta, &b));
  PetscCall(VecRestoreArrayRead(cpl->ex.cloc, &ea));
  PetscFunctionReturn(PETSC_SUCCESS);
}
