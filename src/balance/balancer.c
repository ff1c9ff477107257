/* The load balancer at run time (Golshan & Blais 2022, after Lethe-DEM; DESIGN §1): when its
 * scheme says so it weighs every cell of the Domain's grid, W = alpha n_p + beta (linear) or
 * alpha n_p^2 + beta (quadratic), n_p the particles whose centre lies in the cell, sums the
 * weights over each rank's box into the loads L, and, if it rebalances, computes new per-axis
 * cuts (cuts.c), rebuilds the DMDA with them and moves the fluid fields and the
 * particles onto it, so each rank still owns matching fluid and particle subdomains.
 * Schemes (-lb_scheme): none; once (at -lb_step or -lb_time); frequent (after the first step,
 * then every -lb_interval steps or -lb_interval_time seconds of simulated time); dynamic (checked
 * at that cadence, rebalances when L_max - L_min > eps L_avg, eps = -lb_threshold). Weights (-lb_weight): linear,
 * quadratic (-lb_alpha, -lb_beta) or measured: linear with alpha the measured compute time per
 * particle-step and beta the measured fluid time per cell-step since the last check (beta = 0
 * in a dry run), so the particle/cell ratio follows the machine and the case instead of a
 * hand-set ratio. A rank box never becomes thinner than the DEM halo (2 r_max + skin), the
 * DMDA stencil, or the fluid's two cells. Each check prints one line: the loads, the imbalance,
 * whether it rebalanced and the wall time the check and the move cost.
 * The per-cell particle counts are reduced onto every rank (one integer per cell), which bounds the
 * method to grids of a few million cells; the cut search itself is serial and identical on all
 * ranks. A checkpoint holds the cuts, the schedule and the counters (BalanceCheckpointWrite/Read),
 * so a restart continues on the run's decomposition and checks when the run would have.
 * With mesh walls a cell also weighs alpha c_m n_c, n_c the candidate triangles of its particles
 * (-lb_mesh_cost c_m; measured: the mesh contact loop's time per candidate-step over alpha). */
#include "balance/balancer.h"

typedef enum {
  LB_NONE,
  LB_ONCE,
  LB_FREQUENT,
  LB_DYNAMIC
} LbScheme;
static const char *const LbSchemeNames[] = {"none", "once", "frequent", "dynamic", "LbScheme", "LB_", NULL};
/* -lb_mesh_cost's default: the time of one candidate triangle in the mesh contact loop over the
 * time of one particle-step without it (tools/bench_mesh.sh's bed, doc/performance.md). */
#define BALANCE_MESH_COST 1.3
static const char *const LbWeightNames[] = {"linear", "quadratic", "measured", "LbWeight", "LB_WEIGHT_", NULL};

struct _p_Balance {
  MPI_Comm    comm;
  Domain     *dom;
  Dem         dem;
  Cpl         cpl; /* NULL in a dry run */
  LbScheme    scheme;
  PetscInt    weight; /* 0 linear, 1 quadratic, 2 measured */
  PetscReal   alpha, beta, threshold, once_time, interval_time, next_time;
  PetscInt    once_step, interval, max_sweeps, last_step;
  PetscBool   done_once, verbose;
  BalanceGrid g;
  PetscReal  *w, *load, alpha_used, beta_used;
  PetscInt   *count; /* particles per cell of the global grid */
  /* mesh walls: W gains alpha c_m n_c, n_c the candidate triangles of the cell's particles */
  PetscInt      *ncand; /* per cell of the global grid; NULL without meshes */
  PetscReal      mesh_cost, cm_used;
  PetscBool      mesh_clock; /* the mesh clock covers the time since the last check (not after a restore) */
  PetscLogDouble t_mesh0;
  PetscReal      cand0;
  PetscInt      *l[3];
  /* measured weights: compute times and work at the last check */
  PetscLogDouble t_dem0, t_fluid0;
  PetscInt       cstep0; /* coupling step of the last check */
  /* totals for the summary */
  PetscInt       checks, rebalances;
  PetscLogDouble t_total;
  /* restored from a checkpoint (BalanceCheckpointRead): the schedule is kept by BalanceSetUp,
     and the compute time since the last check carried over (dem, fluid) */
  PetscBool      restored;
  PetscLogDouble t_since[2];
  PetscBool      ckpt_cuts; /* the Domain holds a checkpoint's cuts: BalanceDecompose keeps them */
  /* a coupled run's vessel (DemVesselLevel): the cells whose centre lies in the solid, which
     carry no fluid cost; NULL without a vessel (the weights of before, bit for bit) */
  PetscBool *closed;
  PetscBool  closed_set;
};

