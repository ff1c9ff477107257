/* The STL reader, the placement of a mesh and the closest point of a triangle.
 *
 * Files are written by the test itself (rank 0, in /tmp) and read back on every rank:
 *   round trip   ASCII (coordinates printed with 17 digits, several solids, odd spacing, a
 *                binary-looking name) and binary (float coordinates, a header that begins with
 *                "solid"): every vertex bitwise equal to what was written; normals from the
 *                vertex order, not from the stored (wrong) facet normals, vs the cross product;
 *   skipped      zero-area triangles (collinear, coincident vertices) and duplicates (same
 *                order, rotated, reversed): the exact counts, the kept ones in file order; a
 *                20,000-triangle binary grid written twice, shuffled: 20,000 duplicates;
 *   malformed    missing, empty, not STL (text, short binary), truncated ASCII and binary, a
 *                binary count that disagrees with the size, NaN and Inf coordinates, facets of
 *                2 and 4 vertices, a word that is not a number, no triangles left: the PETSc
 *                error class on every rank, the message naming the file and the triangle
 *                (1-based), and the same message on every rank (run on 1 and 2 ranks).
 * Transform: scale, then quarter turns about x, y, z (exact), then the shift, against
 * hand-rotated points; 30 degrees about z against cos/sin (1e-15).
 * TriClosestPoint: the triangle (0,0,0) (1,0,0) (0,1,0) and points in each of its seven
 * Voronoi regions: the feature, the nearest point, the distance and the direction (1e-15).
 */
/* ranks: 1 2 */
#include <unistd.h>
#include <stdint.h>
#include "check.h"
#include "geom/trimesh.h"

static char last_msg[1024];

static PetscErrorCode RecordError(MPI_Comm comm, int line, const char *fun, const char *file, PetscErrorCode n, PetscErrorType p, const char *mess, void *ctx)
{
  (void)comm, (void)line, (void)fun, (void)file, (void)ctx;
  if (p == PETSC_ERROR_INITIAL) snprintf(last_msg, sizeof last_msg, "%s", mess ? mess : "");
  return n;
}

static char dir[PETSC_MAX_PATH_LEN]; /* /tmp/sable_stl_<pid of rank 0> */

static const char *Path(const char *name)
{
  return CheckName("%s_%s.stl", dir, name);
}

