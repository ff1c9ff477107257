/* Diffusion filter of the spread particle fields (-cpl_filter_width W, in mean particle
 * diameters d; 0: off). After the kernel has spread the particles to the grid, the cell solid
 * fraction and the face fields of the drag (beta = sum K W / V_cell, sum K U W / V_cell and the
 * impulses sum J W / V_cell) are smoothed by n explicit diffusion sweeps in flux form,
 *   a_i <- a_i + sum_e lam_e [(a_{i+e} - a_i) - (a_i - a_{i-e})],  lam_e = sigma^2 / (2 n h_e^2),
 * which add the variance 2 lam_e h_e^2 per sweep along axis e, sigma^2 in all (m^2, the same on
 * every axis: anisotropic cells take their own lam_e), i.e. the convolution with a Gaussian of
 * full width at half maximum W d, sigma = W d / sqrt(8 ln 2) (Capecelatro & Desjardins, J.
 * Comput. Phys. 238 (2013) 1-31, doi:10.1016/j.jcp.2012.12.015; Sun & Xiao, Int. J. Multiphase
 * Flow 72 (2015) 233-247, doi:10.1016/j.ijmultiphaseflow.2015.02.014). n is the least with
 * lam_e <= 1/6 on every axis (each sweep positive and stable). Each flux lam (a_j - a_i) is given
 * to one point and taken from the other, so the sums (solid volume, momentum) are those of the
 * unfiltered fields to roundoff. No flux crosses a wall, inlet or outlet: cells take part up to
 * the domain's faces; a face field of component d takes part on the interior faces only (the
 * exchange's own, CplInteriorFace), the boundary faces keep their values. Periodic axes wrap
 * through the DMDA's ghost points, which also carry the values across ranks. The mean diameter
 * is that of the particles at set-up (shape 0's if there are none) and is kept in checkpoints. */
#include "coupling/coupling_impl.h"

