/* Triangle-mesh walls: their options, read in the walls' block (walls_options.c), k = 0..7:
 *   -dem_mesh_<k>_file path.stl (ASCII or binary, geom/trimesh.h), placed by _scale (about the
 *   origin), then _rotate ax,ay,az (degrees about x, then y, then z), then _translate (m);
 *   material _friction, _restitution, _kn (linear laws) or _youngs_modulus (hertz),
 *   _rolling_friction, each defaulting to the -dem_wall_* material;
 *   motion _velocity vx,vy,vz (m/s), and rotation about the axis through _axis_point (m, moving
 *   with the translation) along _axis, at _omega (rad/s) or after _omega_table t0,w0,t1,w1,...
 *   (s, rad/s: piecewise linear in time, constant outside; the angle is its exact integral);
 *   the gas of a coupled run _fluid inside|outside|none (vessel.c).
 * Each mesh is read on rank 0 and broadcast, then announced in one line (file, triangles, the
 * skipped degenerate and duplicate ones, bounding box). Contacts, lists and motion: walls_mesh.c. */
#include "dem/dem_core.h"
#include "dem/dem_walls.h"

static const char *const DemMeshWordOptions[] = {"-dem_mesh_%d_file", "-dem_mesh_%d_fluid"};
#define DEM_MESH_TAB_MAX 64 /* points of an omega table */

