/* Coupling diagnostics for tests and progress lines: momentum of both phases and the exchange
 * owed, solid volume on the grid against the particles', layer averages for pressure drops, and
 * the minimum fluidization velocity: the run's drag law's (the superficial velocity at which a
 * packed bed's pressure gradient n K U / eps carries its buoyant weight per volume,
 * (1 - eps)(rho_p - rho_f)|g|) and Wen & Yu's correlation (AIChE J. 12, 1966, 610-612, doi
 * 10.1002/aic.690120343): Re_mf = sqrt(33.7^2 + 0.0408 Ar) - 33.7, Ar = rho_f (rho_p - rho_f)
 * |g| d^3 / mu^2, made from beds at eps_mf near 0.4. */
#include "coupling/coupling_impl.h"

typedef struct {
  PetscInt gs[3], gm[3];
} CplGhost;

static inline PetscInt cpl_diag_off(const CplGhost *g, const PetscInt i[3], int d, int shift)
{
  return ((i[2] - (d == 2 ? shift : 0) - g->gs[2]) * g->gm[1] + (i[1] - (d == 1 ? shift : 0) - g->gs[1])) * g->gm[0] + (i[0] - (d == 0 ? shift : 0) - g->gs[0]);
}

PetscErrorCode CplGetMomentum(Cpl cpl, PetscReal pp[3], PetscReal pf[3], PetscReal owed[3])
{
  DemArrays          pa;
  Vec                u, eps;
  const PetscScalar *v, *e, *o, *ar          = NULL;
  PetscInt           xs[3], xm[3], idx[3], c = 0;
  CplGhost           g;
  PetscReal          loc[9] = {0};

  PetscFunctionBeginUser;
  PetscCall(DemGetArrays(cpl->dem, &pa));
  for (PetscInt p = 0; p < pa.nlocal; p++)
    for (int k = 0; k < 3; k++) loc[k] += CplMassOf(cpl, &pa, p) * pa.v[3 * p + k];
  PetscCall(FluidGetVelocity(cpl->fl, &u));
  PetscCall(FluidGetPorosity(cpl->fl, &eps));
  PetscCall(DMGlobalToLocal(cpl->cda, eps, INSERT_VALUES, cpl->ex.cloc));
  PetscCall(DMDAGetGhostCorners(cpl->cda, &g.gs[0], &g.gs[1], &g.gs[2], &g.gm[0], &g.gm[1], &g.gm[2]));
  PetscCall(DMDAGetCorners(cpl->fda, &xs[0], &xs[1], &xs[2], &xm[0], &xm[1], &xm[2]));
  PetscCall(VecGetArrayRead(u, &v));
  PetscCall(VecGetArrayRead(cpl->ex.cloc, &e));
  PetscCall(VecGetArrayRead(cpl->ex.owed, &o));
  if (cpl->ves.on) PetscCall(VecGetArrayRead(cpl->ves.area, &ar));
  for (idx[2] = xs[2]; idx[2] < xs[2] + xm[2]; idx[2]++)
    for (idx[1] = xs[1]; idx[1] < xs[1] + xm[1]; idx[1]++)
      for (idx[0] = xs[0]; idx[0] < xs[0] + xm[0]; idx[0]++, c += 3)
        for (int d = 0; d < 3; d++) {
          if (!CplInteriorFace(cpl->dom, d, idx)) continue;
          const PetscReal ef = 0.5 * (e[cpl_diag_off(&g, idx, d, 0)] + e[cpl_diag_off(&g, idx, d, 1)]);
          loc[3 + d] += cpl->prop.rho * ef * v[c + d] * (ar ? cpl->kern.cell_vol * ar[c + d] : cpl->kern.cell_vol); /* a_f V_cell in a vessel */
          loc[6 + d] += o[c + d];
        }
  if (ar) PetscCall(VecRestoreArrayRead(cpl->ves.area, &ar));
  PetscCall(VecRestoreArrayRead(cpl->ex.owed, &o));
  PetscCall(VecRestoreArrayRead(cpl->ex.cloc, &e));
  PetscCall(VecRestoreArrayRead(u, &v));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, loc, 9, MPIU_REAL, MPIU_SUM, cpl->comm));
  for (int k = 0; k < 3; k++) {
    pp[k]   = loc[k];
    pf[k]   = loc[3 + k];
    owed[k] = loc[6 + k];
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CplGetSolidVolume(Cpl cpl, PetscReal *grid, PetscReal *particles)
{
  DemArrays pa;
  PetscReal v = 0;

  PetscFunctionBeginUser;
  PetscCall(DemGetArrays(cpl->dem, &pa));
  for (PetscInt p = 0; p < pa.nlocal; p++) v += CplVolumeOf(cpl, &pa, p);
  PetscCall(MPIU_Allreduce(&v, particles, 1, MPIU_REAL, MPIU_SUM, cpl->comm));
  *grid = cpl->diag.solid_grid;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CplGetLayer(Cpl cpl, int d, PetscReal z, PetscReal *zc, PetscReal *pavg, PetscReal *eavg, PetscReal *usup)
{
  Vec                p, eps, u;
  const PetscScalar *pa, *e, *v;
  PetscInt           xs[3], xm[3], fxs[3], fxm[3], idx[3], c = 0, f = 0, layer;
  CplGhost           g;
  PetscReal          loc[5] = {0};
  const PetscScalar *vo = NULL, *ao = NULL; /* a vessel cutting the grid: the open cells and faces weigh */

  PetscFunctionBeginUser;
  layer = (PetscInt)PetscFloorReal((z - cpl->dom->lo[d]) / cpl->dom->h[d]);
  layer = PetscMin(PetscMax(layer, 0), cpl->dom->cells[d] - 1);
  if (zc) *zc = cpl->dom->lo[d] + (layer + 0.5) * cpl->dom->h[d];
  PetscCall(FluidGetPressure(cpl->fl, &p));
  PetscCall(FluidGetPorosity(cpl->fl, &eps));
  PetscCall(FluidGetVelocity(cpl->fl, &u));
  PetscCall(DMGlobalToLocal(cpl->cda, eps, INSERT_VALUES, cpl->ex.cloc));
  PetscCall(DMDAGetGhostCorners(cpl->cda, &g.gs[0], &g.gs[1], &g.gs[2], &g.gm[0], &g.gm[1], &g.gm[2]));
  PetscCall(DMDAGetCorners(cpl->cda, &xs[0], &xs[1], &xs[2], &xm[0], &xm[1], &xm[2]));
  PetscCall(DMDAGetCorners(cpl->fda, &fxs[0], &fxs[1], &fxs[2], &fxm[0], &fxm[1], &fxm[2]));
  PetscCall(VecGetArrayRead(p, &pa));
  PetscCall(VecGetArrayRead(cpl->ex.cloc, &e));
  PetscCall(VecGetArrayRead(u, &v));
  if (cpl->ves.on) {
    PetscCall(VecGetArrayRead(cpl->ves.vol, &vo));
    PetscCall(VecGetArrayRead(cpl->ves.area, &ao));
  }
  for (idx[2] = xs[2]; idx[2] < xs[2] + xm[2]; idx[2]++)
    for (idx[1] = xs[1]; idx[1] < xs[1] + xm[1]; idx[1]++)
      for (idx[0] = xs[0]; idx[0] < xs[0] + xm[0]; idx[0]++, c++)
        if (idx[d] == layer && vo) {
          loc[0] += vo[c] * pa[c];
          loc[1] += vo[c] * e[cpl_diag_off(&g, idx, d, 0)];
          loc[3] += vo[c];
        } else if (idx[d] == layer) {
          loc[0] += pa[c];
          loc[1] += e[cpl_diag_off(&g, idx, d, 0)];
          loc[3] += 1;
        }
  for (idx[2] = fxs[2]; idx[2] < fxs[2] + fxm[2]; idx[2]++)
    for (idx[1] = fxs[1]; idx[1] < fxs[1] + fxm[1]; idx[1]++)
      for (idx[0] = fxs[0]; idx[0] < fxs[0] + fxm[0]; idx[0]++, f += 3) {
        PetscBool in = (PetscBool)(idx[d] == layer);
        for (int k = 0; k < 3; k++) in = (PetscBool)(in && (k == d || idx[k] < cpl->dom->cells[k]));
        if (!in) continue;
        const PetscReal ef = layer > 0 || cpl->dom->periodic[d] ? 0.5 * (e[cpl_diag_off(&g, idx, d, 0)] + e[cpl_diag_off(&g, idx, d, 1)]) : e[cpl_diag_off(&g, idx, d, 0)];
        if (ao) { /* the flux through the open area over the open area */
          loc[2] += ao[f + d] * ef * v[f + d];
          loc[4] += ao[f + d];
        } else loc[2] += ef * v[f + d];
      }
  if (vo) {
    PetscCall(VecRestoreArrayRead(cpl->ves.vol, &vo));
    PetscCall(VecRestoreArrayRead(cpl->ves.area, &ao));
  }
  PetscCall(VecRestoreArrayRead(u, &v));
  PetscCall(VecRestoreArrayRead(cpl->ex.cloc, &e));
  PetscCall(VecRestoreArrayRead(p, &pa));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, loc, 5, MPIU_REAL, MPIU_SUM, cpl->comm));
  *pavg = loc[3] > 0 ? loc[0] / loc[3] : 0;
  *eavg = loc[3] > 0 ? loc[1] / loc[3] : 1;
  *usup = cpl->ves.on ? (loc[4] > 0 ? loc[2] / loc[4] : 0) : loc[2] / loc[3];
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CplMeanPorosity(Cpl cpl, int d, PetscReal z0, PetscReal z1, PetscReal *eps)
{
  Vec                e;
  const PetscScalar *a;
  PetscInt           xs[3], xm[3], idx[3], c = 0;
  PetscReal          loc[2] = {0, 0};
  const PetscScalar *vo     = NULL;

  PetscFunctionBeginUser;
  PetscCall(FluidGetPorosity(cpl->fl, &e));
  PetscCall(DMDAGetCorners(cpl->cda, &xs[0], &xs[1], &xs[2], &xm[0], &xm[1], &xm[2]));
  PetscCall(VecGetArrayRead(e, &a));
  if (cpl->ves.on) PetscCall(VecGetArrayRead(cpl->ves.vol, &vo)); /* over the open volume */
  for (idx[2] = xs[2]; idx[2] < xs[2] + xm[2]; idx[2]++)
    for (idx[1] = xs[1]; idx[1] < xs[1] + xm[1]; idx[1]++)
      for (idx[0] = xs[0]; idx[0] < xs[0] + xm[0]; idx[0]++, c++) {
        const PetscReal z = cpl->dom->lo[d] + (idx[d] + 0.5) * cpl->dom->h[d];
        if (z < z0 - 1e-9 * cpl->dom->h[d] || z > z1 + 1e-9 * cpl->dom->h[d]) continue;
        loc[0] += vo ? vo[c] * a[c] : a[c];
        loc[1] += vo ? vo[c] : 1;
      }
  if (vo) PetscCall(VecRestoreArrayRead(cpl->ves.vol, &vo));
  PetscCall(VecRestoreArrayRead(e, &a));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, loc, 2, MPIU_REAL, MPIU_SUM, cpl->comm));
  *eps = cpl->ves.on ? (loc[1] > 0 ? loc[0] / loc[1] : 1) : loc[0] / PetscMax(loc[1], 1);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CplGetBuoyantWeight(Cpl cpl, PetscReal w[3])
{
  DemArrays pa;
  PetscReal loc[3] = {0, 0, 0};

  PetscFunctionBeginUser;
  PetscCall(DemGetArrays(cpl->dem, &pa));
  for (PetscInt p = 0; p < pa.nlocal; p++)
    for (int k = 0; k < 3; k++) loc[k] += (CplMassOf(cpl, &pa, p) - cpl->prop.rho * CplVolumeOf(cpl, &pa, p)) * cpl->prop.g[k];
  PetscCall(MPIU_Allreduce(loc, w, 3, MPIU_REAL, MPIU_SUM, cpl->comm));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CplGetPackedBedGradient(Cpl cpl, PetscReal eps, PetscReal usup, PetscReal *dpdl)
{
  PetscFunctionBeginUser;
  *dpdl = CplPackedBedGradient(cpl->drag.law, eps, usup, cpl->kern.diam[0], cpl->prop.rho, cpl->prop.mu);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CplGetBedDiameter(Cpl cpl, PetscReal *d32, PetscReal *rhop)
{
  DemArrays pa;
  PetscReal loc[4] = {0, 0, 0, 0};

  PetscFunctionBeginUser;
  PetscCall(DemGetArrays(cpl->dem, &pa));
  for (PetscInt p = 0; p < pa.nlocal; p++) {
    const PetscReal v = CplVolumeOf(cpl, &pa, p), d = PetscCbrtReal(6 * v / PETSC_PI);
    loc[0] += d * d * d;
    loc[1] += d * d;
    loc[2] += CplMassOf(cpl, &pa, p);
    loc[3] += v;
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, loc, 4, MPIU_REAL, MPIU_SUM, cpl->comm));
  *d32  = loc[1] > 0 ? loc[0] / loc[1] : cpl->kern.diam[0];
  *rhop = loc[3] > 0 ? loc[2] / loc[3] : cpl->kern.mass[0] / cpl->kern.vol[0];
  PetscFunctionReturn(PETSC_SUCCESS);
}

CplUmfPorosity CplGetUmfPorosity(Cpl cpl, PetscReal eps_bed, PetscReal *eps)
{
  const CplUmfPorosity why = cpl->drag.umf_eps_set ? CPL_UMF_OPTION : (eps_bed <= CPL_LOOSE_PACKING ? CPL_UMF_BED : CPL_UMF_LOOSE);
  *eps                     = why == CPL_UMF_BED ? eps_bed : cpl->drag.umf_eps;
  return why;
}

PetscErrorCode CplGetMinFluidization(Cpl cpl, PetscReal eps, PetscReal d, PetscReal rhop, CplFluidization *f)
{
  const PetscReal g    = PetscSqrtReal(cpl->prop.g[0] * cpl->prop.g[0] + cpl->prop.g[1] * cpl->prop.g[1] + cpl->prop.g[2] * cpl->prop.g[2]);
  const PetscReal load = (1 - eps) * (rhop - cpl->prop.rho) * g; /* Pa/m */
  PetscReal       lo = 0, hi = 1;

  PetscFunctionBeginUser;
  f->eps    = eps;
  f->d      = d;
  f->ar     = cpl->prop.rho * (rhop - cpl->prop.rho) * g * d * d * d / (cpl->prop.mu * cpl->prop.mu);
  f->re_wy  = PetscSqrtReal(33.7 * 33.7 + 0.0408 * f->ar) - 33.7;
  f->umf_wy = f->re_wy * cpl->prop.mu / (cpl->prop.rho * d);
  f->umf    = 0;
  if (!(load > 0 && eps > 0 && eps < 1)) PetscFunctionReturn(PETSC_SUCCESS); /* no packed bed to carry */
  while (CplPackedBedGradient(cpl->drag.law, eps, hi, d, cpl->prop.rho, cpl->prop.mu) < load && hi < 1e12) hi *= 2;
  for (int it = 0; it < 200 && hi - lo > 1e-14 * hi; it++) { /* the gradient grows with U */
    const PetscReal m = 0.5 * (lo + hi);
    if (CplPackedBedGradient(cpl->drag.law, eps, m, d, cpl->prop.rho, cpl->prop.mu) < load) lo = m;
    else hi = m;
  }
  f->umf = 0.5 * (lo + hi);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CplGetOpenArea(Cpl cpl, int d, PetscReal z, PetscReal *area)
{
  const Domain      *dom  = cpl->dom;
  const PetscReal    face = dom->h[(d + 1) % 3] * dom->h[(d + 2) % 3];
  PetscInt           xs[3], xm[3], idx[3], f = 0, plane;
  const PetscScalar *ao;
  PetscReal          a = 0;

  PetscFunctionBeginUser;
  plane = (PetscInt)PetscFloorReal((z - dom->lo[d]) / dom->h[d] + 0.5);
  plane = PetscMin(PetscMax(plane, 0), dom->cells[d]);
  if (!cpl->ves.on) {
    *area = dom->len[(d + 1) % 3] * dom->len[(d + 2) % 3];
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(DMDAGetCorners(cpl->fda, &xs[0], &xs[1], &xs[2], &xm[0], &xm[1], &xm[2]));
  PetscCall(VecGetArrayRead(cpl->ves.area, &ao));
  for (idx[2] = xs[2]; idx[2] < xs[2] + xm[2]; idx[2]++)
    for (idx[1] = xs[1]; idx[1] < xs[1] + xm[1]; idx[1]++)
      for (idx[0] = xs[0]; idx[0] < xs[0] + xm[0]; idx[0]++, f += 3) {
        PetscBool in = (PetscBool)(idx[d] == plane);
        for (int k = 0; k < 3; k++) in = (PetscBool)(in && (k == d || idx[k] < dom->cells[k]));
        if (in) a += ao[f + d] * face;
      }
  PetscCall(VecRestoreArrayRead(cpl->ves.area, &ao));
  PetscCall(MPIU_Allreduce(&a, area, 1, MPIU_REAL, MPIU_SUM, cpl->comm));
  PetscFunctionReturn(PETSC_SUCCESS);
}
