/* balance-sim: what balanced cuts would buy at cluster scale, judged from one particle snapshot.
 * Reads a Sable HDF5 frame (/particles/position, /particles/radius if present), bins the
 * particle centres on a cartesian grid over the box, turns the counts into cell weights
 * W = alpha n + beta or alpha n^2 + beta (Golshan & Blais 2022, eqs. 1-2), and for each
 * hypothetical process grid compares three decompositions with the same code the run uses
 * (src/balance/cuts.c): (a) uniform cuts, what a DMDA does by default, (b) marginal
 * cuts, (c) the optimised cuts of BalanceCuts. Prints a markdown table: ranks, grid, and for
 * each method L_max/L_avg, L_min/L_avg and the ideal speed-up bound S = P L_avg / L_max (the
 * parallel efficiency if time were proportional to the load), and the time BalanceCuts took.
 * Serial; no MPI beyond PetscInitialize.
 * Options: -bsim_frame FILE (required); -domain_lo, -domain_hi (m; default: the particles'
 * extent, centres +- radius); -bsim_cell (m; default 8 r_max, Sable's dry background grid), or
 * -da_grid_x/y/z (cells); -bsim_ranks 8,64,512 (rank counts, factored as PETSc's DMDA does);
 * -bsim_grid px,py,pz[,px,py,pz...] (explicit grids); -bsim_minw (cells, default 1: the halo);
 * -lb_weight linear|quadratic, -lb_alpha (default 1), -lb_beta (default 0.02: alpha/beta = 50,
 * the best linear ratio of the paper). */
#include "io/io.h"
#include "balance/balance.h"

#define BSIM_MAX 32

typedef struct {
  char          frame[PETSC_MAX_PATH_LEN];
  PetscReal     lo[3], hi[3], h[3], cell;
  PetscInt      n[3], ranks[BSIM_MAX], nranks, grids[3 * BSIM_MAX], ngrids, minw, np;
  BalanceWeight wm;
  PetscReal    *w; /* cell weights */
} Sim;

