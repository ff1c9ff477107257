/* The decomposition of a run's start (balance.h): which axes to cut and where, chosen from the
 * particles. PETSc's DMDA splits the longest axis, which cuts a settled bed in a tall box across
 * and leaves most of it on one rank. Here every process grid of `size` ranks whose boxes fit the
 * grid (at least minw cells per box and axis: the halo along a split axis) is estimated, each
 * with the DMDA's uniform cuts and with balanced cuts (BalanceCuts); the estimate is the largest
 * rank cost, a rank's cost being its load (the sum of the cell weights over its box, the
 * balancer's weights) plus its ghosts: the weight of the neighbours' cells within the halo depth
 * (reach / h cells, a fraction of the last layer) of its faces along the split axes, wrapping
 * across periodic ones. A ghost is weighed as an owned particle: each local-ghost pair is
 * computed on both sides and the ghosts are sent every step. Edges and corners are left out.
 * Under gravity the particles fall, settle, fluidize and bubble along it, so step 0's balance
 * along the gravity axis does not last (a fill starts at the top and ends at the bottom; a
 * bed's balanced cut moves as it expands) while a rank's share of the columns across it does:
 * only grids that leave the gravity axis (`whole`) unsplit are considered, and all of them only
 * when none fits. PETSc's own grid with uniform cuts is the reference and is kept, when it
 * qualifies, unless another decomposition lowers the estimate by more than the fraction `gain`,
 * so an even spread of particles keeps the decomposition PETSc users expect. Ties go to the
 * earlier candidate: the reference grid first, splits of x before y before z, uniform before
 * balanced cuts. Pure and serial: every rank computes the same. */
#include "balance/balance.h"

/* Weight of the cells of layer c along axis k over the box lo..hi of the other two axes. */
static PetscReal balance_layer(const PetscInt n[3], const PetscReal *w, int k, PetscInt c, const PetscInt lo[3], const PetscInt hi[3])
{
  PetscInt  a[3], b[3];
  PetscReal s = 0;

  for (int d = 0; d < 3; d++) {
    a[d] = d == k ? c : lo[d];
    b[d] = d == k ? c + 1 : hi[d];
  }
  for (PetscInt z = a[2]; z < b[2]; z++)
    for (PetscInt y = a[1]; y < b[1]; y++)
      for (PetscInt x = a[0]; x < b[0]; x++) s += w[x + n[0] * (y + n[1] * z)];
  return s;
}

/* Ghost weight of the rank box lo..hi: the halo layers beyond its faces along the split axes. */
static PetscReal balance_ghosts(const BalanceDecompProblem *pb, const PetscInt p[3], const PetscReal *w, const PetscInt lo[3], const PetscInt hi[3])
{
  PetscReal g = 0;

  for (int k = 0; k < 3; k++) {
    if (p[k] < 2) continue;
    for (PetscInt j = 0; j < (PetscInt)PetscCeilReal(pb->halo[k]); j++) {
      const PetscReal f    = PetscMin(1, pb->halo[k] - j);
      const PetscInt  c[2] = {lo[k] - 1 - j, hi[k] + j};
      for (int s = 0; s < 2; s++) {
        PetscInt cc = c[s];
        if (cc < 0 || cc >= pb->n[k]) {
          if (!pb->periodic[k]) continue;
          cc = (cc + pb->n[k]) % pb->n[k];
        }
        g += f * balance_layer(pb->n, w, k, cc, lo, hi);
      }
    }
  }
  return g;
}

