/* The vessel's level function (src/dem/vessel.c) against analytic signed distances: phi > 0 in
 * the gas, < 0 in the solid, its value the distance to the wall (a mesh's clamped to the band of
 * two fluid cells).
 *  - a cylinder (-dem_cylinder, the gas inside): phi = R - |rho| to round-off; turning, it still
 *    bounds the gas; -dem_cylinder_fluid no: no vessel;
 *  - a plane: none by default (it lets the gas through), (x - p).n with -dem_plane_0_fluid yes;
 *  - a closed STL cylinder of n facets with its end caps (consistently oriented, the face-normal
 *    sign), gas inside: the smooth capped cylinder's signed distance within the chord error
 *    R (1 - cos(pi/n)), the sign right wherever the smooth distance exceeds it, and phi clamped
 *    to +-band far from the wall; the same mesh as an obstacle (_fluid outside): -phi;
 *  - a closed STL box whose sides are written in mixed orientation (signs by parity ray casts):
 *    the box's exact signed distance to round-off;
 *  - an open box (no lid) asked to bound the gas is refused with the mesh option, the file and
 *    the count of open edges; with _fluid none it is not;
 *  - a closed box on the domain's faces leaves them to the box: phi > 0 on every node of the
 *    domain, its faces included.
 * Random points (a fixed seed) in the meshes' boxes grown by a third. The set-up and evaluation
 * times of a 576- and a 5,184-triangle cylinder are printed (not checked: the machine's; -npts n
 * evaluations, 200000). */
#include <unistd.h>
#include "dem_common.h"
#include "stl_write.h"

static char last_msg[1024];

static PetscErrorCode RecordError(MPI_Comm comm, int line, const char *fun, const char *file, PetscErrorCode n, PetscErrorType p, const char *mess, void *ctx)
{
  (void)comm, (void)line, (void)fun, (void)file, (void)ctx;
  if (p == PETSC_ERROR_INITIAL) snprintf(last_msg, sizeof last_msg, "%s", mess ? mess : "");
  return n;
}

/* A closed cylinder about the z axis, radius R (vertices on the circle), z in [0, L]: n facets
 * around, nl segments along, fans for the caps; outward orientation. Returns the triangle count. */
static PetscInt CylinderTriangles(double R, double L, PetscInt n, PetscInt nl, double *v)
{
  PetscInt t = 0;
#define PUT(p) (v[9 * t + 3 * c] = (p)[0], v[9 * t + 3 * c + 1] = (p)[1], v[9 * t + 3 * c + 2] = (p)[2], c++)
  for (PetscInt i = 0; i < n; i++) {
    const double a0 = 2 * PETSC_PI * i / n, a1 = 2 * PETSC_PI * ((i + 1) % n) / n;
    for (PetscInt j = 0; j < nl; j++) {
      const double z0 = L * j / nl, z1 = L * (j + 1) / nl;
      const double p00[3] = {R * cos(a0), R * sin(a0), z0}, p10[3] = {R * cos(a1), R * sin(a1), z0};
      const double p01[3] = {R * cos(a0), R * sin(a0), z1}, p11[3] = {R * cos(a1), R * sin(a1), z1};
      int          c = 0;
      PUT(p00), PUT(p10), PUT(p11), t++, c = 0;
      PUT(p00), PUT(p11), PUT(p01), t++;
    }
    const double b0[3] = {0, 0, 0}, b1[3] = {0, 0, L};
    const double q0[3] = {R * cos(a0), R * sin(a0), 0}, q1[3] = {R * cos(a1), R * sin(a1), 0};
    const double r0[3] = {R * cos(a0), R * sin(a0), L}, r1[3] = {R * cos(a1), R * sin(a1), L};
    int          c = 0;
    PUT(b0), PUT(q1), PUT(q0), t++, c = 0;
    PUT(b1), PUT(r0), PUT(r1), t++;
  }
#undef PUT
  return t;
}

