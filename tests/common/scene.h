/* Scenes in options files beside the tests: a test's scene (domain, particles, walls, fluid) is
 * a flat PETSc options file in the test's folder, tests/<folder>/<name>.opts, one option per
 * line under a comment header that says what the scene is; the small variations a test applies
 * on top stay short strings in the test. The folder is the test's source folder as the Makefile
 * gives it at compile time (TEST_DIR, an absolute path), so a test finds its scenes from any
 * working directory. */
#pragma once
#include "sable.h"

#ifndef TEST_DIR
  #error "TEST_DIR, the test's source folder, is set by the Makefile: -DTEST_DIR='\"tests/<folder>\"'"
#endif

/* Collective on comm (rank 0 reads the file). Replaces the options database by the scene file
 * `file` of the test's folder, then inserts the options string extra (NULL: none); an option in
 * both takes extra's value. */
static inline PetscErrorCode TestSceneLoad(MPI_Comm comm, const char *file, const char *extra)
{
  char path[PETSC_MAX_PATH_LEN];

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(path, sizeof path, "%s/%s", TEST_DIR, file));
  PetscCall(PetscOptionsClear(NULL));
  PetscCall(PetscOptionsInsertFile(comm, NULL, path, PETSC_TRUE));
  if (extra) PetscCall(PetscOptionsInsertString(NULL, extra));
  PetscFunctionReturn(PETSC_SUCCESS);
}
