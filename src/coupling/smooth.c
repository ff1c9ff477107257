/* The porosity a particle's drag law sees, on a length set in particle diameters instead of the
 * fluid cell (-cpl_porosity_width W, the full width at half maximum of a Gaussian in mean
 * diameters; 0: off, the drag sees the kernel's cell porosity).
 *  - The particles' volumes are put on a fine auxiliary grid (the fluid's cell split in n_e along
 *    each axis, n_e the least giving a spacing a_e <= sigma / 1.5) by cubic B-spline weights (four
 *    nodes per axis), smoothed by a sampled Gaussian in three 1-D passes, and read back at each
 *    particle by the same weights. Each B-spline adds the variance a_e^2 / 3, so the sampled
 *    Gaussian has sigma_g^2 = sigma^2 - 2 a_e^2 / 3: the whole smoothing has the variance sigma^2 =
 *    (W d)^2 / (8 ln 2) on any fluid grid (its shape differs from the Gaussian's by 0.1% of the
 *    peak, coupling/test_smooth). The sampled kernel sums to one (a uniform solid fraction stays
 *    uniform) and spans 4 sigma_g on each side.
 *  - Walls mirror: the weights reaching beyond a non-periodic side come back reflected, so a
 *    uniform bed is uniform up to the wall and the smoothing keeps the solid volume exactly (the
 *    reflected kernel is symmetric). Periodic axes wrap; ranks exchange ghost layers of the
 *    auxiliary grid (a DMDA with the fluid's decomposition, each rank's part n_e times finer).
 *  - A particle's own share of the smoothed field is known exactly (a product of three 1-D sums
 *    over its own weights and the kernel), so -cpl_self_porosity adds it back, with the fade of the
 *    self corrections (self.c): a lone sphere sees porosity 1, a bed the smoothed one.
 *  - The drag also sees the fluid velocity that goes with that porosity: the superficial flux at
 *    the particle (the kernel's interpolation of eps_f u_f, eps_f the face porosity the fluid
 *    uses) over the particle's porosity; a lone particle under the self corrections keeps the
 *    cell's velocity, with the same fade f: u = f u_cell + (1 - f) U_sup / eps_p. The fluid's face
 *    coefficient follows, beta_f = sum_p (K_p f_p + eps_f K_p (1 - f_p) / eps_p) W_pf / V_cell
 *    with sum K v W / V_cell unchanged, so the force on the fluid is that on the particles (the
 *    exchange stays exact through the owed momentum).
 * A bed's top and floor then look the same to the drag wherever the cell faces fall. The fluid
 * itself keeps the kernel's cell porosity. Units SI. */
#include "coupling/coupling_impl.h"

#define CPL_PW_RES 1.5 /* auxiliary nodes per sigma, at least */
#define CPL_SPLINE 4   /* nodes per axis of the deposit and read-back weights */

/* Collective. Widths, auxiliary spacing and the 1-D kernels from -cpl_porosity_width and the mean
 * diameter (dmean <= 0: that of the particles present, shape 0's if there are none; a restart
 * passes the checkpoint's). */
