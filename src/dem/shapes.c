/* The shape table for non-spherical particles: options, construction and mass properties.
 *
 * Each shape index s is either a sphere (radius r) or a convex body (a ConvexShape owned by the
 * table, see convex.h): a built-in polyhedron given by its edge, a cylinder given by its
 * diameter and aspect ratio, or a polyhedron read from a vertex file. A convex shape stores
 *   r    = its bounding radius (broad phase: cells, Verlet list, wall lists, lattice spacing),
 *   vol  = V (exact), m = rho V, J = rho diag(I_1, I_2, I_3) (principal, body axes),
 *   req  = d_eq / 2 = (3V / 4 pi)^(1/3), the radius of the sphere of the same volume, used as the
 *          particle radius R in the contact laws (Hertz R* = R_i R_j / (R_i + R_j), and the
 *          Hertz-equivalent kn of the linear law when it is derived from Young's modulus).
 * Options (one value per shape, in the order of -dem_shape):
 *   -dem_shape sphere|cube|tetrahedron|octahedron|icosahedron|cylinder|polyhedron,...
 *   -dem_shape_size  edge (polyhedra), diameter (sphere, cylinder), scale factor (vertex file) (m)
 *   -dem_shape_deq   volume-equivalent diameter instead of -dem_shape_size (m)
 *   -dem_shape_file  vertex file of each polyhedron entry (convex.h: "x y z" per line, m)
 *   -dem_cylinder_aspect  height / diameter of the cylinders (default 1)
 * Spheres and convex shapes in one scene are refused (no sphere-polyhedron narrow phase yet).
 * Reference: Rakotonirina & Wachs 2018 (Grains3D Part II) §2, the "reference particle". */
#include "dem/dem_core.h"

typedef enum {
  DEM_SHAPE_SPHERE,
  DEM_SHAPE_CUBE,
  DEM_SHAPE_TETRAHEDRON,
  DEM_SHAPE_OCTAHEDRON,
  DEM_SHAPE_ICOSAHEDRON,
  DEM_SHAPE_CYLINDER,
  DEM_SHAPE_POLYHEDRON
} DemShapeKind;
static const char *DemShapeKinds[] = {"sphere", "cube", "tetrahedron", "octahedron", "icosahedron", "cylinder", "polyhedron", "DemShapeKind", "DEM_SHAPE_", NULL};

/* Uniform scaling of a shape about its centre of mass (lengths by s). */
static void DemConvexScale(ConvexShape *c, double s)
{
  for (PetscInt k = 0; k < 3 * c->nv; k++) c->v[k] *= s;
  c->radius *= s;
  c->height *= s;
  c->volume *= s * s * s;
  for (int k = 0; k < 3; k++) {
    c->inertia[k] *= s * s * s * s * s;
    c->com_input[k] *= s;
  }
  c->bounding_radius *= s;
  c->d_eq *= s;
}

typedef struct {
  DemShapeKind kind;
  double       size, deq, aspect; /* size or deq < 0: not given */
  const char  *file;
} DemShapeSpec;