PetscErrorCode BalanceDecompCost(const BalanceDecompProblem *pb, const PetscInt p[3], PetscInt *const l[3], const PetscReal *w, PetscReal *cost, PetscReal *own, PetscReal *ghost)
{
  BalanceGrid g = {{pb->n[0], pb->n[1], pb->n[2]}, {p[0], p[1], p[2]}, {1, 1, 1}, 0};
  PetscReal  *load;
  PetscInt    r = 0, s[3];

  PetscFunctionBegin;
  PetscCall(PetscMalloc1(p[0] * p[1] * p[2], &load));
  PetscCall(BalanceLoads(&g, w, l, load));
  *cost = -1;
  s[2]  = 0;
  for (PetscInt rz = 0; rz < p[2]; s[2] += l[2][rz++]) {
    s[1] = 0;
    for (PetscInt ry = 0; ry < p[1]; s[1] += l[1][ry++]) {
      s[0] = 0;
      for (PetscInt rx = 0; rx < p[0]; s[0] += l[0][rx++], r++) {
        const PetscInt  lo[3] = {s[0], s[1], s[2]}, hi[3] = {s[0] + l[0][rx], s[1] + l[1][ry], s[2] + l[2][rz]};
        const PetscReal gh = balance_ghosts(pb, p, w, lo, hi);
        if (load[r] + gh > *cost) {
          *cost  = load[r] + gh;
          *own   = load[r];
          *ghost = gh;
        }
      }
    }
  }
  PetscCall(PetscFree(load));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Keeps the candidate (p, l) in *d when it is cheaper than d->cost (d->cost < 0: empty). */
static PetscErrorCode BalanceDecompConsider(const BalanceDecompProblem *pb, const PetscInt p[3], PetscInt *const l[3], PetscBool balanced, const PetscReal *w, BalanceDecomp *d)
{
  PetscReal cost, own, ghost;

  PetscFunctionBegin;
  PetscCall(BalanceDecompCost(pb, p, l, w, &cost, &own, &ghost));
  if (d->cost >= 0 && cost >= d->cost) PetscFunctionReturn(PETSC_SUCCESS);
  d->cost     = cost;
  d->own      = own;
  d->ghost    = ghost;
  d->balanced = balanced;
  for (int k = 0; k < 3; k++) {
    d->p[k] = p[k];
    PetscCall(PetscArraycpy(d->l[k], l[k], p[k]));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Both cut choices of the process grid p (the uniform cuts only: uniform) into *d, when p fits
 * the grid; t: scratch cuts. */
static PetscErrorCode BalanceDecompGrid(const BalanceDecompProblem *pb, const PetscInt p[3], PetscBool uniform, const PetscReal *w, PetscInt *const t[3], BalanceDecomp *d)
{
  BalanceGrid g    = {{pb->n[0], pb->n[1], pb->n[2]}, {p[0], p[1], p[2]}, {0, 0, 0}, pb->max_sweeps};
  PetscBool   fits = PETSC_TRUE, uniform_fits = PETSC_TRUE;
  PetscReal   lmax, lavg;

  PetscFunctionBegin;
  for (int k = 0; k < 3; k++) {
    g.minw[k] = p[k] > 1 ? pb->minw_split[k] : pb->minw[k];
    fits      = (PetscBool)(fits && pb->n[k] >= p[k] * g.minw[k]);
  }
  if (!fits) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(BalanceUniformCuts(&g, t));
  for (int k = 0; k < 3; k++)
    for (PetscInt r = 0; r < p[k]; r++) uniform_fits = (PetscBool)(uniform_fits && t[k][r] >= g.minw[k]);
  if (uniform_fits) PetscCall(BalanceDecompConsider(pb, p, t, PETSC_FALSE, w, d));
  if (uniform) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(BalanceCuts(&g, w, t, &lmax, &lavg));
  PetscCall(BalanceDecompConsider(pb, p, t, PETSC_TRUE, w, d));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Whether p leaves the axis pb->whole unsplit (always, without one). */
static PetscBool balance_keeps_whole(const BalanceDecompProblem *pb, const PetscInt p[3])
{
  return (PetscBool)(pb->whole < 0 || p[pb->whole] == 1);
}

PetscErrorCode BalanceBestDecomposition(const BalanceDecompProblem *pb, const PetscReal *w, BalanceDecomp *best, BalanceDecomp *ref)
{
  const PetscInt size = pb->size;
  PetscInt      *t[3];
  PetscBool      ref_ok;

  PetscFunctionBegin;
  PetscCheck(size >= 1, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "rank count %" PetscInt_FMT " must be >= 1", size);
  PetscCall(PetscMalloc3(size, &t[0], size, &t[1], size, &t[2]));
  ref->cost = best->cost = -1;
  /* the reference: PETSc's grid with uniform cuts (when they respect the minimum widths) */
  PetscCall(BalanceDecompGrid(pb, pb->pref, PETSC_TRUE, w, t, ref));
  ref_ok = balance_keeps_whole(pb, pb->pref);
  /* pass 0: the grids that keep the axis `whole` unsplit, the reference's first; pass 1 (none of
     them fits): every grid. Splits of x before y before z on a tie. */
  for (int pass = 0; pass < 2 && best->cost < 0; pass++) {
    if (pass || ref_ok) PetscCall(BalanceDecompGrid(pb, pb->pref, PETSC_FALSE, w, t, best));
    for (PetscInt a = size; a >= 1; a--)
      for (PetscInt b = size / a; b >= 1; b--) {
        const PetscInt p[3] = {a, b, size / (a * b)};
        if (size % (a * b) || (a == pb->pref[0] && b == pb->pref[1])) continue;
        if (!pass && !balance_keeps_whole(pb, p)) continue;
        PetscCall(BalanceDecompGrid(pb, p, PETSC_FALSE, w, t, best));
      }
    ref_ok = (PetscBool)(ref_ok || pass == 1);
  }
  PetscCall(PetscFree3(t[0], t[1], t[2]));
  PetscCheck(best->cost >= 0, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "no process grid of %" PetscInt_FMT " ranks fits the %" PetscInt_FMT " x %" PetscInt_FMT " x %" PetscInt_FMT " cells with boxes at least the halo wide", size, pb->n[0], pb->n[1], pb->n[2]);
  if (ref_ok && ref->cost >= 0 && best->cost > (1 - pb->gain) * ref->cost) {
    best->cost     = ref->cost;
    best->own      = ref->own;
    best->ghost    = ref->ghost;
    best->balanced = PETSC_FALSE;
    for (int k = 0; k < 3; k++) {
      best->p[k] = ref->p[k];
      PetscCall(PetscArraycpy(best->l[k], ref->l[k], ref->p[k]));
    }
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}