static PetscErrorCode SimSetFromOptions(Sim *s, PetscBool *boxset)
{
  PetscBool set, lset, hset;

  PetscFunctionBeginUser;
  s->wm.model = BALANCE_WEIGHT_LINEAR, s->wm.alpha = 1, s->wm.beta = 0.02;
  s->minw = 1, s->cell = 0, s->nranks = BSIM_MAX, s->ngrids = 3 * BSIM_MAX;
  PetscOptionsBegin(PETSC_COMM_WORLD, NULL, "balance-sim: balanced cuts on a snapshot", NULL);
  PetscCall(PetscOptionsString("-bsim_frame", "Sable HDF5 frame with /particles/position", NULL, s->frame, s->frame, sizeof s->frame, NULL));
  PetscCall(SableOptionsRealN("-domain_lo", "Lower corner of the box; default: the particles' extent", "m", s->lo, 0, 3, &lset));
  PetscCall(SableOptionsRealN("-domain_hi", "Upper corner of the box; default: the particles' extent", "m", s->hi, 0, 3, &hset));
  PetscCall(PetscOptionsReal("-bsim_cell", "Cell size of the weight grid (m); default 8 r_max", NULL, s->cell, &s->cell, NULL));
  PetscCall(PetscOptionsIntArray("-bsim_ranks", "Rank counts, factored into a process grid as PETSc's DMDA does", NULL, s->ranks, &s->nranks, &set));
  if (!set) s->nranks = 0;
  PetscCall(PetscOptionsIntArray("-bsim_grid", "Explicit process grids px,py,pz[,px,py,pz...]", NULL, s->grids, &s->ngrids, &set));
  if (!set) s->ngrids = 0;
  PetscCall(PetscOptionsInt("-bsim_minw", "Smallest subdomain width (cells): the halo", NULL, s->minw, &s->minw, NULL));
  PetscCall(PetscOptionsEnum("-lb_weight", "Cell weight model: linear alpha n + beta, quadratic alpha n^2 + beta", NULL, BalanceWeightModels, (PetscEnum)s->wm.model, (PetscEnum *)&s->wm.model, NULL));
  PetscCall(PetscOptionsReal("-lb_alpha", "Weight of a particle (per particle or per particle^2)", NULL, s->wm.alpha, &s->wm.alpha, NULL));
  PetscCall(PetscOptionsReal("-lb_beta", "Weight of a cell", NULL, s->wm.beta, &s->wm.beta, NULL));
  PetscOptionsEnd();
  PetscCheck(s->frame[0], PETSC_COMM_WORLD, PETSC_ERR_ARG_WRONG, "-bsim_frame FILE is required (a Sable HDF5 frame)");
  PetscCheck(lset == hset, PETSC_COMM_WORLD, PETSC_ERR_ARG_WRONG, "give both -domain_lo and -domain_hi, or neither (the particles' extent)");
  PetscCheck(s->nranks + s->ngrids > 0, PETSC_COMM_WORLD, PETSC_ERR_ARG_WRONG, "give -bsim_ranks 8,64,512 and/or -bsim_grid px,py,pz");
  PetscCheck(s->ngrids % 3 == 0, PETSC_COMM_WORLD, PETSC_ERR_ARG_SIZ, "-bsim_grid takes triples px,py,pz; got %" PetscInt_FMT " values", s->ngrids);
  PetscCheck(s->minw >= 1, PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE, "-bsim_minw %" PetscInt_FMT " must be >= 1 (cells)", s->minw);
  PetscCheck(s->cell >= 0, PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE, "-bsim_cell %g must be > 0 (m)", (double)s->cell);
  *boxset = lset;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Box, grid and cell weights from the frame. */
static PetscErrorCode SimLoad(Sim *s, PetscBool boxset)
{
  PetscReal  *x, *r = NULL, rmax = 0;
  PetscInt    nc, nr, rc, *count, N;
  PetscBool   hasr, set;
  const char *opt[3] = {"-da_grid_x", "-da_grid_y", "-da_grid_z"};

  PetscFunctionBeginUser;
  PetscCall(IoReadDataset(s->frame, "/particles/position", &s->np, &nc, &x));
  PetscCheck(nc == 3 && s->np > 0, PETSC_COMM_WORLD, PETSC_ERR_FILE_UNEXPECTED, "%s: /particles/position has %" PetscInt_FMT " rows of %" PetscInt_FMT ", expected rows of 3", s->frame, s->np, nc);
  PetscCall(IoHasDataset(s->frame, "/particles/radius", &hasr));
  if (hasr) {
    PetscCall(IoReadDataset(s->frame, "/particles/radius", &nr, &rc, &r));
    PetscCheck(nr == s->np, PETSC_COMM_WORLD, PETSC_ERR_FILE_UNEXPECTED, "%s: %" PetscInt_FMT " radii for %" PetscInt_FMT " particles", s->frame, nr, s->np);
    for (PetscInt i = 0; i < nr; i++) rmax = PetscMax(rmax, r[i]);
  }
  if (!boxset)
    for (int d = 0; d < 3; d++) {
      s->lo[d] = PETSC_MAX_REAL, s->hi[d] = PETSC_MIN_REAL;
      for (PetscInt i = 0; i < s->np; i++) {
        s->lo[d] = PetscMin(s->lo[d], x[3 * i + d] - (r ? r[i] : 0));
        s->hi[d] = PetscMax(s->hi[d], x[3 * i + d] + (r ? r[i] : 0));
      }
    }
  if (s->cell == 0) s->cell = 8 * rmax;
  for (int d = 0; d < 3; d++) {
    PetscCheck(s->hi[d] > s->lo[d], PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE, "box along %c is empty: [%g, %g] m (give -domain_lo, -domain_hi)", "xyz"[d], (double)s -> lo[d], (double)s -> hi[d]);
    PetscCheck(s->cell > 0, PETSC_COMM_WORLD, PETSC_ERR_ARG_WRONG, "the frame has no radii: give -bsim_cell (m) or -da_grid_x/y/z");
    s->n[d] = PetscMax(1, (PetscInt)PetscFloorReal((s->hi[d] - s->lo[d]) / s->cell));
    PetscCall(PetscOptionsGetInt(NULL, NULL, opt[d], &s->n[d], &set));
    PetscCheck(s->n[d] >= 1, PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE, "%s %" PetscInt_FMT " must be >= 1", opt[d], s->n[d]);
    s->h[d] = (s->hi[d] - s->lo[d]) / s->n[d];
  }
  N = s->n[0] * s->n[1] * s->n[2];
  PetscCall(PetscCalloc1(N, &count));
  PetscCall(PetscMalloc1(N, &s->w));
  for (PetscInt i = 0; i < s->np; i++) {
    PetscInt c[3];
    for (int d = 0; d < 3; d++) c[d] = PetscMin(s->n[d] - 1, PetscMax(0, (PetscInt)PetscFloorReal((x[3 * i + d] - s->lo[d]) / s->h[d])));
    count[c[0] + s->n[0] * (c[1] + s->n[1] * c[2])]++;
  }
  PetscCall(BalanceCellWeights(&s->wm, N, count, s->w));
  PetscCall(PetscFree(count));
  PetscCall(PetscFree(x));
  PetscCall(PetscFree(r));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static void Stats(PetscInt P, const PetscReal *load, PetscReal avg, PetscReal *mx, PetscReal *mn)
{
  *mx = 0, *mn = PETSC_MAX_REAL;
  for (PetscInt r = 0; r < P; r++) *mx = PetscMax(*mx, load[r]), *mn = PetscMin(*mn, load[r]);
  *mx /= avg, *mn /= avg;
}

/* One table row: the three decompositions of process grid p. */
static PetscErrorCode SimRow(const Sim *s, PetscInt ranks, const PetscInt p[3])
{
  const BalanceGrid g = {{s->n[0], s->n[1], s->n[2]}, {p[0], p[1], p[2]}, {s->minw, s->minw, s->minw}, 0};
  const PetscInt    P = p[0] * p[1] * p[2];
  PetscInt         *l[3];
  PetscReal        *load, mx[3], mn[3], lmax, lavg;
  PetscLogDouble    t0, t1;

  PetscFunctionBeginUser;
  for (int d = 0; d < 3; d++)
    if (p[d] * s->minw > s->n[d]) {
      PetscCall(PetscPrintf(PETSC_COMM_WORLD, "| %" PetscInt_FMT " | %" PetscInt_FMT "x%" PetscInt_FMT "x%" PetscInt_FMT " | too fine: %" PetscInt_FMT " cells along %c for %" PetscInt_FMT " ranks of >= %" PetscInt_FMT " | | | | | | | | | |\n", ranks, p[0], p[1], p[2], s->n[d], "xyz"[d], p[d], s -> minw));
      PetscFunctionReturn(PETSC_SUCCESS);
    }
  PetscCall(PetscMalloc4(p[0], &l[0], p[1], &l[1], p[2], &l[2], P, &load));
  PetscCall(PetscTime(&t0));
  PetscCall(BalanceCuts(&g, s->w, l, &lmax, &lavg));
  PetscCall(PetscTime(&t1));
  PetscCall(BalanceLoads(&g, s->w, l, load));
  Stats(P, load, lavg, &mx[2], &mn[2]);
  PetscCall(BalanceUniformCuts(&g, l));
  PetscCall(BalanceLoads(&g, s->w, l, load));
  Stats(P, load, lavg, &mx[0], &mn[0]);
  PetscCall(BalanceMarginalCuts(&g, s->w, l));
  PetscCall(BalanceLoads(&g, s->w, l, load));
  Stats(P, load, lavg, &mx[1], &mn[1]);
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "| %" PetscInt_FMT " | %" PetscInt_FMT "x%" PetscInt_FMT "x%" PetscInt_FMT, ranks, p[0], p[1], p[2]));
  for (int m = 0; m < 3; m++) PetscCall(PetscPrintf(PETSC_COMM_WORLD, " | %.3f | %.3f | %.1f", (double)mx[m], (double)mn[m], (double)(P / mx[m])));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, " | %.3f |\n", (double)(t1 - t0)));
  PetscCall(PetscFree4(l[0], l[1], l[2], load));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  Sim       s;
  PetscBool boxset = PETSC_FALSE;
  PetscReal total  = 0;

  PetscCall(PetscInitialize(&argc, &argv, NULL, "balance-sim: balanced cuts judged on a particle snapshot\n"));
  PetscCall(PetscMemzero(&s, sizeof s));
  PetscCall(SimSetFromOptions(&s, &boxset));
  PetscCall(SimLoad(&s, boxset));
  for (PetscInt c = 0; c < s.n[0] * s.n[1] * s.n[2]; c++) total += s.w[c];
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "frame %s: %" PetscInt_FMT " particles; box [%g, %g] x [%g, %g] x [%g, %g] m; %" PetscInt_FMT " x %" PetscInt_FMT " x %" PetscInt_FMT " cells of %.4g x %.4g x %.4g m; weight %s alpha %g beta %g (total %g); minimum width %" PetscInt_FMT " cells\n\n", s.frame, s.np, (double)s.lo[0], (double)s.hi[0], (double)s.lo[1], (double)s.hi[1], (double)s.lo[2], (double)s.hi[2], s.n[0], s.n[1], s.n[2], (double)s.h[0], (double)s.h[1], (double)s.h[2], BalanceWeightModels[s.wm.model], (double)s.wm.alpha, (double)s.wm.beta, (double)total, s.minw));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "| ranks | grid | uniform max/avg | min/avg | S | marginal max/avg | min/avg | S | optimised max/avg | min/avg | S | t_opt (s) |\n"));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "|---|---|---|---|---|---|---|---|---|---|---|---|\n"));
  for (PetscInt i = 0; i < s.nranks; i++) {
    PetscInt p[3];
    PetscCheck(s.ranks[i] >= 1, PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE, "-bsim_ranks: %" PetscInt_FMT " must be >= 1", s.ranks[i]);
    PetscCall(BalanceProcessGrid(s.n, s.ranks[i], p));
    PetscCall(SimRow(&s, s.ranks[i], p));
  }
  for (PetscInt i = 0; i < s.ngrids / 3; i++) {
    const PetscInt *p = s.grids + 3 * i;
    PetscCheck(p[0] >= 1 && p[1] >= 1 && p[2] >= 1, PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE, "-bsim_grid %" PetscInt_FMT ",%" PetscInt_FMT ",%" PetscInt_FMT ": every count must be >= 1", p[0], p[1], p[2]);
    PetscCall(SimRow(&s, p[0] * p[1] * p[2], p));
  }
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "\nS = P L_avg / L_max: the speed-up bound if time were proportional to the load (P = ranks).\n"));
  PetscCall(PetscFree(s.w));
  PetscCall(PetscFinalize());
  return 0;
}
