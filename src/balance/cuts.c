/* Balanced cuts of a tensor-product decomposition (balance.h). Problem: given cell weights w on
 * an n0 x n1 x n2 grid and a process grid p0 x p1 x p2, choose per-axis cuts (every part at least
 * minw[d] cells wide) minimising L_max = max over ranks of the sum of w over the rank's box. The
 * cuts of one axis are shared by all slabs of the other two (a DMDA is a tensor product), so the
 * axes are coupled and the exact optimum is a hard combinatorial problem; we solve exactly the
 * one-axis subproblem and iterate:
 *   1. start: marginal cuts (project w onto each axis, cut the cumulative sum at j total / p);
 *   2. coordinate descent: for axis d with the other cuts fixed, cell plane i along d carries a
 *      vector v_i of q = p_a p_b loads, one per part pair of the other axes. The cuts of d that
 *      minimise max_parts max_c sum v_i[c] (= L_max) are found exactly: bisection on the
 *      bottleneck B, each probe a feasibility test "can the planes be cut into exactly p parts,
 *      each >= minw planes, each with all components <= B" (a reachability sweep, O(n q + p n):
 *      the farthest end R(s) of a part starting at s is monotone in s, found with two pointers),
 *      a feasible probe lowering the upper bound to the bottleneck it actually achieves; stop when
 *      the bracket is 1e-12 relative. Among optimal cuts the one closest to the current cuts is
 *      kept (fewer cells change owner at run time);
 *   3. repeat over x, y, z until a round improves L_max by less than 1e-12 relative, at most
 *      max_sweeps rounds. L_max never increases;
 *   4. the descent stalls in local optima (the problem is NP-hard beyond one axis), so it runs
 *      from 6 starts (marginal and DMDA-uniform cuts, axis orders xyz, zyx, yzx), keeps the best
 *      (ties: the marginal start), then "kicks": shrink the heaviest rank by one cell on one of
 *      its faces, re-descend the other axes first, keep the move if L_max drops (at most 20).
 * Never worse than the marginal cuts (start 1 is them). Measured (tests/test_cuts.c):
 * the brute-force optimum in 356 of 360 small random cases (the misses up to 7.3% above it, all
 * on sparse hot spots); a column with its weight in the bottom third on 1x1x4 ranks: the 1D
 * optimum. Box loads come from a summed-volume table built once (O(N)), so a sweep costs
 * O((n + 1) q) look-ups plus ~40 probes of O(n q + p n): 4.6 million cells on 512 ranks take
 * 0.25 s, on 4,800 ranks 0.9 s (tools/balance-sim). */
#include "balance/balance.h"

const char *const BalanceWeightModels[] = {"linear", "quadratic", "BalanceWeightModel", "BALANCE_WEIGHT_", NULL};

#define BALANCE_DEFAULT_SWEEPS 20
#define BALANCE_REL_TOL        1e-12
#define BALANCE_STARTS         6
#define BALANCE_KICKS          20

