/* The region option reader (region.h): one syntax for every region a user names. It reads
 * through Sable's range-checked readers (sable.h), in the caller's PetscOptionsBegin block, and
 * leaves what only the caller knows (the domain, a source's particles) to the caller.
 * A patch is given by three corners p0, p1, p2, as the rectangle walls (-dem_rect_<k>) and the
 * sources' patches always were; the outlets' patches took a corner and two edge vectors
 * p,e1,e2 before. Both are nine numbers, so the old spelling cannot be told by its form: values
 * whose edges p1 - p0, p2 - p0 are not a rectangle while e1 = p1, e2 = p2 would be one are
 * refused in one line that gives the corners p, p + e1, p + e2 to write instead; values that are
 * a rectangle read either way (p != 0) are taken as corners with a one-line note giving the
 * corners of the old reading (for an outlet's patch only: the other patches never took edges). */
#include "geom/region.h"
#include "sable.h"
#include <string.h>

const char *const GeomRegionKinds[] = {"box", "cylinder", "patch"};

static const char *const GeomRegionSyntax[] = {"Box: xlo,ylo,zlo,xhi,yhi,zhi", "Cylinder: centre cx,cy,cz, axis ax,ay,az, radius R, length L", "Patch: a rectangle of corners p0, p1, p2 (p1-p0 perpendicular to p2-p0), facing (p1-p0)x(p2-p0): p0x,p0y,p0z,p1x,p1y,p1z,p2x,p2y,p2z"};
static const PetscInt    GeomRegionCount[]  = {6, 8, 9};

/* Whether e1, e2 are non-zero and perpendicular (the cosine within 1e-9); their lengths. */
static PetscBool GeomRegionRectangle(const PetscReal e1[3], const PetscReal e2[3], PetscReal *l1, PetscReal *l2)
{
  *l1 = PetscSqrtReal(convex_dot(e1, e1));
  *l2 = PetscSqrtReal(convex_dot(e2, e2));
  return (PetscBool)(*l1 > 0 && *l2 > 0 && PetscAbsReal(convex_dot(e1, e2)) <= 1e-9 * *l1 * *l2);
}

/* The corners p, p + e1, p + e2 of v read in the old spelling p,e1,e2, as C's printf writes the
 * numbers (as a user writes them; PETSc's adds a '.'). */
static void GeomRegionOldCorners(const PetscReal v[9], char *buf, size_t n)
{
  snprintf(buf, n, "%.15g,%.15g,%.15g,%.15g,%.15g,%.15g,%.15g,%.15g,%.15g", (double)v[0], (double)v[1], (double)v[2], (double)(v[0] + v[3]), (double)(v[1] + v[4]), (double)(v[2] + v[5]), (double)(v[0] + v[6]), (double)(v[1] + v[7]), (double)(v[2] + v[8]));
}

