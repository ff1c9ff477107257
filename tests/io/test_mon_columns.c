/* Monitor columns: a row's values are placed by the name and unit of the column they belong to,
 * not by position alone. Three columns are added (two of them of one unit, so that a swap keeps
 * the count and the units); MonCheckColumn must accept each value under its own column and
 * refuse, in one error, a value under its neighbour's name (a swap), under another unit, and past
 * the last column. The header written must give each column the unit it was added with, in the
 * form "name [unit]" that tools/plot_monitor reads. */
#include "check.h"
#include "io/io.h"
#include <unistd.h>

/* Whether MonCheckColumn refuses (name, unit) for column c, with PETSc's error printing off. */
static PetscErrorCode Refused(Mon mon, PetscInt c, const char *name, const char *unit, PetscBool *refused)
{
  PetscErrorCode ierr;

  PetscFunctionBeginUser;
  PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
  ierr = MonCheckColumn(mon, c, name, unit);
  PetscCall(PetscPopErrorHandler());
  *refused = (PetscBool)(ierr == PETSC_ERR_PLIB);
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  const char *name[3] = {"time", "kinetic_energy", "rotational_energy"}, *unit[3] = {"s", "J", "J"};
  const char *want = "time [s],kinetic_energy [J],rotational_energy [J]";
  char        path[PETSC_MAX_PATH_LEN], dir[] = "/tmp/sable_mon_columns_XXXXXX", header[256] = "";
  PetscInt    accepted = 0;
  PetscBool   refused;
  Mon         mon;
  FILE       *fp;

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCheck(mkdtemp(dir), PETSC_COMM_SELF, PETSC_ERR_SYS, "mkdtemp failed");
  PetscCall(PetscSNPrintf(path, sizeof path, "%s/m.csv", dir));
  PetscCall(PetscOptionsSetValue(NULL, "-mon_interval", "1"));
  PetscCall(PetscOptionsSetValue(NULL, "-mon_file", path));
  PetscCall(MonCreate(PETSC_COMM_SELF, &mon));
  PetscCall(MonSetFromOptions(mon));
  PetscCall(MonSetUp(mon, NULL));
  for (int c = 0; c < 3; c++) PetscCall(MonAddColumn(mon, name[c], unit[c]));
  for (int c = 0; c < 3; c++) {
    PetscCall(Refused(mon, c, name[c], unit[c], &refused));
    accepted += !refused;
  }
  PetscCall(CheckEqual("values under their own columns accepted", accepted, 3));
  PetscCall(Refused(mon, 1, name[2], unit[2], &refused));
  PetscCall(CheckTrue("a value under its neighbour's column of the same unit (a swap) refused", refused, refused ? "refused" : "accepted"));
  PetscCall(Refused(mon, 1, name[1], "W", &refused));
  PetscCall(CheckTrue("a value under its own name with another unit refused", refused, refused ? "refused" : "accepted"));
  PetscCall(Refused(mon, 3, "extra", "-", &refused));
  PetscCall(CheckTrue("a value past the last column refused", refused, refused ? "refused" : "accepted"));
  PetscCall(MonWriteRow(mon, (const PetscReal[]){0, 1, 2}));
  PetscCall(MonDestroy(&mon));
  fp = fopen(path, "r");
  if (fp) {
    if (!fgets(header, sizeof header, fp)) header[0] = 0;
    fclose(fp);
  }
  header[strcspn(header, "\n")] = 0;
  PetscCall(CheckTrue(CheckName("header \"%s\": each column's name and unit as added", want), (PetscBool)!strcmp(header, want), header));
  remove(path);
  rmdir(dir);
  PetscCall(PetscFinalize());
  return check_failures ? 1 : 0;
}
