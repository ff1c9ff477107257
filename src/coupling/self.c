/* The fluid a particle's drag law sees without the particle's own disturbance (-cpl_self_porosity,
 * -cpl_self_velocity). The cube kernel puts a particle's own volume into the porosity of its
 * cells and its own drag into the fluid there; the law wants the undisturbed fluid.
 *  - Porosity: the particle's own dip V_p sum_c W_pc^2 / V_cell (kernel.c) is added back.
 *  - Velocity: the particle's force -F, spread onto the faces by its stencil W and read back by
 *    the same stencil, moves the fluid at the particle by -G F. G is the exact response of the
 *    linearised steady discrete equations (staggered grid, central advection by the slip w along
 *    the force's axis d, unbounded grid): a Brillouin-zone integral, theta_e = k_e h_e in [0, pi],
 *      G_dd = 1 / (pi^3 mu h_x h_y h_z) int prod_e |W_e(theta_e)|^2 P_dd Phi
 *             lam / (lam^2 + (kappa sin(theta_d) / h_d)^2) dtheta,
 *    lam = sum_e 4 sin^2(theta_e / 2) / h_e^2 (the discrete Laplacian), P_dd = 1 - 4
 *    sin^2(theta_d / 2) / (h_d^2 lam) (the discrete projection), kappa = rho |w| / mu, Phi the
 *    diffusion filter's symbol, |W_e|^2 = sum_m c_em cos(m theta_e) the stencil's transform
 *    (c_e0 = sum w^2, c_em = 2 sum w_i w_{i+m}). The moments of cos(m_x) cos(m_y) cos(m_z) are
 *    tabulated once per run over the cell Reynolds number kappa h_d (Duffy quadrature around
 *    the k = 0 singularity), so a particle's G is a short sum over its own stencil.
 *  - F = K (u_und - v) = K (u_seen - v + G F): F = K / (1 - G K) (u_seen - v), an effective
 *    coefficient linear in v, so the DEM's implicit drag and the exact exchange are unchanged.
 * Both fade as f = max(0, 1 - phi_others / -cpl_self_fade): in a bed Beetstra's eps and
 * interstitial velocity include every particle's disturbance, so there the law gets them
 * unchanged, bit for bit. Units SI. */
#include "coupling/coupling_impl.h"

#define CPL_SELF_NR 43 /* table points: cell Reynolds number 10^(-3 + i / 6), i < NR (to 10^4) */

struct _CplSelfTable {
  int     nm;              /* cosine terms per axis: the most weights of a 1-D stencil */
  double  filter_var;      /* the filter variance the table holds */
  double  h[3];            /* cell sizes (m) */
  double  re[CPL_SELF_NR]; /* the tabulated cell Reynolds numbers */
  double *mom[3];          /* per force axis d: [NR][nm][nm][nm] moments (m^2) */
};

/* Gauss-Legendre nodes and weights on [0, 1] (Newton on the Legendre recurrence). */
static void CplGaussLegendre(int n, double *x, double *w)
{
  for (int i = 0; i < n; i++) {
    double z = PetscCosReal(PETSC_PI * (i + 0.75) / (n + 0.5)), dp = 1;
    for (int it = 0; it < 100; it++) {
      double p0 = 1, p1 = z;
      for (int k = 2; k <= n; k++) {
        const double p2 = ((2 * k - 1) * z * p1 - (k - 1) * p0) / k;
        p0 = p1, p1 = p2;
      }
      dp              = n * (z * p1 - p0) / (z * z - 1);
      const double dz = p1 / dp;
      z -= dz;
      if (PetscAbsReal(dz) < 1e-15) break;
    }
    x[i] = 0.5 * (1 - z);
    w[i] = 1 / ((1 - z * z) * dp * dp);
  }
}

/* Adds one quadrature point's contributions (weight wq, point th) to the moments of all three
 * force axes at every tabulated cell Reynolds number. */
