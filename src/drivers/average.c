/* Time averages (average.h): Eulerian running means and RMS fluctuations per cell of the
 * Domain's grid, from -avg_start T. Per cell and sample k the fields are
 *   phi_k  solids fraction: coupled 1 - eps (the fluid's porosity); dry: the volume of the
 *          particles whose centre lies in the cell over the cell volume (centre-in-cell);
 *   uf_k   fluid velocity (coupled): cell-centred, the mean of the cell's two face values;
 *   up_k   particle velocity P_k / M_k, M_k = sum m, P_k = sum m v over the particles whose
 *          centre lies in the cell (no sample where M_k = 0).
 * Samples: the state after each step ending at t_k > T (every -avg_interval of simulated time
 * when given), weighted by w_k = t_k - t_{k-1}, the time since the previous sample (the first
 * from T or from a restart without sums): the right-endpoint rule of the integral over the window.
 *   <q> = sum w_k q_k / sum w_k,   rms q = sqrt(max(0, <q^2> - <q>^2)) per component,
 * and for up the weights w_k M_k (a mass-weighted, Favre, mean; 0 in a cell never holding a
 * particle). The sums are of deviations from the cell's first sample q_0 (sum w (q - q_0), sum
 * w (q - q_0)^2): a steady field gives <q> = q_0 and rms 0 exactly, and the cancellation in the
 * variance is that of the fluctuations alone. The accumulators are one Vec of AVG_NQ values per
 * cell on a DMDA of the Domain's ownership, moved with it (DomainMoveVec) when the balancer
 * changes it; a checkpoint holds them in the natural ordering, so any rank count continues.
 * Particles are deposited by their owner into a ghosted array (a particle a little outside its
 * rank's box between migrations lands in a ghost cell) summed onto the owners (ADD_VALUES). */
#include "drivers/average.h"

enum {           /* per-cell accumulators: reference q_0, sum w d, sum w d^2 (d = q - q_0) */
  AVG_PHI0 = 0,  /* solids fraction: 0, 1, 2 */
  AVG_UF0  = 3,  /* fluid velocity: 3..5, 6..8, 9..11 */
  AVG_WM   = 12, /* sum w M (kg s) */
  AVG_REF  = 13, /* 1 once up_0 is set */
  AVG_UP0  = 14, /* particle velocity: 14..16, 17..19, 20..22 */
  AVG_NQ   = 23
};
#define AVG_NDEP 5 /* deposits per cell: M, particle volume, P[3] */

struct _p_DriverAvg {
  MPI_Comm   comm;
  PetscBool  on;
  PetscReal  start, interval; /* -avg_start, -avg_interval (s) */
  Domain    *dom;
  Dem        dem;
  Fluid      fl;               /* NULL: dry */
  DM         dom_da, ada, dda; /* the Domain's DMDA followed (a reference); accumulators; deposits */
  Vec        acc, dep, deploc; /* acc: AVG_NQ per cell; dep, deploc: AVG_NDEP (global, ghosted) */
  PetscReal  W, t_last, next;  /* sum of weights (s), time of the last sample, next due sample */
  PetscInt   n;                /* samples taken */
  PetscInt   nshape;
  PetscReal *mass, *vol, *scratch; /* per shape (kg, m^3); coupled: 3 per owned cell */
};

