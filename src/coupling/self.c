/* The fluid a particle's drag law sees without the particle's own disturbance (-cpl_self_porosity,
 * -cpl_self_velocity). The cube kernel puts a particle's own volume into the porosity of its
 * cells and its own drag into the fluid there; the law wants the undisturbed fluid.
 *  - Porosity: the particle's own dip V_p sum_c W_pc^2 / V_cell (kernel.c) is added back.
 *  - Velocity: the particle's force -F, spread onto the faces and read back with the same
 *    weights, moves the fluid at the particle by -G F. G is modelled as the centre value of a
 *    Stokeslet regularized by an anisotropic Gaussian of variance sigma_e^2 along axis e:
 *      G_dd = 1/(8 pi^3 mu) int dOmega (1 - n_d^2) sqrt(pi) / (2 sqrt(sum_e sigma_e^2 n_e^2 / 2)),
 *    sigma_e^2 = (beta l_e)^2 + filter_var, l_e = h_e / (2 sqrt(pi) q_e), q_e = sum_i w_ei^2 of
 *    the 1-D weights of component d's stencil (the width of a Gaussian with the same sum of
 *    squared weights: the cell it sits in when the kernel fits in one cell, the kernel's own
 *    width on fine grids). Divided by 1 + oseen Re_sigma (advection carries the disturbance
 *    away; Re_sigma = rho sigma |w| / mu). Isotropic: G = sqrt(2 pi) / (6 pi^2 mu sigma)
 *    (Evrard, Denner & van Wachem 2019; Balachandar, Liu & Lakhote 2019).
 *  - F = K (u_und - v) = K (u_seen - v + G F): F = K / (1 - G K) (u_seen - v), an effective
 *    coefficient linear in v, so the DEM's implicit drag and the exact exchange are unchanged.
 * Both fade as f = max(0, 1 - phi_others / -cpl_self_fade): in a bed Beetstra's eps and
 * interstitial velocity include every particle's disturbance, so there the law gets them
 * unchanged, bit for bit. Units SI. */
#include "coupling/coupling_impl.h"

/* The porosity each local particle's drag sees and the weight f of its self corrections (0: none).
 * With -cpl_self_porosity or -cpl_self_velocity, f = max(0, 1 - phi_others / -cpl_self_fade),
 * phi_others = 1 - eps - self (f = 1 without a fade), and with -cpl_self_porosity eps + f self
 * replaces eps. A particle with f = 0 keeps the uncorrected eps exactly. Collective. */
PetscErrorCode CplSeenPorosity(Cpl cpl, PetscInt n, PetscReal *u, PetscReal *eps, PetscReal *fade)
{
  const PetscBool oneway = (PetscBool)(cpl->mode == CPL_MODE_ONEWAY), any = (PetscBool)(!oneway && (cpl->self_eps || cpl->self_u));
  PetscReal      *self = NULL;

  PetscFunctionBeginUser;
  if (any) PetscCall(PetscMalloc1(n + 1, &self));
  PetscCall(CplInterpolateSelf(cpl, u, eps, self));
  for (PetscInt p = 0; p < n; p++) fade[p] = any ? 1 : 0;
  if (oneway) /* single phase: exactly 1, not the kernel sum's 1 +- roundoff (Beetstra's sqrt(1 - eps)) */
    for (PetscInt p = 0; p < n; p++) eps[p] = 1;
  else if (any)
    for (PetscInt p = 0; p < n; p++) {
      if (cpl->self_fade > 0) fade[p] = PetscMax(0, 1 - (1 - eps[p] - self[p]) / cpl->self_fade);
      if (cpl->self_eps && fade[p] > 0) eps[p] = PetscMin(1, eps[p] + fade[p] * self[p]);
    }
  PetscCall(PetscFree(self));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The Stokes part G_dd (without the 1/mu) of local particle p for d = 0, 1, 2 and the product
 * of the two lateral widths sigma_e sigma_e' (e, e' != d; m^2), from its cached stencil (valid
 * after CplInterpolateSelf). The sphere integral by symmetry over one octant: 6-point
 * Gauss-Legendre in cos(theta) and in phi (smooth: the sigma_e are within a factor ~4). */