/* The smooth capped cylinder's signed distance, positive inside. */
static double CylinderDistance(double R, double L, const double *x)
{
  const double rho = sqrt(x[0] * x[0] + x[1] * x[1]), dr = rho - R, dz = PetscMax(-x[2], x[2] - L);
  if (dr <= 0 && dz <= 0) return -PetscMax(dr, dz);
  return -sqrt(PetscSqr(PetscMax(dr, 0)) + PetscSqr(PetscMax(dz, 0)));
}

static double BoxDistance(const double lo[3], const double hi[3], const double *x)
{
  double out = 0, in = PETSC_MAX_REAL;
  for (int d = 0; d < 3; d++) {
    const double e = PetscMax(lo[d] - x[d], x[d] - hi[d]);
    out += PetscSqr(PetscMax(e, 0));
    in = PetscMin(in, -e);
  }
  return in > 0 ? in : -sqrt(out);
}

static double Uniform(unsigned long long *s)
{
  *s = *s * 6364136223846793005ULL + 1442695040888963407ULL;
  return (double)(*s >> 11) / 9007199254740992.0;
}

/* Sets up a Dem of these options (domain and grid included) and its vessel. */
static PetscErrorCode Vessel(const char *opts, Domain *dom, Dem *dem, PetscBool *any, PetscErrorCode *ierr)
{
  PetscFunctionBeginUser;
  PetscCall(TestDemCreate(opts, dom, dem));
  PetscCall(DemSetUp(*dem));
  if (ierr) {
    PetscCall(PetscPushErrorHandler(RecordError, NULL));
    *ierr = DemVesselSetUp(*dem, any);
    PetscCall(PetscPopErrorHandler());
  } else PetscCall(DemVesselSetUp(*dem, any));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode TestCylinderAndPlane(void)
{
  Domain             dom;
  Dem                dem;
  PetscBool          any;
  double             err = 0;
  unsigned long long s   = 1;

  PetscFunctionBeginUser;
  PetscCall(Vessel("-domain_lo -0.01,-0.01,0 -domain_hi 0.01,0.01,0.02 -da_grid_x 8 -da_grid_y 8 -da_grid_z 8 -dem_radius 0.0005 -dem_kn 100 -dem_dt 1e-5 -dem_cylinder 0.001,0,0,0,0,2,0.008 -dem_cylinder_omega 3", &dom, &dem, &any, NULL));
  PetscCall(CheckTrue("a turning cylinder bounds the gas", any, any ? "yes" : "no"));
  for (int q = 0; q < 1000; q++) {
    const double x[3] = {-0.01 + 0.02 * Uniform(&s), -0.01 + 0.02 * Uniform(&s), 0.02 * Uniform(&s)};
    const double ref  = 0.008 - sqrt(PetscSqr(x[0] - 0.001) + x[1] * x[1]);
    err               = PetscMax(err, PetscAbsReal(DemVesselLevel(x, dem) - ref));
  }
  PetscCall(CheckBelow("cylinder: |phi - (R - |rho|)| over 1000 points [m]", err, 1e-15));
  PetscCall(TestDemDestroy(&dom, &dem));
  PetscCall(Vessel("-domain_lo -0.01,-0.01,0 -domain_hi 0.01,0.01,0.02 -dem_radius 0.0005 -dem_kn 100 -dem_dt 1e-5 -dem_cylinder 0,0,0,0,0,1,0.008 -dem_cylinder_fluid no -dem_plane_0 0,0,0.002,0,0,1", &dom, &dem, &any, NULL));
  PetscCall(CheckTrue("-dem_cylinder_fluid no and a plane of its default: no vessel", (PetscBool)!any, any ? "a vessel" : "none"));
  PetscCall(TestDemDestroy(&dom, &dem));
  PetscCall(Vessel("-domain_lo -0.01,-0.01,0 -domain_hi 0.01,0.01,0.02 -dem_radius 0.0005 -dem_kn 100 -dem_dt 1e-5 -dem_plane_0 0,0,0.002,0,1,1 -dem_plane_0_fluid yes", &dom, &dem, &any, NULL));
  err = 0;
  for (int q = 0; q < 1000; q++) {
    const double x[3] = {-0.01 + 0.02 * Uniform(&s), -0.01 + 0.02 * Uniform(&s), 0.02 * Uniform(&s)};
    err               = PetscMax(err, PetscAbsReal(DemVesselLevel(x, dem) - (x[1] + x[2] - 0.002) / sqrt(2.0)));
  }
  PetscCall(CheckTrue("-dem_plane_0_fluid yes bounds the gas", any, any ? "yes" : "no"));
  PetscCall(CheckBelow("plane: |phi - (x - p).n| over 1000 points [m]", err, 1e-15));
  PetscCall(TestDemDestroy(&dom, &dem));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The closed cylinder of n facets (nl segments), inside and outside, over npts points. */
static PetscErrorCode TestMeshCylinder(PetscInt n, PetscInt nl, PetscInt npts, PetscBool check)
{
  const double       R = 0.008, L = 0.03, sag = R * (1 - cos(PETSC_PI / n));
  char               file[PETSC_MAX_PATH_LEN], opts[2 * PETSC_MAX_PATH_LEN];
  double            *v, err = 0, clamp = 0, band = 0;
  PetscInt           ntri, wrong = 0, near = 0;
  Domain             dom;
  Dem                dem;
  PetscBool          any;
  unsigned long long s = 7;
  PetscLogDouble     t0, t1, t2;
  int                pid = (int)getpid();

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(9 * (2 * n * nl + 2 * n), &v));
  ntri = CylinderTriangles(R, L, n, nl, v);
  PetscCallMPI(MPI_Bcast(&pid, 1, MPI_INT, 0, PETSC_COMM_WORLD));
  PetscCall(PetscSNPrintf(file, sizeof file, "/tmp/sable_test_vessel_cyl_%d.stl", pid));
  PetscCall(TestWriteStl(PETSC_COMM_WORLD, file, ntri, v));
  PetscCall(PetscSNPrintf(opts, sizeof opts, "-domain_lo -0.012,-0.012,-0.004 -domain_hi 0.012,0.012,0.034 -da_grid_x 12 -da_grid_y 12 -da_grid_z 19 -dem_radius 0.0005 -dem_kn 100 -dem_dt 1e-5 -dem_mesh_0_file %s", file));
  PetscCall(PetscTime(&t0));
  PetscCall(Vessel(opts, &dom, &dem, &any, NULL));
  PetscCall(PetscTime(&t1));
  band = 2 * 0.002;
  for (PetscInt q = 0; q < npts; q++) {
    const double x[3] = {-0.0107 + 0.0213 * Uniform(&s), -0.0107 + 0.0213 * Uniform(&s), -0.01 + 0.05 * Uniform(&s)};
    const double phi = DemVesselLevel(x, dem), ref = CylinderDistance(R, L, x);
    if (!check) continue;
    if (PetscAbsReal(ref) > sag && (phi > 0) != (ref > 0)) wrong++;
    if (PetscAbsReal(ref) < band - sag) err = PetscMax(err, PetscAbsReal(phi - ref)), near++;
    if (PetscAbsReal(ref) > band + sag) clamp = PetscMax(clamp, PetscAbsReal(PetscAbsReal(phi) - band));
  }
  PetscCall(PetscTime(&t2));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "# closed cylinder of %" PetscInt_FMT " triangles: vessel set-up %.3f s (with the DEM's), %" PetscInt_FMT " evaluations %.3f s (%.2f us each)\n", ntri, t1 - t0, npts, t2 - t1, 1e6 * (t2 - t1) / npts));
  if (check) {
    PetscCall(CheckTrue(CheckName("STL cylinder of %" PetscInt_FMT " facets bounds the gas", n), any, any ? "yes" : "no"));
    PetscCall(CheckEqual(CheckName("STL cylinder of %" PetscInt_FMT " facets: points on the wrong side (smooth distance beyond the chord error %.3g m)", n, sag), wrong, 0));
    PetscCall(CheckAtMost(CheckName("STL cylinder of %" PetscInt_FMT " facets: |phi - smooth distance| within the band (%" PetscInt_FMT " points) [m] vs the chord error", n, near), err, sag * (1 + 1e-9)));
    PetscCall(CheckBelow(CheckName("STL cylinder of %" PetscInt_FMT " facets: ||phi| - band| beyond the band [m]", n), clamp, 1e-15));
  }
  PetscCall(TestDemDestroy(&dom, &dem));
  if (check) { /* the same mesh as an immersed obstacle */
    PetscCall(PetscSNPrintf(opts, sizeof opts, "-domain_lo -0.012,-0.012,-0.004 -domain_hi 0.012,0.012,0.034 -da_grid_x 12 -da_grid_y 12 -da_grid_z 19 -dem_radius 0.0005 -dem_kn 100 -dem_dt 1e-5 -dem_mesh_0_file %s -dem_mesh_0_fluid outside", file));
    PetscCall(Vessel(opts, &dom, &dem, &any, NULL));
    err = 0;
    for (PetscInt q = 0; q < 1000; q++) {
      const double x[3] = {-0.0107 + 0.0213 * Uniform(&s), -0.0107 + 0.0213 * Uniform(&s), -0.01 + 0.05 * Uniform(&s)};
      const double ref  = CylinderDistance(R, L, x);
      if (PetscAbsReal(ref) < band - sag) err = PetscMax(err, PetscAbsReal(DemVesselLevel(x, dem) + ref));
    }
    PetscCall(CheckAtMost(CheckName("STL cylinder of %" PetscInt_FMT " facets as an obstacle (_fluid outside): |phi + smooth distance| [m] vs the chord error", n), err, sag * (1 + 1e-9)));
    PetscCall(TestDemDestroy(&dom, &dem));
  }
  {
    PetscMPIInt rank;
    PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
    if (!rank) unlink(file);
  }
  PetscCall(PetscFree(v));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode TestMeshBox(void)
{
  const double       lo[3] = {0.001, 0.002, 0.003}, hi[3] = {0.011, 0.009, 0.014};
  char               file[PETSC_MAX_PATH_LEN], opts[2 * PETSC_MAX_PATH_LEN], seen[1100];
  double             v[6 * 8 * 9 * 2], err = 0;
  Domain             dom;
  Dem                dem;
  PetscBool          any;
  PetscErrorCode     ierr;
  unsigned long long s = 3;
  PetscMPIInt        rank;
  int                pid = (int)getpid();

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
  PetscCallMPI(MPI_Bcast(&pid, 1, MPI_INT, 0, PETSC_COMM_WORLD));
  PetscCall(PetscSNPrintf(file, sizeof file, "/tmp/sable_test_vessel_box_%d.stl", pid));
  PetscCall(TestWriteStl(PETSC_COMM_WORLD, file, TestBoxTriangles(lo, hi, 2, PETSC_FALSE, v), v));
  PetscCall(PetscSNPrintf(opts, sizeof opts, "-domain_lo 0,0,0 -domain_hi 0.012,0.012,0.016 -da_grid_x 6 -da_grid_y 6 -da_grid_z 8 -dem_radius 0.0005 -dem_kn 100 -dem_dt 1e-5 -dem_mesh_0_file %s", file));
  PetscCall(Vessel(opts, &dom, &dem, &any, NULL));
  for (int q = 0; q < 20000; q++) {
    const double x[3] = {0.012 * Uniform(&s), 0.012 * Uniform(&s), 0.016 * Uniform(&s)};
    const double ref = BoxDistance(lo, hi, x), phi = DemVesselLevel(x, dem);
    if (PetscAbsReal(ref) < 0.004) err = PetscMax(err, PetscAbsReal(phi - ref));
    else err = PetscMax(err, PetscAbsReal(phi - (ref > 0 ? 0.004 : -0.004)));
  }
  PetscCall(CheckBelow("closed STL box, sides in mixed orientation (ray-cast signs): |phi - the box's signed distance (clamped to the band)| over 20000 points [m]", err, 1e-15));
  PetscCall(TestDemDestroy(&dom, &dem));
  /* open: no lid */
  PetscCall(TestWriteStl(PETSC_COMM_WORLD, file, TestBoxTriangles(lo, hi, 2, PETSC_TRUE, v), v));
  PetscCall(Vessel(opts, &dom, &dem, &any, &ierr));
  PetscCall(PetscSNPrintf(seen, sizeof seen, "\"%s\"", last_msg));
  PetscCall(CheckEqual("open STL box bounding the gas: refused (error code)", ierr, PETSC_ERR_ARG_WRONG));
  PetscCall(CheckTrue("open STL box: the message names the option, the file and the 8 open edges", (PetscBool)(strstr(last_msg, "-dem_mesh_0_fluid inside") && strstr(last_msg, file) && strstr(last_msg, " 8 edges")), seen));
  PetscCall(TestDemDestroy(&dom, &dem));
  PetscCall(PetscStrlcat(opts, " -dem_mesh_0_fluid none", sizeof opts));
  PetscCall(Vessel(opts, &dom, &dem, &any, NULL));
  PetscCall(CheckTrue("open STL box with _fluid none: accepted, no vessel", (PetscBool)!any, any ? "a vessel" : "none"));
  PetscCall(TestDemDestroy(&dom, &dem));
  { /* the box mesh on the domain's faces: they are the box's, the gas fills the domain */
    const double dlo[3] = {0, 0, 0}, dhi[3] = {0.012, 0.012, 0.016};
    double       pmin = PETSC_MAX_REAL;
    PetscCall(TestWriteStl(PETSC_COMM_WORLD, file, TestBoxTriangles(dlo, dhi, 2, PETSC_FALSE, v), v));
    PetscCall(PetscSNPrintf(opts, sizeof opts, "-domain_lo 0,0,0 -domain_hi 0.012,0.012,0.016 -da_grid_x 6 -da_grid_y 6 -da_grid_z 8 -dem_radius 0.0005 -dem_kn 100 -dem_dt 1e-5 -dem_mesh_0_file %s", file));
    PetscCall(Vessel(opts, &dom, &dem, &any, NULL));
    for (int i = 0; i <= 12; i++)
      for (int j = 0; j <= 12; j++)
        for (int k = 0; k <= 16; k++) { /* every half-cell node, the domain's faces included */
          const double x[3] = {0.001 * i, 0.001 * j, 0.001 * k};
          pmin              = PetscMin(pmin, DemVesselLevel(x, dem));
        }
    PetscCall(CheckAbove("STL box on the domain's faces (its triangles are the box's faces): smallest phi over the half-cell nodes, faces included [m]", pmin, 0));
    PetscCall(TestDemDestroy(&dom, &dem));
  }
  if (!rank) unlink(file);
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  PetscInt npts = 200000; /* -npts: the timed evaluations */
  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-npts", &npts, NULL));
  PetscCall(TestCylinderAndPlane());
  PetscCall(TestMeshCylinder(32, 8, 20000, PETSC_TRUE));
  PetscCall(TestMeshCylinder(144, 17, 20000, PETSC_TRUE));
  PetscCall(TestMeshCylinder(32, 8, npts, PETSC_FALSE));
  PetscCall(TestMeshCylinder(144, 17, npts, PETSC_FALSE));
  PetscCall(TestMeshBox());
  PetscCall(PetscFinalize());
  return 0;
}