static void CplSelfTableAdd(Cpl cpl, struct _CplSelfTable *t, const double th[3], double wq)
{
  const int nm = t->nm;
  double    s2[3], lam = 0, phi = 1, cs[3][4], base[64];

  for (int e = 0; e < 3; e++) {
    s2[e] = 4 * PetscSqr(PetscSinReal(0.5 * th[e])) / (t->h[e] * t->h[e]);
    lam += s2[e];
    for (int m = 0; m < nm; m++) cs[e][m] = PetscCosReal(m * th[e]);
  }
  if (t->filter_var > 0) {
    double a = 1;
    for (int e = 0; e < 3; e++) a -= cpl->filt.lam[e] * s2[e] * t->h[e] * t->h[e];
    phi = PetscPowRealInt(a, cpl->filt.n);
  }
  for (int i = 0; i < nm; i++)
    for (int j = 0; j < nm; j++)
      for (int k = 0; k < nm; k++) base[(i * nm + j) * nm + k] = cs[0][i] * cs[1][j] * cs[2][k];
  for (int d = 0; d < 3; d++) {
    const double pdd = 1 - s2[d] / lam, sd = PetscSinReal(th[d]) / (t->h[d] * t->h[d]);
    for (int r = 0; r < CPL_SELF_NR; r++) {
      const double f = wq * pdd * phi * lam / (lam * lam + PetscSqr(t->re[r] * sd));
      double      *m = t->mom[d] + r * nm * nm * nm;
      for (int b = 0; b < nm * nm * nm; b++) m[b] += f * base[b];
    }
  }
}

/* Builds the moment table (not collective: every rank the same). The cube [0, pi]^3 is split
 * into three pyramids by its largest coordinate, th = (r, r u, r v) in each (the Jacobian r^2
 * takes the 1/k^2 singularity), r = pi t^2 graded towards 0 where the Oseen cut-off lives.
 * nm: the most weights of the 1-D stencils in use (rebuilt when more, or the filter changed). */
