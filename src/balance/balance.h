/* Load balancing of the one tensor-product decomposition (DESIGN §1; Lethe-DEM load balancing): per-axis cuts
 * (DMDA ownership ranges lx, ly, lz) that minimise the largest rank load, where a rank's load is
 * the sum of the cell weights W = alpha n_p + beta (linear) or alpha n_p^2 + beta (quadratic) over
 * its box (Golshan & Blais 2022, eqs. 1-2). Everything here is pure, serial and deterministic (no
 * MPI, no options): every rank given the same weights computes the same cuts. The algorithm and
 * its measured quality are described in cuts.c.
 * Conventions: cells w[i + n0 (j + n1 k)] (x fastest); l[d][r] = cells of the r-th rank along
 * axis d, sum_r l[d][r] = n[d], every l[d][r] >= minw[d]; rank loads in rank order, x fastest
 * (rank = rx + p0 (ry + p1 rz), as PETSc's DMDA numbers them). */
#pragma once
#include "sable.h"

typedef enum {
  BALANCE_WEIGHT_LINEAR,
  BALANCE_WEIGHT_QUADRATIC
} BalanceWeightModel;
/* names for PetscOptionsEnum (-lb_weight linear|quadratic) */
extern const char *const BalanceWeightModels[];

typedef struct {
  BalanceWeightModel model;
  PetscReal          alpha; /* weight of a particle (linear) or of n_p^2 (quadratic) */
  PetscReal          beta;  /* weight of a cell */
} BalanceWeight;

typedef struct {
  PetscInt n[3];       /* global cell counts */
  PetscInt p[3];       /* process grid */
  PetscInt minw[3];    /* smallest subdomain width in cells (>= 1; the halo width) */
  PetscInt max_sweeps; /* cap on coordinate-descent rounds (0: default 20) */
} BalanceGrid;

/* Cell weights from per-cell particle counts: w[c] = alpha count[c] + beta or
 * alpha count[c]^2 + beta. Errors when alpha or beta is negative or not finite. */
PetscErrorCode BalanceCellWeights(const BalanceWeight *wm, PetscInt ncells, const PetscInt *count, PetscReal *w);

/* The optimised cuts (see cuts.c): fills l[0][0..p0-1], l[1][..], l[2][..] (arrays owned
 * by the caller) and returns the largest rank load lmax and the mean lavg = total / (p0 p1 p2).
 * Errors (PETSC_ERR_ARG_OUTOFRANGE) when n[d] < p[d] minw[d] or a weight is negative or NaN. */
PetscErrorCode BalanceCuts(const BalanceGrid *g, const PetscReal *w, PetscInt *const l[3], PetscReal *lmax, PetscReal *lavg);
/* The starting point of BalanceCuts: each axis cut where the cumulative projected weight
 * crosses j total / p[d] (nearest cell face), pushed apart to respect minw. */
PetscErrorCode BalanceMarginalCuts(const BalanceGrid *g, const PetscReal *w, PetscInt *const l[3]);
/* What a DMDA does without balancing: l[d][r] = n/p + (n % p > r). */
PetscErrorCode BalanceUniformCuts(const BalanceGrid *g, PetscInt *const l[3]);
/* The load of every rank (p0 p1 p2 entries, rank order x fastest) for the cuts l; each rank's
 * cells are summed in global cell order. */
PetscErrorCode BalanceLoads(const BalanceGrid *g, const PetscReal *w, PetscInt *const l[3], PetscReal *load);
/* The process grid PETSc 3.18's DMDA chooses for `size` ranks on n[0] x n[1] x n[2] cells when
 * -da_processors_x/y/z are not given (the "squarish" factorisation of DMSetUp_DA_3D). Like the
 * DMDA's, it may exceed the cells along an axis: the caller checks p[d] minw[d] <= n[d]. */
PetscErrorCode BalanceProcessGrid(const PetscInt n[3], PetscInt size, PetscInt p[3]);

/* The decomposition of a run's start (decompose.c): the problem, */
typedef struct {
  PetscInt  n[3];          /* global cell counts */
  PetscInt  size;          /* ranks */
  PetscInt  pref[3];       /* the reference process grid (PETSc's default), kept with uniform cuts unless beaten by gain */
  PetscInt  minw[3];       /* thinnest box along an axis of one rank (cells) */
  PetscInt  minw_split[3]; /* thinnest box along a split axis (cells; the halo) */
  PetscReal halo[3];       /* halo depth in cells, reach / h */
  PetscBool periodic[3];
  PetscInt  max_sweeps; /* of BalanceCuts */
  PetscReal gain;       /* relative lowering of the estimate needed to leave the reference */
  PetscInt  whole;      /* an axis to leave unsplit when a grid allows it (gravity's), or -1 */
} BalanceDecompProblem;
/* and a candidate: process grid, cuts l[k][0..p[k]-1] (arrays of pb->size entries owned by the
 * caller), the estimate (largest rank load plus ghosts) and that rank's load and ghosts. */
typedef struct {
  PetscInt  p[3];
  PetscInt *l[3];
  PetscBool balanced; /* cuts from BalanceCuts, else the DMDA's uniform ones */
  PetscReal cost, own, ghost;
} BalanceDecomp;
/* The estimate of the decomposition (p, l) on the cell weights w. */
PetscErrorCode BalanceDecompCost(const BalanceDecompProblem *pb, const PetscInt p[3], PetscInt *const l[3], const PetscReal *w, PetscReal *cost, PetscReal *own, PetscReal *ghost);
/* The best decomposition into *best and the reference into *ref (ref->cost < 0: its uniform
 * cuts are thinner than the minimum widths): among the grids that leave pb->whole unsplit, or
 * all grids when none does. Errors when no process grid fits. */
PetscErrorCode BalanceBestDecomposition(const BalanceDecompProblem *pb, const PetscReal *w, BalanceDecomp *best, BalanceDecomp *ref);