/* The material of mesh k: the walls' unless given. */
static PetscErrorCode DemMeshMaterial(PetscOptionItems *PetscOptionsObject, Dem dem, int k, DemMesh *m)
{
  char      o[5][48];
  PetscBool set[5];
  PetscReal v[5];

  PetscFunctionBeginUser;
  m->mat = dem->contact.wmat;
  PetscCall(PetscSNPrintf(o[0], sizeof o[0], "-dem_mesh_%d_friction", k));
  PetscCall(PetscSNPrintf(o[1], sizeof o[1], "-dem_mesh_%d_restitution", k));
  PetscCall(PetscSNPrintf(o[2], sizeof o[2], "-dem_mesh_%d_kn", k));
  PetscCall(PetscSNPrintf(o[3], sizeof o[3], "-dem_mesh_%d_youngs_modulus", k));
  PetscCall(PetscSNPrintf(o[4], sizeof o[4], "-dem_mesh_%d_rolling_friction", k));
  PetscCall(SableOptionsReal(o[0], "Friction coefficient of this mesh (default -dem_wall_friction)", NULL, "[0,inf)", m->mat.mu, &v[0], &set[0]));
  PetscCall(SableOptionsReal(o[1], "Restitution of this mesh (default -dem_wall_restitution)", NULL, "(0,1]", m->mat.e, &v[1], &set[1]));
  PetscCall(SableOptionsReal(o[2], "Normal stiffness of this mesh, linear laws (default -dem_wall_kn)", "N/m", "(0,inf)", m->mat.kn, &v[2], &set[2]));
  PetscCall(SableOptionsReal(o[3], "Young's modulus of this mesh (default -dem_wall_youngs_modulus)", "Pa", "(0,inf)", m->mat.E, &v[3], &set[3]));
  PetscCall(SableOptionsReal(o[4], "Rolling friction of this mesh (default -dem_wall_rolling_friction)", NULL, "[0,inf)", m->mat.mur, &v[4], &set[4]));
  PetscCheck(!set[2] || dem->contact.law != DEM_LAW_HERTZ, dem->comm, PETSC_ERR_ARG_INCOMP, "%s is ignored by -dem_contact_law hertz, which takes the stiffness from %s", o[2], o[3]);
  PetscCheck(!set[3] || dem->contact.law == DEM_LAW_HERTZ || !(set[2] || m->mat.kn_set), dem->comm, PETSC_ERR_ARG_INCOMP, "%s is ignored: the wall stiffness is given by %s (give one of them)", o[3], set[2] ? o[2] : "-dem_wall_kn or -dem_kn");
  PetscCheck(!set[4] || dem->contact.roll != DEM_ROLL_NONE, dem->comm, PETSC_ERR_ARG_INCOMP, "%s is ignored by -dem_rolling_model none: give -dem_rolling_model constant, viscous or kms", o[4]);
  if (set[0]) m->mat.mu = v[0];
  if (set[1]) m->mat.e = v[1];
  if (set[2]) m->mat.kn = v[2], m->mat.kn_set = PETSC_TRUE;
  if (set[3]) m->mat.E = v[3], m->mat.E_set = PETSC_TRUE;
  if (set[4]) m->mat.mur = v[4];
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The motion of mesh k: translation, rotation at a constant rate or after a table. */
static PetscErrorCode DemMeshMotion(PetscOptionItems *PetscOptionsObject, Dem dem, int k, DemMesh *m)
{
  char      o[5][48];
  PetscBool vset, wset, pset, aset, tset;
  PetscReal tab[2 * DEM_MESH_TAB_MAX];
  PetscInt  nt = 2 * DEM_MESH_TAB_MAX;

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(o[0], sizeof o[0], "-dem_mesh_%d_velocity", k));
  PetscCall(PetscSNPrintf(o[1], sizeof o[1], "-dem_mesh_%d_omega", k));
  PetscCall(PetscSNPrintf(o[2], sizeof o[2], "-dem_mesh_%d_axis_point", k));
  PetscCall(PetscSNPrintf(o[3], sizeof o[3], "-dem_mesh_%d_axis", k));
  PetscCall(PetscSNPrintf(o[4], sizeof o[4], "-dem_mesh_%d_omega_table", k));
  m->ax_u[2] = 1;
  PetscCall(SableOptionsRealN(o[0], "Translation velocity of this mesh", "m/s", m->vel, 3, 3, &vset));
  PetscCall(SableOptionsReal(o[1], "Angular velocity of this mesh about its axis (right hand)", "rad/s", NULL, 0, &m->omega, &wset));
  PetscCall(SableOptionsRealN(o[2], "A point of the rotation axis at t = 0 (it moves with -dem_mesh_<k>_velocity)", "m", m->ax_p, 3, 3, &pset));
  PetscCall(SableOptionsRealN(o[3], "Direction of the rotation axis", NULL, m->ax_u, 3, 3, &aset));
  PetscCall(SableOptionsRealArray(o[4], "Angular velocity table t0,w0,t1,w1,... (s, rad/s), times increasing: piecewise linear, constant outside", NULL, tab, 0, &nt, &tset));
  for (int j = 0; j < 3; j++) PetscCheck(!PetscIsInfOrNanReal(m->vel[j]) && !PetscIsInfOrNanReal(m->ax_p[j]) && !PetscIsInfOrNanReal(m->ax_u[j]), dem->comm, PETSC_ERR_ARG_OUTOFRANGE, "%s, %s and %s must be finite", o[0], o[2], o[3]);
  PetscCheck(!(wset && tset), dem->comm, PETSC_ERR_ARG_INCOMP, "%s and %s both set the rotation: give one of them", o[1], o[4]);
  PetscCheck(!(pset || aset) || wset || tset, dem->comm, PETSC_ERR_ARG_WRONG, "%s given without %s or %s", pset ? o[2] : o[3], o[1], o[4]);
  const double ul = sqrt(dem_dot(m->ax_u, m->ax_u));
  PetscCheck(ul > 0, dem->comm, PETSC_ERR_ARG_OUTOFRANGE, "%s %g,%g,%g must be non-zero", o[3], (double)m->ax_u[0], (double)m->ax_u[1], (double)m->ax_u[2]);
  for (int j = 0; j < 3; j++) m->ax_u[j] /= ul;
  if (tset) {
    PetscCheck(nt >= 2 && nt % 2 == 0, dem->comm, PETSC_ERR_ARG_SIZ, "%s has %" PetscInt_FMT " values: it takes pairs t,w (at most %d)", o[4], nt, DEM_MESH_TAB_MAX);
    for (PetscInt j = 0; j < nt; j++) PetscCheck(!PetscIsInfOrNanReal(tab[j]), dem->comm, PETSC_ERR_ARG_OUTOFRANGE, "%s: value %" PetscInt_FMT " (%g) must be finite", o[4], j + 1, (double)tab[j]);
    for (PetscInt j = 2; j < nt; j += 2) PetscCheck(tab[j] > tab[j - 2], dem->comm, PETSC_ERR_ARG_OUTOFRANGE, "%s: time %g must exceed the previous one %g (s)", o[4], (double)tab[j], (double)tab[j - 2]);
    m->ntab = nt / 2;
    PetscCall(PetscMalloc1(nt, &m->tab));
    PetscCall(PetscArraycpy(m->tab, tab, nt));
  }
  m->moving = (PetscBool)(m->omega != 0 || m->tab || m->vel[0] != 0 || m->vel[1] != 0 || m->vel[2] != 0);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Whether mesh k bounds the gas of a coupled run (vessel.c): -1 when not given (the default: inside
 * for a mesh at rest, none for a moving one). */
static PetscErrorCode DemMeshFluid(PetscOptionItems *PetscOptionsObject, Dem dem, int k, DemMesh *m)
{
  static const char *const names[] = {"none", "inside", "outside"};
  char                     o[48];
  PetscInt                 v;
  PetscBool                set;

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(o, sizeof o, DemMeshWordOptions[1], k));
  PetscCall(SableOptionsEnum(o, "Whether this mesh bounds the gas of a coupled run: inside (the gas inside a closed mesh, a vessel; default for a mesh at rest), outside (an immersed obstacle) or none (the particles only; default for a moving mesh)", names, 3, DEM_MESH_FLUID_INSIDE, &v, &set));
  PetscCheck(!set || !m->moving || v == DEM_MESH_FLUID_NONE, dem->comm, PETSC_ERR_SUP, "%s %s: the mesh moves, and the gas sees still walls only: give %s none (it then bounds the particles only)", o, names[v], o);
  m->fluid = set ? (int)v : -1;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The placement of mesh k: scale, rotation (deg), translation (m). */
static PetscErrorCode DemMeshPlacement(PetscOptionItems *PetscOptionsObject, Dem dem, int k, PetscReal *scale, PetscReal rot[3], PetscReal shift[3])
{
  char o[3][48];

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(o[0], sizeof o[0], "-dem_mesh_%d_scale", k));
  PetscCall(PetscSNPrintf(o[1], sizeof o[1], "-dem_mesh_%d_rotate", k));
  PetscCall(PetscSNPrintf(o[2], sizeof o[2], "-dem_mesh_%d_translate", k));
  PetscCall(SableOptionsReal(o[0], "Scale factor of the mesh's coordinates (about the origin, before rotation and translation)", NULL, "(0,inf)", 1, scale, NULL));
  PetscCall(SableOptionsRealN(o[1], "Rotation of the mesh: degrees about x, then y, then z (fixed axes), after the scale", "deg", rot, 3, 3, NULL));
  PetscCall(SableOptionsRealN(o[2], "Translation of the mesh, after the rotation", "m", shift, 3, 3, NULL));
  for (int j = 0; j < 3; j++) PetscCheck(!PetscIsInfOrNanReal(rot[j]) && !PetscIsInfOrNanReal(shift[j]), dem->comm, PETSC_ERR_ARG_OUTOFRANGE, "%s and %s must be finite", o[1], o[2]);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Reads and places mesh k (its file option is set), and announces it. */
static PetscErrorCode DemMeshLoad(PetscOptionItems *PetscOptionsObject, Dem dem, int k, DemMesh *m)
{
  PetscReal scale = 1, rot[3] = {0, 0, 0}, shift[3] = {0, 0, 0}, lo[3], hi[3];

  PetscFunctionBeginUser;
  PetscCall(DemMeshPlacement(PetscOptionsObject, dem, k, &scale, rot, shift));
  {
    PetscBool ok = PETSC_FALSE;
    PetscCall(PetscTestFile(m->file, 'r', &ok));
    PetscCheck(ok, dem->comm, PETSC_ERR_FILE_OPEN, "-dem_mesh_%d_file %s: no such readable file", k, m->file);
  }
  PetscCall(TriMeshReadSTL(dem->comm, m->file, &m->ref));
  PetscCheck(m->ref.ntri > 0, dem->comm, PETSC_ERR_FILE_UNEXPECTED, "-dem_mesh_%d_file %s: no triangle left to touch", k, m->file);
  PetscCall(TriMeshTransform(&m->ref, scale, rot, shift));
  for (int j = 0; j < 3; j++) lo[j] = PETSC_MAX_REAL, hi[j] = -PETSC_MAX_REAL;
  for (PetscInt v = 0; v < 3 * m->ref.ntri; v++)
    for (int j = 0; j < 3; j++) lo[j] = PetscMin(lo[j], m->ref.v[3 * v + j]), hi[j] = PetscMax(hi[j], m->ref.v[3 * v + j]);
  PetscCall(PetscPrintf(dem->comm, "mesh %s: %s, %" PetscInt_FMT " triangles, box %g,%g,%g .. %g,%g,%g m%s\n", m->name, m->file, m->ref.ntri, lo[0], lo[1], lo[2], hi[0], hi[1], hi[2], m->moving ? ", moving" : ""));
  if (m->ref.ndegen || m->ref.nduplicate) PetscCall(PetscPrintf(dem->comm, "warning: mesh %s: %s: skipped %" PetscInt_FMT " zero-area and %" PetscInt_FMT " duplicate triangles\n", m->name, m->file, m->ref.ndegen, m->ref.nduplicate));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* -help lists every mesh's options, given or not, and reads no mesh file (a mesh not given is
 * read into a scratch copy). */
PetscErrorCode DemMeshesSetFromOptions(PetscOptionItems *PetscOptionsObject, Dem dem)
{
  PetscBool help;

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsHasHelp(NULL, &help));
  for (int k = 0; k < DEM_MAX_MESHES; k++) {
    DemMesh  *m = &dem->meshes.m[dem->meshes.n];
    char      opt[48];
    PetscBool set;
    PetscCall(PetscSNPrintf(opt, sizeof opt, DemMeshWordOptions[0], k));
    PetscCall(PetscMemzero(m, sizeof *m));
    PetscCall(SableOptionsString(opt, "Triangle-mesh wall: an STL file (ASCII or binary)", m->file, sizeof m->file, &set));
    PetscCall(PetscSNPrintf(m->name, sizeof m->name, "-dem_mesh_%d", k));
    if (help && (!set || !m->file[0])) {
      DemMesh   scratch;
      PetscReal scale = 1, rot[3] = {0, 0, 0}, shift[3] = {0, 0, 0};
      PetscCall(PetscMemzero(&scratch, sizeof scratch));
      PetscCall(DemMeshMaterial(PetscOptionsObject, dem, k, &scratch));
      PetscCall(DemMeshMotion(PetscOptionsObject, dem, k, &scratch));
      PetscCall(DemMeshFluid(PetscOptionsObject, dem, k, &scratch));
      PetscCall(DemMeshPlacement(PetscOptionsObject, dem, k, &scale, rot, shift));
      PetscCall(PetscFree(scratch.tab));
      continue;
    }
    if (!set) { /* its other options would be ignored */
      const char *sub[] = {"scale", "rotate", "translate", "friction", "restitution", "kn", "youngs_modulus", "rolling_friction", "velocity", "omega", "axis_point", "axis", "omega_table", "fluid"};
      for (size_t j = 0; j < sizeof sub / sizeof sub[0]; j++) {
        PetscBool has;
        PetscCall(PetscSNPrintf(opt, sizeof opt, "-dem_mesh_%d_%s", k, sub[j]));
        PetscCall(PetscOptionsHasName(NULL, NULL, opt, &has));
        PetscCheck(!has, dem->comm, PETSC_ERR_ARG_WRONG, "%s given without -dem_mesh_%d_file", opt, k);
      }
      continue;
    }
    PetscCheck(m->file[0], dem->comm, PETSC_ERR_ARG_WRONG, "-dem_mesh_%d_file needs a file name", k);
    PetscCall(DemMeshMaterial(PetscOptionsObject, dem, k, m));
    PetscCall(DemMeshMotion(PetscOptionsObject, dem, k, m));
    PetscCall(DemMeshFluid(PetscOptionsObject, dem, k, m));
    if (help) { /* its options listed, its file not read */
      PetscReal scale = 1, rot[3] = {0, 0, 0}, shift[3] = {0, 0, 0};
      PetscCall(DemMeshPlacement(PetscOptionsObject, dem, k, &scale, rot, shift));
      PetscCall(PetscFree(m->tab));
      continue;
    }
    PetscCall(DemMeshLoad(PetscOptionsObject, dem, k, m));
    dem->meshes.n++;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. The meshes' pair parameters (after DemMaterialsSetUp), the travel bound of the
 * rotating ones, and their pose at the current time. */
PetscErrorCode DemMeshesSetUp(Dem dem)
{
  PetscFunctionBeginUser;
  for (PetscInt k = 0; k < dem->meshes.n; k++) {
    DemMesh *m = &dem->meshes.m[k];
    PetscCheck(dem->contact.law != DEM_LAW_HERTZ || m->mat.E_set, dem->comm, PETSC_ERR_ARG_WRONG, "-dem_contact_law hertz needs the Young's modulus of mesh %s (-dem_wall_youngs_modulus or %s_youngs_modulus)", m->name, m->name);
    PetscReal tc[DEM_MAX_SHAPES];
    PetscCall(DemWallPairsFill(dem, &m->mat, m->pw, tc));
    for (PetscInt s = 0; s < dem->shapes.nshape; s++)
      PetscCheck(dem->clock.dt <= dem->clock.dt_frac * tc[s], dem->comm, PETSC_ERR_ARG_OUTOFRANGE, "-dem_dt %g s exceeds -dem_dt_max_fraction %g x the contact time %g s with mesh %s (radius %g m): use -dem_dt <= %g or a softer %s material", (double)dem->clock.dt, (double)dem->clock.dt_frac, (double)tc[s], m->name, (double)dem->shapes.shp[s].r, (double)(dem->clock.dt_frac * tc[s]), m->name);
    if (m->mat.mu > 0 || m->mat.mur > 0) dem->contact.rotation = PETSC_TRUE;
    m->raxis = 0;
    for (PetscInt v = 0; v < 3 * m->ref.ntri; v++) {
      const double *x = m->ref.v + 3 * v, d[3] = {x[0] - m->ax_p[0], x[1] - m->ax_p[1], x[2] - m->ax_p[2]}, a = dem_dot(d, m->ax_u);
      m->raxis = PetscMax(m->raxis, sqrt(PetscMax(dem_dot(d, d) - a * a, 0.0)));
    }
    if (!m->moving) m->cur = m->ref.v;
    else PetscCall(PetscMalloc1(9 * (size_t)m->ref.ntri, &m->cur));
  }
  PetscCall(DemMeshesMove(dem, dem->clock.t, NULL));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemMeshesDestroy(Dem dem)
{
  PetscFunctionBeginUser;
  for (PetscInt k = 0; k < dem->meshes.n; k++) {
    DemMesh *m = &dem->meshes.m[k];
    if (m->cur != m->ref.v) PetscCall(PetscFree(m->cur));
    PetscCall(DemVesselMeshDestroy(m));
    PetscCall(TriMeshDestroy(&m->ref));
    PetscCall(PetscFree(m->tab));
    PetscCall(PetscFree(m->loc));
    PetscCall(PetscFree(m->cstart));
    PetscCall(PetscFree(m->ctri));
    PetscCall(PetscFree(m->slot));
  }
  dem->meshes.n = 0;
  PetscFunctionReturn(PETSC_SUCCESS);
}
