/* Bad convex-shape input gives a clear error, never a crash or a silent wrong shape.
 *
 * Each case calls a constructor with an error handler that records the first (innermost)
 * message, then checks that the call failed with the expected PETSc error class and that the
 * message names the problem (and, for files, the file and the offending line). Measured value
 * printed: 0 when both hold, 1 otherwise (bound 0).
 */
#include <unistd.h>
#include "geom/convex.h"

static int  nfail = 0;
static char last_msg[1024];

static PetscErrorCode RecordError(MPI_Comm comm, int line, const char *fun, const char *file, PetscErrorCode n, PetscErrorType p, const char *mess, void *ctx)
{
  (void)comm, (void)line, (void)fun, (void)file, (void)ctx;
  if (p == PETSC_ERROR_INITIAL) snprintf(last_msg, sizeof last_msg, "%s", mess ? mess : "");
  return n;
}

/* ierr must be expect, and the message must contain each of the (up to two) fragments. */
static void expect(const char *name, PetscErrorCode ierr, PetscErrorCode expect_code, const char *frag1, const char *frag2)
{
  const int ok = ierr == expect_code && strstr(last_msg, frag1) && (!frag2 || strstr(last_msg, frag2));
  if (!ok) nfail++;
  printf("%s %s: %d (bound 0)   [error %d, \"%s\"]\n", ok ? "PASS" : "FAIL", name, !ok, (int)ierr, last_msg);
  last_msg[0] = 0;
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
  const PetscReal three[9]     = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const PetscReal coplanar[15] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 0.3, 0.4, 0};
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
  expect("3 vertices rejected", ierr, PETSC_ERR_ARG_SIZ, "3 vertices given, at least 4", NULL);
  ierr = ConvexShapeCreateFromVertices(5, coplanar, &s);
  expect("coplanar vertices rejected", ierr, PETSC_ERR_ARG_WRONG, "coplanar", NULL);
  ierr = ConvexShapeCreateFromVertices(4, collinear, &s);
  expect("collinear vertices rejected", ierr, PETSC_ERR_ARG_WRONG, "collinear", NULL);
  ierr = ConvexShapeCreateCube(-1.0, &s);
  expect("negative cube edge rejected", ierr, PETSC_ERR_ARG_OUTOFRANGE, "cube edge -1", "> 0");
  ierr = ConvexShapeCreateFromFile("/nonexistent/sable/shape.txt", &s);
  expect("unreadable file rejected", ierr, PETSC_ERR_FILE_OPEN, "/nonexistent/sable/shape.txt", "cannot open");
  ierr = ConvexShapeCreateFromFile(bad, &s);
  expect("bad line rejected, names file and line", ierr, PETSC_ERR_FILE_UNEXPECTED, bad, "line 4");
  ierr = ConvexShapeCreateFromFile(flat, &s);
  expect("coplanar file rejected, names file", ierr, PETSC_ERR_FILE_UNEXPECTED, flat, "coplanar");
  PetscCall(PetscPopErrorHandler());

  PetscCall(ConvexShapeCreateFromFile(good, &s));
  {
    const double e = fabs(s.volume - 1.0 / 6) * 6;
    if (e > 1e-14) nfail++;
    printf("%s vertex file with comments and blank lines: volume rel. error %.3e (bound 1.0e-14)\n", e <= 1e-14 ? "PASS" : "FAIL", e);
  }
  PetscCall(ConvexShapeDestroy(&s));
  remove(bad);
  remove(flat);
  remove(good);
  PetscCall(PetscFinalize());
  return nfail ? 1 : 0;
}
