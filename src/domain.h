/* The one cartesian decomposition of a run (DESIGN §1). A cell-centred PETSc DMDA over the box
 * [lo, hi] decides the process grid and each rank's box; the fluid uses it as its grid, a dry
 * case uses it as a coarse background grid, and the DEM owns the particles whose centre lies in
 * the rank's box. Options: -domain_lo, -domain_hi (m), -domain_periodic_x/y/z, and PETSc's own
 * -da_grid_x/y/z and -da_processors_x/y/z; -domain_cell sets the default cell size. */
#pragma once
#include "sable.h"

typedef struct {
  MPI_Comm  comm;
  PetscReal cell; /* -domain_cell (m), when cell_set */
  PetscBool cell_set;
  PetscReal lo[3], hi[3], len[3]; /* global box (m) */
  PetscBool periodic[3];
  DM        da;                   /* cell-centred DMDA, one dof */
  PetscInt  cells[3];             /* global cell counts */
  PetscReal h[3];                 /* cell size (m) */
  PetscInt  cstart[3], ccount[3]; /* this rank's owned cells */
  PetscReal sublo[3], subhi[3];   /* this rank's box (m) */
  PetscInt  nranks[3];            /* process grid */
} Domain;

/* Collective. Reads the -domain_ options (the box is known, the grid is not yet built), so that
 * the objects whose options decide the default cell can be read before DomainSetUp. */
PetscErrorCode DomainSetFromOptions(MPI_Comm comm, Domain *dom);
/* Collective. Builds the DMDA: the default cell count per axis is len/cell (at least 1), cell =
 * -domain_cell or else default_cell. stencil_width is the DMDA ghost width the caller needs. */
PetscErrorCode DomainSetUp(Domain *dom, PetscReal default_cell, PetscInt stencil_width);
/* Collective. DomainSetFromOptions then DomainSetUp. */
PetscErrorCode DomainCreate(MPI_Comm comm, PetscReal default_cell, PetscInt stencil_width, Domain *dom);
PetscErrorCode DomainDestroy(Domain *dom);
/* Collective. Replaces the DMDA by one with the same grid and process grid but the per-axis
 * ownership ranges l[k][0..nranks[k]-1] (cells per rank column, summing to cells[k]), and
 * updates this rank's cells and box. The caller moves the data living on the old layout. */
PetscErrorCode DomainSetOwnership(Domain *dom, PetscInt *const l[3]);
/* Collective. As DomainSetOwnership, with the process grid p[0] x p[1] x p[2] (same rank count)
 * as well: l[k][0..p[k]-1]. */
PetscErrorCode DomainSetDecomposition(Domain *dom, const PetscInt p[3], PetscInt *const l[3]);
/* Not collective. Whether the user gave any of -da_processors_x/y/z (then the process grid is
 * theirs and Sable does not choose one). */
PetscErrorCode DomainProcessGridGiven(PetscBool *given);
/* Collective. Moves the global Vec *v of DMDA from onto DMDA to (same grid and dofs, another
 * ownership) through the natural ordering: every value lands bit for bit at the same grid
 * point. *v is destroyed and replaced. */
PetscErrorCode DomainMoveVec(DM from, DM to, Vec *v);