static PetscErrorCode CplSelfTableSetUp(Cpl cpl, int nm)
{
  enum {
    NT = 40,
    NU = 28
  };
  struct _CplSelfTable *t = cpl->self.tab;
  double                xt[NT], wt[NT], xu[NU], wu[NU];

  PetscFunctionBeginUser;
  if (t && t->filter_var == cpl->filt.var && t->nm >= nm) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(CplSelfTableDestroy(cpl));
  PetscCall(PetscNew(&t));
  cpl->self.tab = t;
  t->nm         = PetscMax(2, nm);
  for (int e = 0; e < 3; e++) t->h[e] = cpl->dom->h[e];
  t->filter_var = cpl->filt.var;
  for (int r = 0; r < CPL_SELF_NR; r++) t->re[r] = PetscPowReal(10.0, -3 + r / 6.0);
  for (int d = 0; d < 3; d++) PetscCall(PetscCalloc1(CPL_SELF_NR * t->nm * t->nm * t->nm, &t->mom[d]));
  CplGaussLegendre(NT, xt, wt);
  CplGaussLegendre(NU, xu, wu);
  for (int a = 0; a < NT; a++) {
    const double r = PETSC_PI * xt[a] * xt[a], wr = wt[a] * 2 * PETSC_PI * xt[a] * r * r;
    for (int b = 0; b < NU; b++)
      for (int c = 0; c < NU; c++)
        for (int p = 0; p < 3; p++) {
          double th[3];
          th[p]           = r;
          th[(p + 1) % 3] = r * xu[b];
          th[(p + 2) % 3] = r * xu[c];
          CplSelfTableAdd(cpl, t, th, wr * wu[b] * wu[c]);
        }
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CplSelfTableDestroy(Cpl cpl)
{
  PetscFunctionBeginUser;
  if (!cpl->self.tab) PetscFunctionReturn(PETSC_SUCCESS);
  for (int d = 0; d < 3; d++) PetscCall(PetscFree(cpl->self.tab->mom[d]));
  PetscCall(PetscFree(cpl->self.tab));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The porosity each local particle's drag sees and the weight f of its self corrections (0: none).
 * With -cpl_self_porosity or -cpl_self_velocity, f = max(0, 1 - phi_others / -cpl_self_fade),
 * phi_others = 1 - eps - self (f = 1 without a fade), and with -cpl_self_porosity eps + f self
 * replaces eps. A particle with f = 0 keeps the uncorrected eps exactly. With -cpl_self_velocity
 * the response table is built (or widened) for the stencils in use. Collective. */
PetscErrorCode CplSeenPorosity(Cpl cpl, PetscInt n, PetscReal *u, PetscReal *eps, PetscReal *fade)
{
  const PetscBool oneway = (PetscBool)(cpl->drag.mode == CPL_MODE_ONEWAY), any = (PetscBool)(!oneway && (cpl->self.eps || cpl->self.u));
  const PetscBool smooth = (PetscBool)(!oneway && cpl->pw.width > 0);
  PetscReal      *self = NULL, *usup = NULL;

  PetscFunctionBeginUser;
  if (any && !smooth) PetscCall(PetscMalloc1(n + 1, &self));
  if (smooth) PetscCall(PetscMalloc1(3 * n + 1, &usup));
  PetscCall(CplInterpolateSelf(cpl, u, eps, self, usup));
  for (PetscInt p = 0; p < n; p++) fade[p] = any ? 1 : 0;
  if (oneway) /* single phase: exactly 1, not the kernel sum's 1 +- roundoff (Beetstra's sqrt(1 - eps)) */
    for (PetscInt p = 0; p < n; p++) eps[p] = 1;
  else if (smooth) { /* smooth.c: the porosity on the particle's scale; the superficial flux over it
                        in a bed, the cell's velocity for a lone particle (the self corrections') */
    PetscCall(CplSmoothProject(cpl));
    PetscCall(CplSmoothSeen(cpl, n, eps, fade));
    for (PetscInt p = 0; p < 3 * n; p++) u[p] = fade[p / 3] * u[p] + (1 - fade[p / 3]) * usup[p] / eps[p / 3];
  } else if (any)
    for (PetscInt p = 0; p < n; p++) {
      if (cpl->self.fade > 0) fade[p] = PetscMax(0, 1 - (1 - eps[p] - self[p]) / cpl->self.fade);
      if (cpl->self.eps && fade[p] > 0) eps[p] = PetscMin(1, eps[p] + fade[p] * self[p]);
    }
  PetscCall(PetscFree(self));
  PetscCall(PetscFree(usup));
  if (!oneway && cpl->self.u && n > 0) {
    int nm = 2;
    for (PetscInt p = 0; p < n; p++)
      for (int e = 0; e < 3; e++) nm = PetscMax(nm, PetscMax(cpl->kern.stc[p].nc[e], cpl->kern.stc[p].nf[e]));
    PetscCall(CplSelfTableSetUp(cpl, nm));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* G_dd (m/(N s) times mu: divide by mu) of local particle p for d = 0, 1, 2 at cell Reynolds
 * numbers kappa h_d (kappa = rho |w| / mu), from its cached stencil (valid after
 * CplInterpolateSelf) and the table: cubic (Catmull-Rom) in log10 of the cell Reynolds number,
 * the first point below 1e-3 (Stokes to O(1e-3)), the last times 1e4 / Re above. */
static void CplSelfGreen(Cpl cpl, PetscInt p, PetscReal kappa, PetscReal g[3])
{
  const struct _CplSelfTable *t  = cpl->self.tab;
  const CplStencil           *st = &cpl->kern.stc[p];
  const int                   nm = t->nm;

  for (int d = 0; d < 3; d++) {
    double c[3][4] = {{0}}, acc[4] = {0}, x = PetscLog10Real(PetscMax(kappa * t->h[d], 1e-300)), s, scale = 1, wi[4];
    int    r;
    for (int e = 0; e < 3; e++) {
      const double *w = e == d ? st->wf[e] : st->wc[e];
      const int     n = e == d ? st->nf[e] : st->nc[e];
      for (int i = 0; i < n; i++)
        for (int j = i; j < n; j++) c[e][j - i] += (j == i ? 1 : 2) * w[i] * w[j];
    }
    s = 6 * (x + 3);
    if (s < 0) s = 0;
    if (s > CPL_SELF_NR - 1) {
      scale = PetscPowReal(10.0, (CPL_SELF_NR - 1) / 6.0 - 3 - x);
      s     = CPL_SELF_NR - 1;
    }
    r = PetscMin((int)s, CPL_SELF_NR - 2);
    s -= r;
    /* Catmull-Rom weights of points r - 1 .. r + 2 (clamped at the ends) */
    wi[0] = 0.5 * (-s + 2 * s * s - s * s * s);
    wi[1] = 0.5 * (2 - 5 * s * s + 3 * s * s * s);
    wi[2] = 0.5 * (s + 4 * s * s - 3 * s * s * s);
    wi[3] = 0.5 * (-s * s + s * s * s);
    for (int q = 0; q < 4; q++) {
      const double *m = t->mom[d] + PetscMin(PetscMax(r - 1 + q, 0), CPL_SELF_NR - 1) * nm * nm * nm;
      for (int i = 0; i < nm; i++)
        for (int j = 0; j < nm; j++)
          for (int k = 0; k < nm; k++) acc[q] += c[0][i] * c[1][j] * c[2][k] * m[(i * nm + j) * nm + k];
    }
    g[d] = scale * (wi[0] * acc[0] + wi[1] * acc[1] + wi[2] * acc[2] + wi[3] * acc[3]) / (PetscPowRealInt(PETSC_PI, 3) * t->h[0] * t->h[1] * t->h[2]);
  }
}

/* The mean of G_dd / mu over the slip direction n2 at slip speed w. */
static PetscReal CplSelfMean(Cpl cpl, PetscInt p, const PetscReal n2[3], PetscReal w)
{
  PetscReal g[3];

  CplSelfGreen(cpl, p, cpl->prop.rho * w / cpl->prop.mu, g);
  return (n2[0] * g[0] + n2[1] * g[1] + n2[2] * g[2]) / cpl->prop.mu;
}

/* The drag coefficient on the undisturbed slip of local particle p (diameter d, seen porosity
 * eps, seen fluid velocity u, velocity v): K' = K / (1 - f G K), K at the undisturbed slip
 * w = |u - v| / (1 - f G K) (a fixed point, at most 30 iterations; f G K is capped at 0.9). G
 * is the mean of G_dd over the slip direction (the advection taken along the force's axis),
 * at the slip w (1 - f G_0 K) of the fluid the particle has slowed, G_0 the response at w: the
 * linear response at w leaves +4.5% on 2 d cells at Re 10 (a cell centre), where the particle
 * slows its cell's fluid by a quarter. *capped: f G K reached the cap. G K >= 1 means the grid's
 * response to the particle's own drag, G F, exceeds its whole slip F / K: no coefficient on the
 * seen slip gives the law (a kernel hydrodynamically smaller than the sphere, e.g. cells of 1 d
 * with -cpl_kernel_scale 1). Not collective. */
PetscReal CplUndisturbedK(Cpl cpl, PetscInt p, PetscReal d, PetscReal eps, const PetscReal u[3], const PetscReal v[3], PetscReal fade, PetscBool *capped)
{
  PetscReal n2[3], w2 = 0, ws, wt, k = 0, gk = 0;

  for (int e = 0; e < 3; e++) w2 += PetscSqr(u[e] - v[e]);
  for (int e = 0; e < 3; e++) n2[e] = w2 > 0 ? PetscSqr(u[e] - v[e]) / w2 : 1.0 / 3;
  ws = PetscSqrtReal(w2);
  wt = ws;
  for (int it = 0; it < 30; it++) {
    k = 3 * PETSC_PI * cpl->prop.mu * d * CplDragFactor(cpl->drag.law, eps, cpl->prop.rho * d * eps * wt / cpl->prop.mu);
    {
      const PetscReal gk0 = PetscMin(0.9, fade * CplSelfMean(cpl, p, n2, wt) * k);
      gk                  = PetscMin(0.9, fade * CplSelfMean(cpl, p, n2, wt * (1 - gk0)) * k);
    }
    if (PetscAbsReal(ws / (1 - gk) - wt) <= 1e-12 * wt) break;
    wt = ws / (1 - gk);
  }
  *capped = (PetscBool)(gk >= 0.9);
  return k / (1 - gk);
}
