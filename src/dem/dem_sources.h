/* DEM private header of the particles that enter and leave: the initial insertion (lattice,
 * init file) and its overlap check, particle sources and their size distributions, outlets and
 * the in/out mass balance. Their state (DemInsertion, DemFlow, DemSinks, DemSources) is in
 * dem_sources_state.h, which the object's layout needs. */
#pragma once
#include "dem/dem_sources_state.h"

PetscErrorCode DemInsertSetFromOptions(Dem dem);                          /* insert.c */
PetscErrorCode DemInsert(Dem dem);                                        /* insert.c */
PetscErrorCode DemInsertRestartSizes(Dem dem);                            /* insert.c */
double         DemLatticeSpacing(Dem dem);                                /* insert.c */
PetscErrorCode DemSourcesSetFromOptions(Dem dem);                         /* sources_options.c */
PetscErrorCode DemSourcesSetUp(Dem dem);                                  /* sources_options.c: after the time step is known */
double         DemSourceMass(Dem dem, const DemSource *s, double d);      /* sources_options.c: a particle of diameter d (kg) */
PetscBool      DemSourcesDue(Dem dem);                                    /* sources.c: a batch is placed at this step (same on every rank) */
PetscErrorCode DemSourcesPlace(Dem dem);                                  /* sources.c: collective; the batch, pending until the rebuild */
PetscErrorCode DemSourcesAddPending(Dem dem);                             /* sources.c: in DemRebuild, ghosts dropped */
PetscErrorCode DemSourcesCheckpoint(Dem dem, IoCkpt ck, PetscBool write); /* sources.c */
PetscErrorCode DemSourcesDestroy(Dem dem);                                /* sources.c */
PetscErrorCode DemCheckPlacement(Dem dem);                                /* placement.c */

/* Outlets and the mass balance (sinks.c): called by dem.c (DemStep), rebuild.c and the
 * checkpoints; sinks.c calls particles.c and diag.c only. */
PetscErrorCode DemSinksSetFromOptions(Dem dem);
PetscErrorCode DemSinksMark(Dem dem);                                   /* not collective: the particles the outlets take at this step */
PetscErrorCode DemSinksRemove(Dem dem);                                 /* collective: removes the marked ones; global totals */
PetscErrorCode DemCheckBalance(Dem dem);                                /* collective: initial + inserted - removed = present */
PetscErrorCode DemSinksCheckpoint(Dem dem, IoCkpt ck, PetscBool write); /* collective: dem->flow and the outlets' totals */
PetscErrorCode DemSinksDestroy(Dem dem);