PetscErrorCode DriverAvgCreate(MPI_Comm comm, DriverAvg *a)
{
  PetscFunctionBeginUser;
  PetscCall(PetscNew(a));
  (*a)->comm = comm;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DriverAvgSetFromOptions(DriverAvg a)
{
  PetscBool iset;

  PetscFunctionBeginUser;
  PetscOptionsBegin(a->comm, NULL, "Time averages", NULL);
  PetscCall(SableOptionsReal("-avg_start", "Simulated time from which every frame carries running means and RMS fluctuations per cell of the solids fraction, fluid and particle velocity (avg_*, rms_*)", "s", "[0,inf)", -1, &a->start, &a->on));
  PetscCall(SableOptionsReal("-avg_interval", "Simulated time between samples of the time averages", "s; 0 = every step (a dry run's DEM step, a coupled run's coupling step)", "[0,inf)", 0, &a->interval, &iset));
  PetscOptionsEnd();
  PetscCheck(!iset || a->on, a->comm, PETSC_ERR_ARG_INCOMP, "-avg_interval %g: time averages need -avg_start (s)", (double)a->interval);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The accumulator and deposit DMDAs on the Domain's current ownership; the sums, if any, moved
 * onto them bit for bit. */
static PetscErrorCode AvgFollowDomain(DriverAvg a)
{
  const Domain   *dom = a->dom;
  DMBoundaryType  bt[3];
  const PetscInt *l[3];
  DM              ada, dda;

  PetscFunctionBeginUser;
  if (a->dom_da == dom->da) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(DMDAGetInfo(dom->da, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL, &bt[0], &bt[1], &bt[2], NULL));
  PetscCall(DMDAGetOwnershipRanges(dom->da, &l[0], &l[1], &l[2]));
  PetscCall(DMDACreate3d(a->comm, bt[0], bt[1], bt[2], DMDA_STENCIL_BOX, dom->cells[0], dom->cells[1], dom->cells[2], dom->nranks[0], dom->nranks[1], dom->nranks[2], AVG_NQ, 0, l[0], l[1], l[2], &ada));
  PetscCall(DMSetUp(ada));
  PetscCall(DMDACreate3d(a->comm, bt[0], bt[1], bt[2], DMDA_STENCIL_BOX, dom->cells[0], dom->cells[1], dom->cells[2], dom->nranks[0], dom->nranks[1], dom->nranks[2], AVG_NDEP, 1, l[0], l[1], l[2], &dda));
  PetscCall(DMSetUp(dda));
  if (a->acc) PetscCall(DomainMoveVec(a->ada, ada, &a->acc));
  else PetscCall(DMCreateGlobalVector(ada, &a->acc));
  PetscCall(VecDestroy(&a->dep));
  PetscCall(VecDestroy(&a->deploc));
  PetscCall(DMCreateGlobalVector(dda, &a->dep));
  PetscCall(DMCreateLocalVector(dda, &a->deploc));
  PetscCall(DMDestroy(&a->ada));
  PetscCall(DMDestroy(&a->dda));
  PetscCall(DMDestroy(&a->dom_da));
  a->ada = ada;
  a->dda = dda;
  PetscCall(PetscObjectReference((PetscObject)dom->da));
  a->dom_da = dom->da;
  PetscCall(PetscFree(a->scratch));
  PetscCall(PetscMalloc1(3 * dom->ccount[0] * dom->ccount[1] * dom->ccount[2], &a->scratch));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DriverAvgSetUp(DriverAvg a, Domain *dom, Dem dem, Fluid fl, Io io)
{
  PetscFunctionBeginUser;
  if (!a || !a->on) PetscFunctionReturn(PETSC_SUCCESS);
  a->dom    = dom;
  a->dem    = dem;
  a->fl     = fl;
  a->t_last = a->start;
  PetscCall(DemGetShapeCount(dem, &a->nshape));
  PetscCall(PetscMalloc2(a->nshape, &a->mass, a->nshape, &a->vol));
  for (PetscInt s = 0; s < a->nshape; s++) {
    PetscReal r, d;
    PetscCall(DemGetShape(dem, s, &r, &a->mass[s]));
    PetscCall(DemGetShapeGeometry(dem, s, &a->vol[s], &d));
  }
  PetscCall(AvgFollowDomain(a));
  if (io && !fl) PetscCall(IoSetFluidMesh(io, dom->lo, dom->h, dom->cells)); /* a restarted index may list averaged frames before the next */
  if (a->interval > 0) PetscCall(PetscPrintf(a->comm, "averages: from t = %g s, a sample every %g s; frames carry avg_* and rms_* on the %" PetscInt_FMT " x %" PetscInt_FMT " x %" PetscInt_FMT " %s grid\n", (double)a->start, (double)a->interval, dom->cells[0], dom->cells[1], dom->cells[2], fl ? "fluid" : "background"));
  else PetscCall(PetscPrintf(a->comm, "averages: from t = %g s, a sample every %s step; frames carry avg_* and rms_* on the %" PetscInt_FMT " x %" PetscInt_FMT " x %" PetscInt_FMT " %s grid\n", (double)a->start, fl ? "coupling" : "DEM", dom->cells[0], dom->cells[1], dom->cells[2], fl ? "fluid" : "background"));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The particle mass, volume and momentum per cell (dep, on the owners). Summed in registers over
 * each run of consecutive particles in one cell, then added to the cell: the loop is not bound
 * by the latency of adding into the same few cells again and again. */
static PetscErrorCode AvgDeposit(DriverAvg a)
{
  const Domain    *dom  = a->dom;
  const PetscReal *mass = a->mass, *vol = a->vol;
  DemArrays        p;
  PetscScalar     *d;
  PetscInt         gs[3], gm[3], lo[3], hi[3];
  PetscReal        x0[3], h[3], run[AVG_NDEP] = {0};

  PetscFunctionBeginUser;
  PetscCall(DMDAGetGhostCorners(a->dda, &gs[0], &gs[1], &gs[2], &gm[0], &gm[1], &gm[2]));
  for (int k = 0; k < 3; k++) { /* the cells a particle may land in: the ghosted box, and the grid along a wall */
    lo[k] = dom->periodic[k] ? gs[k] : PetscMax(gs[k], 0);
    hi[k] = dom->periodic[k] ? gs[k] + gm[k] - 1 : PetscMin(gs[k] + gm[k], dom->cells[k]) - 1;
    x0[k] = dom->lo[k];
    h[k]  = dom->h[k];
  }
  PetscCall(VecZeroEntries(a->deploc));
  PetscCall(VecGetArray(a->deploc, &d));
  PetscCall(DemGetArrays(a->dem, &p));
  for (PetscInt i = 0, cur = -1; i <= p.nlocal; i++) {
    PetscInt cell = -1;
    if (i < p.nlocal) {
      PetscInt c[3];
      for (int k = 0; k < 3; k++) c[k] = PetscMin(PetscMax((PetscInt)PetscFloorReal((p.x[3 * i + k] - x0[k]) / h[k]), lo[k]), hi[k]) - gs[k];
      cell = c[0] + gm[0] * (c[1] + gm[1] * c[2]);
    }
    if (cell != cur) { /* a run of particles in one cell (the DEM keeps them sorted by space) ends */
      if (cur >= 0)
        for (int k = 0; k < AVG_NDEP; k++) d[AVG_NDEP * cur + k] += run[k];
      for (int k = 0; k < AVG_NDEP; k++) run[k] = 0;
      cur = cell;
    }
    if (i < p.nlocal) {
      const PetscInt   s = p.shape[i];
      const PetscReal *v = p.v + 3 * i;
      run[0] += mass[s];
      run[1] += vol[s];
      for (int k = 0; k < 3; k++) run[2 + k] += mass[s] * v[k];
    }
  }
  PetscCall(VecRestoreArray(a->deploc, &d));
  PetscCall(VecZeroEntries(a->dep));
  PetscCall(DMLocalToGlobal(a->dda, a->deploc, ADD_VALUES, a->dep));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* One sample of weight w of nc components q into the sums s (reference s[0..nc), first sum
 * s[nc..2nc), second s[2nc..3nc)); first: the sample sets the reference. */
static inline void avg_add(PetscScalar *s, const PetscReal *q, int nc, PetscReal w, PetscBool first)
{
  for (int k = 0; k < nc; k++) {
    if (first) s[k] = q[k];
    const PetscReal dev = q[k] - s[k];
    s[nc + k] += w * dev;
    s[2 * nc + k] += w * dev * dev;
  }
}

PetscErrorCode DriverAvgSample(DriverAvg a, PetscReal t)
{
  const Domain      *dom = a->dom;
  const PetscScalar *dep, *eps = NULL;
  PetscScalar       *acc;
  PetscReal          w, vcell;
  PetscInt           n;

  PetscFunctionBeginUser;
  if (!a || !a->on || !a->dom || !(t > a->start)) PetscFunctionReturn(PETSC_SUCCESS);
  if (a->interval > 0 && t < a->next - 1e-6 * a->interval) PetscFunctionReturn(PETSC_SUCCESS); /* IoDue's tolerance */
  w = t - a->t_last;
  if (!(w > 0)) PetscFunctionReturn(PETSC_SUCCESS);
  if (a->interval > 0) a->next = (PetscFloorReal(t / a->interval + 1e-6) + 1) * a->interval;
  PetscCall(AvgFollowDomain(a));
  PetscCall(AvgDeposit(a));
  n     = dom->ccount[0] * dom->ccount[1] * dom->ccount[2];
  vcell = dom->h[0] * dom->h[1] * dom->h[2];
  if (a->fl) {
    Vec e;
    PetscCall(FluidGetPorosity(a->fl, &e));
    PetscCall(FluidGetCellVelocity(a->fl, a->scratch));
    PetscCall(VecGetArrayRead(e, &eps));
  }
  PetscCall(VecGetArrayRead(a->dep, &dep));
  PetscCall(VecGetArray(a->acc, &acc));
  for (PetscInt o = 0; o < n; o++) {
    const PetscScalar *q   = dep + AVG_NDEP * o;
    PetscScalar       *s   = acc + AVG_NQ * o;
    const PetscReal    phi = eps ? 1 - eps[o] : q[1] / vcell;
    avg_add(s + AVG_PHI0, &phi, 1, w, (PetscBool)(a->n == 0));
    if (eps) avg_add(s + AVG_UF0, a->scratch + 3 * o, 3, w, (PetscBool)(a->n == 0));
    if (q[0] > 0) {
      const PetscReal up[3] = {q[2] / q[0], q[3] / q[0], q[4] / q[0]};
      avg_add(s + AVG_UP0, up, 3, w * q[0], (PetscBool)(s[AVG_REF] == 0));
      s[AVG_REF] = 1;
      s[AVG_WM] += w * q[0];
    }
  }
  PetscCall(VecRestoreArray(a->acc, &acc));
  PetscCall(VecRestoreArrayRead(a->dep, &dep));
  if (eps) {
    Vec e;
    PetscCall(FluidGetPorosity(a->fl, &e));
    PetscCall(VecRestoreArrayRead(e, &eps));
  }
  a->W += w;
  a->t_last = t;
  a->n++;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Mean and RMS of nc components from the sums s (see avg_add) and the weight W > 0. */
static inline void avg_stats(const PetscScalar *s, int nc, PetscReal W, PetscReal *mean, PetscReal *rms)
{
  for (int k = 0; k < nc; k++) {
    const PetscReal m1 = s[nc + k] / W, var = s[2 * nc + k] / W - m1 * m1;
    mean[k] = s[k] + m1;
    rms[k]  = var > 0 ? PetscSqrtReal(var) : 0; /* round-off may leave a negative variance */
  }
}

PetscErrorCode DriverAvgWriteOutput(DriverAvg a, Io io)
{
  const char        *names[6] = {"avg_solids_fraction", "rms_solids_fraction", "avg_fluid_velocity", "rms_fluid_velocity", "avg_particle_velocity", "rms_particle_velocity"};
  const int          nc[6]    = {1, 1, 3, 3, 3, 3};
  const Domain      *dom      = a->dom;
  const PetscScalar *acc;
  PetscReal         *f[6];
  PetscInt           n;
  PetscBool          want = PETSC_FALSE;

  PetscFunctionBeginUser;
  if (io) PetscCall(IoFrameWants(io, "fluid", NULL, &want)); /* the averages go with the fluid fields */
  if (!a || !a->on || !a->dom || !want || a->n == 0) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(AvgFollowDomain(a));
  n = dom->ccount[0] * dom->ccount[1] * dom->ccount[2];
  PetscCall(PetscMalloc6(n, &f[0], n, &f[1], 3 * n, &f[2], 3 * n, &f[3], 3 * n, &f[4], 3 * n, &f[5]));
  PetscCall(VecGetArrayRead(a->acc, &acc));
  for (PetscInt o = 0; o < n; o++) {
    const PetscScalar *s = acc + AVG_NQ * o;
    avg_stats(s + AVG_PHI0, 1, a->W, f[0] + o, f[1] + o);
    avg_stats(s + AVG_UF0, 3, a->W, f[2] + 3 * o, f[3] + 3 * o);
    if (s[AVG_WM] > 0) avg_stats(s + AVG_UP0, 3, s[AVG_WM], f[4] + 3 * o, f[5] + 3 * o);
    else
      for (int k = 0; k < 3; k++) f[4][3 * o + k] = f[5][3 * o + k] = 0;
  }
  PetscCall(VecRestoreArrayRead(a->acc, &acc));
  if (!a->fl) PetscCall(IoSetFluidMesh(io, dom->lo, dom->h, dom->cells));
  for (int k = 0; k < 6; k++)
    if (a->fl || (k != 2 && k != 3)) PetscCall(IoWriteField(io, names[k], nc[k], dom->cstart, dom->ccount, f[k]));
  PetscCall(PetscFree6(f[0], f[1], f[2], f[3], f[4], f[5]));
  PetscFunctionReturn(PETSC_SUCCESS);
}

#define AVG_NSTATE 6 /* avg/state: start, interval, W, t_last, next, n */

PetscErrorCode DriverAvgCheckpointWrite(DriverAvg a, IoCkpt ck)
{
  const PetscReal s[AVG_NSTATE] = {a->start, a->interval, a->W, a->t_last, a->next, (PetscReal)a->n};

  PetscFunctionBeginUser;
  if (!a || !a->on || !a->dom) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(AvgFollowDomain(a));
  PetscCall(IoCkptWriteShared(ck, "avg/state", IO_CKPT_REAL, AVG_NSTATE, s));
  PetscCall(FluidCheckpointWriteVec(ck, "avg/sums", a->acc));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DriverAvgCheckpointRead(DriverAvg a, IoCkpt ck, PetscReal t)
{
  PetscReal   s[AVG_NSTATE];
  PetscBool   has;
  const char *path;

  PetscFunctionBeginUser;
  if (!a || !a->on || !a->dom) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(AvgFollowDomain(a));
  PetscCall(IoCkptHas(ck, "avg/state", &has));
  if (has) PetscCall(IoCkptReadShared(ck, "avg/state", IO_CKPT_REAL, AVG_NSTATE, s));
  if (has && s[0] == a->start) {
    a->W      = s[2];
    a->t_last = s[3];
    a->next   = s[1] == a->interval ? s[4] : 0; /* another interval: the next step samples */
    a->n      = (PetscInt)s[5];
    PetscCall(FluidCheckpointReadVec(ck, "avg/sums", a->acc));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  a->t_last = PetscMax(a->start, t);
  PetscCall(IoCkptGetPath(ck, &path));
  if (t > a->start) PetscCall(PetscPrintf(a->comm, "warning: -restart %s: the checkpoint holds no time averages from -avg_start %g: the averages cover t > %g only\n", path, (double)a->start, (double)t));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DriverAvgDestroy(DriverAvg *a)
{
  PetscFunctionBeginUser;
  if (!*a) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(VecDestroy(&(*a)->acc));
  PetscCall(VecDestroy(&(*a)->dep));
  PetscCall(VecDestroy(&(*a)->deploc));
  PetscCall(DMDestroy(&(*a)->ada));
  PetscCall(DMDestroy(&(*a)->dda));
  PetscCall(DMDestroy(&(*a)->dom_da));
  PetscCall(PetscFree2((*a)->mass, (*a)->vol));
  PetscCall(PetscFree((*a)->scratch));
  PetscCall(PetscFree(*a));
  PetscFunctionReturn(PETSC_SUCCESS);
}
