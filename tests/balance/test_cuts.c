/* Balanced cuts of the tensor-product decomposition (src/balance/cuts.c).
 *
 * The cuts must be valid (sum to n, every part >= minw), reproduce the obvious optimum on uniform
 * weights and on a column whose weight lies in its bottom third, never be worse than the
 * marginal cuts they start from, and come close to the true optimum, which brute force over
 * every cut position finds on small grids (the measured gap is printed: 0 means the optimum was
 * found). Loads of integer-valued weights must sum to the total exactly. Bad input stops with
 * PETSC_ERR_ARG_OUTOFRANGE naming the axis or the cell. Finally the DMDA-like process grid and
 * uniform cuts are compared with a real DMDA on this communicator.
 */
/* ranks: 1 4 */
#include "check.h"
#include "balance/balance.h"

static unsigned long long rng_state = 88172645463325252ULL;

static double rng(void) /* xorshift64, uniform in [0, 1) */
{
  rng_state ^= rng_state << 13;
  rng_state ^= rng_state >> 7;
  rng_state ^= rng_state << 17;
  return (double)(rng_state >> 11) / 9007199254740992.0;
}

static PetscBool CutsValid(const BalanceGrid *g, PetscInt *const l[3])
{
  for (int d = 0; d < 3; d++) {
    PetscInt s = 0;
    for (PetscInt r = 0; r < g->p[d]; r++) {
      if (l[d][r] < g->minw[d]) return PETSC_FALSE;
      s += l[d][r];
    }
    if (s != g->n[d]) return PETSC_FALSE;
  }
  return PETSC_TRUE;
}