/* Collective. The number-mean diameter of the particles present (shape 0's if there are none). */
PetscErrorCode CplMeanDiameter(Cpl cpl, PetscReal *dmean)
{
  DemArrays pa;
  PetscReal s[2] = {0, 0};

  PetscFunctionBeginUser;
  PetscCall(DemGetArrays(cpl->dem, &pa));
  for (PetscInt p = 0; p < pa.nlocal; p++) s[0] += CplDiameterOf(cpl, &pa, p);
  s[1] = (PetscReal)pa.nlocal;
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, s, 2, MPIU_REAL, MPIU_SUM, cpl->comm));
  *dmean = s[1] > 0 ? s[0] / s[1] : cpl->kern.diam[0];
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. The filter's variance, sweeps and coefficients from -cpl_filter_width and the
 * particles present (a restart calls it again with the checkpoint's mean diameter, dmean > 0). */
PetscErrorCode CplFilterSetUp(Cpl cpl, PetscReal dmean)
{
  const Domain *dom  = cpl->dom;
  PetscReal     hmin = PETSC_MAX_REAL;

  PetscFunctionBeginUser;
  cpl->filt.var = 0;
  cpl->filt.n   = 0;
  if (cpl->filt.width <= 0) PetscFunctionReturn(PETSC_SUCCESS);
  if (dmean <= 0) PetscCall(CplMeanDiameter(cpl, &dmean));
  cpl->filt.d   = dmean;
  cpl->filt.var = PetscSqr(cpl->filt.width * dmean) / (8 * PetscLogReal(2.0));
  for (int e = 0; e < 3; e++) hmin = PetscMin(hmin, dom->h[e]);
  cpl->filt.n = (PetscInt)PetscCeilReal(3 * cpl->filt.var / (hmin * hmin) * (1 - 1e-12));
  cpl->filt.n = PetscMax(cpl->filt.n, 1);
  PetscCheck(cpl->filt.n <= 100, cpl->comm, PETSC_ERR_ARG_OUTOFRANGE, "-cpl_filter_width %g (x mean diameter %g m) takes %" PetscInt_FMT " diffusion sweeps per field and step on cells of %g m; the limit is 100 (a width up to about %.3g): lower the width or coarsen the grid", (double)cpl->filt.width, (double)dmean, cpl->filt.n, (double)hmin, (double)(PetscSqrtReal(100.0 / 3.0 * 8 * PetscLogReal(2.0)) * hmin / dmean));
  for (int e = 0; e < 3; e++) cpl->filt.lam[e] = cpl->filt.var / (2.0 * cpl->filt.n * dom->h[e] * dom->h[e]);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The points of component d of a face field (faces) or of a cell field that take part, a box
 * in global indices: inside the grid along non-periodic axes and, for faces, an interior face of
 * the exchange (CplInteriorFace: not on a boundary plane, not an unused extra point); periodic
 * axes are unbounded. */
static void cpl_filter_box(const Domain *dom, PetscBool faces, int d, PetscInt lo[3], PetscInt hi[3])
{
  for (int e = 0; e < 3; e++) {
    lo[e] = dom->periodic[e] ? PETSC_MIN_INT : (faces && e == d ? 1 : 0);
    hi[e] = dom->periodic[e] ? PETSC_MAX_INT : dom->cells[e] - 1;
  }
}

/* One sweep: g (owned points) <- loc (the same field with its ghosts) + the fluxes from the
 * neighbours inside the box. Line by line along x, the y and z neighbours decided once per line;
 * the fluxes are added in the order e = x, y, z, side - then +. */
static void cpl_filter_sweep(Cpl cpl, const PetscInt gs[3], const PetscInt gm[3], const PetscInt xs[3], const PetscInt xm[3], PetscInt dof, const PetscScalar *a, PetscScalar *g, PetscBool *busy)
{
  const Domain   *dom   = cpl->dom;
  const PetscBool faces = (PetscBool)(dof == 3);
  const PetscInt  st[3] = {dof, dof * gm[0], dof * gm[0] * gm[1]};
  const double    l0 = cpl->filt.lam[0], l1 = cpl->filt.lam[1], l2 = cpl->filt.lam[2];

  /* busy[k]: ghosted z-plane k holds a non-zero value. A plane whose own and neighbouring planes
   * are all zero stays zero (every flux is 0) and is skipped: the freeboard above a bed. */
  for (PetscInt k = 0; k < gm[2]; k++) {
    const PetscScalar *p  = a + k * st[2];
    PetscBool          nz = PETSC_FALSE;
    for (PetscInt q = 0; q < st[2]; q++) nz = (PetscBool)(nz | (p[q] != 0));
    busy[k] = nz;
  }

  for (int d = 0; d < dof; d++) {
    PetscInt lo[3], hi[3], b0[3], b1[3];
    cpl_filter_box(dom, faces, d, lo, hi);
    for (int e = 0; e < 3; e++) {
      b0[e] = PetscMax(xs[e], lo[e]);
      b1[e] = PetscMin(xs[e] + xm[e] - 1, hi[e]);
    }
    for (PetscInt k = b0[2]; k <= b1[2]; k++) {
      const PetscInt kl = k - gs[2]; /* the owned plane's ghosted index: kl - 1 and kl + 1 exist */
      if (!busy[kl] && !busy[kl - 1] && !busy[kl + 1]) continue;
      for (PetscInt j = b0[1]; j <= b1[1]; j++) {
        const PetscBool zm = (PetscBool)(k > lo[2]), zp = (PetscBool)(k < hi[2]), ym = (PetscBool)(j > lo[1]), yp = (PetscBool)(j < hi[1]);
        PetscInt        o = dof * (((k - gs[2]) * gm[1] + (j - gs[1])) * gm[0] + (b0[0] - gs[0])) + d;
        PetscInt        c = dof * (((k - xs[2]) * xm[1] + (j - xs[1])) * xm[0] + (b0[0] - xs[0])) + d;
        for (PetscInt i = b0[0]; i <= b1[0]; i++, o += dof, c += dof) {
          const double ao = a[o];
          double       f  = 0;
          if (i > lo[0] && i < hi[0] && ym && yp && zm && zp) { /* the bulk: no test per neighbour */
            f = l0 * (a[o - st[0]] - ao);
            f += l0 * (a[o + st[0]] - ao);
            f += l1 * (a[o - st[1]] - ao);
            f += l1 * (a[o + st[1]] - ao);
            f += l2 * (a[o - st[2]] - ao);
            f += l2 * (a[o + st[2]] - ao);
            g[c] = ao + f;
            continue;
          }
          if (i > lo[0]) f += l0 * (a[o - st[0]] - ao);
          if (i < hi[0]) f += l0 * (a[o + st[0]] - ao);
          if (ym) f += l1 * (a[o - st[1]] - ao);
          if (yp) f += l1 * (a[o + st[1]] - ao);
          if (zm) f += l2 * (a[o - st[2]] - ao);
          if (zp) f += l2 * (a[o + st[2]] - ao);
          g[c] = ao + f;
        }
      }
    }
  }
}

/* Collective. Filters the global Vec g of the cell DMDA (cells) or the face DMDA (faces) in
 * place: filter_n sweeps, each a ghost update into the work local Vec and one flux pass.
 * Nothing when the filter is off. */
PetscErrorCode CplFilter(Cpl cpl, Vec g, PetscBool faces)
{
  DM           da  = faces ? cpl->fda : cpl->cda;
  Vec          loc = faces ? cpl->ex.floc[0] : cpl->ex.cloc;
  PetscInt     gs[3], gm[3], xs[3], xm[3];
  PetscScalar *ga;
  PetscBool   *busy;

  PetscFunctionBeginUser;
  if (cpl->filt.n == 0) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscLogEventBegin(cpl->ev.filter, 0, 0, 0, 0));
  PetscCall(DMDAGetGhostCorners(da, &gs[0], &gs[1], &gs[2], &gm[0], &gm[1], &gm[2]));
  PetscCall(DMDAGetCorners(da, &xs[0], &xs[1], &xs[2], &xm[0], &xm[1], &xm[2]));
  PetscCall(PetscMalloc1(gm[2], &busy));
  for (PetscInt s = 0; s < cpl->filt.n; s++) {
    const PetscScalar *a;
    PetscCall(DMGlobalToLocal(da, g, INSERT_VALUES, loc));
    PetscCall(VecGetArrayRead(loc, &a));
    PetscCall(VecGetArray(g, &ga));
    cpl_filter_sweep(cpl, gs, gm, xs, xm, faces ? 3 : 1, a, ga, busy);
    PetscCall(VecRestoreArray(g, &ga));
    PetscCall(VecRestoreArrayRead(loc, &a));
  }
  PetscCall(PetscFree(busy));
  PetscCall(PetscLogEventEnd(cpl->ev.filter, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}
