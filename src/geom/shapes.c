/* Catalogue of convex shapes: built-in solids scaled by a size, and vertex files.
 *
 * Built-in polyhedra are generated from their textbook vertex coordinates and then go through
 * the general path (hull, exact mass properties), so their analytic values test that path:
 *   cube, edge a:                 (+-a/2, +-a/2, +-a/2);          V = a^3,            I = V a^2/6
 *   regular tetrahedron, edge a:  s(1,1,1), s(1,-1,-1), s(-1,1,-1), s(-1,-1,1), s = a/(2 sqrt 2);
 *                                 V = a^3/(6 sqrt 2),            I = V a^2/20
 *   octahedron, edge a:           (+-s,0,0) and permutations, s = a/sqrt 2;
 *                                 V = sqrt(2) a^3/3,             I = V a^2/10
 *   icosahedron, edge a:          (0, +-s, +-s phi) and cyclic permutations, s = a/2, phi golden;
 *                                 V = 5(3+sqrt 5) a^3/12,        I = V phi^2 a^2/10
 * The cylinder is analytic (no vertices; see polyhedron.c for its moments).
 * Vertex file: one vertex per line, "x y z" (whitespace separated); blank lines and text after
 * '#' are ignored; any other content is an error naming the file and the line.
 */
#include "geom/convex_impl.h"