/* The patch of corners v = p0, p1, p2 into r. */
static PetscErrorCode GeomRegionPatch(MPI_Comm comm, const char *opt, const PetscReal v[9], GeomRegion *r)
{
  PetscReal e1[3], e2[3], n[3], l1, l2, m1, m2;

  PetscFunctionBeginUser;
  for (int d = 0; d < 3; d++) {
    e1[d] = v[3 + d] - v[d];
    e2[d] = v[6 + d] - v[d];
  }
  if (!GeomRegionRectangle(e1, e2, &l1, &l2)) {
    char corners[256];
    GeomRegionOldCorners(v, corners, sizeof corners);
    PetscCheck(!strstr(opt, "_outlet_") || !GeomRegionRectangle(v + 3, v + 6, &m1, &m2), comm, PETSC_ERR_ARG_WRONG, "%s takes three corners p0,p1,p2 now (as -dem_rect_<k>), not a corner and two edges p,e1,e2: write %s for the rectangle p + s e1 + t e2", opt, corners);
    SETERRQ(comm, PETSC_ERR_ARG_OUTOFRANGE, "%s: the edges p1 - p0 = %g,%g,%g and p2 - p0 = %g,%g,%g must be non-zero and perpendicular (a degenerate patch)", opt, (double)e1[0], (double)e1[1], (double)e1[2], (double)e2[0], (double)e2[1], (double)e2[2]);
  }
  if (strstr(opt, "_outlet_") && (v[0] != 0 || v[1] != 0 || v[2] != 0) && GeomRegionRectangle(v + 3, v + 6, &m1, &m2)) {
    char corners[256]; /* both readings are rectangles, and they differ (p != 0) */
    GeomRegionOldCorners(v, corners, sizeof corners);
    PetscCall(PetscPrintf(comm, "note: %s is read as three corners p0,p1,p2 (the rectangle from p0 with edges p1 - p0, p2 - p0); before, this option took a corner and two edges p,e1,e2, which would be the corners p, p + e1, p + e2 = %s: write those corners if that was meant\n", opt, corners));
  }
  convex_cross(e1, e2, n);
  r->kind  = GEOM_REGION_PATCH;
  r->depth = 0;
  for (int d = 0; d < 3; d++) {
    r->g[d]     = v[d];
    r->g[3 + d] = e1[d];
    r->g[6 + d] = e2[d];
    r->n[d]     = n[d] / (l1 * l2);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode GeomRegionOption_Private(PetscOptionItems *PetscOptionsObject, const char opt[], GeomRegionKind kind, const char text[], GeomRegion *r, PetscBool *set)
{
  const MPI_Comm comm = PetscOptionsObject->comm;
  PetscReal      v[9];
  PetscBool      given;

  PetscFunctionBeginUser;
  PetscCall(SableOptionsRealN(opt, text ? text : GeomRegionSyntax[kind], "m", v, 0, GeomRegionCount[kind], &given));
  if (set) *set = given;
  if (!given) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscMemzero(r, sizeof *r)); /* the fields the kind does not use are 0, not the caller's */
  if (kind == GEOM_REGION_PATCH) PetscCall(GeomRegionPatch(comm, opt, v, r));
  else if (kind == GEOM_REGION_BOX) {
    for (int d = 0; d < 3; d++) PetscCheck(v[d] < v[3 + d], comm, PETSC_ERR_ARG_OUTOFRANGE, "%s %g,%g,%g,%g,%g,%g: need lo < hi on every axis (m)", opt, (double)v[0], (double)v[1], (double)v[2], (double)v[3], (double)v[4], (double)v[5]);
    r->kind = GEOM_REGION_BOX;
    for (int d = 0; d < 6; d++) r->g[d] = v[d];
  } else {
    const PetscReal l = PetscSqrtReal(convex_dot(v + 3, v + 3));
    PetscCheck(l > 0 && v[6] > 0 && v[7] > 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "%s: the axis must be non-zero and R %g, L %g > 0", opt, (double)v[6], (double)v[7]);
    r->kind = GEOM_REGION_CYLINDER;
    for (int d = 0; d < 8; d++) r->g[d] = v[d];
    for (int d = 0; d < 3; d++) r->g[3 + d] /= l;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode GeomRegionOptions_Private(PetscOptionItems *PetscOptionsObject, const GeomRegionSpec *spec, GeomRegion *r, PetscBool *set)
{
  const char *first = NULL;

  PetscFunctionBeginUser;
  for (int k = 0; k < 3; k++) {
    PetscBool given;
    if (!spec->opt[k]) continue;
    PetscCall(GeomRegionOption_Private(PetscOptionsObject, spec->opt[k], (GeomRegionKind)k, spec->text[k], r, &given));
    PetscCheck(!given || !first, PetscOptionsObject->comm, PETSC_ERR_ARG_INCOMP, "%s and %s both give the region: give one of them", first, spec->opt[k]);
    if (given) first = spec->opt[k];
  }
  if (set) *set = (PetscBool)(first != NULL);
  PetscFunctionReturn(PETSC_SUCCESS);
}