static PetscErrorCode MaxLoad(const BalanceGrid *g, const PetscReal *w, PetscInt *const l[3], PetscReal *lmax)
{
  PetscReal load[512];

  PetscFunctionBeginUser;
  PetscCall(BalanceLoads(g, w, l, load));
  *lmax = 0;
  for (PetscInt r = 0; r < g->p[0] * g->p[1] * g->p[2]; r++) *lmax = PetscMax(*lmax, load[r]);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* every composition of n into p parts >= minw, appended to list (p entries each) */
static void Compositions(PetscInt n, PetscInt p, PetscInt minw, PetscInt *cur, PetscInt depth, PetscInt *list, PetscInt *count)
{
  if (depth == p - 1) {
    cur[depth] = n;
    for (PetscInt i = 0; i < p; i++) list[*count * p + i] = cur[i];
    (*count)++;
    return;
  }
  for (PetscInt v = minw; n - v >= (p - 1 - depth) * minw; v++) {
    cur[depth] = v;
    Compositions(n - v, p, minw, cur, depth + 1, list, count);
  }
}

/* the optimal L_max over all cut positions (small grids only) */
static PetscErrorCode BruteForce(const BalanceGrid *g, const PetscReal *w, PetscReal *best)
{
  PetscInt *list[3], cnt[3], cur[16];

  PetscFunctionBeginUser;
  for (int d = 0; d < 3; d++) {
    PetscCall(PetscMalloc1(20000 * g->p[d], &list[d]));
    cnt[d] = 0;
    Compositions(g->n[d], g->p[d], g->minw[d], cur, 0, list[d], &cnt[d]);
  }
  *best = PETSC_MAX_REAL;
  for (PetscInt a = 0; a < cnt[0]; a++)
    for (PetscInt b = 0; b < cnt[1]; b++)
      for (PetscInt c = 0; c < cnt[2]; c++) {
        PetscInt *const l[3] = {list[0] + a * g->p[0], list[1] + b * g->p[1], list[2] + c * g->p[2]};
        PetscReal       m    = 0;
        PetscCall(MaxLoad(g, w, l, &m));
        *best = PetscMin(*best, m);
      }
  for (int d = 0; d < 3; d++) PetscCall(PetscFree(list[d]));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* kind 0: uniform random in [0, 1); kind 1: sparse hot spots over a small cell weight; kind 2:
 * a settled bed (particles below a random height, denser at the bottom, a random empty corner) */
static void RandomWeights(const BalanceGrid *g, int kind, PetscReal *w)
{
  const PetscInt  N   = g->n[0] * g->n[1] * g->n[2];
  const PetscReal top = 0.3 + 0.5 * rng(), cx = rng(), cy = rng();
  for (PetscInt c = 0; c < N; c++) {
    const PetscReal x = ((c % g->n[0]) + 0.5) / g->n[0], y = (((c / g->n[0]) % g->n[1]) + 0.5) / g->n[1], z = ((c / (g->n[0] * g->n[1])) + 0.5) / g->n[2];
    if (kind == 0) w[c] = rng();
    else if (kind == 1) w[c] = 0.1 + (rng() < 0.1 ? 10 + 90 * rng() : 0);
    else w[c] = 0.05 + ((z < top && (x - cx) * (x - cx) + (y - cy) * (y - cy) > 0.1) ? PetscFloorReal(8 * (1 - 0.5 * z / top) * (0.5 + rng())) : 0);
  }
}

static PetscErrorCode TestBruteForce(const char *label, const BalanceGrid *g, PetscInt trials)
{
  const PetscInt  N = g->n[0] * g->n[1] * g->n[2];
  PetscReal      *w, worst = 0, worse_than_marginal = 0, worst_initial = 0;
  PetscInt        lx[8], ly[8], lz[8], mx[8], my[8], mz[8], exact[3] = {0, 0, 0}, valid = 0;
  PetscInt *const l[3] = {lx, ly, lz}, *const m[3] = {mx, my, mz};
  const char *kinds[3] = {"uniform random", "hot spots", "settled bed"};

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(N, &w));
  for (int kind = 0; kind < 3; kind++) {
    PetscReal gap = 0, mean = 0;
    for (PetscInt t = 0; t < trials; t++) {
      PetscReal lmax, lavg, opt = 0, marg = 0;
      RandomWeights(g, kind, w);
      PetscCall(BalanceCuts(g, w, l, &lmax, &lavg));
      PetscCall(BalanceMarginalCuts(g, w, m));
      PetscCall(MaxLoad(g, w, m, &marg));
      PetscCall(BruteForce(g, w, &opt));
      valid += CutsValid(g, l) && CutsValid(g, m);
      gap = PetscMax(gap, lmax / opt - 1);
      mean += (lmax / opt - 1) / trials;
      exact[kind] += lmax <= opt * (1 + 1e-12);
      worse_than_marginal = PetscMax(worse_than_marginal, lmax / marg - 1);
      worst_initial       = PetscMax(worst_initial, marg / opt - 1);
    }
    CheckDetail("optimum found in %" PetscInt_FMT " of %" PetscInt_FMT " trials", exact[kind], trials);
    PetscCall(CheckAtMost(CheckName("%s, %s: gap L_max/L_opt - 1, mean", label, kinds[kind]), mean, 0.01));
    PetscCall(CheckAtMost(CheckName("%s, %s: gap L_max/L_opt - 1, largest", label, kinds[kind]), gap, 0.15));
    worst = PetscMax(worst, gap);
  }
  PetscCall(CheckEqual(CheckName("%s: cases whose cuts sum to n and respect minw", label), valid, 3 * trials));
  CheckDetail("marginal cuts were up to %.3f above the optimum", (double)worst_initial);
  PetscCall(CheckAtMost(CheckName("%s: never worse than the marginal cuts: max(L_max/L_marginal - 1)", label), worse_than_marginal, 1e-12));
  PetscCall(PetscFree(w));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode TestUniform(void)
{
  const BalanceGrid g = {{12, 12, 12}, {2, 3, 4}, {1, 1, 1}, 0};
  PetscReal         w[1728], lmax, lavg;
  PetscInt          lx[2], ly[3], lz[4], eq = 1;
  PetscInt *const   l[3] = {lx, ly, lz};

  PetscFunctionBeginUser;
  for (PetscInt c = 0; c < 1728; c++) w[c] = 1.5;
  PetscCall(BalanceCuts(&g, w, l, &lmax, &lavg));
  for (int d = 0; d < 3; d++)
    for (PetscInt r = 0; r < g.p[d]; r++) eq = eq && l[d][r] == g.n[d] / g.p[d];
  PetscCall(CheckTrue("uniform weights, 12^3 cells on 2x3x4: equal cuts", (PetscBool)eq, NULL));
  PetscCall(CheckClose("uniform weights, 12^3 cells on 2x3x4: L_max/L_avg", lmax / lavg, 1.0, 1e-14));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* a column whose weight (particles) lies in its bottom third, 1x1x4 ranks */
static PetscErrorCode TestColumn(void)
{
  const BalanceGrid   g  = {{4, 4, 72}, {1, 1, 4}, {1, 1, 2}, 0};
  const BalanceWeight wm = {BALANCE_WEIGHT_LINEAR, 1.0, 0.0};
  PetscInt            count[1152], lz[4], mz[4], one[2] = {4, 4}, cnt = 0, *list;
  PetscInt *const l[3] = {one, one + 1, lz}, *const m[3] = {one, one + 1, mz};
  PetscReal w[1152], lmax, lavg, marg = 0, opt = PETSC_MAX_REAL;
  PetscInt  cur[4];

  PetscFunctionBeginUser;
  for (PetscInt c = 0; c < 1152; c++) count[c] = (c / 16 < 24) ? (PetscInt)(10 * rng()) : 0;
  PetscCall(BalanceCellWeights(&wm, 1152, count, w));
  PetscCall(BalanceCuts(&g, w, l, &lmax, &lavg));
  PetscCall(BalanceMarginalCuts(&g, w, m));
  PetscCall(MaxLoad(&g, w, m, &marg));
  PetscCall(PetscMalloc1(4 * 50000, &list));
  Compositions(72, 4, 2, cur, 0, list, &cnt);
  for (PetscInt a = 0; a < cnt; a++) {
    PetscInt *const lb[3] = {one, one + 1, list + 4 * a};
    PetscReal       mm    = 0;
    PetscCall(MaxLoad(&g, w, lb, &mm));
    opt = PetscMin(opt, mm);
  }
  PetscCall(PetscFree(list));
  CheckDetail("cuts %" PetscInt_FMT ",%" PetscInt_FMT ",%" PetscInt_FMT ",%" PetscInt_FMT "; marginal cuts %.4f, uniform cuts 4.0", lz[0], lz[1], lz[2], lz[3], (double)(marg / lavg));
  PetscCall(CheckBelow("column, weight in the bottom third, 1x1x4 ranks: L_max/L_avg", lmax / lavg, 1.05));
  CheckDetail("bound L_opt (1 + 1e-12); L_max/L_opt - 1 = %.1e", (double)(lmax / opt - 1));
  PetscCall(CheckAtMost(CheckName("column: L_max equal to the brute-force optimum over %" PetscInt_FMT " cuts", cnt), lmax, opt * (1 + 1e-12)));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* all the weight in 3 planes, minw 3: the optimum wants thinner parts than allowed */
static PetscErrorCode TestMinWidth(void)
{
  const BalanceGrid g = {{4, 4, 30}, {1, 1, 5}, {1, 1, 3}, 0};
  PetscReal         w[480], lmax, lavg, opt = PETSC_MAX_REAL;
  PetscInt          one[2] = {4, 4}, lz[5], mn = 30, cur[5], cnt = 0, *list;
  PetscInt *const   l[3] = {one, one + 1, lz};

  PetscFunctionBeginUser;
  for (PetscInt c = 0; c < 480; c++) w[c] = (c / 16 >= 10 && c / 16 < 13) ? 1 + rng() : 0;
  PetscCall(BalanceCuts(&g, w, l, &lmax, &lavg));
  for (PetscInt r = 0; r < 5; r++) mn = PetscMin(mn, lz[r]);
  PetscCall(PetscMalloc1(5 * 5000, &list));
  Compositions(30, 5, 3, cur, 0, list, &cnt);
  for (PetscInt a = 0; a < cnt; a++) {
    PetscInt *const lb[3] = {one, one + 1, list + 5 * a};
    PetscReal       mm    = 0;
    PetscCall(MaxLoad(&g, w, lb, &mm));
    opt = PetscMin(opt, mm);
  }
  PetscCall(PetscFree(list));
  PetscCall(CheckTrue("weight in 3 planes, 5 ranks, minw 3: cuts valid (sum to 30, parts >= minw)", CutsValid(&g, l), NULL));
  PetscCall(CheckAtLeast("weight in 3 planes, 5 ranks, minw 3: narrowest part [cells]", mn, 3));
  CheckDetail("bound L_opt (1 + 1e-12); L_max/L_opt - 1 = %.1e, L_max/L_avg = %.3f", (double)(lmax / opt - 1), (double)(lmax / lavg));
  PetscCall(CheckAtMost(CheckName("same: L_max equal to the brute-force optimum over %" PetscInt_FMT " cuts with minw 3", cnt), lmax, opt * (1 + 1e-12)));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* integer-valued weights: every partial sum is exact in double */
static PetscErrorCode TestLoadSum(void)
{
  const BalanceGrid   g  = {{13, 7, 11}, {3, 2, 2}, {2, 2, 2}, 0};
  const BalanceWeight wm = {BALANCE_WEIGHT_QUADRATIC, 2.0, 1.0};
  PetscInt            count[1001], lx[3], ly[2], lz[2];
  PetscInt *const     l[3] = {lx, ly, lz};
  PetscReal           w[1001], load[12], lmax, lavg, sum = 0, total = 0;

  PetscFunctionBeginUser;
  for (PetscInt c = 0; c < 1001; c++) count[c] = (PetscInt)(6 * rng() * rng());
  PetscCall(BalanceCellWeights(&wm, 1001, count, w));
  for (PetscInt c = 0; c < 1001; c++) total += w[c];
  PetscCall(BalanceCuts(&g, w, l, &lmax, &lavg));
  PetscCall(BalanceLoads(&g, w, l, load));
  for (PetscInt r = 0; r < 12; r++) sum += load[r];
  PetscCall(CheckEqualReal("rank loads (quadratic weights 2 n^2 + 1) sum to the total", sum, total));
  PetscCall(CheckEqualReal("rank loads: 12 L_avg is the total", lavg * 12, total));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* degenerate input: no weight at all, a grid exactly p minw wide, a single rank */
static PetscErrorCode TestEdges(void)
{
  const BalanceGrid g0 = {{6, 5, 7}, {2, 1, 3}, {1, 1, 2}, 0}, g1 = {{6, 5, 9}, {3, 1, 3}, {2, 1, 3}, 0}, g2 = {{6, 5, 7}, {1, 1, 1}, {1, 1, 1}, 0};
  PetscReal         w[270], lmax = -1, lavg = -1, l1max, l1avg, l2max, l2avg, total = 0;
  PetscInt          a[3], b[3], c[3];
  PetscInt *const   l[3] = {a, b, c};
  PetscBool         ok0, ok1, ok2;

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < 270; i++) w[i] = 0;
  PetscCall(BalanceCuts(&g0, w, l, &lmax, &lavg));
  ok0 = (PetscBool)(CutsValid(&g0, l) && lmax == 0 && lavg == 0);
  for (PetscInt i = 0; i < 270; i++) w[i] = rng();
  for (PetscInt i = 0; i < 210; i++) total += w[i]; /* g2 has 210 cells */
  PetscCall(BalanceCuts(&g1, w, l, &l1max, &l1avg));
  ok1 = (PetscBool)(CutsValid(&g1, l) && a[0] == 2 && a[2] == 2 && c[0] == 3 && c[2] == 3);
  PetscCall(BalanceCuts(&g2, w, l, &l2max, &l2avg));
  ok2 = (PetscBool)(a[0] == 6 && b[0] == 5 && c[0] == 7 && PetscAbsReal(l2max - total) <= 1e-13 * total && l2max == l2avg);
  PetscCall(CheckTrue("edge case zero weights: valid cuts, L_max = L_avg = 0", ok0, NULL));
  PetscCall(CheckTrue("edge case n = p minw exactly: all parts minw", ok1, NULL));
  PetscCall(CheckTrue("edge case one rank: whole grid, L_max = total", ok2, NULL));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static char last_msg[1024];

static PetscErrorCode RecordError(MPI_Comm comm, int line, const char *fun, const char *file, PetscErrorCode n, PetscErrorType p, const char *mess, void *ctx)
{
  (void)comm, (void)line, (void)fun, (void)file, (void)ctx;
  if (p == PETSC_ERROR_INITIAL) snprintf(last_msg, sizeof last_msg, "%s", mess ? mess : "");
  return n;
}

static PetscErrorCode TestErrors(void)
{
  const BalanceGrid thin = {{8, 6, 10}, {2, 2, 4}, {1, 1, 3}, 0}, g = {{2, 2, 2}, {1, 1, 2}, {1, 1, 1}, 0};
  PetscReal         w[8] = {1, 1, 1, 1, 1, 1, 1, 1}, lmax, lavg;
  PetscInt          a[4], b[4], c[4];
  PetscInt *const   l[3] = {a, b, c};
  PetscErrorCode    ierr;

  PetscFunctionBeginUser;
  PetscCall(PetscPushErrorHandler(RecordError, NULL));
  ierr = BalanceCuts(&thin, w, l, &lmax, &lavg);
  PetscCall(CheckEqual("10 cells, 4 ranks, minw 3 along z rejected: error code", ierr, PETSC_ERR_ARG_OUTOFRANGE));
  PetscCall(CheckTrue("10 cells, 4 ranks, minw 3 along z rejected: the message names the axis and the ranks", (PetscBool)(strstr(last_msg, "axis z: 10 cells") && strstr(last_msg, "4 ranks of at least 3")), last_msg));
  w[5] = -1;
  ierr = BalanceCuts(&g, w, l, &lmax, &lavg);
  PetscCall(CheckEqual("negative weight rejected: error code", ierr, PETSC_ERR_ARG_OUTOFRANGE));
  PetscCall(CheckTrue("negative weight rejected: the message names the cell", (PetscBool) !!strstr(last_msg, "cell (1, 0, 1)"), last_msg));
  w[5] = NAN;
  ierr = BalanceCuts(&g, w, l, &lmax, &lavg);
  PetscCall(CheckEqual("NaN weight rejected: error code", ierr, PETSC_ERR_ARG_OUTOFRANGE));
  PetscCall(CheckTrue("NaN weight rejected: the message says nan", (PetscBool) !!strstr(last_msg, "nan"), last_msg));
  PetscCall(PetscPopErrorHandler());
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* BalanceProcessGrid and BalanceUniformCuts against a real DMDA on this communicator */
static PetscErrorCode TestDMDA(void)
{
  const PetscInt grids[3][3] = {{20, 10, 30}, {40, 8, 8}, {9, 27, 12}};
  PetscMPIInt    size;
  PetscInt       bad = 0;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));
  for (int t = 0; t < 3; t++) {
    DM              da;
    PetscInt        p[3], q[3], lx[64], ly[64], lz[64];
    PetscInt *const l[3] = {lx, ly, lz};
    const PetscInt *own[3];
    PetscCall(DMDACreate3d(PETSC_COMM_WORLD, DM_BOUNDARY_NONE, DM_BOUNDARY_NONE, DM_BOUNDARY_NONE, DMDA_STENCIL_BOX, grids[t][0], grids[t][1], grids[t][2], PETSC_DECIDE, PETSC_DECIDE, PETSC_DECIDE, 1, 1, NULL, NULL, NULL, &da));
    PetscCall(DMSetUp(da));
    PetscCall(DMDAGetInfo(da, NULL, NULL, NULL, NULL, &p[0], &p[1], &p[2], NULL, NULL, NULL, NULL, NULL, NULL));
    PetscCall(DMDAGetOwnershipRanges(da, &own[0], &own[1], &own[2]));
    PetscCall(BalanceProcessGrid(grids[t], size, q));
    {
      const BalanceGrid g = {{grids[t][0], grids[t][1], grids[t][2]}, {q[0], q[1], q[2]}, {1, 1, 1}, 0};
      PetscCall(BalanceUniformCuts(&g, l));
    }
    for (int d = 0; d < 3; d++) {
      bad += p[d] != q[d];
      for (PetscInt r = 0; r < p[d] && p[d] == q[d]; r++) bad += own[d][r] != l[d][r];
    }
    PetscCall(DMDestroy(&da));
  }
  PetscCall(CheckEqual(CheckName("process grid and uniform cuts equal a real DMDA's on %d ranks (3 grids): differences", (int)size), bad, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  const BalanceGrid g1 = {{8, 6, 10}, {2, 2, 2}, {1, 1, 1}, 0}, g2 = {{8, 6, 10}, {3, 2, 2}, {2, 1, 2}, 0}, g3 = {{7, 7, 12}, {2, 2, 3}, {1, 1, 2}, 0};

  PetscCall(PetscInitialize(&argc, &argv, NULL, "balanced cuts test"));
  PetscCall(TestUniform());
  PetscCall(TestColumn());
  PetscCall(TestMinWidth());
  PetscCall(TestLoadSum());
  PetscCall(TestEdges());
  PetscCall(TestBruteForce("n 8x6x10 on 2x2x2", &g1, 50));
  PetscCall(TestBruteForce("n 8x6x10 on 3x2x2, minw 2,1,2", &g2, 50));
  PetscCall(TestBruteForce("n 7x7x12 on 2x2x3, minw 1,1,2", &g3, 20));
  PetscCall(TestErrors());
  PetscCall(TestDMDA());
  PetscCall(PetscFinalize());
  return check_failures ? 1 : 0;
}