static PetscErrorCode BalanceCheckGrid(const BalanceGrid *g, PetscBool usemin)
{
  PetscFunctionBegin;
  for (int d = 0; d < 3; d++) {
    const PetscInt mw = usemin ? g->minw[d] : 1;
    PetscCheck(g->n[d] >= 1 && g->p[d] >= 1 && mw >= 1, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "axis %c: cells %" PetscInt_FMT ", ranks %" PetscInt_FMT " and minimum width %" PetscInt_FMT " must all be >= 1", "xyz"[d], g -> n[d], g -> p[d], mw);
    PetscCheck(g->n[d] >= g->p[d] * mw, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "axis %c: %" PetscInt_FMT " cells cannot be cut into %" PetscInt_FMT " ranks of at least %" PetscInt_FMT " cells each (the minimum width is the halo): use fewer ranks along %c or smaller cells", "xyz"[d], g -> n[d], g -> p[d], mw, "xyz"[d]);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode BalanceCheckWeights(const BalanceGrid *g, const PetscReal *w, PetscReal *total)
{
  const PetscInt n0 = g->n[0], n1 = g->n[1], N = g->n[0] * g->n[1] * g->n[2];

  PetscFunctionBegin;
  *total = 0;
  for (PetscInt c = 0; c < N; c++) {
    /* !(w >= 0) also catches NaN */
    PetscCheck(w[c] >= 0 && !PetscIsInfReal(w[c]), PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "weight %g of cell (%" PetscInt_FMT ", %" PetscInt_FMT ", %" PetscInt_FMT ") must be finite and >= 0", (double)w[c], c % n0, (c / n0) % n1, c / (n0 * n1));
    *total += w[c];
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* own[i] = the part of cell i along an axis cut as l[0..p-1] */
static void balance_owner(PetscInt p, const PetscInt *l, PetscInt *own)
{
  for (PetscInt r = 0, i = 0; r < p; r++)
    for (PetscInt k = 0; k < l[r]; k++) own[i++] = r;
}

PetscErrorCode BalanceCellWeights(const BalanceWeight *wm, PetscInt ncells, const PetscInt *count, PetscReal *w)
{
  PetscFunctionBegin;
  PetscCheck(wm->alpha >= 0 && wm->beta >= 0 && !PetscIsInfReal(wm->alpha) && !PetscIsInfReal(wm->beta), PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "-lb_alpha %g and -lb_beta %g must be finite and >= 0", (double)wm->alpha, (double)wm->beta);
  for (PetscInt c = 0; c < ncells; c++) {
    const PetscReal np = (PetscReal)count[c];
    PetscCheck(count[c] >= 0, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "particle count %" PetscInt_FMT " of cell %" PetscInt_FMT " must be >= 0", count[c], c);
    w[c] = wm->beta + wm->alpha * (wm->model == BALANCE_WEIGHT_QUADRATIC ? np * np : np);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode BalanceUniformCuts(const BalanceGrid *g, PetscInt *const l[3])
{
  PetscFunctionBegin;
  PetscCall(BalanceCheckGrid(g, PETSC_FALSE));
  for (int d = 0; d < 3; d++)
    for (PetscInt r = 0; r < g->p[d]; r++) l[d][r] = g->n[d] / g->p[d] + ((g->n[d] % g->p[d]) > r);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode BalanceLoads(const BalanceGrid *g, const PetscReal *w, PetscInt *const l[3], PetscReal *load)
{
  const PetscInt *n = g->n, *p = g->p;
  PetscInt       *own[3];

  PetscFunctionBegin;
  PetscCall(BalanceCheckGrid(g, PETSC_FALSE));
  for (int d = 0; d < 3; d++) {
    PetscInt sum = 0;
    for (PetscInt r = 0; r < p[d]; r++) {
      PetscCheck(l[d][r] >= 0, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "axis %c: part %" PetscInt_FMT " has %" PetscInt_FMT " cells", "xyz"[d], r, l[d][r]);
      sum += l[d][r];
    }
    PetscCheck(sum == n[d], PETSC_COMM_SELF, PETSC_ERR_ARG_SIZ, "axis %c: the cuts hold %" PetscInt_FMT " cells, the grid %" PetscInt_FMT, "xyz"[d], sum, n[d]);
  }
  PetscCall(PetscMalloc3(n[0], &own[0], n[1], &own[1], n[2], &own[2]));
  for (int d = 0; d < 3; d++) balance_owner(p[d], l[d], own[d]);
  PetscCall(PetscArrayzero(load, p[0] * p[1] * p[2]));
  for (PetscInt k = 0, c = 0; k < n[2]; k++)
    for (PetscInt j = 0; j < n[1]; j++) {
      PetscReal *row = load + p[0] * (own[1][j] + p[1] * own[2][k]);
      for (PetscInt i = 0; i < n[0]; i++, c++) row[own[0][i]] += w[c];
    }
  PetscCall(PetscFree3(own[0], own[1], own[2]));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Cuts of one axis from its projected weights m[0..n-1]: the face nearest to where the
 * cumulative sum F crosses j total / p, clamped so that every part keeps minw cells (clamping
 * left to right always succeeds when n >= p minw). No weight at all: uniform cuts. */
static void balance_marginal_axis(PetscInt n, PetscInt p, PetscInt minw, const PetscReal *m, PetscReal *F, PetscInt *l)
{
  PetscInt prev = 0, f = 0;

  F[0] = 0;
  for (PetscInt i = 0; i < n; i++) F[i + 1] = F[i] + m[i];
  if (!(F[n] > 0)) {
    for (PetscInt r = 0; r < p; r++) l[r] = n / p + ((n % p) > r);
    return;
  }
  for (PetscInt j = 1; j < p; j++) {
    const PetscReal t = j * F[n] / p;
    PetscInt        c;
    while (f < n && F[f] < t) f++; /* first face with F >= t */
    c        = (f > 0 && t - F[f - 1] < F[f] - t) ? f - 1 : f;
    c        = PetscMin(PetscMax(c, prev + minw), n - (p - j) * minw);
    l[j - 1] = c - prev;
    prev     = c;
  }
  l[p - 1] = n - prev;
}

PetscErrorCode BalanceMarginalCuts(const BalanceGrid *g, const PetscReal *w, PetscInt *const l[3])
{
  const PetscInt *n = g->n;
  PetscReal      *m[3], *F, total;

  PetscFunctionBegin;
  PetscCall(BalanceCheckGrid(g, PETSC_TRUE));
  PetscCall(BalanceCheckWeights(g, w, &total));
  PetscCall(PetscCalloc3(n[0], &m[0], n[1], &m[1], n[2], &m[2]));
  PetscCall(PetscMalloc1(PetscMax(n[0], PetscMax(n[1], n[2])) + 1, &F));
  for (PetscInt k = 0, c = 0; k < n[2]; k++)
    for (PetscInt j = 0; j < n[1]; j++)
      for (PetscInt i = 0; i < n[0]; i++, c++) {
        m[0][i] += w[c];
        m[1][j] += w[c];
        m[2][k] += w[c];
      }
  for (int d = 0; d < 3; d++) balance_marginal_axis(n[d], g->p[d], g->minw[d], m[d], F, l[d]);
  PetscCall(PetscFree3(m[0], m[1], m[2]));
  PetscCall(PetscFree(F));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* One axis of the coordinate descent: planes 0..n-1, each a vector of q loads, prefix sums
 * P[i q + c] = sum over planes < i of component c. start[0..p] are part boundaries (start[0] = 0,
 * start[p] = n). */
typedef struct {
  PetscInt         n, p, minw, q;
  const PetscReal *P;
  PetscInt        *R;     /* farthest end of a part starting at s with load <= B, -1 if none */
  PetscInt        *diff;  /* n + 2 entries, difference array of the reachable ends */
  char            *reach; /* reach[k (n+1) + e]: planes [0, e) cut into k valid parts */
} BalanceAxis;

/* largest component of the load of planes [a, b) */
static inline PetscReal balance_axis_load(const BalanceAxis *ax, PetscInt a, PetscInt b)
{
  const PetscReal *Pa = ax->P + a * ax->q, *Pb = ax->P + b * ax->q;
  PetscReal        m = 0;
  for (PetscInt c = 0; c < ax->q; c++) m = PetscMax(m, Pb[c] - Pa[c]);
  return m;
}

static PetscReal balance_axis_bottleneck(const BalanceAxis *ax, const PetscInt *start)
{
  PetscReal m = 0;
  for (PetscInt k = 0; k < ax->p; k++) m = PetscMax(m, balance_axis_load(ax, start[k], start[k + 1]));
  return m;
}

/* Whether the planes can be cut into exactly p parts of >= minw planes and load <= B; if so,
 * out[] receives such cuts, each boundary as close as possible to cur[] (backtracking from the
 * right). The loads are non-negative, so a part [s, e) fits iff s + minw <= e <= R(s). */
static PetscBool balance_axis_feasible(BalanceAxis *ax, PetscReal B, const PetscInt *cur, PetscInt *out)
{
  const PetscInt n = ax->n, p = ax->p, mw = ax->minw;
  PetscInt       e = 0;

  for (PetscInt s = 0; s <= n - mw; s++) {
    /* e >= s + minw came from an earlier start s' < s with load(s', e) <= B, so load(s, e) <= B */
    e = PetscMax(e, s + mw);
    if (balance_axis_load(ax, s, e) > B) {
      ax->R[s] = -1;
      continue;
    }
    while (e < n && balance_axis_load(ax, s, e + 1) <= B) e++;
    ax->R[s] = e;
  }
  memset(ax->reach, 0, (size_t)((p + 1) * (n + 1)));
  ax->reach[0] = 1;
  for (PetscInt k = 1; k <= p; k++) {
    const char *prev = ax->reach + (k - 1) * (n + 1);
    char       *next = ax->reach + k * (n + 1);
    PetscInt    open = 0, *diff = ax->diff;
    for (PetscInt i = 0; i <= n + 1; i++) diff[i] = 0;
    for (PetscInt s = 0; s <= n - mw; s++)
      if (prev[s] && ax->R[s] >= 0) {
        diff[s + mw]++;
        diff[ax->R[s] + 1]--;
      }
    for (PetscInt i = 0; i <= n; i++) next[i] = (char)((open += diff[i]) > 0);
  }
  if (!ax->reach[p * (n + 1) + n]) return PETSC_FALSE;
  out[p] = n;
  for (PetscInt k = p; k >= 1; k--) {
    const char *prev = ax->reach + (k - 1) * (n + 1);
    PetscInt    best = -1;
    for (PetscInt s = 0; s <= out[k] - mw; s++)
      if (prev[s] && ax->R[s] >= out[k] && (best < 0 || PetscAbsInt(s - cur[k - 1]) < PetscAbsInt(best - cur[k - 1]))) best = s;
    out[k - 1] = best; /* >= 0: reach[k][out[k]] guarantees a candidate */
  }
  return PETSC_TRUE;
}

/* Summed-volume table: S[i + (n0 + 1) (j + (n1 + 1) k)] = sum of w over [0,i) x [0,j) x [0,k), so
 * that every box load costs 8 look-ups and a sweep never touches the cells again. Its roundoff,
 * a few ulps of the total per box, is far below the 1e-12 bracket for any realistic rank count;
 * the loads reported to the caller are summed directly (BalanceLoads). */
static PetscErrorCode BalanceSatCreate(const BalanceGrid *g, const PetscReal *w, PetscReal **S)
{
  const PetscInt m0 = g->n[0] + 1, m1 = g->n[1] + 1, m2 = g->n[2] + 1;
  PetscReal     *s;

  PetscFunctionBegin;
  PetscCall(PetscCalloc1(m0 * m1 * m2, &s));
  for (PetscInt k = 0, c = 0; k < g->n[2]; k++)
    for (PetscInt j = 0; j < g->n[1]; j++)
      for (PetscInt i = 0; i < g->n[0]; i++, c++) s[(i + 1) + m0 * ((j + 1) + m1 * (k + 1))] = w[c];
  for (PetscInt k = 1; k < m2; k++) /* cumulate along x, then y, then z */
    for (PetscInt j = 1; j < m1; j++)
      for (PetscInt i = 1; i < m0; i++) s[i + m0 * (j + m1 * k)] += s[(i - 1) + m0 * (j + m1 * k)];
  for (PetscInt k = 1; k < m2; k++)
    for (PetscInt j = 1; j < m1; j++)
      for (PetscInt i = 0; i < m0; i++) s[i + m0 * (j + m1 * k)] += s[i + m0 * ((j - 1) + m1 * k)];
  for (PetscInt k = 1; k < m2; k++)
    for (PetscInt j = 0; j < m1; j++)
      for (PetscInt i = 0; i < m0; i++) s[i + m0 * (j + m1 * k)] += s[i + m0 * (j + m1 * (k - 1))];
  *S = s;
  PetscFunctionReturn(PETSC_SUCCESS);
}

static inline PetscReal balance_sat(const BalanceGrid *g, const PetscReal *S, const PetscInt x[3])
{
  return S[x[0] + (g->n[0] + 1) * (x[1] + (g->n[1] + 1) * x[2])];
}

/* sum of w over the box [lo, hi): inclusion-exclusion, a corner with an even number of upper
 * coordinates counts negative */
static PetscReal balance_box(const BalanceGrid *g, const PetscReal *S, const PetscInt lo[3], const PetscInt hi[3])
{
  PetscReal sum = 0;
  for (int corner = 0; corner < 8; corner++) {
    const PetscInt x[3] = {corner & 1 ? hi[0] : lo[0], corner & 2 ? hi[1] : lo[1], corner & 4 ? hi[2] : lo[2]};
    const int upper = (corner & 1) + ((corner >> 1) & 1) + ((corner >> 2) & 1);
    sum += (upper % 2) ? balance_sat(g, S, x) : -balance_sat(g, S, x);
  }
  return sum;
}

/* the largest rank load of the cuts l, from the table */
static PetscReal balance_sat_lmax(const BalanceGrid *g, const PetscReal *S, PetscInt *const l[3], PetscInt *rmax)
{
  PetscReal m = -1;
  PetscInt  lo[3], hi[3], r = 0;

  lo[2] = 0;
  for (PetscInt rz = 0; rz < g->p[2]; rz++, lo[2] = hi[2]) {
    hi[2] = lo[2] + l[2][rz];
    lo[1] = 0;
    for (PetscInt ry = 0; ry < g->p[1]; ry++, lo[1] = hi[1]) {
      hi[1] = lo[1] + l[1][ry];
      lo[0] = 0;
      for (PetscInt rx = 0; rx < g->p[0]; rx++, lo[0] = hi[0], r++) {
        const PetscReal v = (hi[0] = lo[0] + l[0][rx], balance_box(g, S, lo, hi));
        if (v > m) m = v, *rmax = r;
      }
    }
  }
  return m;
}

/* The exact optimum of axis d's cuts with the other two axes fixed. lmax: in, L_max of l (any
 * summation order); out, L_max of the new cuts. The cuts change only on a strict improvement. */
static PetscErrorCode BalanceSweepAxis(const BalanceGrid *g, const PetscReal *S, PetscInt *const l[3], int d, PetscReal *lmax)
{
  const int      a = (d + 1) % 3, b = (d + 2) % 3;
  const PetscInt n = g->n[d], p = g->p[d], q = g->p[a] * g->p[b];
  PetscInt      *cur, *out, *best, lo[3], hi[3];
  PetscReal     *P, blo = 0, bhi;
  BalanceAxis    ax;

  PetscFunctionBegin;
  if (p == 1) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscMalloc1((n + 1) * q, &P));
  /* P[i q + c]: the load of planes [0, i) in part pair c = A + p_a B of the other two axes */
  lo[d] = 0;
  lo[b] = 0;
  for (PetscInt B = 0; B < g->p[b]; B++, lo[b] = hi[b]) {
    hi[b] = lo[b] + l[b][B];
    lo[a] = 0;
    for (PetscInt A = 0; A < g->p[a]; A++, lo[a] = hi[a]) {
      hi[a] = lo[a] + l[a][A];
      for (PetscInt i = 0; i <= n; i++) {
        hi[d]                      = i;
        P[i * q + A + g->p[a] * B] = balance_box(g, S, lo, hi);
      }
    }
  }
  ax.n = n, ax.p = p, ax.minw = g->minw[d], ax.q = q, ax.P = P;
  PetscCall(PetscMalloc3(n + 1, &ax.R, n + 2, &ax.diff, (p + 1) * (n + 1), &ax.reach));
  PetscCall(PetscMalloc3(p + 1, &cur, p + 1, &out, p + 1, &best));
  cur[0] = 0;
  for (PetscInt k = 0; k < p; k++) cur[k + 1] = cur[k] + l[d][k];
  PetscCall(PetscArraycpy(best, cur, p + 1));
  bhi = balance_axis_bottleneck(&ax, cur);
  for (PetscInt c = 0; c < q; c++) blo = PetscMax(blo, P[n * q + c] / p); /* no cut beats the mean */
  for (int it = 0; it < 200 && bhi > 0 && bhi - blo > BALANCE_REL_TOL * bhi; it++) {
    const PetscReal mid = blo + 0.5 * (bhi - blo);
    if (balance_axis_feasible(&ax, mid, cur, out)) {
      bhi = balance_axis_bottleneck(&ax, out); /* <= mid */
      PetscCall(PetscArraycpy(best, out, p + 1));
    } else blo = mid;
  }
  for (PetscInt k = 0; k < p; k++) l[d][k] = best[k + 1] - best[k];
  *lmax = PetscMin(*lmax, bhi);
  PetscCall(PetscFree3(ax.R, ax.diff, ax.reach));
  PetscCall(PetscFree3(cur, out, best));
  PetscCall(PetscFree(P));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscReal balance_max(PetscInt n, const PetscReal *v)
{
  PetscReal m = 0;
  for (PetscInt i = 0; i < n; i++) m = PetscMax(m, v[i]);
  return m;
}

/* Coordinate descent from the cuts in l (see the file header); obj: L_max of l, in and out. */
static PetscErrorCode BalanceDescend(const BalanceGrid *g, const PetscReal *S, PetscInt *const l[3], const int order[3], PetscReal *obj, PetscInt *rounds)
{
  const PetscInt sweeps = g->max_sweeps > 0 ? g->max_sweeps : BALANCE_DEFAULT_SWEEPS;

  PetscFunctionBegin;
  for (*rounds = 1; *rounds <= sweeps; (*rounds)++) {
    const PetscReal before = *obj;
    for (int d = 0; d < 3; d++) PetscCall(BalanceSweepAxis(g, S, l, order[d], obj));
    if (!(*obj < before * (1 - BALANCE_REL_TOL))) break;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Escape from a local optimum of the descent: shrink the heaviest rank's box by one cell on one
 * of its (up to) six faces, re-optimise the other two axes first, then all; keep the first move
 * that lowers L_max and start again, at most BALANCE_KICKS times. t[] is work space. */
static PetscErrorCode BalanceKick(const BalanceGrid *g, const PetscReal *S, PetscInt *const l[3], PetscInt *const t[3], PetscReal *obj, PetscInt *kicks)
{
  PetscFunctionBegin;
  for (*kicks = 0; *kicks < BALANCE_KICKS; (*kicks)++) {
    PetscInt  r        = 0, rc[3];
    PetscBool improved = PETSC_FALSE;
    (void)balance_sat_lmax(g, S, l, &r);
    rc[0] = r % g->p[0], rc[1] = (r / g->p[0]) % g->p[1], rc[2] = r / (g->p[0] * g->p[1]);
    for (int m = 0; m < 6 && !improved; m++) {
      const int      e = m / 2, lower = m % 2, order[3] = {(e + 1) % 3, (e + 2) % 3, e};
      const PetscInt nb = lower ? rc[e] - 1 : rc[e] + 1; /* the neighbour that grows */
      PetscReal      o;
      PetscInt       rounds, rr;
      if (nb < 0 || nb >= g->p[e] || l[e][rc[e]] - 1 < g->minw[e]) continue;
      for (int d = 0; d < 3; d++) PetscCall(PetscArraycpy(t[d], l[d], g->p[d]));
      t[e][rc[e]]--;
      t[e][nb]++;
      o = balance_sat_lmax(g, S, t, &rr);
      PetscCall(BalanceDescend(g, S, t, order, &o, &rounds));
      if (o < *obj * (1 - BALANCE_REL_TOL)) {
        for (int d = 0; d < 3; d++) PetscCall(PetscArraycpy(l[d], t[d], g->p[d]));
        *obj     = o;
        improved = PETSC_TRUE;
      }
    }
    if (!improved) break;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode BalanceCuts(const BalanceGrid *g, const PetscReal *w, PetscInt *const l[3], PetscReal *lmax, PetscReal *lavg)
{
  const PetscInt np                        = g->p[0] * g->p[1] * g->p[2];
  const int      orders[BALANCE_STARTS][3] = {{0, 1, 2}, {0, 1, 2}, {2, 1, 0}, {2, 1, 0}, {1, 2, 0}, {1, 2, 0}};
  PetscReal     *load, *S = NULL, total, best = PETSC_MAX_REAL, start = 0;
  PetscInt      *t[3], *mc[3], rounds = 0, kicks, rr;

  PetscFunctionBegin;
  PetscCall(BalanceCheckGrid(g, PETSC_TRUE));
  PetscCall(BalanceCheckWeights(g, w, &total));
  PetscCall(PetscMalloc1(np, &load));
  PetscCall(PetscMalloc3(g->p[0], &t[0], g->p[1], &t[1], g->p[2], &t[2]));
  PetscCall(PetscMalloc3(g->p[0], &mc[0], g->p[1], &mc[1], g->p[2], &mc[2]));
  PetscCall(BalanceMarginalCuts(g, w, mc));
  PetscCall(BalanceSatCreate(g, w, &S));
  for (int s = 0; s < BALANCE_STARTS; s++) {
    PetscReal obj;
    PetscInt  r;
    if (s % 2 == 0)
      for (int d = 0; d < 3; d++) PetscCall(PetscArraycpy(t[d], mc[d], g->p[d]));
    else PetscCall(BalanceUniformCuts(g, t));
    obj = balance_sat_lmax(g, S, t, &rr);
    if (s == 0) start = obj;
    PetscCall(BalanceDescend(g, S, t, orders[s], &obj, &r));
    rounds += r;
    if (obj < best) { /* ties keep the earlier start: the marginal one first */
      best = obj;
      for (int d = 0; d < 3; d++) PetscCall(PetscArraycpy(l[d], t[d], g->p[d]));
    }
  }
  PetscCall(BalanceKick(g, S, l, t, &best, &kicks));
  PetscCall(BalanceLoads(g, w, l, load));
  *lmax = balance_max(np, load);
  *lavg = total / np;
  PetscCall(PetscInfo(NULL, "BalanceCuts: L_max %g (marginal cuts) -> %g after %" PetscInt_FMT " rounds from %d starts and %" PetscInt_FMT " kicks, L_avg %g\n", (double)start, (double)*lmax, rounds, BALANCE_STARTS, kicks, (double)*lavg));
  PetscCall(PetscFree3(t[0], t[1], t[2]));
  PetscCall(PetscFree3(mc[0], mc[1], mc[2]));
  PetscCall(PetscFree(S));
  PetscCall(PetscFree(load));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* DMSetUp_DA_3D, all of m, n, p left to PETSc: n ~ (N^2 size / (M P))^(1/3) rounded and lowered
 * to a divisor of size, then m ~ sqrt(M size / (P n)) lowered until m n divides size, p the rest;
 * m and p swapped when M > P but m < p. */
PetscErrorCode BalanceProcessGrid(const PetscInt n[3], PetscInt size, PetscInt p[3])
{
  const double M = (double)n[0], N = (double)n[1], Q = (double)n[2];
  PetscInt     pm, py, px, pz = 1;

  PetscFunctionBegin;
  PetscCheck(size >= 1, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "rank count %" PetscInt_FMT " must be >= 1", size);
  py = (PetscInt)(0.5 + pow(N * N * (double)size / (Q * M), 1. / 3.));
  if (!py) py = 1;
  while (py > 0) {
    pm = size / py;
    if (py * pm == size) break;
    py--;
  }
  if (!py) py = 1;
  px = (PetscInt)(0.5 + sqrt(M * (double)size / (Q * (double)py)));
  if (!px) px = 1;
  while (px > 0) {
    pz = size / (px * py);
    if (px * py * pz == size) break;
    px--;
  }
  if (M > Q && px < pz) {
    const PetscInt t = px;
    px = pz, pz = t;
  }
  p[0] = px, p[1] = py, p[2] = pz;
  PetscCheck(px * py * pz == size, PETSC_COMM_SELF, PETSC_ERR_PLIB, "no process grid for %" PetscInt_FMT " ranks", size);
  PetscFunctionReturn(PETSC_SUCCESS);
}