PetscErrorCode CplSmoothSetUp(Cpl cpl, PetscReal dmean)
{
  const Domain *dom = cpl->dom;

  PetscFunctionBeginUser;
  if (cpl->pw.width <= 0) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(CplSmoothDestroyGrid(cpl)); /* built anew at first use with these widths */
  if (dmean <= 0) PetscCall(CplMeanDiameter(cpl, &dmean));
  cpl->pw.d     = dmean;
  cpl->pw.sigma = cpl->pw.width * dmean / PetscSqrtReal(8 * PetscLogReal(2.0));
  for (int e = 0; e < 3; e++) {
    const PetscReal sg = cpl->pw.sigma;
    PetscInt        n  = (PetscInt)PetscCeilReal(CPL_PW_RES * dom->h[e] / sg * (1 - 1e-12));
    PetscReal       a, var, sum = 0;
    n               = PetscMax(n, 1);
    a               = dom->h[e] / n;
    var             = sg * sg - 2 * a * a / 3;
    cpl->pw.n[e]    = n;
    cpl->pw.h[e]    = a;
    cpl->pw.half[e] = (int)PetscCeilReal(4 * PetscSqrtReal(var) / a);
    PetscCheck(dom->periodic[e] || cpl->pw.half[e] <= dom->cells[e] * n, cpl->comm, PETSC_ERR_ARG_OUTOFRANGE, "-cpl_porosity_width %g (x mean diameter %g m) reaches %g m, beyond the domain's length %g m on axis %d: lower the width", (double)cpl->pw.width, (double)dmean, (double)(cpl->pw.half[e] * a), (double)dom->len[e], e);
    PetscCall(PetscFree(cpl->pw.k[e]));
    PetscCall(PetscMalloc1(2 * cpl->pw.half[e] + 1, &cpl->pw.k[e]));
    for (int m = -cpl->pw.half[e]; m <= cpl->pw.half[e]; m++) sum += cpl->pw.k[e][m + cpl->pw.half[e]] = PetscExpReal(-0.5 * m * m * a * a / var);
    for (int m = 0; m <= 2 * cpl->pw.half[e]; m++) cpl->pw.k[e][m] /= sum;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The auxiliary grid's ghost width (nodes): the smoothing's reach, and a fluid cell plus the
 * B-spline's reach for particles that strayed out of their box since the last list build. */
static PetscInt CplSmoothStencil(Cpl cpl)
{
  PetscInt sw = 0;
  for (int e = 0; e < 3; e++) sw = PetscMax(sw, PetscMax(cpl->pw.half[e], cpl->pw.n[e] + 2));
  return sw;
}

PetscErrorCode CplGetMinBoxWidth(Cpl cpl, PetscInt cells[3])
{
  PetscFunctionBeginUser;
  for (int e = 0; e < 3; e++) cells[e] = 2; /* the kernel's ghost cells */
  if (cpl->pw.width > 0 && cpl->pw.n[0] > 0) {
    const PetscInt sw = CplSmoothStencil(cpl);
    for (int e = 0; e < 3; e++) cells[e] = PetscMax(2, (sw + cpl->pw.n[e] - 1) / cpl->pw.n[e]);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. The auxiliary grid on the current decomposition (after a redistribution: anew). */
static PetscErrorCode CplSmoothGrid(Cpl cpl)
{
  const Domain   *dom = cpl->dom;
  const PetscInt *own[3];
  PetscInt       *lx[3], np[3], sw = 0, xm[3];
  DMBoundaryType  bt[3];

  PetscFunctionBeginUser;
  if (cpl->pw.da) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(DMDAGetInfo(cpl->cda, NULL, NULL, NULL, NULL, &np[0], &np[1], &np[2], NULL, NULL, NULL, NULL, NULL, NULL));
  PetscCall(DMDAGetOwnershipRanges(cpl->cda, &own[0], &own[1], &own[2]));
  PetscCall(DMDAGetCorners(cpl->cda, NULL, NULL, NULL, &xm[0], &xm[1], &xm[2]));
  sw = CplSmoothStencil(cpl);
  for (int e = 0; e < 3; e++) {
    PetscInt thin = xm[e] * cpl->pw.n[e];
    bt[e]         = dom->periodic[e] ? DM_BOUNDARY_PERIODIC : DM_BOUNDARY_NONE;
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &thin, 1, MPIU_INT, MPI_MIN, cpl->comm));
    PetscCheck((np[e] == 1 && !dom->periodic[e]) || thin >= sw, cpl->comm, PETSC_ERR_ARG_OUTOFRANGE, "-cpl_porosity_width %g reaches %g m beyond a rank's box, more than the thinnest box along axis %d (%g m; periodic on one rank: the domain): lower the width, or use fewer ranks along that axis", (double)cpl->pw.width, (double)(sw * cpl->pw.h[e]), e, (double)(thin * cpl->pw.h[e]));
    PetscCall(PetscMalloc1(np[e], &lx[e]));
    for (PetscInt r = 0; r < np[e]; r++) lx[e][r] = own[e][r] * cpl->pw.n[e];
  }
  PetscCall(DMDACreate3d(cpl->comm, bt[0], bt[1], bt[2], DMDA_STENCIL_BOX, dom->cells[0] * cpl->pw.n[0], dom->cells[1] * cpl->pw.n[1], dom->cells[2] * cpl->pw.n[2], np[0], np[1], np[2], 1, sw, lx[0], lx[1], lx[2], &cpl->pw.da));
  PetscCall(DMSetUp(cpl->pw.da));
  PetscCall(DMCreateLocalVector(cpl->pw.da, &cpl->pw.loc));
  PetscCall(DMCreateGlobalVector(cpl->pw.da, &cpl->pw.glob));
  for (int e = 0; e < 3; e++) PetscCall(PetscFree(lx[e]));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. Drops the auxiliary grid (the fluid's decomposition changed). */
PetscErrorCode CplSmoothDestroyGrid(Cpl cpl)
{
  PetscFunctionBeginUser;
  PetscCall(VecDestroy(&cpl->pw.loc));
  PetscCall(VecDestroy(&cpl->pw.glob));
  PetscCall(DMDestroy(&cpl->pw.da));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CplSmoothDestroy(Cpl cpl)
{
  PetscFunctionBeginUser;
  PetscCall(CplSmoothDestroyGrid(cpl));
  for (int e = 0; e < 3; e++) PetscCall(PetscFree(cpl->pw.k[e]));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Cubic B-spline weights of coordinate x on axis e of the auxiliary grid (cell centres (i + 1/2) a):
 * four nodes and weights (summing to one, variance a^2 / 3); a node beyond a non-periodic side is
 * its mirror (cpl_reflect); on a periodic axis x is first taken to the image nearest this rank's
 * box. */
static inline PetscInt cpl_reflect(const Cpl cpl, int e, PetscInt j);
static inline void     cpl_spline(const Cpl cpl, int e, double x, PetscInt node[CPL_SPLINE], double w[CPL_SPLINE])
{
  const Domain *dom = cpl->dom;
  double        u, t, s;
  PetscInt      i0;

  if (dom->periodic[e]) {
    const double mid = 0.5 * (dom->sublo[e] + dom->subhi[e]);
    x                = dom->lo[e] + (x - dom->lo[e]) - dom->len[e] * PetscFloorReal((x - dom->lo[e]) / dom->len[e]);
    if (x - mid > 0.5 * dom->len[e]) x -= dom->len[e];
    else if (x - mid < -0.5 * dom->len[e]) x += dom->len[e];
  } else x = PetscMin(PetscMax(x, dom->lo[e]), dom->hi[e]);
  u    = (x - dom->lo[e]) / cpl->pw.h[e] - 0.5;
  i0   = (PetscInt)PetscFloorReal(u);
  t    = u - (double)i0;
  s    = 1 - t;
  w[0] = s * s * s / 6;
  w[1] = (3 * t * t * t - 6 * t * t + 4) / 6;
  w[2] = (-3 * t * t * t + 3 * t * t + 3 * t + 1) / 6;
  w[3] = t * t * t / 6;
  for (int m = 0; m < CPL_SPLINE; m++) node[m] = cpl_reflect(cpl, e, i0 - 1 + m);
}

/* The index a convolution reads for node i + m on axis e: mirrored at a non-periodic side. */
static inline PetscInt cpl_reflect(const Cpl cpl, int e, PetscInt j)
{
  const PetscInt M = cpl->dom->cells[e] * cpl->pw.n[e];
  if (cpl->dom->periodic[e]) return j;
  if (j < 0) return -1 - j;
  if (j >= M) return 2 * M - 1 - j;
  return j;
}

typedef struct {
  PetscInt gs[3], gm[3];
} CplAuxBox;

static inline PetscInt cpl_aoff(const CplAuxBox *b, PetscInt i, PetscInt j, PetscInt k)
{
  return ((k - b->gs[2]) * b->gm[1] + (j - b->gs[1])) * b->gm[0] + (i - b->gs[0]);
}

/* The particle's nodes on all three axes, checked against the ghost box. */
static PetscErrorCode CplSplineAll(Cpl cpl, const CplAuxBox *b, const PetscReal x[3], PetscInt id, PetscInt node[3][CPL_SPLINE], double w[3][CPL_SPLINE])
{
  PetscFunctionBeginUser;
  for (int e = 0; e < 3; e++) {
    PetscInt lo, hi;
    cpl_spline(cpl, e, x[e], node[e], w[e]);
    lo = hi = node[e][0];
    for (int m = 1; m < CPL_SPLINE; m++) lo = PetscMin(lo, node[e][m]), hi = PetscMax(hi, node[e][m]);
    PetscCheck(lo >= b->gs[e] && hi < b->gs[e] + b->gm[e], PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "particle %" PetscInt_FMT ": -cpl_porosity_width's grid node %" PetscInt_FMT " on axis %d is beyond this rank's ghost nodes [%" PetscInt_FMT ", %" PetscInt_FMT "): the particle left its rank's box (needs particle migration)", id, lo < b->gs[e] ? lo : hi, e, b->gs[e], b->gs[e] + b->gm[e]);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. The smoothed solid fraction of the local particles on the auxiliary grid, left in
 * cpl->aloc with its ghosts for CplSmoothAt. */
PetscErrorCode CplSmoothProject(Cpl cpl)
{
  DemArrays    pa;
  CplAuxBox    b;
  PetscScalar *a, *g;
  double      *line;
  PetscInt     xs[3], xm[3];
  const double va = cpl->pw.h[0] * cpl->pw.h[1] * cpl->pw.h[2];

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(cpl->ev.smooth, 0, 0, 0, 0));
  PetscCall(CplSmoothGrid(cpl));
  PetscCall(DemGetArrays(cpl->dem, &pa));
  PetscCall(DMDAGetGhostCorners(cpl->pw.da, &b.gs[0], &b.gs[1], &b.gs[2], &b.gm[0], &b.gm[1], &b.gm[2]));
  PetscCall(DMDAGetCorners(cpl->pw.da, &xs[0], &xs[1], &xs[2], &xm[0], &xm[1], &xm[2]));
  PetscCall(VecZeroEntries(cpl->pw.loc));
  PetscCall(VecGetArray(cpl->pw.loc, &a));
  for (PetscInt p = 0; p < pa.nlocal; p++) {
    PetscInt     node[3][CPL_SPLINE];
    double       w[3][CPL_SPLINE];
    const double f = CplVolumeOf(cpl, &pa, p) / va;
    PetscCall(CplSplineAll(cpl, &b, pa.x + 3 * p, pa.id[p], node, w));
    for (int k = 0; k < CPL_SPLINE; k++)
      for (int j = 0; j < CPL_SPLINE; j++)
        for (int i = 0; i < CPL_SPLINE; i++) a[cpl_aoff(&b, node[0][i], node[1][j], node[2][k])] += f * w[0][i] * w[1][j] * w[2][k];
  }
  PetscCall(VecRestoreArray(cpl->pw.loc, &a));
  PetscCall(VecZeroEntries(cpl->pw.glob));
  PetscCall(DMLocalToGlobal(cpl->pw.da, cpl->pw.loc, ADD_VALUES, cpl->pw.glob));
  PetscCall(PetscMalloc1(PetscMax(PetscMax(xm[0], xm[1]), xm[2]) + 2 * PetscMax(PetscMax(cpl->pw.half[0], cpl->pw.half[1]), cpl->pw.half[2]), &line));
  for (int e = 0; e < 3; e++) { /* one 1-D pass per axis, line by line: ghosts (or mirrors) in, owned nodes out */
    const int      h = cpl->pw.half[e], e1 = (e + 1) % 3, e2 = (e + 2) % 3;
    const double  *kw     = cpl->pw.k[e];
    const PetscInt gst[3] = {1, b.gm[0], b.gm[0] * b.gm[1]}, ost[3] = {1, xm[0], xm[0] * xm[1]};
    PetscCall(DMGlobalToLocal(cpl->pw.da, cpl->pw.glob, INSERT_VALUES, cpl->pw.loc));
    PetscCall(VecGetArray(cpl->pw.loc, &a));
    PetscCall(VecGetArray(cpl->pw.glob, &g));
    for (PetscInt i2 = xs[e2]; i2 < xs[e2] + xm[e2]; i2++)
      for (PetscInt i1 = xs[e1]; i1 < xs[e1] + xm[e1]; i1++) {
        PetscInt id[3];
        id[e1] = i1, id[e2] = i2, id[e] = b.gs[e];
        const PetscInt base = cpl_aoff(&b, id[0], id[1], id[2]);
        const PetscInt ob   = (i1 - xs[e1]) * ost[e1] + (i2 - xs[e2]) * ost[e2];
        PetscBool      any  = PETSC_FALSE;
        for (PetscInt j = 0; j < xm[e] + 2 * h; j++) {
          line[j] = a[base + (cpl_reflect(cpl, e, xs[e] - h + j) - b.gs[e]) * gst[e]];
          any     = (PetscBool)(any || line[j] != 0);
        }
        if (!any) { /* no solids within reach (the freeboard): nothing to add up */
          for (PetscInt i = 0; i < xm[e]; i++) g[ob + i * ost[e]] = 0;
          continue;
        }
        for (PetscInt i = 0; i < xm[e]; i++) {
          double acc = 0;
          for (int m = 0; m <= 2 * h; m++) acc += kw[m] * line[i + m];
          g[ob + i * ost[e]] = acc;
        }
      }
    PetscCall(VecRestoreArray(cpl->pw.glob, &g));
    PetscCall(VecRestoreArray(cpl->pw.loc, &a));
  }
  PetscCall(PetscFree(line));
  PetscCall(DMGlobalToLocal(cpl->pw.da, cpl->pw.glob, INSERT_VALUES, cpl->pw.loc));
  PetscCall(PetscLogEventEnd(cpl->ev.smooth, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The share of the 1-D pass on axis e that a unit put on nodes (node, w) gives back at the same
 * nodes: sum_a sum_b w_a w_b K(a, b), K(a, b) = sum_m k_m [reflect(a + m) = b]: k_(b - a) and, near
 * a non-periodic side, the mirror's k_(-1 - a - b) or k_(2 M - 1 - a - b); periodic: the images
 * k_(b - a + j M). */
static double cpl_own_1d(const Cpl cpl, int e, const PetscInt node[CPL_SPLINE], const double w[CPL_SPLINE])
{
  const int      h = cpl->pw.half[e];
  const PetscInt M = cpl->dom->cells[e] * cpl->pw.n[e];
  const double  *k = cpl->pw.k[e] + h;
  double         s = 0;

  for (int ia = 0; ia < CPL_SPLINE; ia++)
    for (int ib = 0; ib < CPL_SPLINE; ib++) {
      const PetscInt a = node[ia], b = node[ib];
      double         q = 0;
      if (cpl->dom->periodic[e]) {
        const PetscInt t = b - a + h, fl = t >= 0 ? t / M : -((-t + M - 1) / M);
        for (PetscInt m = b - a - M * fl; m <= h; m += M) q += k[m]; /* from the least image >= -h */
      } else {
        const PetscInt lo = -1 - a - b, hi = 2 * M - 1 - a - b;
        if (PetscAbsInt(b - a) <= h) q += k[b - a];
        if (lo >= -h) q += k[lo];
        if (hi <= h) q += k[hi];
      }
      s += w[ia] * w[ib] * q;
    }
  return s;
}

/* Not collective (after CplSmoothProject). The smoothed solid fraction phi at each of the n local
 * particles and, if own != NULL, its own share. */
PetscErrorCode CplSmoothAt(Cpl cpl, PetscInt n, PetscReal *phi, PetscReal *own)
{
  DemArrays          pa;
  CplAuxBox          b;
  const PetscScalar *a;
  const double       va = cpl->pw.h[0] * cpl->pw.h[1] * cpl->pw.h[2];

  PetscFunctionBeginUser;
  PetscCall(DemGetArrays(cpl->dem, &pa));
  PetscCheck(n <= pa.nlocal, PETSC_COMM_SELF, PETSC_ERR_PLIB, "CplSmoothAt: %" PetscInt_FMT " particles asked, %" PetscInt_FMT " local", n, pa.nlocal);
  PetscCall(DMDAGetGhostCorners(cpl->pw.da, &b.gs[0], &b.gs[1], &b.gs[2], &b.gm[0], &b.gm[1], &b.gm[2]));
  PetscCall(VecGetArrayRead(cpl->pw.loc, &a));
  for (PetscInt p = 0; p < n; p++) {
    PetscInt node[3][CPL_SPLINE];
    double   w[3][CPL_SPLINE], s = 0;
    PetscCall(CplSplineAll(cpl, &b, pa.x + 3 * p, pa.id[p], node, w));
    for (int k = 0; k < CPL_SPLINE; k++)
      for (int j = 0; j < CPL_SPLINE; j++)
        for (int i = 0; i < CPL_SPLINE; i++) s += w[0][i] * w[1][j] * w[2][k] * a[cpl_aoff(&b, node[0][i], node[1][j], node[2][k])];
    phi[p] = s;
    if (own) own[p] = CplVolumeOf(cpl, &pa, p) / va * cpl_own_1d(cpl, 0, node[0], w[0]) * cpl_own_1d(cpl, 1, node[1], w[1]) * cpl_own_1d(cpl, 2, node[2], w[2]);
  }
  PetscCall(VecRestoreArrayRead(cpl->pw.loc, &a));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Not collective (after CplSmoothProject). The porosity the drag law sees at each local particle:
 * 1 - phi, its own share added back with the self corrections' fade under -cpl_self_porosity,
 * raised to the floor; fade (may be NULL) gets the fade factor. */
PetscErrorCode CplSmoothSeen(Cpl cpl, PetscInt n, PetscReal *eps, PetscReal *fade)
{
  const PetscBool self = (PetscBool)(cpl->self.eps || cpl->self.u);
  PetscReal      *phi, *own;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc2(n + 1, &phi, n + 1, &own));
  PetscCall(CplSmoothAt(cpl, n, phi, self ? own : NULL));
  for (PetscInt p = 0; p < n; p++) {
    PetscReal f = 0;
    if (self) f = cpl->self.fade > 0 ? PetscMax(0, 1 - (phi[p] - own[p]) / cpl->self.fade) : 1;
    eps[p] = 1 - phi[p];
    if (cpl->self.eps && f > 0) eps[p] = PetscMin(1, eps[p] + f * own[p]);
    eps[p] = PetscMax(eps[p], cpl->drag.eps_floor);
    if (fade) fade[p] = f;
  }
  PetscCall(PetscFree2(phi, own));
  PetscFunctionReturn(PETSC_SUCCESS);
}
