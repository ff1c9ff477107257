/* DEM private header of the checkpoints (checkpoint.c, checkpoint_remap.c): the per-rank
 * counters, the table of per-particle datasets and the read on another rank count. */
#pragma once
#include "dem/dem.h"

PetscErrorCode DemCheckpointNeedsRemap(Dem dem, IoCkpt ck, PetscBool *remap); /* checkpoint_remap.c: another rank count or other boxes */
PetscErrorCode DemCheckpointReadRemap(Dem dem, IoCkpt ck);                    /* checkpoint_remap.c */

/* Checkpoints (checkpoint.c, checkpoint_remap.c). The per-rank counters of dem/counters, in
 * their stored order (DemCkptCounters). */
enum {
  CK_N,
  CK_NG,
  CK_NEXT_ID,
  CK_BUILDS,
  CK_SORTS,
  CK_STEP,
  CK_STATE,
  CK_INITIAL_N,
  CK_NWALL,
  CK_MIGRATED,
  CK_NC0,
  CK_NC1,
  CK_NC2,
  CK_NEED_BUILD,
  DEM_CKPT_NCOUNT
};
