/* Bad convex-shape input gives a clear error, never a crash or a silent wrong shape.
 *
 * Each case calls a constructor with an error handler that records the first (innermost)
 * message, then checks that the call failed with the expected PETSc error class and that the
 * message names the problem (and, for files, the file and the offending line): two checks per
 * case, the error code and the message.
 */
#include <unistd.h>
#include "check.h"
#include "geom/convex.h"

static char last_msg[1024];

static PetscErrorCode RecordError(MPI_Comm comm, int line, const char *fun, const char *file, PetscErrorCode n, PetscErrorType p, const char *mess, void *ctx)
{
  (void)comm, (void)line, (void)fun, (void)file, (void)ctx;
  if (p == PETSC_ERROR_INITIAL) snprintf(last_msg, sizeof last_msg, "%s", mess ? mess : "");
  return n;
}

/* ierr must be expect, and the message must contain each of the (up to two) fragments. */
static PetscErrorCode expect(const char *name, PetscErrorCode ierr, PetscErrorCode expect_code, const char *frag1, const char *frag2)
{
  char seen[1100];

  PetscFunctionBeginUser;
  PetscCall(CheckEqual(CheckName("%s: error code", name), ierr, expect_code));
  snprintf(seen, sizeof seen, "\"%s\"", last_msg);
  PetscCall(CheckTrue(CheckName("%s: the message names it", name), (PetscBool)(strstr(last_msg, frag1) && (!frag2 || strstr(last_msg, frag2))), seen));
  last_msg[0] = 0;
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode WriteFile(const char *path, const char *text)
{
  FILE *fp = fopen(path, "w");

  PetscFunctionBeginUser;
  PetscCheck(fp, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "cannot write test file %s", path);
  fputs(text, fp);
  fclose(fp);
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  const PetscReal three[9]      = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const PetscReal coplanar[15]  = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 0.3, 0.4, 0};
  const PetscReal collinear[12] = {0, 0, 0, 1, 1, 1, 2, 2, 2, -1, -1, -1};
  char            bad[PETSC_MAX_PATH_LEN], flat[PETSC_MAX_PATH_LEN], good[PETSC_MAX_PATH_LEN];
  ConvexShape     s;
  PetscErrorCode  ierr;

  PetscCall(PetscInitialize(&argc, &argv, NULL, "convex shape input errors test"));
  snprintf(bad, sizeof bad, "/tmp/sable_convex_bad_%d.txt", (int)getpid());
  snprintf(flat, sizeof flat, "/tmp/sable_convex_flat_%d.txt", (int)getpid());
  snprintf(good, sizeof good, "/tmp/sable_convex_good_%d.txt", (int)getpid());
  PetscCall(WriteFile(bad, "# a cube missing a coordinate\n0 0 0\n1 0 0\n1 1\n0 1 0\n"));
  PetscCall(WriteFile(flat, "0 0 0\n1 0 0\n1 1 0\n0 1 0\n"));
  PetscCall(WriteFile(good, "# unit tetrahedron\n0 0 0\n1 0 0   # comment\n\n0 1 0\n0 0 1\n"));

  PetscCall(PetscPushErrorHandler(RecordError, NULL));
  ierr = ConvexShapeCreateFromVertices(3, three, &s);
  PetscCall(expect("3 vertices rejected", ierr, PETSC_ERR_ARG_SIZ, "3 vertices given, at least 4", NULL));
  ierr = ConvexShapeCreateFromVertices(5, coplanar, &s);
  PetscCall(expect("coplanar vertices rejected", ierr, PETSC_ERR_ARG_WRONG, "coplanar", NULL));
  ierr = ConvexShapeCreateFromVertices(4, collinear, &s);
  PetscCall(expect("collinear vertices rejected", ierr, PETSC_ERR_ARG_WRONG, "collinear", NULL));
  ierr = ConvexShapeCreateCube(-1.0, &s);
  PetscCall(expect("negative cube edge rejected", ierr, PETSC_ERR_ARG_OUTOFRANGE, "cube edge -1", "> 0"));
  ierr = ConvexShapeCreateFromFile("/nonexistent/sable/shape.txt", &s);
  PetscCall(expect("unreadable file rejected", ierr, PETSC_ERR_FILE_OPEN, "/nonexistent/sable/shape.txt", "cannot open"));
  ierr = ConvexShapeCreateFromFile(bad, &s);
  PetscCall(expect("bad line rejected, names file and line", ierr, PETSC_ERR_FILE_UNEXPECTED, bad, "line 4"));
  ierr = ConvexShapeCreateFromFile(flat, &s);
  PetscCall(expect("coplanar file rejected, names file", ierr, PETSC_ERR_FILE_UNEXPECTED, flat, "coplanar"));
  PetscCall(PetscPopErrorHandler());

  PetscCall(ConvexShapeCreateFromFile(good, &s));
  PetscCall(CheckAtMost("vertex file with comments and blank lines: volume rel. error", fabs(s.volume - 1.0 / 6) * 6, 1e-14));
  PetscCall(ConvexShapeDestroy(&s));
  remove(bad);
  remove(flat);
  remove(good);
  PetscCall(PetscFinalize());
  return check_failures ? 1 : 0;
}
