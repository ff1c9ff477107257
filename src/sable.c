/* Sable-wide helpers: the unused-option check (DESIGN §9). */
#include "sable.h"

/* Options of a multigrid preconditioner's levels are read when the solver is set up, after the
 * start-up check: they are checked at the end of the run instead (SableWarnOptionsUnused). */
static PetscBool SableReadAtSolverSetUp(const char *name) { return (PetscBool)(strstr(name, "_mg_levels_") || strstr(name, "_mg_coarse_")); }

PetscErrorCode SableWarnOptionsUnused(MPI_Comm comm)
{
  PetscInt n;
  char   **names, **values;

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsLeftGet(NULL, &n, &names, &values));
  for (PetscInt i = 0; i < n; i++)
    if (SableReadAtSolverSetUp(names[i])) PetscCall(PetscPrintf(comm, "warning: option -%s %s was never read (a typo? -help lists the valid options)\n", names[i], values[i] ? values[i] : ""));
  PetscCall(PetscOptionsLeftRestore(NULL, &n, &names, &values));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SableCheckOptionsUsed(MPI_Comm comm)
{
  PetscInt n, bad = -1;
  char   **names, **values;
  char     msg[512] = "";

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsLeftGet(NULL, &n, &names, &values));
  for (PetscInt i = 0; i < n && bad < 0; i++) {
    /* options that steer PETSc's run-time system, read after us or not at all */
    const char *skip[] = {"options_left", "log_view", "malloc", "help", "on_error", "info", "history", "options_file", "fp_trap", "check_pointer_intensity", "use_gpu_aware_mpi"};
    PetscBool   ok     = SableReadAtSolverSetUp(names[i]);
    for (size_t k = 0; k < sizeof skip / sizeof skip[0]; k++)
      if (!strncmp(names[i], skip[k], strlen(skip[k]))) ok = PETSC_TRUE;
    if (!ok) {
      bad = i;
      PetscCall(PetscSNPrintf(msg, sizeof msg, "option -%s %s was given but nothing reads it (a typo? -help lists the valid options)", names[i], values[i] ? values[i] : ""));
    }
  }
  PetscCall(PetscOptionsLeftRestore(NULL, &n, &names, &values));
  PetscCheck(bad < 0, comm, PETSC_ERR_ARG_WRONG, "%s", msg);
  PetscFunctionReturn(PETSC_SUCCESS);
}
