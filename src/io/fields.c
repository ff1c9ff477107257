/* The datasets of a frame that -io_fields chooses from (see io.h): a table of every dataset a
 * frame may hold, by group and kind (0 the particles' cadence, 1 the fluid's), the reader of
 * -io_fields, and IoFrameWants, which the writers ask before they gather a dataset. A dataset
 * written under a name not in the table is always written: a new dataset is one line here.
 * particles/position is written (with the vertex list) whenever any particle dataset is: it is
 * the points every particle dataset lies on; -io_fields without any (fluid only) writes no
 * particle frames. The fluid grid lives in the XDMF index and needs no dataset. */
#include "io/io_private.h"

static const struct {
  const char *group, *name;
  int         kind;
} io_fields[] = {
  {"particles", "position", 0},
  {"particles", "velocity", 0},
  {"particles", "angular_velocity", 0},
  {"particles", "quaternion", 0},
  {"particles", "radius", 0},
  {"particles", "id", 0},
  {"particles", "shape", 0},
  {"surface", "surface", 0},
  {"fluid", "eps", 1},
  {"fluid", "p", 1},
  {"fluid", "velocity", 1},
  {"fluid", "vessel", 1},
  {"fluid", "avg_solids_fraction", 1},
  {"fluid", "rms_solids_fraction", 1},
  {"fluid", "avg_fluid_velocity", 1},
  {"fluid", "rms_fluid_velocity", 1},
  {"fluid", "avg_particle_velocity", 1},
  {"fluid", "rms_particle_velocity", 1},
};
#define IO_NFIELDS ((int)(sizeof io_fields / sizeof io_fields[0]))
_Static_assert(sizeof io_fields / sizeof io_fields[0] <= IO_MAX_FIELDS, "IO_MAX_FIELDS (io_private.h) holds every dataset of the table");

/* The entry of group/name in io_fields, -1 if none. */
static int io_field_find(const char *group, const char *name)
{
  for (int k = 0; k < IO_NFIELDS; k++)
    if (!strcmp(io_fields[k].group, group) && !strcmp(io_fields[k].name, name)) return k;
  return -1;
}

/* Marks in sel the entries an item of -io_fields names: a group (particles: with the surface;
 * fluid: with the averages), group/name, or a name that only one group has. Returns the count
 * marked (0: unknown; -1: a name of two groups). */
static int io_field_select(const char *item, PetscBool sel[])
{
  const char *slash = strchr(item, '/');
  int         n     = 0;

  if (!strcmp(item, "particles") || !strcmp(item, "fluid")) {
    for (int k = 0; k < IO_NFIELDS; k++)
      if (io_fields[k].kind == (item[0] == 'f')) sel[k] = PETSC_TRUE, n++;
    return n;
  }
  for (int k = 0; k < IO_NFIELDS; k++) {
    size_t lg = strlen(io_fields[k].group);
    if (slash ? (!strncmp(item, io_fields[k].group, lg) && item + lg == slash && !strcmp(slash + 1, io_fields[k].name)) : !strcmp(item, io_fields[k].name)) n++;
  }
  if (n != 1) return n > 1 ? -1 : 0;
  for (int k = 0; k < IO_NFIELDS; k++) {
    size_t lg = strlen(io_fields[k].group);
    if (slash ? (!strncmp(item, io_fields[k].group, lg) && item + lg == slash && !strcmp(slash + 1, io_fields[k].name)) : !strcmp(item, io_fields[k].name)) sel[k] = PETSC_TRUE;
  }
  return 1;
}

/* Collective. -io_fields into io->skip: unknown or ambiguous names are one error line listing
 * the valid ones; particles/position is always written (the points every particle dataset
 * lies on). */
PetscErrorCode IoReadFields(Io io, PetscOptionItems *PetscOptionsObject)
{
  char     *items[IO_MAX_FIELDS];
  PetscInt  n = IO_MAX_FIELDS;
  PetscBool set, sel[IO_MAX_FIELDS] = {PETSC_FALSE};
  char      valid[1024] = "particles, fluid";

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsStringArray("-io_fields", "Datasets a frame holds, comma separated: particles, fluid (a whole group), or particles/<name>, fluid/<name>, surface, or a name only one group has (eps); particles/position goes with any particle dataset; default all", NULL, items, &n, &set));
  if (!set) PetscFunctionReturn(PETSC_SUCCESS);
  for (int k = 0; k < IO_NFIELDS; k++) {
    PetscCall(PetscStrlcat(valid, ", ", sizeof valid));
    if (strcmp(io_fields[k].group, "surface")) {
      PetscCall(PetscStrlcat(valid, io_fields[k].group, sizeof valid));
      PetscCall(PetscStrlcat(valid, "/", sizeof valid));
    }
    PetscCall(PetscStrlcat(valid, io_fields[k].name, sizeof valid));
  }
  for (PetscInt i = 0; i < n; i++) {
    int  m = io_field_select(items[i], sel);
    char item[128];
    if (m > 0) continue;
    PetscCall(PetscStrncpy(item, items[i], sizeof item));
    for (PetscInt j = 0; j < n; j++) PetscCall(PetscFree(items[j]));
    PetscCheck(m == 0, io->comm, PETSC_ERR_ARG_WRONG, "-io_fields %s: both particles/%s and fluid/%s: say which", item, item, item);
    SETERRQ(io->comm, PETSC_ERR_ARG_WRONG, "-io_fields %s: not a dataset of a frame; valid: %s (a bare name where one group has it)", item, valid);
  }
  for (PetscInt j = 0; j < n; j++) PetscCall(PetscFree(items[j]));
  { /* particles/position goes with any particle dataset (the points they lie on); none chosen: no particle frames */
    PetscBool any = PETSC_FALSE;
    for (int k = 0; k < IO_NFIELDS; k++) any = (PetscBool)(any || (io_fields[k].kind == 0 && sel[k]));
    if (any) sel[io_field_find("particles", "position")] = PETSC_TRUE;
  }
  for (int k = 0; k < IO_NFIELDS; k++) io->skip[k] = (PetscBool)!sel[k];
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IoFrameWants(Io io, const char *group, const char *name, PetscBool *wants)
{
  int k = -1;

  PetscFunctionBeginUser;
  *wants = io->kind[strcmp(group, "fluid") ? 0 : 1];
  if (name) k = io_field_find(group, name);
  else if (*wants) { /* any dataset of the group */
    PetscBool any = PETSC_FALSE;
    for (int j = 0; j < IO_NFIELDS; j++) any = (PetscBool)(any || (!strcmp(io_fields[j].group, group) && !io->skip[j]));
    *wants = any;
  }
  if (k >= 0 && io->skip[k]) *wants = PETSC_FALSE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscBool IoKindChosen(Io io, int kind)
{
  for (int k = 0; k < IO_NFIELDS; k++)
    if (io_fields[k].kind == kind && !io->skip[k]) return PETSC_TRUE;
  return PETSC_FALSE;
}
