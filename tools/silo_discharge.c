/* Discharge of a silo (cases/silo_cubes): reads the frames <dir>/<prefix>_NNNNNN.h5 written every
 * -silo_interval seconds, counts in each the particles whose centre is above the orifice plane
 * z = -silo_z0, and prints the count against time and the mean discharge rate (particles per
 * second and kg/s with -silo_mass) between 20% and 80% of the particles discharged (a linear
 * regime for a silo: Beverloo's law), or, if 80% is not reached, from 0.1 s to the last frame,
 * then the discharge time: the time of the first frame with no particle left above the orifice
 * (González-Montellano et al.'s and Grains3D's "discharge time": the silo is empty), or, if the
 * frames stop before, its estimate N0 / rate at the constant (Beverloo) rate.
 * Options: -silo_dir, -silo_prefix, -silo_interval (s), -silo_z0 (m), -silo_mass (kg per
 * particle). */
#include "io/io.h"
#include <unistd.h>

/* The run's XDMF index <dir>/<prefix>.xmf as text (NULL if absent): a frame file counts only if
 * the index names it, so frames left by an earlier, longer run with the same prefix are not read. */
static PetscErrorCode ReadIndex(const char *dir, const char *prefix, char **text)
{
  char  path[PETSC_MAX_PATH_LEN + 80];
  FILE *fp;
  long  len;

  PetscFunctionBeginUser;
  *text = NULL;
  PetscCall(PetscSNPrintf(path, sizeof path, "%s/%s.xmf", dir, prefix));
  fp = fopen(path, "r");
  if (!fp) PetscFunctionReturn(PETSC_SUCCESS);
  fseek(fp, 0, SEEK_END);
  len = ftell(fp);
  rewind(fp);
  PetscCall(PetscMalloc1(len + 1, text));
  (*text)[fread(*text, 1, (size_t)len, fp)] = 0;
  fclose(fp);
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  char      dir[PETSC_MAX_PATH_LEN] = "out/silo_cubes", prefix[64] = "discharge", path[PETSC_MAX_PATH_LEN + 80];
  PetscReal dt = 0.05, z0 = 0, mass = 0, t20 = -1, t80 = -1;
  PetscInt  n0 = -1, n20 = 0, n80 = 0, n01 = 0, nlast = 0;
  PetscReal tlast = 0, tempty = -1, rate = 0, t0 = 0;
  char     *index;

  PetscCall(PetscInitialize(&argc, &argv, NULL, "silo_discharge: particles above the orifice against time\n"));
  PetscOptionsBegin(PETSC_COMM_WORLD, NULL, "silo discharge", NULL);
  PetscCall(PetscOptionsString("-silo_dir", "Output directory", NULL, dir, dir, sizeof dir, NULL));
  PetscCall(PetscOptionsString("-silo_prefix", "Frame file prefix", NULL, prefix, prefix, sizeof prefix, NULL));
  PetscCall(PetscOptionsReal("-silo_interval", "Time between frames (s), used only for frames without a time attribute", NULL, dt, &dt, NULL));
  PetscCall(PetscOptionsReal("-silo_z0", "Height of the orifice (m)", NULL, z0, &z0, NULL));
  PetscCall(PetscOptionsReal("-silo_mass", "Mass of one particle (kg), for kg/s", NULL, mass, &mass, NULL));
  PetscOptionsEnd();
  PetscCheck(dt > 0, PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE, "-silo_interval %g must be > 0 (s)", (double)dt);
  PetscCall(ReadIndex(dir, prefix, &index));
  for (PetscInt f = 0;; f++) {
    PetscReal *x;
    PetscInt   n, nc, above = 0;
    PetscReal  tf;
    PetscBool  has_t;
    PetscCall(PetscSNPrintf(path, sizeof path, "%s/%s_%06" PetscInt_FMT ".h5", dir, prefix, f));
    if (access(path, R_OK) || (index && !strstr(index, strrchr(path, '/') + 1))) {
      PetscCheck(f > 0, PETSC_COMM_WORLD, PETSC_ERR_FILE_OPEN, "no frame %s", path);
      break;
    }
    PetscCall(IoReadTime(path, &tf, &has_t));
    if (f == 0) t0 = has_t ? tf : 0;
    tf = has_t ? tf - t0 : f * dt; /* the frame's own time: output steps need not be evenly spaced */
    PetscCall(IoReadDataset(path, "/particles/position", &n, &nc, &x));
    for (PetscInt i = 0; i < n; i++) above += x[3 * i + 2] > z0;
    PetscCall(PetscFree(x));
    if (n0 < 0) n0 = above;
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "t %.3f s  above the orifice %" PetscInt_FMT "\n", (double)tf, above));
    if (tf <= 0.1 + 1e-9) n01 = above;
    nlast = above, tlast = tf;
    if (t20 < 0 && n0 - above >= 0.2 * n0) t20 = tf, n20 = above;
    if (t80 < 0 && n0 - above >= 0.8 * n0) t80 = tf, n80 = above;
    if (tempty < 0 && above == 0) tempty = tf;
  }
  if (t80 > t20 && t20 >= 0) {
    rate = (n20 - n80) / (t80 - t20);
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "discharge rate (20%% -> 80%%): %.1f particles/s, %.4f kg/s\n", (double)rate, (double)(rate * mass)));
  } else if (nlast < n0 && tlast > 0.1) { /* not 80% yet: from 0.1 s (start-up) to the last frame */
    rate = (n01 - nlast) / (tlast - 0.1);
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "discharge rate (0.1 s -> %.2f s, %.0f%% discharged, not yet 80%%): %.1f particles/s, %.4f kg/s\n", (double)tlast, 100.0 * (n0 - nlast) / n0, (double)rate, (double)(rate * mass)));
  } else PetscCall(PetscPrintf(PETSC_COMM_WORLD, "discharge rate: no discharge in the frames read\n"));
  if (tempty >= 0) PetscCall(PetscPrintf(PETSC_COMM_WORLD, "discharge time (no particle left above the orifice): %.2f s\n", (double)tempty));
  else if (rate > 0) PetscCall(PetscPrintf(PETSC_COMM_WORLD, "discharge time: not reached (%" PetscInt_FMT " of %" PetscInt_FMT " left at %.2f s); at the rate above, N0 / rate = %.1f s\n", nlast, n0, (double)tlast, (double)(n0 / rate)));
  PetscCall(PetscFree(index));
  PetscCall(PetscFinalize());
  return 0;
}
