/* Explicit momentum terms on the staggered grid, per unit volume, at the active faces.
 * Advection, conservative: A_d = rho sum_e [F_e(+) u_d(+) - F_e(-) u_d(-)] / h_e over the faces
 * of the control volume around the d-face P, where F_e is the mass flux eps u_e averaged onto
 * the control-volume face (eps on a velocity face is the mean of its two cells) and u_d there
 * is central (mean of the two neighbours) or upwind-biased TVD with the van Leer limiter.
 * Viscous, 2 mu div(eps D(u)): tau_dd = 2 mu eps (du_d/dx_d) at cell centres, tau_de = mu eps
 * (du_d/dx_e + du_e/dx_d) at cell edges with eps the mean of the four cells around the edge.
 * Both are second order on a uniform grid; boundary conditions arrive through the ghosts (bc.c).
 * For the implicit viscous option only the transpose part mu eps du_e/dx_d of the shear stress
 * is explicit (viscous.c treats the rest). Units: N/m^3. */
#include "fluid/fluid_impl.h"

/* Value of u_d on the interface between L and R = L+e given the neighbours LL = L-e and
 * RR = R+e and the sign of the flux through it (van Leer limited slope, upwind side). The
 * quotient is formed only where the slopes agree (never 0/0, also under -fp_trap). */
static inline PetscScalar fluid_tvd_face(PetscScalar LL, PetscScalar L, PetscScalar R, PetscScalar RR, PetscScalar F)
{
  PetscScalar up, dn, dd;
  if (F >= 0) {
    up = L;
    dn = R;
    dd = L - LL;
  } else {
    up = R;
    dn = L;
    dd = R - RR;
  }
  const PetscScalar D = dn - up;
  return up + (dd * D > 0 ? dd * D / (dd + D) : 0);
}

/* rho F_m v_m at the lower e-face of the control volume around the d-face at point f: the flux
 * through that face, F_m the mean of the mass fluxes eps u_e (M, by face point) of the two
 * e-faces it joins, times the advected value there. The upper face of this volume is the lower
 * face of the volume at f + e, so each is computed once (FluidAdvectionTerm). */
static inline PetscScalar fluid_advective_flux(const FluidGrid *g, PetscBool tvd, const PetscScalar *u, const PetscScalar *M, PetscInt f, int d, int e)
{
  const PetscInt    fe = g->fs[e], fd = g->fs[d];
  const PetscScalar Fm  = 0.5 * (M[f / 3] + M[(f - fd) / 3]);
  const PetscScalar um1 = u[f - fe + d], u0 = u[f + d];
  const PetscScalar vm = tvd ? fluid_tvd_face(u[f - 2 * fe + d], um1, u0, u[f + fe + d], Fm) : 0.5 * (um1 + u0);
  return Fm * vm;
}

static PetscScalar FluidViscousAt(Fluid fl, const PetscScalar *u, const PetscScalar *eps, PetscInt f, PetscInt c, int d, PetscBool transpose_only)
{
  const FluidGrid *g  = &fl->g;
  const PetscInt   fd = g->fs[d], cd = g->cs[d];
  const PetscReal  hd  = g->h[d];
  PetscScalar      sum = 0;

  if (!transpose_only) {
    const PetscScalar tp = 2 * fl->prop.mu * eps[c] * (u[f + fd + d] - u[f + d]) / hd;
    const PetscScalar tm = 2 * fl->prop.mu * eps[c - cd] * (u[f + d] - u[f - fd + d]) / hd;
    sum += (tp - tm) / hd;
  }
  for (int e = 0; e < 3; e++) {
    if (e == d) continue;
    const PetscInt  fe = g->fs[e], ce = g->cs[e];
    const PetscReal he = g->h[e];
    PetscScalar     tau[2];
    for (int s = 0; s < 2; s++) { /* edge Q = P + s e */
      const PetscInt    fq = f + s * fe, cq = c + s * ce;
      const PetscScalar ee = 0.25 * (eps[cq] + eps[cq - cd] + eps[cq - ce] + eps[cq - cd - ce]);
      const PetscScalar tr = (u[fq + e] - u[fq - fd + e]) / hd;
      const PetscScalar dn = transpose_only ? 0 : (u[fq + d] - u[fq - fe + d]) / he;
      tau[s]               = fl->prop.mu * ee * (dn + tr);
    }
    sum += (tau[1] - tau[0]) / he;
  }
  return sum;
}

