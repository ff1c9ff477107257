/* The rebuild: everything that changes the local particles' order and the lists at once, run by
 * DemSetUp, by DemStep when a particle or a wall moved more than skin/2 since the last one (all
 * ranks agree, dem.c), and by DemRedistribute after the decomposition changed:
 *   springs saved by id pair (springs.c; the mesh walls' slots, walls_mesh.c) -> the particles outlets took removed (sinks.c: their
 *   springs find no partner) -> migration of the particles that left the box, to a
 *   neighbour (exchange.c) or, after a remap, to any rank (redistribute.c) -> re-sort of the
 *   locals every -dem_sort_interval builds (neighbours.c) -> ghost creation (exchange.c) -> bins
 *   and pair list (neighbours.c) -> springs restored by id pair -> wall lists (walls.c) and mesh
 *   candidates (walls_mesh.c) -> the
 *   reference positions of the rebuild check (x0, the walls' travel) reset.
 * It sits above the files it calls; none of them calls it back. */
#include "dem/dem_core.h"
#include "dem/dem_walls.h"
#include "dem/dem_sources.h"

/* Collective. The rebuild from the migration on, with the springs as id-keyed records (sorted;
 * freed here): DemRebuild's after it saved them, a checkpoint's read on another rank count. */
PetscErrorCode DemRebuildFrom(Dem dem, DemSpring *recs, PetscInt nrec, PetscInt caprec)
{
  PetscFunctionBeginUser;
  dem->state++; /* migration and re-sorting change the local order */
  dem->p.ng = 0;
  if (dem->sinks.nout) PetscCall(DemSinksRemove(dem)); /* the particles outlets took (sinks.c) */
  PetscCall(PetscLogEventBegin(DEM_Exchange, 0, 0, 0, 0));
  PetscCall(DemCheckInDomain(dem));
  if (dem->ex.remap) PetscCall(DemMigrateGlobal(dem, &recs, &nrec, &caprec));
  else PetscCall(DemMigrate(dem, &recs, &nrec, &caprec));
  dem->ex.remap = PETSC_FALSE;
  PetscCall(PetscLogEventEnd(DEM_Exchange, 0, 0, 0, 0));
  PetscCall(DemNeighSort(dem));
  PetscCall(PetscLogEventBegin(DEM_Exchange, 0, 0, 0, 0));
  PetscCall(DemGhostsCreate(dem));
  PetscCall(PetscLogEventEnd(DEM_Exchange, 0, 0, 0, 0));
  PetscCall(DemNeighBuildList(dem));
  if (dem->contact.law != DEM_LAW_LINEAR_NOHIST) PetscCall(DemSpringsRestore(dem, recs, nrec));
  PetscCall(DemWallsBuildLists(&dem->walls, &dem->p, &dem->shapes, dem->nl.skin, recs, nrec));
  if (dem->meshes.n) PetscCall(DemMeshesBuildLists(dem, recs, nrec)); /* walls_mesh.c */
  PetscCall(PetscArraycpy(dem->p.x0, dem->p.x, 3 * dem->p.n));
  for (PetscInt w = 0; w < dem->walls.nwall; w++) dem->walls.wall[w].moved = 0;
  dem->need_build = PETSC_FALSE;
  PetscCall(PetscFree(recs));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. Rebuilds exchange, cells, lists and springs. */
PetscErrorCode DemRebuild(Dem dem)
{
  DemSpring *recs;
  PetscInt   nrec, caprec;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(DEM_Neighbours, 0, 0, 0, 0));
  PetscCall(DemSpringsSave(dem, &recs, &nrec, &caprec));
  if (dem->meshes.n) PetscCall(DemMeshesSaveSprings(dem, &recs, &nrec, &caprec)); /* walls_mesh.c */
  PetscCall(DemSourcesAddPending(dem));                                           /* a source's batch joins once the springs are saved */
  PetscCall(DemRebuildFrom(dem, recs, nrec, caprec));
  PetscCall(PetscLogEventEnd(DEM_Neighbours, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemRedistribute(Dem dem)
{
  PetscFunctionBeginUser;
  PetscCall(DemExchangeSetUp(dem));   /* same neighbours; re-checks the box widths */
  PetscCall(DemNeighResetCells(dem)); /* the cell grid covers the new box */
  dem->ex.remap = PETSC_TRUE;
  PetscCall(DemRebuild(dem));
  PetscFunctionReturn(PETSC_SUCCESS);
}