static PetscErrorCode DemConvexCreate(Dem dem, const DemShapeSpec *sp, ConvexShape *c)
{
  const double a = sp->size > 0 ? sp->size : 1; /* with -dem_shape_deq: unit size, scaled below */

  PetscFunctionBeginUser;
  switch (sp->kind) {
  case DEM_SHAPE_CUBE:
    PetscCall(ConvexShapeCreateCube(a, c));
    break;
  case DEM_SHAPE_TETRAHEDRON:
    PetscCall(ConvexShapeCreateTetrahedron(a, c));
    break;
  case DEM_SHAPE_OCTAHEDRON:
    PetscCall(ConvexShapeCreateOctahedron(a, c));
    break;
  case DEM_SHAPE_ICOSAHEDRON:
    PetscCall(ConvexShapeCreateIcosahedron(a, c));
    break;
  case DEM_SHAPE_CYLINDER:
    PetscCall(ConvexShapeCreateCylinder(0.5 * a, sp->aspect * a, c));
    break;
  case DEM_SHAPE_POLYHEDRON:
    PetscCall(ConvexShapeCreateFromFile(sp->file, c));
    if (sp->size > 0) DemConvexScale(c, sp->size);
    break;
  default:
    SETERRQ(dem->comm, PETSC_ERR_ARG_WRONG, "-dem_shape: not a convex kind");
  }
  if (sp->deq > 0) DemConvexScale(c, sp->deq / c->d_eq);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Fills shape s from its spec (collective: every rank builds the same table). */
static PetscErrorCode DemShapeBuild(Dem dem, PetscInt s, const DemShapeSpec *sp)
{
  DemShape *sh = &dem->shapes.shp[s];

  PetscFunctionBeginUser;
  sh->rho = dem->shapes.shp[0].rho;
  if (sp->kind == DEM_SHAPE_SPHERE) {
    sh->r   = sp->deq > 0 ? 0.5 * sp->deq : 0.5 * sp->size;
    sh->cvx = NULL;
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(DemConvexCreate(dem, sp, &dem->shapes.cvx[s]));
  sh->cvx = &dem->shapes.cvx[s];
  sh->r   = dem->shapes.cvx[s].bounding_radius;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* PETSc's own message for an unknown enum in an array does not list the valid names: check the
 * raw -dem_shape value first. */
static PetscErrorCode DemShapeKindsCheck(Dem dem)
{
  const char *val;
  char        buf[PETSC_MAX_PATH_LEN], *tok, *save = NULL;
  PetscBool   set;

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsFindPair(NULL, NULL, "-dem_shape", &val, &set));
  if (!set || !val) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscStrncpy(buf, val, sizeof buf));
  for (tok = strtok_r(buf, ",", &save); tok; tok = strtok_r(NULL, ",", &save)) {
    PetscBool eq = PETSC_FALSE; /* case-insensitive, as the enum parser compares */
    for (PetscInt k = 0; k < 7 && !eq; k++) PetscCall(PetscStrcasecmp(tok, DemShapeKinds[k], &eq));
    PetscCheck(eq, dem->comm, PETSC_ERR_ARG_OUTOFRANGE, "-dem_shape: unknown shape '%s'; valid: sphere, cube, tetrahedron, octahedron, icosahedron, cylinder, polyhedron (one per shape, comma-separated)", tok);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode DemShapeSpecsRead(Dem dem, PetscInt *ns, DemShapeSpec sp[], char *files[])
{
  PetscEnum kind[DEM_MAX_SHAPES] = {0}; /* initialised: -help prints the arrays */
  PetscReal size[DEM_MAX_SHAPES] = {0}, deq[DEM_MAX_SHAPES] = {0}, aspect = 1;
  PetscInt  nk = DEM_MAX_SHAPES, nsz = DEM_MAX_SHAPES, nd = DEM_MAX_SHAPES, nfile = DEM_MAX_SHAPES, used = 0;
  PetscBool kset, sset, dset, fset, rset;

  PetscFunctionBeginUser;
  PetscCall(DemShapeKindsCheck(dem));
  PetscOptionsBegin(dem->comm, NULL, "DEM shapes", NULL);
  PetscCall(PetscOptionsEnumArray("-dem_shape", "Shape of each particle type: sphere, cube, tetrahedron, octahedron, icosahedron, cylinder, polyhedron", NULL, DemShapeKinds, kind, &nk, &kset));
  PetscCall(SableOptionsRealArray("-dem_shape_size", "Edge (polyhedra), diameter (sphere, cylinder) or scale of the vertex file, per shape", "m", size, 0, &nsz, &sset));
  PetscCall(SableOptionsRealArray("-dem_shape_deq", "Volume-equivalent diameter per shape, instead of -dem_shape_size", "m", deq, 0, &nd, &dset));
  PetscCall(PetscOptionsStringArray("-dem_shape_file", "Vertex file of each polyhedron shape (x y z per line, m)", NULL, files, &nfile, &fset));
  PetscCall(SableOptionsReal("-dem_cylinder_aspect", "Height / diameter of the cylinder shapes", NULL, "(0,inf)", aspect, &aspect, NULL));
  PetscOptionsEnd();
  *ns = kset ? nk : 0;
  if (!fset) nfile = 0;
  if (!kset) {
    PetscCheck(!sset && !dset && !fset, dem->comm, PETSC_ERR_ARG_WRONG, "-dem_shape_size, -dem_shape_deq and -dem_shape_file need -dem_shape");
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(PetscOptionsHasName(NULL, NULL, "-dem_radius", &rset));
  PetscCheck(!rset, dem->comm, PETSC_ERR_ARG_WRONG, "give either -dem_radius (spheres) or -dem_shape with -dem_shape_size, not both");
  PetscCheck(!(sset && dset), dem->comm, PETSC_ERR_ARG_WRONG, "give either -dem_shape_size or -dem_shape_deq, not both");
  PetscCheck(!sset || nsz == nk, dem->comm, PETSC_ERR_ARG_SIZ, "-dem_shape_size has %" PetscInt_FMT " values for %" PetscInt_FMT " shapes", nsz, nk);
  PetscCheck(!dset || nd == nk, dem->comm, PETSC_ERR_ARG_SIZ, "-dem_shape_deq has %" PetscInt_FMT " values for %" PetscInt_FMT " shapes", nd, nk);
  for (PetscInt s = 0; s < nk; s++) {
    sp[s].kind   = (DemShapeKind)kind[s];
    sp[s].size   = sset ? size[s] : -1;
    sp[s].deq    = dset ? deq[s] : -1;
    sp[s].aspect = aspect;
    sp[s].file   = NULL;
    PetscCheck(!sset || size[s] > 0, dem->comm, PETSC_ERR_ARG_OUTOFRANGE, "-dem_shape_size %g must be > 0 (m)", (double)size[s]);
    PetscCheck(!dset || deq[s] > 0, dem->comm, PETSC_ERR_ARG_OUTOFRANGE, "-dem_shape_deq %g must be > 0 (m)", (double)deq[s]);
    if (sp[s].kind == DEM_SHAPE_POLYHEDRON) {
      PetscCheck(used < nfile, dem->comm, PETSC_ERR_ARG_WRONG, "-dem_shape entry %" PetscInt_FMT " is a polyhedron: -dem_shape_file needs a vertex file for it", s);
      sp[s].file = files[used++];
    } else PetscCheck(sset || dset, dem->comm, PETSC_ERR_ARG_WRONG, "-dem_shape %s needs -dem_shape_size or -dem_shape_deq (m)", DemShapeKinds[sp[s].kind]);
    PetscCheck((sp[s].kind == DEM_SHAPE_SPHERE) == (sp[0].kind == DEM_SHAPE_SPHERE), dem->comm, PETSC_ERR_SUP, "-dem_shape: spheres and convex shapes in one scene are not supported (no sphere-polyhedron narrow phase)");
  }
  PetscCheck(used == nfile, dem->comm, PETSC_ERR_ARG_SIZ, "-dem_shape_file has %" PetscInt_FMT " files for %" PetscInt_FMT " polyhedron shapes", nfile, used);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemShapesSetFromOptions(Dem dem)
{
  DemShapeSpec sp[DEM_MAX_SHAPES];
  char        *files[DEM_MAX_SHAPES] = {NULL};
  PetscInt     ns                    = 0;

  PetscFunctionBeginUser;
  PetscCall(DemShapeSpecsRead(dem, &ns, sp, files));
  if (ns) {
    PetscCall(DemShapesDestroy(dem));
    for (PetscInt s = 0; s < ns; s++) PetscCall(DemShapeBuild(dem, s, &sp[s]));
    dem->shapes.nshape = ns;
    dem->shapes.convex = (PetscBool)(sp[0].kind != DEM_SHAPE_SPHERE);
  }
  for (PetscInt s = 0; s < DEM_MAX_SHAPES; s++) PetscCall(PetscFree(files[s]));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Mass properties from the density (after dem.c has set those of the spheres). */
PetscErrorCode DemShapesSetUp(Dem dem)
{
  PetscFunctionBeginUser;
  for (PetscInt s = 0; s < dem->shapes.nshape; s++) {
    DemShape *sh = &dem->shapes.shp[s];
    if (!sh->cvx) {
      sh->vol = 4.0 / 3.0 * PETSC_PI * sh->r * sh->r * sh->r;
      sh->req = sh->r;
      for (int k = 0; k < 3; k++) {
        sh->J[k]    = sh->inertia;
        sh->invJ[k] = sh->invi;
      }
      continue;
    }
    sh->vol  = sh->cvx->volume;
    sh->req  = 0.5 * sh->cvx->d_eq;
    sh->m    = sh->rho * sh->vol;
    sh->invm = 1.0 / sh->m;
    for (int k = 0; k < 3; k++) {
      sh->J[k]    = sh->rho * sh->cvx->inertia[k];
      sh->invJ[k] = 1.0 / sh->J[k];
    }
    sh->inertia = (sh->J[0] + sh->J[1] + sh->J[2]) / 3.0; /* only for reports */
    PetscCall(ConvexAxesDestroy(&sh->ax));
    PetscCall(ConvexAxesCreate(sh->cvx, &sh->ax)); /* for the separating-axis tests (convex_contacts.c) */
    sh->iso  = (PetscBool)(PetscAbsReal(sh->J[0] - sh->J[2]) <= 1e-12 * sh->J[2] && PetscAbsReal(sh->J[1] - sh->J[2]) <= 1e-12 * sh->J[2]);
    sh->invi = 1.0 / sh->inertia;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemShapesDestroy(Dem dem)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree(dem->narrow.sepax));
  PetscCall(PetscFree2(dem->narrow.rot, dem->narrow.rot_stamp));
  dem->narrow.rot_cap = dem->narrow.rot_pass = dem->narrow.rot_pairs = 0;
  for (PetscInt s = 0; s < DEM_MAX_SHAPES; s++) {
    PetscCall(ConvexShapeDestroy(&dem->shapes.cvx[s]));
    if (dem->shapes.shp[s].cvx) PetscCall(ConvexAxesDestroy(&dem->shapes.shp[s].ax));
    dem->shapes.shp[s].cvx    = NULL;
    dem->shapes.shp[s].ax.nfn = 0;
    dem->shapes.shp[s].ax.nen = 0;
    dem->shapes.shp[s].ax.box = PETSC_FALSE;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemHasConvexShapes(Dem dem, PetscBool *convex)
{
  PetscFunctionBeginUser;
  *convex = dem->shapes.convex;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemGetLargestRadius(Dem dem, PetscReal *r)
{
  PetscFunctionBeginUser;
  *r = 0;
  for (PetscInt s = 0; s < dem->shapes.nshape; s++) *r = PetscMax(*r, dem->shapes.shp[s].r);
  if (dem->shapes.poly) *r = PetscMax(*r, dem->shapes.r_source_max);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemGetOwnSizes(Dem dem, PetscBool *poly, PetscReal *rmin, PetscReal *rmax)
{
  PetscFunctionBeginUser;
  *poly = dem->shapes.poly;
  *rmin = *rmax = 0;
  if (!dem->shapes.poly) PetscFunctionReturn(PETSC_SUCCESS);
  *rmin = dem->shapes.r_source_min > 0 ? dem->shapes.r_source_min : PETSC_MAX_REAL;
  *rmax = dem->shapes.r_source_max;
  for (PetscInt s = 0; s < dem->shapes.nshape; s++) {
    *rmin = PetscMin(*rmin, dem->shapes.shp[s].r);
    *rmax = PetscMax(*rmax, dem->shapes.shp[s].r);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemSetOwnSizes(Dem dem, PetscReal rmin, PetscReal rmax)
{
  PetscFunctionBeginUser;
  PetscCheck(rmin > 0 && rmax >= rmin, dem->comm, PETSC_ERR_ARG_OUTOFRANGE, "sizes of their own: radii [%g, %g] m must satisfy 0 < rmin <= rmax", (double)rmin, (double)rmax);
  dem->shapes.r_source_min = dem->shapes.r_source_min > 0 ? PetscMin(dem->shapes.r_source_min, rmin) : rmin;
  dem->shapes.r_source_max = PetscMax(dem->shapes.r_source_max, rmax);
  dem->shapes.poly         = PETSC_TRUE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemGetShapeGeometry(Dem dem, PetscInt s, PetscReal *volume, PetscReal *d_eq)
{
  PetscFunctionBeginUser;
  PetscCheck(s >= 0 && s < dem->shapes.nshape, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "shape %" PetscInt_FMT " not in [0, %" PetscInt_FMT ")", s, dem->shapes.nshape);
  if (volume) *volume = dem->shapes.shp[s].vol;
  if (d_eq) *d_eq = 2 * dem->shapes.shp[s].req;
  PetscFunctionReturn(PETSC_SUCCESS);
}