static PetscErrorCode CheckSize(const char *what, const char *name, PetscReal size)
{
  PetscFunctionBegin;
  PetscCheck(size > 0 && !PetscIsInfOrNanReal(size), PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "%s %s %g must be a finite length > 0", what, name, (double)size);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ConvexShapeCreateCube(PetscReal edge, ConvexShape *shape)
{
  PetscReal x[24];

  PetscFunctionBegin;
  PetscCall(CheckSize("cube", "edge", edge));
  for (int i = 0; i < 8; i++)
    for (int d = 0; d < 3; d++) x[3 * i + d] = ((i >> d) & 1 ? 0.5 : -0.5) * edge;
  PetscCall(ConvexShapeCreateFromVertices(8, x, shape));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ConvexShapeCreateTetrahedron(PetscReal edge, ConvexShape *shape)
{
  const PetscReal s     = edge / (2 * PETSC_SQRT2);
  PetscReal       x[12] = {s, s, s, s, -s, -s, -s, s, -s, -s, -s, s};

  PetscFunctionBegin;
  PetscCall(CheckSize("tetrahedron", "edge", edge));
  PetscCall(ConvexShapeCreateFromVertices(4, x, shape));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ConvexShapeCreateOctahedron(PetscReal edge, ConvexShape *shape)
{
  const PetscReal s = edge / PETSC_SQRT2;
  PetscReal       x[18];

  PetscFunctionBegin;
  PetscCall(CheckSize("octahedron", "edge", edge));
  for (int i = 0; i < 6; i++)
    for (int d = 0; d < 3; d++) x[3 * i + d] = (d == i / 2) ? (i % 2 ? -s : s) : 0;
  PetscCall(ConvexShapeCreateFromVertices(6, x, shape));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ConvexShapeCreateIcosahedron(PetscReal edge, ConvexShape *shape)
{
  const PetscReal s = edge / 2, phi = (1 + PetscSqrtReal(5.0)) / 2;
  PetscReal       x[36];

  PetscFunctionBegin;
  PetscCall(CheckSize("icosahedron", "edge", edge));
  for (int c = 0; c < 3; c++) /* cyclic permutation c of (0, +-1, +-phi) */
    for (int k = 0; k < 4; k++) {
      PetscReal *p   = &x[3 * (4 * c + k)];
      p[c]           = 0;
      p[(c + 1) % 3] = (k & 1 ? -s : s);
      p[(c + 2) % 3] = (k & 2 ? -s : s) * phi;
    }
  PetscCall(ConvexShapeCreateFromVertices(12, x, shape));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ConvexShapeCreateCylinder(PetscReal radius, PetscReal height, ConvexShape *shape)
{
  PetscFunctionBegin;
  PetscCall(CheckSize("cylinder", "radius", radius));
  PetscCall(CheckSize("cylinder", "height", height));
  PetscCall(PetscMemzero(shape, sizeof(*shape)));
  shape->kind       = CONVEX_CYLINDER;
  shape->radius     = radius;
  shape->height     = height;
  shape->volume     = PETSC_PI * radius * radius * height;
  shape->inertia[0] = shape->volume * (3 * radius * radius + height * height) / 12;
  shape->inertia[1] = shape->inertia[0];
  shape->inertia[2] = shape->volume * radius * radius / 2;
  for (int i = 0; i < 9; i++) shape->rot_input[i] = (i % 4 == 0) ? 1 : 0;
  shape->bounding_radius = PetscSqrtReal(radius * radius + height * height / 4);
  shape->d_eq            = PetscCbrtReal(6 * shape->volume / PETSC_PI);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Parse "x y z" (after comment stripping); returns the number of values read, or -1 when the
 * line has extra or non-numeric content. */
static int ParseVertexLine(char *line, PetscReal p[3])
{
  char *c = strchr(line, '#'), *end;
  int   k = 0;

  if (c) *c = 0;
  for (c = line; k < 4; k++) {
    double v;
    while (*c == ' ' || *c == '\t' || *c == '\r' || *c == '\n') c++;
    if (!*c) break;
    if (k == 3) return -1;
    v = strtod(c, &end);
    if (end == c || PetscIsInfOrNanReal(v)) return -1;
    p[k] = v;
    c    = end;
  }
  return k;
}

PetscErrorCode ConvexShapeCreateFromFile(const char path[], ConvexShape *shape)
{
  FILE      *fp;
  char       line[1024];
  PetscReal *x = NULL;
  PetscInt   n = 0, cap = 0, lineno = 0;
  ConvexHull hull;

  PetscFunctionBegin;
  PetscCall(PetscMemzero(shape, sizeof(*shape)));
  fp = fopen(path, "r");
  PetscCheck(fp, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "convex vertex file %s: cannot open it for reading", path);
  while (fgets(line, sizeof line, fp)) {
    PetscReal p[3];
    int       k;
    lineno++;
    k = ParseVertexLine(line, p);
    if (k == 0) continue;
    if (k != 3) {
      (void)fclose(fp);
      PetscCall(PetscFree(x));
      SETERRQ(PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "convex vertex file %s line %" PetscInt_FMT ": expected three numbers \"x y z\"", path, lineno);
    }
    if (n == cap) {
      cap = 2 * cap + 16;
      PetscCall(PetscRealloc(sizeof(PetscReal) * 3 * (size_t)cap, &x));
    }
    for (int d = 0; d < 3; d++) x[3 * n + d] = p[d];
    n++;
  }
  (void)fclose(fp);
  if (n < 4) PetscCall(PetscFree(x));
  PetscCheck(n >= 4, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "convex vertex file %s: %" PetscInt_FMT " vertices in %" PetscInt_FMT " lines, at least 4 needed", path, n, lineno);
  PetscCall(ConvexHullBuild(n, x, &hull));
  if (hull.status != CONVEX_HULL_OK) PetscCall(PetscFree(x));
  PetscCheck(hull.status == CONVEX_HULL_OK, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "convex vertex file %s: its %" PetscInt_FMT " vertices do not span a solid: %s (largest spread %g <= tolerance %g)", path, n, ConvexHullStatusText(hull.status), (double)hull.measure, (double)hull.tol);
  PetscCall(PetscFree(hull.f));
  PetscCall(ConvexShapeCreateFromVertices(n, x, shape));
  PetscCall(PetscFree(x));
  PetscFunctionReturn(PETSC_SUCCESS);
}