/* With a vessel (vessel.c): u_d at the neighbour of P along e on side s, the stored value or,
 * across a wall link, the linear extrapolation through the wall value 0 at theta h_e (no-slip),
 * or u_P (slip: no flux to the wall). */
static inline PetscScalar fluid_vessel_neighbour(const FluidVessel *v, const PetscScalar *u, PetscInt f, PetscInt st, int d, PetscInt w, int e, int s)
{
  if (w >= 0) {
    const PetscReal th = v->theta[w + 2 * e + s];
    if (th > 0) return v->slip ? u[f + d] : u[f + d] * (1 - 1 / th);
  }
  return u[f + (s ? st : -st) + d];
}

/* Whether the stencil of the d-face P (its two cells and the four cells around each of its four
 * edges) has only full cells (vessel.c: volume 1, six open faces). */
static inline PetscBool fluid_vessel_full_stencil(const FluidGrid *g, const PetscReal *full, PetscInt c, int d)
{
  const PetscInt cd = g->cs[d];
  if (full[c] != 1 || full[c - cd] != 1) return PETSC_FALSE;
  for (int e = 0; e < 3; e++) {
    if (e == d) continue;
    const PetscInt ce = g->cs[e];
    if (full[c + ce] != 1 || full[c - ce] != 1 || full[c - cd + ce] != 1 || full[c - cd - ce] != 1) return PETSC_FALSE;
  }
  return PETSC_TRUE;
}

/* FluidViscousAt with a vessel. Where the stencil is full, the box's stress. Elsewhere the
 * Laplacian part div(mu eps grad u_d) alone, with the wall links above: the transpose part
 * div(mu eps (grad u)^T) is mu eps grad(div u) for constant eps, zero in the fluid, but its
 * discrete form reads the zeros of the closed faces (an O(1) error at the wall otherwise); it is
 * left out whole at such a face, never in part. The implicit option (transpose_only) has the
 * Laplacian part in its matrix (viscous.c: with a vessel the normal part too has factor 1), so
 * here it gets the whole transpose part at full stencils and nothing elsewhere. */
static PetscScalar FluidViscousAtVessel(Fluid fl, const PetscScalar *u, const PetscScalar *eps, PetscInt f, PetscInt c, PetscInt o, int d, PetscBool transpose_only)
{
  const FluidGrid   *g  = &fl->g;
  const FluidVessel *v  = &fl->ves;
  const PetscInt     fd = g->fs[d], cd = g->cs[d], w = v->wl[o + d];
  const PetscReal    hd  = g->h[d];
  PetscScalar        sum = 0;

  if (fluid_vessel_full_stencil(g, v->full, c, d)) {
    if (!transpose_only) return FluidViscousAt(fl, u, eps, f, c, d, PETSC_FALSE);
    sum = fl->prop.mu * (eps[c] * (u[f + fd + d] - u[f + d]) - eps[c - cd] * (u[f + d] - u[f - fd + d])) / (hd * hd);
    return sum + FluidViscousAt(fl, u, eps, f, c, d, PETSC_TRUE);
  }
  if (transpose_only) return 0;
  for (int e = 0; e < 3; e++) {
    const PetscInt  fe = g->fs[e], ce = g->cs[e];
    const PetscReal he = g->h[e];
    PetscScalar     tau[2];
    for (int s = 0; s < 2; s++) { /* lower (s = 0) and upper face of P's control volume along e */
      const PetscScalar nb = fluid_vessel_neighbour(v, u, f, fe, d, w, e, s);
      PetscScalar       ee;
      if (e == d) ee = eps[s ? c : c - cd];
      else {
        const PetscInt cq = c + s * ce;
        ee                = 0.25 * (eps[cq] + eps[cq - cd] + eps[cq - ce] + eps[cq - cd - ce]);
      }
      tau[s] = fl->prop.mu * ee * (s ? nb - u[f + d] : u[f + d] - nb) / he;
    }
    sum += (tau[1] - tau[0]) / he;
  }
  return sum;
}