static void CplSelfGreen(Cpl cpl, PetscInt p, PetscReal g[3], PetscReal lat[3])
{
  static const double x6[6] = {0.0337652428984240, 0.1693953067668677, 0.3806904069584015, 0.6193095930415985, 0.8306046932331323, 0.9662347571015760};
  static const double w6[6] = {0.0856622461895852, 0.1803807865240693, 0.2339569672863455, 0.2339569672863455, 0.1803807865240693, 0.0856622461895852};
  const CplStencil   *st    = &cpl->stc[p];
  PetscReal           s2[3];

  for (int d = 0; d < 3; d++) {
    double acc = 0;
    for (int e = 0; e < 3; e++) {
      const double *w = e == d ? st->wf[e] : st->wc[e];
      const int     n = e == d ? st->nf[e] : st->nc[e];
      double        q = 0;
      for (int i = 0; i < n; i++) q += w[i] * w[i];
      s2[e] = PetscSqr(cpl->self_beta * cpl->dom->h[e] / (2 * PetscSqrtReal(PETSC_PI) * q)) + cpl->filter_var;
    }
    lat[d] = PetscSqrtReal(s2[(d + 1) % 3] * s2[(d + 2) % 3]);
    for (int a = 0; a < 6; a++)
      for (int b = 0; b < 6; b++) {
        const double ct = x6[a], st1 = PetscSqrtReal(1 - ct * ct), ph = 0.5 * PETSC_PI * x6[b];
        const double n[3] = {st1 * PetscCosReal(ph), st1 * PetscSinReal(ph), ct};
        acc += w6[a] * w6[b] * (1 - n[d] * n[d]) / PetscSqrtReal(0.5 * (s2[0] * n[0] * n[0] + s2[1] * n[1] * n[1] + s2[2] * n[2] * n[2]));
      }
    /* one octant is (cos theta, phi) in [0,1] x [0, pi/2]; 8 octants */
    g[d] = 8 * 0.5 * PETSC_PI * acc * PetscSqrtReal(PETSC_PI) / 2 / (8 * PETSC_PI * PETSC_PI * PETSC_PI);
  }
}

/* The drag coefficient on the undisturbed slip of local particle p (diameter d, seen porosity
 * eps, seen fluid velocity u, velocity v): K' = K / (1 - f G K), K at the undisturbed slip
 * |u - v| / (1 - f G K) (a fixed point, at most 30 iterations; f G K is capped at 0.9). G is the
 * mean of G_dd over the slip direction, each G_dd = 1 / (1 / G_stokes + oseen rho |w| c
 * sigma_e sigma_e'), c = 6 pi^2 / sqrt(2 pi): isotropic, G_stokes / (1 + oseen Re_sigma); the
 * advective limit is the deficit rho |w| A carried off through the lateral area A = 4 pi
 * sigma_e sigma_e' of the disturbance. Not collective. */
PetscReal CplUndisturbedK(Cpl cpl, PetscInt p, PetscReal d, PetscReal eps, const PetscReal u[3], const PetscReal v[3], PetscReal fade)
{
  const PetscReal c = 6 * PETSC_PI * PETSC_PI / PetscSqrtReal(2 * PETSC_PI);
  PetscReal       g[3], lat[3], n2[3], w2 = 0, wt, k = 0, gk = 0;

  CplSelfGreen(cpl, p, g, lat);
  for (int e = 0; e < 3; e++) w2 += PetscSqr(u[e] - v[e]);
  for (int e = 0; e < 3; e++) n2[e] = w2 > 0 ? PetscSqr(u[e] - v[e]) / w2 : 1.0 / 3;
  wt = PetscSqrtReal(w2);
  for (int it = 0; it < 30; it++) {
    const PetscReal re = cpl->rho * d * eps * wt / cpl->mu;
    PetscReal       gs = 0;
    for (int e = 0; e < 3; e++) gs += n2[e] / (cpl->mu / g[e] + cpl->self_oseen * cpl->rho * wt * c * lat[e]);
    k  = 3 * PETSC_PI * cpl->mu * d * CplDragFactor(cpl->law, eps, re);
    gk = PetscMin(0.9, fade * gs * k);
    if (PetscAbsReal(PetscSqrtReal(w2) / (1 - gk) - wt) <= 1e-12 * wt) break;
    wt = PetscSqrtReal(w2) / (1 - gk);
  }
  return k / (1 - gk);
}