PetscErrorCode BalanceCreate(Domain *dom, Dem dem, Cpl cpl, Balance *lb)
{
  Balance b;

  PetscFunctionBeginUser;
  PetscCall(PetscNew(&b));
  b->comm          = dom->comm;
  b->dom           = dom;
  b->dem           = dem;
  b->cpl           = cpl;
  b->alpha         = 1.0;
  b->beta          = 0.02; /* alpha/beta = 50: Lethe's best linear ratio (§3.2) */
  b->threshold     = 0.8;  /* Lethe's silo (§3.5) */
  b->interval      = 1000;
  b->interval_time = 0;
  b->once_step     = 0;
  b->once_time     = -1;
  b->verbose       = PETSC_TRUE;
  b->mesh_cost     = BALANCE_MESH_COST;
  *lb              = b;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode BalanceSetFromOptions(Balance b)
{
  PetscBool set[4]; /* -lb_interval, -lb_step, -lb_interval_time, -lb_time given */
  PetscInt  scheme;

  PetscFunctionBeginUser;
  PetscOptionsBegin(b->comm, NULL, "Load balancing (moves the shared DMDA cuts)", NULL);
  PetscCall(SableOptionsEnum("-lb_scheme", "When to rebalance", LbSchemeNames, 4, (PetscInt)b->scheme, &scheme, NULL));
  b->scheme = (LbScheme)scheme;
  PetscCall(SableOptionsEnum("-lb_weight", "Cell weight: linear alpha n + beta, quadratic alpha n^2 + beta, measured (linear, alpha and beta from measured costs)", LbWeightNames, 3, b->weight, &b->weight, NULL));
  PetscCall(SableOptionsReal("-lb_alpha", "Weight of a particle in a cell", NULL, "[0,inf)", b->alpha, &b->alpha, NULL));
  PetscCall(SableOptionsReal("-lb_beta", "Weight of a cell", NULL, "[0,inf)", b->beta, &b->beta, NULL));
  PetscCall(SableOptionsReal("-lb_threshold", "dynamic: rebalance when (L_max - L_min) / L_avg exceeds it", NULL, "(0,inf)", b->threshold, &b->threshold, NULL));
  PetscCall(SableOptionsInt("-lb_interval", "frequent/dynamic: steps between checks", NULL, "[1,inf)", b->interval, &b->interval, &set[0]));
  PetscCall(SableOptionsReal("-lb_interval_time", "frequent/dynamic: simulated time between checks (replaces -lb_interval); default none: -lb_interval counts", "s", "(0,inf)", b->interval_time, &b->interval_time, &set[2]));
  PetscCall(SableOptionsInt("-lb_step", "once: the step after which to rebalance", NULL, "[0,inf)", b->once_step, &b->once_step, &set[1]));
  PetscCall(SableOptionsReal("-lb_time", "once: the simulated time after which to rebalance (replaces -lb_step); default none: -lb_step counts", "s", "[0,inf)", b->once_time, &b->once_time, &set[3]));
  PetscCall(SableOptionsInt("-lb_max_sweeps", "Coordinate-descent rounds of the cut search (0: the marginal cuts only get refined by the default 20)", NULL, "[0,inf)", b->max_sweeps, &b->max_sweeps, NULL));
  PetscCall(SableOptionsReal("-lb_mesh_cost", "Weight of a particle's candidate mesh triangle relative to the particle (linear, quadratic; -lb_weight measured measures it)", NULL, "[0,inf)", b->mesh_cost, &b->mesh_cost, NULL));
  PetscCall(SableOptionsBool("-lb_verbose", "Print one line per check", b->verbose, &b->verbose, NULL));
  PetscOptionsEnd();
  { /* the time-based option replaces the step-based one: both given, one would be ignored */
    const char *steps[2] = {"-lb_interval", "-lb_step"}, *times[2] = {"-lb_interval_time", "-lb_time"};
    for (int k = 0; k < 2; k++)
      PetscCheck(!set[k] || !set[k + 2], b->comm, PETSC_ERR_ARG_INCOMP, "%s and %s are both given; %s replaces %s, which would be ignored: give one of them", steps[k], times[k], times[k], steps[k]);
  }
  PetscCheck(b->alpha > 0 || b->beta > 0, b->comm, PETSC_ERR_ARG_OUTOFRANGE, "-lb_alpha and -lb_beta are both 0: every cell would weigh nothing");
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The thinnest box along axis k in cells: the DEM halo and the DMDA stencil when the axis is
 * split or periodic, and the coupling's (CplGetMinBoxWidth: two cells for the fluid's stencils,
 * more for -cpl_porosity_width's grid on a split or periodic axis). */
static PetscErrorCode BalanceMinWidth(Balance b, PetscInt minw[3])
{
  PetscReal reach;
  PetscInt  sw, cw[3] = {0, 0, 0}; /* the coupling's thinnest box (cells), 0 in a dry run */

  PetscFunctionBeginUser;
  PetscCall(DemGetHaloWidth(b->dem, &reach));
  PetscCall(DMDAGetInfo(b->dom->da, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL, &sw, NULL, NULL, NULL, NULL));
  if (b->cpl) PetscCall(CplGetMinBoxWidth(b->cpl, cw));
  for (int k = 0; k < 3; k++) {
    minw[k] = PetscMax(1, sw);
    if (b->dom->nranks[k] > 1 || b->dom->periodic[k]) minw[k] = PetscMax(minw[k], (PetscInt)PetscCeilReal(reach / b->dom->h[k] * (1 - 1e-12)));
    minw[k] = PetscMax(minw[k], b->dom->nranks[k] > 1 || b->dom->periodic[k] ? cw[k] : PetscMin(cw[k], 2));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode BalanceSetUp(Balance b)
{
  PetscInt ncell, nmesh;

  PetscFunctionBeginUser;
  for (int k = 0; k < 3; k++) {
    b->g.n[k] = b->dom->cells[k];
    b->g.p[k] = b->dom->nranks[k];
  }
  b->g.max_sweeps = b->max_sweeps;
  PetscCall(BalanceMinWidth(b, b->g.minw));
  ncell = b->g.n[0] * b->g.n[1] * b->g.n[2];
  PetscCall(PetscMalloc3(ncell, &b->count, ncell, &b->w, b->g.p[0] * b->g.p[1] * b->g.p[2], &b->load));
  for (int k = 0; k < 3; k++) PetscCall(PetscMalloc1(b->g.p[k], &b->l[k]));
  PetscCall(DemGetMeshCount(b->dem, &nmesh));
  if (nmesh) PetscCall(PetscMalloc1(ncell, &b->ncand));
  PetscCall(DemGetMeshTime(b->dem, &b->t_mesh0, &b->cand0));
  b->mesh_clock = (PetscBool)!b->restored;
  b->cm_used    = b->mesh_cost;
  /* frequent and dynamic check after the first step (a start, or a restart on another rank
     count, may be imbalanced), then at their cadence; a restart keeps the run's schedule */
  if (!b->restored) {
    PetscCall(DemGetTime(b->dem, &b->next_time, &b->last_step));
    b->last_step -= b->interval;
  }
  PetscCall(DemGetComputeTime(b->dem, &b->t_dem0));
  b->t_dem0 -= b->t_since[0];
  b->t_fluid0 -= b->t_since[1];
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode BalanceDestroy(Balance *lb)
{
  PetscFunctionBeginUser;
  if (!*lb) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscFree3((*lb)->count, (*lb)->w, (*lb)->load));
  for (int k = 0; k < 3; k++) PetscCall(PetscFree((*lb)->l[k]));
  PetscCall(PetscFree((*lb)->ncand));
  PetscCall(PetscFree((*lb)->closed));
  PetscCall(PetscFree(*lb));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* alpha and beta of the measured mode: the mean compute time per particle-step and per
 * cell-step over all ranks since the last check (s); with mesh walls alpha leaves out the mesh
 * contacts' time, and c_m is their time per candidate-step over alpha. */
static PetscErrorCode BalanceMeasuredWeights(Balance b, PetscReal *alpha, PetscReal *beta, PetscReal *cm)
{
  PetscLogDouble td, tf = 0, tm;
  PetscInt       step, n, cstep = 0;
  PetscReal      loc[6], glob[6], cand;

  PetscFunctionBeginUser;
  PetscCall(DemGetComputeTime(b->dem, &td));
  PetscCall(DemGetTime(b->dem, NULL, &step));
  PetscCall(DemGetLocalCount(b->dem, &n));
  if (b->cpl) PetscCall(CplGetFluidTime(b->cpl, &tf));
  if (b->cpl) PetscCall(CplGetTime(b->cpl, NULL, &cstep));
  loc[0] = td - b->t_dem0;
  loc[1] = tf - b->t_fluid0;
  loc[2] = (PetscReal)n * (step - b->last_step);
  loc[3] = b->cpl ? (PetscReal)b->dom->ccount[0] * b->dom->ccount[1] * b->dom->ccount[2] * (cstep - b->cstep0) : 0;
  PetscCall(DemGetMeshTime(b->dem, &tm, &cand));
  loc[4] = b->mesh_clock ? tm - b->t_mesh0 : 0; /* after a restore: the fixed c_m once */
  loc[5] = b->mesh_clock ? cand - b->cand0 : 0;
  PetscCallMPI(MPIU_Allreduce(loc, glob, b->ncand ? 6 : 4, MPIU_REAL, MPI_SUM, b->comm));
  if (!b->ncand) glob[4] = glob[5] = 0;
  if (glob[0] > 0 && glob[2] > 0) { /* else nothing measured yet: the -lb_alpha, -lb_beta values */
    *alpha = (glob[0] - glob[4]) / glob[2];
    *beta  = glob[3] > 0 ? glob[1] / glob[3] : 0;
    if (glob[5] > 0 && *alpha > 0) *cm = glob[4] / glob[5] / *alpha;
  }
  b->t_mesh0    = tm;
  b->cand0      = cand;
  b->mesh_clock = PETSC_TRUE;
  if (b->cpl) b->cstep0 = cstep;
  b->t_dem0   = td;
  b->t_fluid0 = tf;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. Adds am n_c to each cell's weight, n_c the candidate mesh triangles of its particles
 * summed over all ranks into ncand (am = alpha c_m: the cost of one candidate). */
static PetscErrorCode BalanceMeshWeights(Balance b, PetscReal am, PetscInt *ncand, PetscReal *w)
{
  const PetscInt ncell = b->dom->cells[0] * b->dom->cells[1] * b->dom->cells[2];

  PetscFunctionBeginUser;
  PetscCall(PetscArrayzero(ncand, ncell));
  PetscCall(DemGetCellMeshCounts(b->dem, ncand));
  PetscCallMPI(MPIU_Allreduce(MPI_IN_PLACE, ncand, (PetscMPIInt)ncell, MPIU_INT, MPI_SUM, b->comm));
  for (PetscInt c = 0; c < ncell; c++) w[c] += am * (PetscReal)ncand[c];
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Not collective (the same on every rank). A coupled run's vessel: the fluid cost beta leaves the
 * cells whose centre lies in the solid (DemVesselLevel <= 0: closed or nearly, the fluid skips
 * them), found once; nothing changes without a vessel. */
static PetscErrorCode BalanceVesselWeights(Balance b, PetscReal beta, PetscReal *w)
{
  const Domain  *dom   = b->dom;
  const PetscInt ncell = dom->cells[0] * dom->cells[1] * dom->cells[2];

  PetscFunctionBeginUser;
  if (!b->closed_set) {
    PetscBool vessel;
    b->closed_set = PETSC_TRUE;
    PetscCall(DemVesselGetActive(b->dem, &vessel));
    if (!vessel || !b->cpl) PetscFunctionReturn(PETSC_SUCCESS);
    PetscCall(PetscMalloc1(ncell, &b->closed));
    for (PetscInt c = 0; c < ncell; c++) {
      const PetscInt  i[3] = {c % dom->cells[0], (c / dom->cells[0]) % dom->cells[1], c / (dom->cells[0] * dom->cells[1])};
      const PetscReal x[3] = {dom->lo[0] + (i[0] + 0.5) * dom->h[0], dom->lo[1] + (i[1] + 0.5) * dom->h[1], dom->lo[2] + (i[2] + 0.5) * dom->h[2]};
      b->closed[c]         = (PetscBool)(DemVesselLevel(x, b->dem) <= 0);
    }
  }
  if (b->closed)
    for (PetscInt c = 0; c < ncell; c++)
      if (b->closed[c]) w[c] = PetscMax(w[c] - beta, 0.0);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Cell weights over the global grid (every rank gets all of them) and the current loads. */
static PetscErrorCode BalanceWeigh(Balance b, PetscReal *lmin, PetscReal *lmax, PetscReal *lavg)
{
  const PetscInt  P = b->g.p[0] * b->g.p[1] * b->g.p[2], ncell = b->g.n[0] * b->g.n[1] * b->g.n[2];
  const PetscInt *l[3];
  PetscReal       alpha = b->alpha, beta = b->beta, cm = b->mesh_cost, sum = 0;

  PetscFunctionBeginUser;
  PetscCall(PetscArrayzero(b->count, ncell));
  PetscCall(DemGetCellCounts(b->dem, b->count));
  PetscCallMPI(MPIU_Allreduce(MPI_IN_PLACE, b->count, (PetscMPIInt)ncell, MPIU_INT, MPI_SUM, b->comm));
  if (b->weight == 2) PetscCall(BalanceMeasuredWeights(b, &alpha, &beta, &cm));
  {
    const BalanceWeight wm = {b->weight == 1 ? BALANCE_WEIGHT_QUADRATIC : BALANCE_WEIGHT_LINEAR, alpha, beta};
    PetscCall(BalanceCellWeights(&wm, ncell, b->count, b->w));
  }
  if (b->ncand) PetscCall(BalanceMeshWeights(b, alpha * cm, b->ncand, b->w));
  PetscCall(BalanceVesselWeights(b, beta, b->w));
  b->alpha_used = alpha;
  b->beta_used  = beta;
  b->cm_used    = cm;
  PetscCall(DMDAGetOwnershipRanges(b->dom->da, &l[0], &l[1], &l[2]));
  for (int k = 0; k < 3; k++) PetscCall(PetscArraycpy(b->l[k], l[k], b->g.p[k]));
  PetscCall(BalanceLoads(&b->g, b->w, b->l, b->load));
  *lmin = PETSC_MAX_REAL;
  *lmax = 0;
  for (PetscInt r = 0; r < P; r++) {
    *lmin = PetscMin(*lmin, b->load[r]);
    *lmax = PetscMax(*lmax, b->load[r]);
    sum += b->load[r];
  }
  *lavg = sum / P;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Whether the scheme asks for a check after this step. */
static PetscBool BalanceDue(Balance b, PetscReal t, PetscReal dt, PetscInt step)
{
  switch (b->scheme) {
  case LB_NONE:
    return PETSC_FALSE;
  case LB_ONCE:
    return (PetscBool)(!b->done_once && (b->once_time >= 0 ? t >= b->once_time - 0.5 * dt : step >= b->once_step));
  default:
    return (PetscBool)(b->interval_time > 0 ? t >= b->next_time - 0.5 * dt : step - b->last_step >= b->interval);
  }
}

PetscErrorCode BalanceCheck(Balance b, PetscBool force, PetscBool *moved)
{
  PetscReal      t, dt, lmin, lmax, lavg, nmax, navg;
  PetscInt       step;
  PetscLogDouble t0, t1;
  PetscBool      go, same = PETSC_TRUE;

  PetscFunctionBeginUser;
  if (moved) *moved = PETSC_FALSE;
  PetscCall(DemGetTime(b->dem, &t, &step));
  PetscCall(DemGetTimeStep(b->dem, &dt));
  if (!force && !BalanceDue(b, t, dt, step)) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscTime(&t0));
  PetscCall(BalanceWeigh(b, &lmin, &lmax, &lavg));
  b->last_step = step;
  while (b->interval_time > 0 && b->next_time <= t + 0.5 * dt) b->next_time += b->interval_time;
  b->done_once = PETSC_TRUE;
  b->checks++;
  go = (PetscBool)(force || b->scheme != LB_DYNAMIC || lmax - lmin > b->threshold * lavg);
  if (go) {
    PetscCall(BalanceCuts(&b->g, b->w, b->l, &nmax, &navg));
    const PetscInt *l[3];
    PetscCall(DMDAGetOwnershipRanges(b->dom->da, &l[0], &l[1], &l[2]));
    for (int k = 0; k < 3; k++)
      for (PetscInt r = 0; r < b->g.p[k]; r++) same = (PetscBool)(same && l[k][r] == b->l[k][r]);
    go = (PetscBool)!same;
  }
  if (go) {
    PetscCall(DomainSetOwnership(b->dom, b->l));
    if (b->cpl) PetscCall(CplRedistribute(b->cpl));
    else PetscCall(DemRedistribute(b->dem));
    b->rebalances++;
    if (moved) *moved = PETSC_TRUE;
  }
  PetscCall(PetscTime(&t1));
  b->t_total += t1 - t0;
  if (b->verbose) {
    PetscCall(PetscPrintf(b->comm, "lb: step %" PetscInt_FMT " t %.6g s  load min/avg/max %.4g/%.4g/%.4g  (Lmax-Lmin)/Lavg %.3f  Lmax/Lavg %.3f", step, (double)t, (double)lmin, (double)lavg, (double)lmax, (double)((lmax - lmin) / lavg), (double)(lmax / lavg)));
    if (b->weight == 2) PetscCall(PetscPrintf(b->comm, "  measured alpha %.3g s/particle-step, beta %.3g s/cell-step", (double)b->alpha_used, (double)b->beta_used));
    if (b->weight == 2 && b->ncand) PetscCall(PetscPrintf(b->comm, ", c_m %.3g per candidate triangle", (double)b->cm_used));
    if (go) PetscCall(PetscPrintf(b->comm, "  -> rebalanced, predicted Lmax/Lavg %.3f, cost %.3g s\n", (double)(nmax / navg), t1 - t0));
    else PetscCall(PetscPrintf(b->comm, "  -> kept%s, cost %.3g s\n", same ? "" : " (below threshold)", t1 - t0));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode BalanceGetLoads(Balance b, PetscReal *lmin, PetscReal *lmax, PetscReal *lavg)
{
  PetscFunctionBeginUser;
  PetscCall(BalanceWeigh(b, lmin, lmax, lavg));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode BalanceView(Balance b, PetscViewer viewer)
{
  PetscFunctionBeginUser;
  if (b->scheme == LB_NONE) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscViewerASCIIPrintf(viewer, "load balancing: scheme %s, weight %s, %" PetscInt_FMT " checks, %" PetscInt_FMT " rebalances, %.3g s in checks and moves\n", LbSchemeNames[b->scheme], LbWeightNames[b->weight], b->checks, b->rebalances, b->t_total));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode BalanceSetCoupling(Balance b, Cpl cpl)
{
  PetscFunctionBeginUser;
  b->cpl = cpl;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode BalanceIsActive(Balance b, PetscBool *on)
{
  PetscFunctionBeginUser;
  *on = (PetscBool)(b->scheme != LB_NONE);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The problem of BalanceDecompose: the Domain's grid, the minimum widths of BalanceMinWidth for
 * an axis of one rank and a split one, the halo depth in cells. */
static PetscErrorCode BalanceDecompProblemSet(Balance b, BalanceDecompProblem *pb)
{
  const Domain *dom = b->dom;
  PetscReal     reach;
  PetscInt      sw, cw[3] = {0, 0, 0}; /* the coupling's thinnest box (cells), 0 in a dry run */
  PetscMPIInt   size;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(b->comm, &size));
  if (b->cpl) PetscCall(CplGetMinBoxWidth(b->cpl, cw));
  PetscCall(DemGetHaloWidth(b->dem, &reach));
  PetscCall(DMDAGetInfo(dom->da, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL, &sw, NULL, NULL, NULL, NULL));
  pb->size       = size;
  pb->max_sweeps = b->max_sweeps;
  pb->gain       = 0.05;
  pb->whole      = -1;
  {
    PetscReal g[3], gmax = 0;
    PetscCall(DemGetGravity(b->dem, g));
    for (int k = 0; k < 3; k++)
      if (PetscAbsReal(g[k]) > gmax) {
        gmax      = PetscAbsReal(g[k]);
        pb->whole = k;
      }
  }
  for (int k = 0; k < 3; k++) {
    const PetscInt halo = (PetscInt)PetscCeilReal(reach / dom->h[k] * (1 - 1e-12));
    pb->n[k]            = dom->cells[k];
    pb->pref[k]         = dom->nranks[k];
    pb->periodic[k]     = dom->periodic[k];
    pb->halo[k]         = reach / dom->h[k];
    pb->minw_split[k]   = PetscMax(PetscMax(1, sw), halo);
    pb->minw[k]         = dom->periodic[k] ? pb->minw_split[k] : PetscMax(1, sw);
    pb->minw[k]         = PetscMax(pb->minw[k], dom->periodic[k] ? cw[k] : PetscMin(cw[k], 2));
    pb->minw_split[k]   = PetscMax(pb->minw_split[k], cw[k]);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* One line: the decomposition d, and why (its estimate against the reference's). */
static PetscErrorCode BalanceDecompPrint(Balance b, const BalanceDecompProblem *pb, const BalanceDecomp *d, const BalanceDecomp *ref, PetscReal total, PetscBool moved)
{
  char axes[8] = "", cuts[256] = "";

  PetscFunctionBeginUser;
  for (int k = 0; k < 3; k++)
    if (d->p[k] > 1) {
      size_t len = strlen(axes);
      PetscCall(PetscSNPrintf(axes + len, sizeof axes - len, "%s%c", len ? "," : "", "xyz"[k]));
      if (d->balanced) {
        len = strlen(cuts);
        PetscCall(PetscSNPrintf(cuts + len, sizeof cuts - len, "%s%c", len ? "; " : ", balanced cuts (cells per rank) ", "xyz"[k]));
        for (PetscInt r = 0; r < d->p[k]; r++) {
          len = strlen(cuts);
          PetscCall(PetscSNPrintf(cuts + len, sizeof cuts - len, "%s%" PetscInt_FMT, r ? "," : " ", d->l[k][r]));
        }
      }
    }
  PetscCall(PetscPrintf(b->comm, "decomposition: %" PetscInt_FMT " x %" PetscInt_FMT " x %" PetscInt_FMT " ranks, cut along %s%s: largest rank %.0f%% of the load + %.0f%% in ghosts", d->p[0], d->p[1], d->p[2], axes, d->balanced ? cuts : ", uniform cuts", (double)(100 * d->own / total), (double)(100 * d->ghost / total)));
  if (!moved) PetscCall(PetscPrintf(b->comm, " (PETSc's default; no other is 5%% lower)"));
  else if (ref->cost >= 0) PetscCall(PetscPrintf(b->comm, ", against %.0f%% + %.0f%% for PETSc's default %" PetscInt_FMT " x %" PetscInt_FMT " x %" PetscInt_FMT, (double)(100 * ref->own / total), (double)(100 * ref->ghost / total), ref->p[0], ref->p[1], ref->p[2]));
  if (pb->whole >= 0 && d->p[pb->whole] == 1) PetscCall(PetscPrintf(b->comm, "; %c, the gravity axis, is not cut (the particles move along it)", "xyz"[pb->whole]));
  PetscCall(PetscPrintf(b->comm, "; -da_processors_x/y/z choose another\n"));
  PetscFunctionReturn(PETSC_SUCCESS);
}

#define BALANCE_DECOMP_MAX_CELLS 16777216 /* 64 MB of counts and weights on every rank */

PetscErrorCode BalanceDecompose(Balance b)
{
  Domain              *dom   = b->dom;
  const PetscInt       ncell = dom->cells[0] * dom->cells[1] * dom->cells[2];
  const BalanceWeight  wm    = {b->weight == 1 ? BALANCE_WEIGHT_QUADRATIC : BALANCE_WEIGHT_LINEAR, b->alpha, b->beta};
  BalanceDecompProblem pb;
  BalanceDecomp        best, ref;
  PetscInt            *count, *buf, np = 0, nmesh;
  PetscReal           *w, total     = 0;
  PetscBool            given, moved = PETSC_FALSE;
  const PetscInt      *l[3];

  PetscFunctionBeginUser;
  PetscCall(BalanceDecompProblemSet(b, &pb));
  if (pb.size == 1) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(DomainProcessGridGiven(&given));
  if (given || b->ckpt_cuts) {
    PetscCall(PetscPrintf(b->comm, "decomposition: %" PetscInt_FMT " x %" PetscInt_FMT " x %" PetscInt_FMT " ranks, %s\n", dom->nranks[0], dom->nranks[1], dom->nranks[2], b->ckpt_cuts ? "the checkpoint's process grid and cuts" : "as given by -da_processors_x/y/z"));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  if (ncell > BALANCE_DECOMP_MAX_CELLS) { /* every rank would hold the counts of the whole grid */
    PetscCall(PetscPrintf(b->comm, "decomposition: %" PetscInt_FMT " x %" PetscInt_FMT " x %" PetscInt_FMT " ranks, PETSc's default (the grid's %" PetscInt_FMT " cells are too many to weigh at set-up, more than %d)\n", dom->nranks[0], dom->nranks[1], dom->nranks[2], ncell, BALANCE_DECOMP_MAX_CELLS));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(PetscCalloc2(ncell, &count, ncell, &w));
  PetscCall(DemGetCellCounts(b->dem, count));
  PetscCallMPI(MPIU_Allreduce(MPI_IN_PLACE, count, (PetscMPIInt)ncell, MPIU_INT, MPI_SUM, b->comm));
  for (PetscInt c = 0; c < ncell; c++) np += count[c];
  if (!np) {
    PetscCall(PetscPrintf(b->comm, "decomposition: %" PetscInt_FMT " x %" PetscInt_FMT " x %" PetscInt_FMT " ranks, PETSc's default (no particles at set-up to choose from)\n", dom->nranks[0], dom->nranks[1], dom->nranks[2]));
    PetscCall(PetscFree2(count, w));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(BalanceCellWeights(&wm, ncell, count, w));
  PetscCall(DemGetMeshCount(b->dem, &nmesh));
  if (nmesh) { /* the fixed c_m: nothing measured yet */
    PetscInt *ncand;
    PetscCall(PetscMalloc1(ncell, &ncand));
    PetscCall(BalanceMeshWeights(b, b->alpha * b->mesh_cost, ncand, w));
    PetscCall(PetscFree(ncand));
  }
  PetscCall(BalanceVesselWeights(b, b->beta, w));
  for (PetscInt c = 0; c < ncell; c++) total += w[c];
  PetscCall(PetscMalloc1(6 * pb.size, &buf));
  for (int k = 0; k < 3; k++) {
    best.l[k] = buf + k * pb.size;
    ref.l[k]  = buf + (3 + k) * pb.size;
  }
  PetscCall(BalanceBestDecomposition(&pb, w, &best, &ref));
  PetscCall(DMDAGetOwnershipRanges(dom->da, &l[0], &l[1], &l[2]));
  for (int k = 0; k < 3; k++) {
    moved = (PetscBool)(moved || best.p[k] != dom->nranks[k]);
    for (PetscInt r = 0; r < best.p[k] && !moved; r++) moved = (PetscBool)(best.l[k][r] != l[k][r]);
  }
  if (moved) {
    PetscCall(DomainSetDecomposition(dom, best.p, best.l));
    PetscCall(DemRedistribute(b->dem));
  }
  PetscCall(BalanceDecompPrint(b, &pb, &best, &ref, total, moved));
  PetscCall(PetscFree(buf));
  PetscCall(PetscFree2(count, w));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Checkpoints. The cuts are part of the decomposition a checkpoint's per-rank state belongs to,
 * so a restart on the same rank count puts them back before anything is set up on the Domain;
 * the schedule (last check, next check time, once done) and the counters continue, so the
 * restarted run checks and moves exactly when the uninterrupted one does. Datasets (shared, one
 * copy): lb/grid (cells and process grid), lb/cuts (l[0], l[1], l[2]), lb/state (last check
 * step, once done, checks, rebalances, coupling step of the last check), lb/clock (next check
 * time, time in checks and moves, last measured alpha and beta); per rank: lb/measured (compute
 * time since the last check, DEM and fluid, for -lb_weight measured). */
#define LB_CKPT_NSTATE 5
#define LB_CKPT_NCLOCK 4

PetscErrorCode BalanceCheckpointWrite(Balance b, IoCkpt ck)
{
  const PetscInt *l[3];
  PetscInt        grid[6], *cuts, np = 0, st[LB_CKPT_NSTATE];
  PetscReal       clk[LB_CKPT_NCLOCK], since[2];
  PetscLogDouble  td, tf = 0;

  PetscFunctionBeginUser;
  PetscCall(DMDAGetOwnershipRanges(b->dom->da, &l[0], &l[1], &l[2]));
  for (int k = 0; k < 3; k++) {
    grid[k]     = b->dom->cells[k];
    grid[3 + k] = b->dom->nranks[k];
  }
  PetscCall(PetscMalloc1(b->dom->nranks[0] + b->dom->nranks[1] + b->dom->nranks[2], &cuts));
  for (int k = 0; k < 3; k++)
    for (PetscInt r = 0; r < b->dom->nranks[k]; r++) cuts[np++] = l[k][r];
  st[0]  = b->last_step;
  st[1]  = b->done_once;
  st[2]  = b->checks;
  st[3]  = b->rebalances;
  st[4]  = b->cstep0;
  clk[0] = b->next_time;
  clk[1] = b->t_total;
  clk[2] = b->alpha_used;
  clk[3] = b->beta_used;
  PetscCall(DemGetComputeTime(b->dem, &td));
  if (b->cpl) PetscCall(CplGetFluidTime(b->cpl, &tf));
  since[0] = td - b->t_dem0;
  since[1] = tf - b->t_fluid0;
  PetscCall(IoCkptWriteShared(ck, "lb/grid", IO_CKPT_INT, 6, grid));
  PetscCall(IoCkptWriteShared(ck, "lb/cuts", IO_CKPT_INT, np, cuts));
  PetscCall(IoCkptWriteShared(ck, "lb/state", IO_CKPT_INT, LB_CKPT_NSTATE, st));
  PetscCall(IoCkptWriteShared(ck, "lb/clock", IO_CKPT_REAL, LB_CKPT_NCLOCK, clk));
  PetscCall(IoCkptWriteRows(ck, "lb/measured", IO_CKPT_REAL, 2, since));
  PetscCall(PetscFree(cuts));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. The checkpoint's cuts onto the Domain, after checking that they belong to this
 * run's grid and process grid. */
/* Collective. Whether the checkpoint's grid and process grid are this run's (then its cuts apply). */
static PetscErrorCode BalanceCkptSameGrid(Balance b, IoCkpt ck, PetscBool *same)
{
  Domain  *dom = b->dom;
  PetscInt grid[6];

  PetscFunctionBeginUser;
  PetscCall(IoCkptReadShared(ck, "lb/grid", IO_CKPT_INT, 6, grid));
  *same = (PetscBool)(grid[0] == dom->cells[0] && grid[1] == dom->cells[1] && grid[2] == dom->cells[2] && grid[3] == dom->nranks[0] && grid[4] == dom->nranks[1] && grid[5] == dom->nranks[2]);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. A run that leaves the process grid to Sable restarts on the checkpoint's, when the
 * rank count and the grid are the checkpoint's: the cuts chosen at its start (BalanceDecompose)
 * stay. */
static PetscErrorCode BalanceCkptAdoptGrid(Balance b, IoCkpt ck)
{
  Domain   *dom = b->dom;
  PetscInt  grid[6], *l[3];
  PetscBool given;

  PetscFunctionBeginUser;
  PetscCall(DomainProcessGridGiven(&given));
  PetscCall(IoCkptReadShared(ck, "lb/grid", IO_CKPT_INT, 6, grid));
  if (given || grid[0] != dom->cells[0] || grid[1] != dom->cells[1] || grid[2] != dom->cells[2]) PetscFunctionReturn(PETSC_SUCCESS);
  if (grid[3] == dom->nranks[0] && grid[4] == dom->nranks[1] && grid[5] == dom->nranks[2]) PetscFunctionReturn(PETSC_SUCCESS);
  {
    BalanceGrid g = {{grid[0], grid[1], grid[2]}, {grid[3], grid[4], grid[5]}, {1, 1, 1}, 0};
    PetscCall(PetscMalloc3(grid[3], &l[0], grid[4], &l[1], grid[5], &l[2]));
    PetscCall(BalanceUniformCuts(&g, l));
    PetscCall(DomainSetDecomposition(dom, g.p, l));
    PetscCall(PetscFree3(l[0], l[1], l[2]));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode BalanceCkptReadCuts(Balance b, IoCkpt ck)
{
  Domain  *dom = b->dom;
  PetscInt np  = dom->nranks[0] + dom->nranks[1] + dom->nranks[2], *cuts, *l[3];

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(np, &cuts));
  PetscCall(IoCkptReadShared(ck, "lb/cuts", IO_CKPT_INT, np, cuts));
  l[0] = cuts;
  l[1] = l[0] + dom->nranks[0];
  l[2] = l[1] + dom->nranks[1];
  PetscCall(DomainSetOwnership(dom, l));
  PetscCall(PetscFree(cuts));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode BalanceCheckpointRead(Balance b, IoCkpt ck)
{
  const char *path;
  PetscInt    st[LB_CKPT_NSTATE];
  PetscReal   clk[LB_CKPT_NCLOCK], since[2];
  int         ranks;
  PetscMPIInt size;
  PetscBool   same = PETSC_FALSE;

  PetscFunctionBeginUser;
  PetscCall(IoCkptGetPath(ck, &path));
  PetscCall(IoCkptGetRanks(ck, &ranks));
  PetscCallMPI(MPI_Comm_size(b->comm, &size));
  PetscCall(IoCkptReadShared(ck, "lb/state", IO_CKPT_INT, LB_CKPT_NSTATE, st));
  PetscCall(IoCkptReadShared(ck, "lb/clock", IO_CKPT_REAL, LB_CKPT_NCLOCK, clk));
  b->checks     = st[2];
  b->rebalances = st[3];
  b->t_total    = clk[1];
  b->alpha_used = clk[2];
  b->beta_used  = clk[3];
  if (ranks == size) PetscCall(BalanceCkptAdoptGrid(b, ck));
  if (ranks == size) PetscCall(BalanceCkptSameGrid(b, ck, &same));
  if (!same) { /* the cuts belong to another grid or process grid: the DMDA's, and a check soon */
    PetscCall(PetscPrintf(b->comm, "lb: restart on %d ranks (process grid %d x %d x %d) from a checkpoint of %d ranks%s: default cuts, not the checkpoint's%s\n", (int)size, (int)b->dom->nranks[0], (int)b->dom->nranks[1], (int)b->dom->nranks[2], ranks, ranks == size ? " on another grid or process grid (lb/grid)" : "", b->scheme == LB_NONE ? "" : "; the balancer checks after the first step"));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(BalanceCkptReadCuts(b, ck));
  b->ckpt_cuts = PETSC_TRUE;
  PetscCall(IoCkptReadRowsInto(ck, "lb/measured", IO_CKPT_REAL, 2, since));
  b->last_step  = st[0];
  b->done_once  = (PetscBool)(st[1] != 0);
  b->cstep0     = st[4];
  b->next_time  = clk[0];
  b->t_since[0] = since[0];
  b->t_since[1] = since[1];
  b->restored   = PETSC_TRUE;
  if (b->verbose && b->scheme != LB_NONE) {
    const PetscInt *l[3];
    PetscCall(DMDAGetOwnershipRanges(b->dom->da, &l[0], &l[1], &l[2]));
    PetscCall(PetscPrintf(b->comm, "lb: restart: the checkpoint's cuts (cells per rank)"));
    for (int k = 0; k < 3; k++) {
      PetscCall(PetscPrintf(b->comm, "%s %c", k ? ";" : "", "xyz"[k]));
      for (PetscInt r = 0; r < b->dom->nranks[k]; r++) PetscCall(PetscPrintf(b->comm, "%s%" PetscInt_FMT, r ? "," : " ", l[k][r]));
    }
    PetscCall(PetscPrintf(b->comm, "; last check at step %" PetscInt_FMT ", %" PetscInt_FMT " checks, %" PetscInt_FMT " rebalances so far\n", b->last_step, b->checks, b->rebalances));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}
