/* The DEM's profiling events, one per phase (-log_view): list rebuild (DemNeighbours, which
 * contains the migration and ghost creation counted again under DemExchange), ghost exchange,
 * pair contacts, wall contacts, integration, output, the placement check. Registered once per
 * process, by the first DemCreate. */
#include "dem/dem_core.h"

PetscLogEvent DEM_Exchange;
PetscLogEvent DEM_Neighbours;
PetscLogEvent DEM_Contacts;
PetscLogEvent DEM_Walls;
PetscLogEvent DEM_Integrate;
PetscLogEvent DEM_Output;
PetscLogEvent DEM_Placement;

static PetscClassId DEM_CLASSID;
static PetscBool    dem_registered = PETSC_FALSE;

PetscErrorCode DemEventsRegister(void)
{
  PetscFunctionBeginUser;
  if (dem_registered) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscClassIdRegister("DEM", &DEM_CLASSID));
  PetscCall(PetscLogEventRegister("DemNeighbours", DEM_CLASSID, &DEM_Neighbours));
  PetscCall(PetscLogEventRegister("DemExchange", DEM_CLASSID, &DEM_Exchange));
  PetscCall(PetscLogEventRegister("DemContacts", DEM_CLASSID, &DEM_Contacts));
  PetscCall(PetscLogEventRegister("DemWalls", DEM_CLASSID, &DEM_Walls));
  PetscCall(PetscLogEventRegister("DemIntegrate", DEM_CLASSID, &DEM_Integrate));
  PetscCall(PetscLogEventRegister("DemOutput", DEM_CLASSID, &DEM_Output));
  PetscCall(PetscLogEventRegister("DemPlacement", DEM_CLASSID, &DEM_Placement));
  dem_registered = PETSC_TRUE;
  PetscFunctionReturn(PETSC_SUCCESS);
}
