/* Domain: the box, its periodicity and the DMDA that decomposes it (see domain.h). The rank box
 * is the union of its owned cells, so particle and fluid ownership coincide by construction. */
#include "domain.h"

PetscErrorCode DomainSetFromOptions(MPI_Comm comm, Domain *dom)
{
  PetscBool set;

  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(dom, sizeof *dom)); /* defaults: unit box, not periodic */
  for (int k = 0; k < 3; k++) dom->hi[k] = 1;
  dom->comm = comm;
  PetscOptionsBegin(comm, NULL, "Domain (shared by DEM and fluid)", NULL);
  PetscCall(SableOptionsRealN("-domain_lo", "Lower corner of the domain box", "m", dom->lo, 3, 3, &set));
  PetscCall(SableOptionsRealN("-domain_hi", "Upper corner of the domain box", "m", dom->hi, 3, 3, &set));
  PetscCall(SableOptionsBool("-domain_periodic_x", "Periodic along x", dom->periodic[0], &dom->periodic[0], NULL));
  PetscCall(SableOptionsBool("-domain_periodic_y", "Periodic along y", dom->periodic[1], &dom->periodic[1], NULL));
  PetscCall(SableOptionsBool("-domain_periodic_z", "Periodic along z", dom->periodic[2], &dom->periodic[2], NULL));
  PetscCall(SableOptionsReal("-domain_cell", "Cell size of the grid; -da_grid_x/y/z override it; default 4 largest particle diameters (1.25 with -lb_scheme)", "m", "(0,inf)", 0, &dom->cell, &dom->cell_set));
  PetscOptionsEnd();
  for (int k = 0; k < 3; k++) {
    dom->len[k] = dom->hi[k] - dom->lo[k];
    PetscCheck(dom->len[k] > 0, PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE, "-domain_hi[%d] = %g must exceed -domain_lo[%d] = %g", k, (double)dom->hi[k], k, (double)dom->lo[k]);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* PETSc's own message for a process grid that does not fit is terse; say which option and why. */
static PetscErrorCode DomainCheckProcessGrid(MPI_Comm comm, const PetscInt m[3])
{
  const char *opt[3] = {"-da_processors_x", "-da_processors_y", "-da_processors_z"}, *grid[3] = {"-da_grid_x", "-da_grid_y", "-da_grid_z"};
  PetscInt    p[3] = {0, 0, 0}, prod = 1, cells, pc[3] = {0, 0, 0}, c[3];
  PetscBool   set[3], gset, all = PETSC_TRUE, fits = PETSC_FALSE;
  PetscMPIInt size;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  for (int k = 0; k < 3; k++) {
    PetscCall(PetscOptionsGetInt(NULL, NULL, opt[k], &p[k], &set[k]));
    cells = m[k];
    PetscCall(PetscOptionsGetInt(NULL, NULL, grid[k], &cells, &gset));
    c[k] = cells;
    PetscCheck(cells >= 1, comm, PETSC_ERR_ARG_OUTOFRANGE, "%s %" PetscInt_FMT " must be >= 1", grid[k], cells);
    if (!set[k]) {
      all = PETSC_FALSE;
      continue;
    }
    pc[k] = cells;
    prod *= PetscMax(p[k], 1);
  }
  PetscCheck(all ? prod == size : size % prod == 0, comm, PETSC_ERR_ARG_INCOMP, "the process grid -da_processors_x/y/z (%" PetscInt_FMT " x %" PetscInt_FMT " x %" PetscInt_FMT ", 0 = free) does not fit the %d MPI ranks: the product must %s %d", p[0], p[1], p[2], (int)size, all ? "equal" : "divide", (int)size);
  for (int k = 0; k < 3; k++)
    PetscCheck(!set[k] || (p[k] >= 1 && p[k] <= pc[k]), comm, PETSC_ERR_ARG_OUTOFRANGE, "%s %" PetscInt_FMT " must be in [1, %" PetscInt_FMT "], the cells along that axis (-domain_cell or -da_grid_%c)", opt[k], p[k], pc[k], "xyz"[k]);
  /* PETSc's message when no process grid fits the cells is "Partition in z direction is too
     fine! 1 2": look for one first (every rank needs a cell along each axis) */
  for (PetscInt a = 1; a <= size && !fits; a++)
    for (PetscInt b = 1; a * b <= size && !fits; b++) {
      const PetscInt q[3] = {a, b, size / (a * b)};
      if (size % (a * b)) continue;
      fits = PETSC_TRUE;
      for (int k = 0; k < 3; k++) fits = (PetscBool)(fits && q[k] <= c[k] && (!set[k] || !p[k] || p[k] == q[k]));
    }
  PetscCheck(fits, comm, PETSC_ERR_ARG_INCOMP, "the grid of %" PetscInt_FMT " x %" PetscInt_FMT " x %" PetscInt_FMT " cells cannot be split over %d ranks (each needs a cell along every axis): a smaller -domain_cell (by default 4 particle diameters) or -da_grid_x/y/z, or fewer ranks", c[0], c[1], c[2], (int)size);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The grid, the process grid and this rank's cells and box, read back from dom->da. */
static PetscErrorCode DomainSetBoxes(Domain *dom)
{
  PetscFunctionBeginUser;
  PetscCall(DMDAGetInfo(dom->da, NULL, &dom->cells[0], &dom->cells[1], &dom->cells[2], &dom->nranks[0], &dom->nranks[1], &dom->nranks[2], NULL, NULL, NULL, NULL, NULL, NULL));
  PetscCall(DMDAGetCorners(dom->da, &dom->cstart[0], &dom->cstart[1], &dom->cstart[2], &dom->ccount[0], &dom->ccount[1], &dom->ccount[2]));
  for (int k = 0; k < 3; k++) {
    dom->h[k]     = dom->len[k] / dom->cells[k];
    dom->sublo[k] = dom->lo[k] + dom->cstart[k] * dom->h[k];
    /* the last rank's upper face is exactly hi, not lo + cells*h with roundoff */
    dom->subhi[k] = (dom->cstart[k] + dom->ccount[k] == dom->cells[k]) ? dom->hi[k] : dom->lo[k] + (dom->cstart[k] + dom->ccount[k]) * dom->h[k];
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DomainSetUp(Domain *dom, PetscReal default_cell, PetscInt stencil_width)
{
  DMBoundaryType bt[3];
  PetscInt       m[3];
  MPI_Comm       comm = dom->comm;

  PetscFunctionBeginUser;
  if (dom->cell_set) default_cell = dom->cell;
  PetscCheck(default_cell > 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-domain_cell %g must be > 0 (m)", (double)default_cell);
  { /* -da_grid_x/y/z override -domain_cell axis by axis: with all three it would be ignored */
    PetscBool g[3];
    PetscCall(PetscOptionsHasName(NULL, NULL, "-da_grid_x", &g[0]));
    PetscCall(PetscOptionsHasName(NULL, NULL, "-da_grid_y", &g[1]));
    PetscCall(PetscOptionsHasName(NULL, NULL, "-da_grid_z", &g[2]));
    PetscCheck(!dom->cell_set || !(g[0] && g[1] && g[2]), comm, PETSC_ERR_ARG_INCOMP, "-domain_cell %g and -da_grid_x, -da_grid_y, -da_grid_z are all given; the grid counts override -domain_cell, which would be ignored: give one of them", (double)default_cell);
  }
  for (int k = 0; k < 3; k++) { /* a count beyond PetscInt would wrap (to 1 cell, or a negative one) */
    const PetscReal n = PetscFloorReal(dom->len[k] / default_cell);
    PetscCheck(n <= PETSC_MAX_INT, comm, PETSC_ERR_ARG_OUTOFRANGE, "-domain_cell %g m (by default 4 particle diameters) gives %g cells along %c, more than %" PetscInt_FMT ": give a larger cell", (double)default_cell, (double)n, "xyz"[k], (PetscInt)PETSC_MAX_INT);
    m[k]  = PetscMax(1, (PetscInt)n);
    bt[k] = dom->periodic[k] ? DM_BOUNDARY_PERIODIC : DM_BOUNDARY_GHOSTED;
  }
  PetscCall(DomainCheckProcessGrid(comm, m));
  PetscCall(DMDACreate3d(comm, bt[0], bt[1], bt[2], DMDA_STENCIL_BOX, m[0], m[1], m[2], PETSC_DECIDE, PETSC_DECIDE, PETSC_DECIDE, 1, stencil_width, NULL, NULL, NULL, &dom->da));
  PetscCall(DMSetFromOptions(dom->da));
  PetscCall(DMSetUp(dom->da));
  PetscCall(DomainSetBoxes(dom));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DomainDestroy(Domain *dom)
{
  PetscFunctionBeginUser;
  PetscCall(DMDestroy(&dom->da));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DomainSetDecomposition(Domain *dom, const PetscInt p[3], PetscInt *const l[3])
{
  DM             da;
  DMBoundaryType bt[3];
  PetscInt       sw;
  MPI_Comm       comm = PetscObjectComm((PetscObject)dom->da);

  PetscFunctionBeginUser;
  PetscCall(DMDAGetInfo(dom->da, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL, &sw, &bt[0], &bt[1], &bt[2], NULL));
  for (int k = 0; k < 3; k++) {
    PetscInt sum = 0;
    for (PetscInt r = 0; r < p[k]; r++) {
      PetscCheck(l[k][r] >= 1, comm, PETSC_ERR_ARG_OUTOFRANGE, "new ownership along %c: rank column %" PetscInt_FMT " gets %" PetscInt_FMT " cells, must be >= 1", "xyz"[k], r, l[k][r]);
      sum += l[k][r];
    }
    PetscCheck(sum == dom->cells[k], comm, PETSC_ERR_ARG_SIZ, "new ownership along %c sums to %" PetscInt_FMT " cells, the grid has %" PetscInt_FMT, "xyz"[k], sum, dom -> cells[k]);
  }
  /* the new DMDA before the old one goes: they share PETSc's inner communicator, which objects
     created on the old one (the fluid's) keep using */
  PetscCall(DMDACreate3d(comm, bt[0], bt[1], bt[2], DMDA_STENCIL_BOX, dom->cells[0], dom->cells[1], dom->cells[2], p[0], p[1], p[2], 1, sw, l[0], l[1], l[2], &da));
  PetscCall(DMSetUp(da));
  PetscCall(DMDestroy(&dom->da));
  dom->da = da;
  PetscCall(DomainSetBoxes(dom));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DomainSetOwnership(Domain *dom, PetscInt *const l[3])
{
  const PetscInt p[3] = {dom->nranks[0], dom->nranks[1], dom->nranks[2]};

  PetscFunctionBeginUser;
  PetscCall(DomainSetDecomposition(dom, p, l));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DomainProcessGridGiven(PetscBool *given)
{
  PetscBool set;

  PetscFunctionBeginUser;
  *given = PETSC_FALSE;
  for (int k = 0; k < 3; k++) {
    const char *opt[3] = {"-da_processors_x", "-da_processors_y", "-da_processors_z"};
    PetscCall(PetscOptionsHasName(NULL, NULL, opt[k], &set));
    *given = (PetscBool)(*given || set);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DomainMoveVec(DM from, DM to, Vec *v)
{
  Vec        nfrom, nto, out;
  VecScatter sc;
  IS         is;
  PetscInt   rs, re;

  PetscFunctionBeginUser;
  PetscCall(DMDACreateNaturalVector(from, &nfrom));
  PetscCall(DMDAGlobalToNaturalBegin(from, *v, INSERT_VALUES, nfrom));
  PetscCall(DMDAGlobalToNaturalEnd(from, *v, INSERT_VALUES, nfrom));
  PetscCall(DMDACreateNaturalVector(to, &nto));
  PetscCall(VecGetOwnershipRange(nto, &rs, &re));
  PetscCall(ISCreateStride(PetscObjectComm((PetscObject)to), re - rs, rs, 1, &is));
  PetscCall(VecScatterCreate(nfrom, is, nto, is, &sc));
  PetscCall(VecScatterBegin(sc, nfrom, nto, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(sc, nfrom, nto, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(DMCreateGlobalVector(to, &out));
  PetscCall(DMDANaturalToGlobalBegin(to, nto, INSERT_VALUES, out));
  PetscCall(DMDANaturalToGlobalEnd(to, nto, INSERT_VALUES, out));
  PetscCall(VecScatterDestroy(&sc));
  PetscCall(ISDestroy(&is));
  PetscCall(VecDestroy(&nfrom));
  PetscCall(VecDestroy(&nto));
  PetscCall(VecDestroy(v));
  *v = out;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DomainCreate(MPI_Comm comm, PetscReal default_cell, PetscInt stencil_width, Domain *dom)
{
  PetscFunctionBeginUser;
  PetscCall(DomainSetFromOptions(comm, dom));
  PetscCall(DomainSetUp(dom, default_cell, stencil_width));
  PetscFunctionReturn(PETSC_SUCCESS);
}