PetscErrorCode FluidAdvectionTerm(Fluid fl, const PetscScalar *u, const PetscScalar *eps, PetscScalar *out)
{
  const FluidGrid *g   = &fl->g;
  const PetscBool  tvd = (PetscBool)(fl->mom.adv == FLUID_ADV_TVD);
  const PetscInt   np  = g->gfm[0] * g->gfm[1] * g->gfm[2];
  PetscInt         idx[3], f, c, o;

  PetscFunctionBeginUser;
  FLUID_FOR_OWNED_FACES(g, idx, f, c, o)
  for (int d = 0; d < 3; d++) out[o + d] = 0;
  if (fl->mom.adv == FLUID_ADV_NONE) PetscFunctionReturn(PETSC_SUCCESS);
  if (fl->mom.advbuf_n < 2 * np) {
    PetscCall(PetscFree(fl->mom.advbuf));
    PetscCall(PetscMalloc1(2 * np, &fl->mom.advbuf));
    fl->mom.advbuf_n = 2 * np;
  }
  for (int e = 0; e < 3; e++) {
    PetscScalar   *M  = fl->mom.advbuf + np; /* mass flux eps u_e by face point, f / 3 */
    const PetscInt pe = g->fs[e] / 3;
    PetscInt       hi[3];
    for (int k = 0; k < 3; k++) hi[k] = g->xs[k] + g->fxm[k] + (k == e);
    /* on the points the fluxes below read: down to one point before the owned ones */
    for (idx[2] = g->xs[2] - 1; idx[2] < hi[2]; idx[2]++)
      for (idx[1] = g->xs[1] - 1; idx[1] < hi[1]; idx[1]++) {
        f = FluidFaceOff(g, g->xs[0] - 1, idx[1], idx[2]);
        c = FluidCellOff(g, g->xs[0] - 1, idx[1], idx[2]);
        for (idx[0] = g->xs[0] - 1; idx[0] < hi[0]; idx[0]++, f += 3, c++) M[f / 3] = 0.5 * (eps[c] + eps[c - g->cs[e]]) * u[f + e];
      }
    for (int d = 0; d < 3; d++) {
      PetscScalar *B = fl->mom.advbuf; /* by face point: f / 3 */
      /* lower-face fluxes of every owned volume and of the one above the last along e */
      for (idx[2] = g->xs[2]; idx[2] < hi[2]; idx[2]++)
        for (idx[1] = g->xs[1]; idx[1] < hi[1]; idx[1]++) {
          f = FluidFaceOff(g, g->xs[0], idx[1], idx[2]);
          for (idx[0] = g->xs[0]; idx[0] < hi[0]; idx[0]++, f += 3) B[f / 3] = fluid_advective_flux(g, tvd, u, M, f, d, e);
        }
      /* the same sum, in the same order, as (F+ v+ - F- v-) / h_e over e = x, y, z */
      FLUID_FOR_OWNED_FACES(g, idx, f, c, o)
      out[o + d] += (B[f / 3 + pe] - B[f / 3]) / g->h[e];
    }
  }
  FLUID_FOR_OWNED_FACES(g, idx, f, c, o)
  for (int d = 0; d < 3; d++) out[o + d] = FluidFaceActive(fl, d, idx) ? fl->prop.rho * out[o + d] : 0;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FluidViscousTerm(Fluid fl, const PetscScalar *u, const PetscScalar *eps, PetscBool transpose_only, PetscScalar *out)
{
  const FluidGrid *g = &fl->g;
  PetscInt         idx[3], f, c, o;

  PetscFunctionBeginUser;
  if (fl->ves.cut) {
    FLUID_FOR_OWNED_FACES(g, idx, f, c, o)
    for (int d = 0; d < 3; d++) out[o + d] = FluidFaceActive(fl, d, idx) ? FluidViscousAtVessel(fl, u, eps, f, c, o, d, transpose_only) : 0;
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  FLUID_FOR_OWNED_FACES(g, idx, f, c, o)
  for (int d = 0; d < 3; d++) out[o + d] = FluidFaceActive(fl, d, idx) ? FluidViscousAt(fl, u, eps, f, c, d, transpose_only) : 0;
  PetscFunctionReturn(PETSC_SUCCESS);
}