/* Rank 0 writes len bytes (len < 0: a C string) to the file name. */
static PetscErrorCode WriteBytes(const char *name, const void *data, long len)
{
  PetscMPIInt rank;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
  if (rank == 0) {
    FILE *fp = fopen(Path(name), "wb");

    PetscCheck(fp, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "cannot write test file %s", Path(name));
    if (len < 0) len = (long)strlen((const char *)data);
    PetscCheck(fwrite(data, 1, (size_t)len, fp) == (size_t)len, PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "cannot write test file %s", Path(name));
    fclose(fp);
  }
  PetscCallMPI(MPI_Barrier(PETSC_COMM_WORLD));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* An ASCII facet with a deliberately wrong stored normal. */
static void AsciiFacet(char *s, size_t len, const double *t)
{
  size_t k = strlen(s);

  snprintf(s + k, len - k, "  facet normal 9 9 9\n    outer loop\n      vertex %.17g %.17g %.17g\n      vertex %.17g %.17g %.17g\n\tvertex   %.17g %.17g %.17g\n    endloop\n  endfacet\n", t[0], t[1], t[2], t[3], t[4], t[5], t[6], t[7], t[8]);
}

/* A binary STL of n triangles t (9 floats each), with header text and count given. */
static PetscErrorCode WriteBinary(const char *name, const char *header, uint32_t count, PetscInt n, const float *t, long extra)
{
  size_t         len = 84 + 50 * (size_t)n + (size_t)PetscMax(0, extra);
  unsigned char *b;

  PetscFunctionBeginUser;
  PetscCall(PetscCalloc1(len, &b));
  memcpy(b, header, PetscMin(strlen(header), 80));
  for (int k = 0; k < 4; k++) b[80 + k] = (unsigned char)(count >> (8 * k));
  for (PetscInt i = 0; i < n; i++) {
    for (int j = 0; j < 12; j++) {
      float    f = j < 3 ? 9.0f : t[9 * i + j - 3]; /* a wrong stored normal */
      uint32_t u;

      memcpy(&u, &f, 4);
      for (int k = 0; k < 4; k++) b[84 + 50 * i + 4 * j + k] = (unsigned char)(u >> (8 * k));
    }
  }
  PetscCall(WriteBytes(name, b, (long)len + (extra < 0 ? extra : 0)));
  PetscCall(PetscFree(b));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Vertices bitwise equal to ref (n triangles), normals within 1e-15 of the cross product. */
static PetscErrorCode CheckMesh(const char *what, const TriMesh *m, PetscInt n, const double *ref)
{
  PetscInt  bad  = 0;
  PetscReal nerr = 0;

  PetscFunctionBeginUser;
  PetscCall(CheckEqual(CheckName("%s: triangles kept", what), m->ntri, n));
  for (PetscInt i = 0; i < 9 * PetscMin(n, m->ntri); i++) bad += m->v[i] != ref[i];
  PetscCall(CheckEqual(CheckName("%s: vertex coordinates differing bitwise from those written", what), bad, 0));
  for (PetscInt t = 0; t < PetscMin(n, m->ntri); t++) {
    const double *a = ref + 9 * t, *b = a + 3, *c = a + 6;
    double        x[3], len;

    x[0] = (b[1] - a[1]) * (c[2] - a[2]) - (b[2] - a[2]) * (c[1] - a[1]);
    x[1] = (b[2] - a[2]) * (c[0] - a[0]) - (b[0] - a[0]) * (c[2] - a[2]);
    x[2] = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
    len  = PetscSqrtReal(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
    for (int k = 0; k < 3; k++) nerr = PetscMax(nerr, PetscAbsReal(m->n[3 * t + k] - x[k] / len));
  }
  PetscCall(CheckAtMost(CheckName("%s: normals vs (b - a) x (c - a) / |..|", what), nerr, 1e-15));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static const double tri_ref[4][9] = {
  {0.1, 0.2, 0.3, 1.7, -0.25, 1e-3, -3.3333333333333335, 2.5, 0.75},
  {1, 0, 0, 0, 1, 0, 0, 0, 1},
  {-1e5, 2e-7, 3, 12345.678, 0.5, -0.125, 7, 8, 9.0000000000000018},
  {0, 0, 0, 0.001, 0, 0, 0, 0, 0.002},
};

static PetscErrorCode TestRoundTrip(void)
{
  char    s[4096] = "solid part one 1.0 facet endsolid\n";
  float   f[36];
  double  fd[36];
  TriMesh m;

  PetscFunctionBeginUser;
  AsciiFacet(s, sizeof s, tri_ref[0]);
  AsciiFacet(s, sizeof s, tri_ref[1]);
  strcat(s, "endsolid part one\nsolid\n");
  AsciiFacet(s, sizeof s, tri_ref[2]);
  AsciiFacet(s, sizeof s, tri_ref[3]);
  strcat(s, "endsolid");
  PetscCall(WriteBytes("ascii", s, -1));
  PetscCall(TriMeshReadSTL(PETSC_COMM_WORLD, Path("ascii"), &m));
  PetscCall(CheckMesh("ASCII, two solids", &m, 4, &tri_ref[0][0]));
  PetscCall(CheckEqual("ASCII: nothing skipped", m.ndegen + m.nduplicate, 0));
  PetscCall(TriMeshDestroy(&m));

  for (int i = 0; i < 36; i++) fd[i] = f[i] = (float)tri_ref[i / 9][i % 9];
  PetscCall(WriteBinary("binary", "solid that is binary: decided by the size", 4, 4, f, 0));
  PetscCall(TriMeshReadSTL(PETSC_COMM_WORLD, Path("binary"), &m));
  PetscCall(CheckMesh("binary whose header begins with 'solid'", &m, 4, fd));
  PetscCall(TriMeshDestroy(&m));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Zero-area and duplicate triangles: exact counts, survivors in file order. */
static PetscErrorCode TestSkipped(void)
{
  const double g[3][9] = {
    {0, 0, 0, 1, 0, 0, 0, 1, 0},
    {1, 0, 0, 1, 1, 0, 0, 1, 0},
    {0, 0, 1, 1, 0, 1, 0, 1, 1},
  };
  const double z[2][9] = {
    {0, 0, 0, 1, 1, 1, 3, 3, 3},        /* collinear */
    {5, 5, 5, 5, 5, 5, 5, 5, 5 + 1e-7}, /* two coincident vertices */
  };
  const double d[3][9] = {
    {1, 0, 0, 1, 1, 0, 0, 1, 0}, /* g[1] again */
    {1, 0, 0, 0, 0, 0, 0, 1, 0}, /* g[0] turned: b, a, c (reversed orientation) */
    {0, 1, 1, 0, 0, 1, 1, 0, 1}, /* g[2] rotated: c, a, b */
  };
  char    s[8192] = "solid skip\n";
  double  kept[27];
  TriMesh m;

  PetscFunctionBeginUser;
  AsciiFacet(s, sizeof s, g[0]);
  AsciiFacet(s, sizeof s, z[0]);
  AsciiFacet(s, sizeof s, d[1]);
  AsciiFacet(s, sizeof s, g[1]);
  AsciiFacet(s, sizeof s, d[0]);
  AsciiFacet(s, sizeof s, z[1]);
  AsciiFacet(s, sizeof s, g[2]);
  AsciiFacet(s, sizeof s, d[2]);
  strcat(s, "endsolid skip\n");
  PetscCall(WriteBytes("skip", s, -1));
  PetscCall(TriMeshReadSTL(PETSC_COMM_WORLD, Path("skip"), &m));
  PetscCall(CheckEqual("zero-area triangles counted (collinear, coincident)", m.ndegen, 2));
  PetscCall(CheckEqual("duplicates counted (same order, reversed, rotated)", m.nduplicate, 3));
  for (int i = 0; i < 27; i++) kept[i] = g[i / 9][i % 9];
  PetscCall(CheckMesh("skipped triangles", &m, 3, kept));
  PetscCall(TriMeshDestroy(&m));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* A grid of 2 x 100 x 100 triangles, written twice in a scrambled order, rotated vertices. */
static PetscErrorCode TestManyDuplicates(void)
{
  const PetscInt n = 100, ntri = 2 * n * n;
  float         *f;
  TriMesh        m;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(2 * 9 * ntri, &f));
  for (PetscInt i = 0; i < n; i++)
    for (PetscInt j = 0; j < n; j++) {
      const float x0 = (float)i, y0 = (float)j, x1 = x0 + 1, y1 = y0 + 1;
      const float t[18] = {x0, y0, 0, x1, y0, 0, x1, y1, 0, x0, y0, 0, x1, y1, 0, x0, y1, 0};

      for (int k = 0; k < 18; k++) f[18 * (i * n + j) + k] = t[k];
    }
  for (PetscInt t = 0; t < ntri; t++) { /* the copy: triangle (7919 t) mod ntri, vertices rotated */
    const PetscInt src = (7919 * t) % ntri;

    for (int k = 0; k < 9; k++) f[9 * (ntri + t) + k] = f[9 * src + (k + 3 * (t % 3)) % 9];
  }
  PetscCall(WriteBinary("many", "grid", (uint32_t)(2 * ntri), 2 * ntri, f, 0));
  PetscCall(TriMeshReadSTL(PETSC_COMM_WORLD, Path("many"), &m));
  PetscCall(CheckEqual("20,000-triangle grid written twice: duplicates counted", m.nduplicate, ntri));
  PetscCall(CheckEqual("20,000-triangle grid written twice: triangles kept", m.ntri, ntri));
  PetscCall(TriMeshDestroy(&m));
  PetscCall(PetscFree(f));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Reading name fails with code on every rank, the message holds the path and frag, the same on all. */
static PetscErrorCode ExpectError(const char *what, const char *name, PetscErrorCode code, const char *frag)
{
  char           path[PETSC_MAX_PATH_LEN], msg0[sizeof last_msg], seen[1200];
  TriMesh        m;
  PetscErrorCode ierr;
  int            mine[2], all[2];

  PetscFunctionBeginUser;
  snprintf(path, sizeof path, "%s", name[0] == '/' ? name : Path(name));
  last_msg[0] = 0;
  PetscCall(PetscPushErrorHandler(RecordError, NULL));
  ierr = TriMeshReadSTL(PETSC_COMM_WORLD, path, &m);
  PetscCall(PetscPopErrorHandler());
  PetscCall(PetscArraycpy(msg0, last_msg, sizeof msg0));
  PetscCallMPI(MPI_Bcast(msg0, sizeof msg0, MPI_CHAR, 0, PETSC_COMM_WORLD));
  mine[0] = ierr == code, mine[1] = !strcmp(msg0, last_msg) && strstr(last_msg, path) && strstr(last_msg, frag);
  PetscCallMPI(MPI_Allreduce(mine, all, 2, MPI_INT, MPI_MIN, PETSC_COMM_WORLD));
  PetscCall(CheckTrue(CheckName("%s: error class %d on every rank", what, (int)code), (PetscBool)all[0], CheckName("rank 0: %d", (int)ierr)));
  snprintf(seen, sizeof seen, "\"%s\"", msg0);
  PetscCall(CheckTrue(CheckName("%s: one message naming the file and '%s', the same on every rank", what, frag), (PetscBool)all[1], seen));
  if (!ierr) PetscCall(TriMeshDestroy(&m));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static const char *facet_text(const char *v1, const char *v2, const char *v3)
{
  return CheckName("facet normal 0 0 1\nouter loop\nvertex %s\nvertex %s\nvertex %s\nendloop\nendfacet\n", v1, v2, v3);
}

static PetscErrorCode TestMalformedAscii(void)
{
  char good[512], s[2048];

  PetscFunctionBeginUser;
  snprintf(good, sizeof good, "solid x\n%s", facet_text("0 0 0", "1 0 0", "0 1 0"));
  PetscCall(ExpectError("missing file", "/nonexistent/sable/mesh.stl", PETSC_ERR_FILE_OPEN, "cannot open"));
  PetscCall(WriteBytes("empty", "", 0));
  PetscCall(ExpectError("empty file", "empty", PETSC_ERR_FILE_UNEXPECTED, "empty"));
  PetscCall(WriteBytes("text", "mesh\n0 0 0\n1 0 0\n0 1 0\n", -1));
  PetscCall(ExpectError("text that is not STL", "text", PETSC_ERR_FILE_UNEXPECTED, "not STL"));
  snprintf(s, sizeof s, "%s%s", good, "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 ");
  PetscCall(WriteBytes("trunc", s, -1));
  PetscCall(ExpectError("ASCII truncated inside a facet", "trunc", PETSC_ERR_FILE_UNEXPECTED, "truncated: end of file inside triangle 2"));
  snprintf(s, sizeof s, "%s%s", good, good + 8);
  PetscCall(WriteBytes("noend", s, -1));
  PetscCall(ExpectError("ASCII without endsolid", "noend", PETSC_ERR_FILE_UNEXPECTED, "after triangle 2"));
  snprintf(s, sizeof s, "%s%s%sendsolid\n", good, good + 8, facet_text("0 0 0", "1 nan 0", "0 1 0"));
  PetscCall(WriteBytes("nan", s, -1));
  PetscCall(ExpectError("ASCII NaN coordinate", "nan", PETSC_ERR_FILE_UNEXPECTED, "triangle 3 (line 19) vertex 2 has a non-finite coordinate"));
  snprintf(s, sizeof s, "%s%sendsolid\n", good, facet_text("0 0 0", "1 0 0", "-inf 1 0"));
  PetscCall(WriteBytes("inf", s, -1));
  PetscCall(ExpectError("ASCII infinite coordinate", "inf", PETSC_ERR_FILE_UNEXPECTED, "triangle 2 (line 13) vertex 3 has a non-finite"));
  snprintf(s, sizeof s, "%s%sendsolid\n", good, facet_text("0 0 0", "1 0 0", "0 1 0\nvertex 1 1 0"));
  PetscCall(WriteBytes("four", s, -1));
  PetscCall(ExpectError("ASCII facet of 4 vertices", "four", PETSC_ERR_FILE_UNEXPECTED, "triangle 2 (its endloop on line 15) has 4 vertices"));
  snprintf(s, sizeof s, "solid x\n%sendsolid\n", "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\nendfacet\n");
  PetscCall(WriteBytes("two", s, -1));
  PetscCall(ExpectError("ASCII facet of 2 vertices", "two", PETSC_ERR_FILE_UNEXPECTED, "triangle 1 (its endloop on line 6) has 2 vertices"));
  snprintf(s, sizeof s, "%s%sendsolid\n", good, facet_text("0 0 0", "1 0 0", "0 one 0"));
  PetscCall(WriteBytes("word", s, -1));
  PetscCall(ExpectError("ASCII word for a number", "word", PETSC_ERR_FILE_UNEXPECTED, "triangle 2 (line 13): 'one' is not a number"));
  snprintf(s, sizeof s, "solid x\n%s%sendsolid\n", facet_text("0 0 0", "1 1 1", "2 2 2"), facet_text("0 0 0", "1 0 0", "1 0 0"));
  PetscCall(WriteBytes("degen", s, -1));
  PetscCall(ExpectError("only zero-area triangles", "degen", PETSC_ERR_FILE_UNEXPECTED, "no triangles left: all 2 are zero-area (2)"));
  PetscCall(WriteBytes("nofacet", "solid nothing\nendsolid nothing\n", -1));
  PetscCall(ExpectError("a solid without facets", "nofacet", PETSC_ERR_FILE_UNEXPECTED, "no triangles"));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode TestMalformedBinary(void)
{
  float f[27];

  PetscFunctionBeginUser;
  for (int i = 0; i < 27; i++) f[i] = (float)(i % 9 == 3 * (i / 9 % 3) ? 1 : (i % 9) * 0.25 + i / 9);
  PetscCall(WriteBinary("bshort", "short", 3, 0, f, -20));
  PetscCall(ExpectError("binary shorter than its header", "bshort", PETSC_ERR_FILE_UNEXPECTED, "not STL"));
  PetscCall(WriteBinary("btrunc", "three", 3, 3, f, -60));
  PetscCall(ExpectError("binary truncated", "btrunc", PETSC_ERR_FILE_UNEXPECTED, "truncated binary STL: the header counts 3 triangles (234 bytes), the file has 174: triangle 2 is incomplete"));
  PetscCall(WriteBinary("bcount", "solid two", 2, 3, f, 0));
  PetscCall(ExpectError("binary count below the size", "bcount", PETSC_ERR_FILE_UNEXPECTED, "the header counts 2 triangles (184 bytes) but the file has 234 bytes, room for 3: the count disagrees with the size after triangle 2"));
  f[22] = NAN;
  PetscCall(WriteBinary("bnan", "nan", 3, 3, f, 0));
  PetscCall(ExpectError("binary NaN coordinate", "bnan", PETSC_ERR_FILE_UNEXPECTED, "triangle 3 (binary) vertex 2 has a non-finite coordinate"));
  f[22] = 1;
  PetscCall(WriteBinary("bzero", "solid none", 0, 0, f, 0));
  PetscCall(ExpectError("binary of 0 triangles", "bzero", PETSC_ERR_FILE_UNEXPECTED, "no triangles"));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* scale 2, quarter turns, shift: (1, 2, 3) by hand; 30 degrees about z vs cos and sin. */
static PetscErrorCode TestTransform(void)
{
  const double p0[9] = {1, 2, 3, 1, 0, 0, 0, 1, 0}, s[3] = {1, 1, 1}, o[3] = {0, 0, 0};
  const struct {
    double rot[3], x[3]; /* (1,2,3) scaled by 2, rotated, shifted by s */
  } c[4] = {
    {{90, 0, 0}, {3, -5, 5}},  /* Rx: (x, y, z) -> (x, -z, y) */
    {{0, 90, 0}, {7, 5, -1}},  /* Ry: (x, y, z) -> (z, y, -x) */
    {{0, 0, 90}, {-3, 3, 7}},  /* Rz: (x, y, z) -> (-y, x, z) */
    {{90, 90, 0}, {5, -5, -1}} /* Rx then Ry: (2,4,6) -> (2,-6,4) -> (4,-6,-2) */
  };
  TriMesh m;
  double  r[3], n[3];

  PetscFunctionBeginUser;
  for (int i = 0; i < 4; i++) {
    PetscCall(TriMeshCreate(1, &m));
    PetscCall(PetscArraycpy(m.v, p0, 9));
    PetscCall(TriMeshFinish(&m));
    PetscCall(TriMeshTransform(&m, 2, c[i].rot, s));
    for (int k = 0; k < 3; k++) PetscCall(CheckEqualReal(CheckName("scale 2, rotation (%g, %g, %g) deg, shift (1,1,1): vertex (1,2,3) -> %c", c[i].rot[0], c[i].rot[1], c[i].rot[2], 'x' + k), m.v[k], c[i].x[k]));
    PetscCall(TriMeshDestroy(&m));
  }
  PetscCall(TriMeshCreate(1, &m));
  PetscCall(PetscArraycpy(m.v, p0, 9));
  PetscCall(TriMeshFinish(&m));
  PetscCall(PetscArraycpy(n, m.n, 3));
  PetscCall(TriMeshTransform(&m, 1, (const double[3]){0, 0, 30}, o));
  r[0] = cos(PETSC_PI / 6) * p0[0] - sin(PETSC_PI / 6) * p0[1];
  r[1] = sin(PETSC_PI / 6) * p0[0] + cos(PETSC_PI / 6) * p0[1];
  r[2] = p0[2];
  PetscCall(CheckAtMost("30 deg about z: |vertex - Rz vertex|", PetscSqrtReal(PetscSqr(m.v[0] - r[0]) + PetscSqr(m.v[1] - r[1]) + PetscSqr(m.v[2] - r[2])), 1e-15));
  r[0] = cos(PETSC_PI / 6) * n[0] - sin(PETSC_PI / 6) * n[1];
  r[1] = sin(PETSC_PI / 6) * n[0] + cos(PETSC_PI / 6) * n[1];
  r[2] = n[2];
  PetscCall(CheckAtMost("30 deg about z: |normal - Rz normal|", PetscSqrtReal(PetscSqr(m.n[0] - r[0]) + PetscSqr(m.n[1] - r[1]) + PetscSqr(m.n[2] - r[2])), 1e-15));
  PetscCall(TriMeshDestroy(&m));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* One point p in a Voronoi region: feature, nearest point, distance and direction. */
static PetscErrorCode ClosestCase(const char *region, const double p[3], TriFeature f, const double q[3])
{
  const double a[3] = {0, 0, 0}, b[3] = {1, 0, 0}, c[3] = {0, 1, 0};
  double       got[3], d = 0, dref = 0, dir = 0;
  TriFeature   g = TriClosestPoint(a, b, c, p, got);

  PetscFunctionBeginUser;
  PetscCall(CheckEqual(CheckName("closest point, %s region: feature", region), g, f));
  for (int k = 0; k < 3; k++) {
    d += PetscSqr(p[k] - got[k]);
    dref += PetscSqr(p[k] - q[k]);
  }
  d = PetscSqrtReal(d), dref = PetscSqrtReal(dref);
  for (int k = 0; k < 3; k++) dir = PetscMax(dir, PetscAbsReal((p[k] - got[k]) / d - (p[k] - q[k]) / dref));
  PetscCall(CheckCloseAbs(CheckName("closest point, %s region: distance", region), d, dref, 1e-15));
  PetscCall(CheckAtMost(CheckName("closest point, %s region: direction error", region), dir, 1e-15));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode TestClosest(void)
{
  PetscFunctionBeginUser;
  PetscCall(ClosestCase("face", (const double[3]){0.2, 0.3, 0.5}, TRI_FACE, (const double[3]){0.2, 0.3, 0}));
  PetscCall(ClosestCase("edge AB", (const double[3]){0.4, -0.3, 0.4}, TRI_EDGE_AB, (const double[3]){0.4, 0, 0}));
  PetscCall(ClosestCase("edge BC", (const double[3]){0.7, 0.7, 0.2}, TRI_EDGE_BC, (const double[3]){0.5, 0.5, 0}));
  PetscCall(ClosestCase("edge CA", (const double[3]){-0.3, 0.4, -0.4}, TRI_EDGE_CA, (const double[3]){0, 0.4, 0}));
  PetscCall(ClosestCase("vertex A", (const double[3]){-0.3, -0.4, 0.1}, TRI_VERT_A, (const double[3]){0, 0, 0}));
  PetscCall(ClosestCase("vertex B", (const double[3]){1.3, -0.4, -0.1}, TRI_VERT_B, (const double[3]){1, 0, 0}));
  PetscCall(ClosestCase("vertex C", (const double[3]){-0.4, 1.3, 0.2}, TRI_VERT_C, (const double[3]){0, 1, 0}));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* test_stl FILE (used by geom/test_make_stl.sh): reads FILE and prints
 * "mesh <triangles> <zero-area> <duplicates> <area> <enclosed volume>" (SI), nothing checked. */
static PetscErrorCode MeshSummary(const char *path)
{
  TriMesh m;
  double  area = 0, vol = 0;

  PetscFunctionBeginUser;
  PetscCall(TriMeshReadSTL(PETSC_COMM_WORLD, path, &m));
  for (PetscInt t = 0; t < m.ntri; t++) {
    const double *a = m.v + 9 * t, *b = a + 3, *c = a + 6;
    const double  x[3] = {b[1] * c[2] - b[2] * c[1], b[2] * c[0] - b[0] * c[2], b[0] * c[1] - b[1] * c[0]};
    double        u[3], w[3], y[3];

    for (int k = 0; k < 3; k++) u[k] = b[k] - a[k], w[k] = c[k] - a[k];
    y[0] = u[1] * w[2] - u[2] * w[1], y[1] = u[2] * w[0] - u[0] * w[2], y[2] = u[0] * w[1] - u[1] * w[0];
    area += 0.5 * PetscSqrtReal(y[0] * y[0] + y[1] * y[1] + y[2] * y[2]);
    vol += (a[0] * x[0] + a[1] * x[1] + a[2] * x[2]) / 6;
  }
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "mesh %" PetscInt_FMT " %" PetscInt_FMT " %" PetscInt_FMT " %.17g %.17g\n", m.ntri, m.ndegen, m.nduplicate, area, vol));
  PetscCall(TriMeshDestroy(&m));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  int         pid;
  PetscMPIInt rank;

  PetscCall(PetscInitialize(&argc, &argv, NULL, "STL reader, mesh transform and closest point test"));
  if (argc > 1 && argv[1][0] != '-') {
    PetscCall(MeshSummary(argv[1]));
    PetscCall(PetscFinalize());
    return 0;
  }
  PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
  pid = (int)getpid();
  PetscCallMPI(MPI_Bcast(&pid, 1, MPI_INT, 0, PETSC_COMM_WORLD));
  snprintf(dir, sizeof dir, "/tmp/sable_stl_%d", pid);
  PetscCall(TestRoundTrip());
  PetscCall(TestSkipped());
  PetscCall(TestManyDuplicates());
  PetscCall(TestMalformedAscii());
  PetscCall(TestMalformedBinary());
  PetscCall(TestTransform());
  PetscCall(TestClosest());
  PetscCallMPI(MPI_Barrier(PETSC_COMM_WORLD));
  if (rank == 0) {
    const char *names[] = {"ascii", "binary", "skip", "many", "empty", "text", "trunc", "noend", "nan", "inf", "four", "two", "word", "degen", "nofacet", "bshort", "btrunc", "bcount", "bnan", "bzero"};

    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++) remove(Path(names[i]));
  }
  PetscCall(PetscFinalize());
  return check_failures ? 1 : 0;
}
