/* Placement check at start-up. The particles insertion put into the scene (the lattice,
 * -dem_lattice*, and the init file, -dem_init_file; insert.c) must start clear of the walls and
 * of each other: otherwise the first steps blast them apart and the run stops later on a
 * diverging overlap with advice about the time step (diag.c), which is not the cause.
 * Overlap delta over the radius (of the smaller particle of a pair; convex shapes: the narrow
 * phase's depth over d_eq/2, as in the statistics). A particle wholly behind a plane, or outside
 * a cylinder, overlaps it by 2 radii or more. A mesh's triangles (two-sided) are walls too: a
 * particle that meets one overlaps it (a particle wholly outside a mesh vessel is not seen). Limits:
 *   a lattice particle with a wall, another lattice particle or a file particle: any overlap
 *   above round-off (DEM_PLACE_ROUNDOFF). A lattice is built apart (spacing >= the largest
 *   diameter, jitter within the gap), so an overlap means that its block crosses a wall, wraps
 *   a periodic axis or lies on the file's particles;
 *   a file particle with a wall or another file particle: above -dem_init_file_overlap_max,
 *   by default twice the deepest overlap the contact design reaches at -dem_impact_velocity
 *   (the figure DemView prints), and at least 0.05 radii. A frame of a bed holds contacts, and
 *   the stiffness sets their overlap: measured (the largest of any frame) 3.2e-4 radii in the
 *   settled frames of cases/settle/quick.opts and 1.2e-3 while it settles (design 0.007, limit
 *   0.05); 0.015 in the bubbling bed of cases/fluidized_bed/small.opts to t = 100 (design 0.065,
 *   limit 0.13) and 0.0039 in bed.opts to t = 120 (design 0.071, limit 0.14). Deeper is no
 *   contact a run reaches; a run counts as diverged from 0.5 (-dem_overlap_max).
 * When: right after the first list build (DemSetUp), so that pairs across ranks and periodic
 * sides are seen: every overlapping pair is in the list, in the local particle's row (a
 * local-ghost pair on both ranks). Cost: one pass over the list, one over the particles per wall.
 * Origin by id (insert.c): the lattice's ids are [file_end, file_end + lat_count) (it follows the file's), the file's
 * below file_end; particles a program added itself (DemAddParticle) are not checked.
 * All ranks agree on the worst finding (by kind in the order above, then depth, then id) and
 * stop with one message from the rank that found it: what overlaps what, where, by how much,
 * which option placed it, what to change. */
#include "dem/dem_core.h"
#include "dem/dem_walls.h"
#include "dem/dem_sources.h"

#define DEM_PLACE_ROUNDOFF 1e-9 /* radii: a lattice on a wall or touching lattice sites */
#define DEM_PLACE_FILE_MIN 0.05 /* radii: the least default limit of a file's overlaps */
#define DEM_PLACE_MSG      1024

typedef enum {
  PLACE_OTHER,
  PLACE_LATTICE,
  PLACE_FILE
} DemPlaceOrigin;
typedef enum {
  FIND_LATTICE_WALL,
  FIND_LATTICE_LATTICE,
  FIND_LATTICE_FILE,
  FIND_FILE_WALL,
  FIND_FILE_FILE,
  FIND_NONE
} DemPlaceKind;

typedef struct {
  double   key[3]; /* kind, depth (radii), smallest id: what the ranks compare */
  PetscInt i, j;   /* the local particle and its partner (local or ghost; -1: a wall) */
  PetscInt wall;
} DemPlaceFind;

static DemPlaceOrigin dem_origin(const Dem dem, PetscInt id)
{
  if (dem->insert.lat_count > 0 && id >= dem->insert.file_end && id < dem->insert.file_end + dem->insert.lat_count) return PLACE_LATTICE;
  return id < dem->insert.file_end ? PLACE_FILE : PLACE_OTHER;
}

/* Whether key a is a worse finding than key b: a lower kind, then deeper, then a smaller id. */
static PetscBool dem_place_worse(const double *a, const double *b)
{
  if (a[0] != b[0]) return (PetscBool)(a[0] < b[0]);
  if (a[1] != b[1]) return (PetscBool)(a[1] > b[1]);
  return (PetscBool)(a[2] < b[2]);
}

static void dem_place_consider(const Dem dem, DemPlaceKind kind, double depth, PetscInt i, PetscInt j, PetscInt wall, DemPlaceFind *best)
{
  const double key[3] = {(double)kind, depth, (double)(j < 0 ? dem->p.id[i] : PetscMin(dem->p.id[i], dem->p.id[j]))};
  if (!dem_place_worse(key, best->key)) return;
  for (int k = 0; k < 3; k++) best->key[k] = key[k];
  best->i    = i;
  best->j    = j;
  best->wall = wall;
}

/* The limit of a file particle's overlaps (radii): -dem_init_file_overlap_max, or twice the
 * deepest contact the design reaches at -dem_impact_velocity (DemView), at least
 * DEM_PLACE_FILE_MIN. */
static double DemPlaceFileLimit(Dem dem)
{
  double ov = 0;

  if (dem->insert.init_overlap_max > 0) return dem->insert.init_overlap_max;
  for (PetscInt s = 0; s < dem->shapes.nshape; s++)
    for (PetscInt t = -1; t < dem->shapes.nshape; t++) {
      const DemPairParams *p = t < 0 ? &dem->contact.pw[s] : &dem->contact.pp[s * dem->shapes.nshape + t];
      const DemShape      *a = &dem->shapes.shp[s], *b = &dem->shapes.shp[t < 0 ? s : t];
      ov = PetscMax(ov, DemImpactOverlap(dem, p) / (dem->shapes.convex ? PetscMin(a->req, b->req) : PetscMin(a->r, b->r)));
    }
  return PetscMax(DEM_PLACE_FILE_MIN, 2 * ov);
}

/* Overlap of local particle i with wall wi, in radii (0: clear); wi >= nwall: mesh wi - nwall. */
static PetscErrorCode DemPlaceWallDepth(Dem dem, PetscInt wi, PetscInt i, double *depth)
{
  const DemShape *s = &dem->shapes.shp[dem->p.shape[i]];
  const double   *x = dem->p.x + 3 * i, r = DemRadius(&dem->p, &dem->shapes, i);
  const DemWall  *w = &dem->walls.wall[wi];

  PetscFunctionBeginUser;
  *depth = 0;
  if (wi >= dem->walls.nwall) {
    PetscCall(DemMeshDepth(dem, wi - dem->walls.nwall, i, depth)); /* walls_mesh.c */
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  if (dem->shapes.convex) {
    const ConvexPose pose = DemPose(x, dem->p.q + 4 * i);
    ConvexContact    c;
    PetscCall(ConvexCollidePlane(s->cvx, &pose, w->s.p, w->s.n, &c));
    if (c.overlap && DemWallCovers(w, c.point, x)) *depth = c.depth / s->req;
  } else {
    double nrm[3];
    *depth = PetscMax(0.0, dem_wall_sphere(w, x, r, nrm)) / r;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Overlap of the pair (i, j) in radii of the smaller (0: clear). */
static PetscErrorCode DemPlacePairDepth(Dem dem, PetscInt i, PetscInt j, double *depth)
{
  const DemShape *si = &dem->shapes.shp[dem->p.shape[i]], *sj = &dem->shapes.shp[dem->p.shape[j]];

  PetscFunctionBeginUser;
  *depth = 0;
  if (dem->shapes.convex) {
    ConvexContact c;
    PetscCall(DemConvexPairContact(dem, i, j, &c));
    if (c.overlap) *depth = c.depth / PetscMin(si->req, sj->req);
  } else {
    const double d[3] = {dem->p.x[3 * j] - dem->p.x[3 * i], dem->p.x[3 * j + 1] - dem->p.x[3 * i + 1], dem->p.x[3 * j + 2] - dem->p.x[3 * i + 2]};
    const double ri = DemRadius(&dem->p, &dem->shapes, i), rj = DemRadius(&dem->p, &dem->shapes, j);
    *depth = PetscMax(0.0, ri + rj - sqrt(dem_dot(d, d))) / PetscMin(ri, rj);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode DemPlaceScan(Dem dem, double limit, DemPlaceFind *best)
{
  const DemNeigh *nl = &dem->nl;

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < dem->p.n; i++) {
    const DemPlaceOrigin oi = dem_origin(dem, dem->p.id[i]);
    if (oi == PLACE_OTHER) continue;
    for (PetscInt w = 0; w < dem->walls.nwall + dem->meshes.n; w++) { /* the walls, then the meshes */
      double depth;
      PetscCall(DemPlaceWallDepth(dem, w, i, &depth));
      if (depth > (oi == PLACE_LATTICE ? DEM_PLACE_ROUNDOFF : limit)) dem_place_consider(dem, oi == PLACE_LATTICE ? FIND_LATTICE_WALL : FIND_FILE_WALL, depth, i, -1, w, best);
    }
    for (PetscInt a = nl->start[i]; a < nl->start[i + 1]; a++) {
      const PetscInt       j  = nl->nbr[a];
      const DemPlaceOrigin oj = dem_origin(dem, dem->p.id[j]);
      DemPlaceKind         kind;
      double               depth;
      if (oj == PLACE_OTHER || dem->p.id[j] == dem->p.id[i]) continue; /* a periodic image of itself */
      if (oi == PLACE_LATTICE) kind = oj == PLACE_LATTICE ? FIND_LATTICE_LATTICE : FIND_LATTICE_FILE;
      else kind = oj == PLACE_LATTICE ? FIND_LATTICE_FILE : FIND_FILE_FILE;
      PetscCall(DemPlacePairDepth(dem, i, j, &depth));
      if (depth > (kind == FIND_FILE_FILE ? limit : DEM_PLACE_ROUNDOFF)) dem_place_consider(dem, kind, depth, i, j, -1, best);
    }
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The wall wi (a mesh from nwall on) by its option, and where it is when that is short to say. */
static PetscErrorCode DemPlaceWallText(Dem dem, PetscInt wi, char *buf, size_t len)
{
  const DemWall *w = &dem->walls.wall[wi];

  PetscFunctionBeginUser;
  if (wi >= dem->walls.nwall) {
    PetscCall(PetscSNPrintf(buf, len, "a triangle of mesh %s", dem->meshes.m[wi - dem->walls.nwall].name));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(PetscSNPrintf(buf, len, "%s", w->name));
  if (w->s.kind == SURFACE_CYLINDER) PetscCall(PetscSNPrintf(buf, len, "%s (radius %.6g)", w->name, w->s.R));
  else if (w->s.kind == SURFACE_PLANE)
    for (int k = 0; k < 3; k++)
      if (PetscAbsReal(w->s.n[k]) > 1 - 1e-12) PetscCall(PetscSNPrintf(buf, len, "%s (%c = %.6g)", w->name, "xyz"[k], w -> s.p[k]));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The lattice's options as given, and the extent of the filled block (m) along each axis. */
static PetscErrorCode DemPlaceLatticeText(Dem dem, char *buf, size_t len, double ext[3])
{
  const double   a   = DemLatticeSpacing(dem);
  const PetscInt cnt = dem->insert.lat_count, nx = dem->insert.lat[0], nxy = dem->insert.lat[0] * dem->insert.lat[1];

  PetscFunctionBeginUser;
  ext[0] = a * PetscMin(nx, cnt);
  ext[1] = a * PetscMin(dem->insert.lat[1], (cnt + nx - 1) / nx);
  ext[2] = a * ((cnt + nxy - 1) / nxy);
  PetscCall(PetscSNPrintf(buf, len, "-dem_lattice %" PetscInt_FMT ",%" PetscInt_FMT ",%" PetscInt_FMT " from -dem_lattice_origin %.6g,%.6g,%.6g%s, -dem_lattice_spacing %.6g%s", dem->insert.lat[0], dem->insert.lat[1], dem->insert.lat[2], dem->insert.lat_origin[0], dem->insert.lat_origin[1], dem->insert.lat_origin[2], dem->insert.lat_origin_set ? "" : " (default: the domain's lower corner)", a,
                          dem->insert.lat_a > 0 ? "" : " (default: 1.05 x the largest diameter)"));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* A lattice origin that puts the block in front of an axis-aligned plane, or "". */
static PetscErrorCode DemPlaceOriginHint(Dem dem, const DemWall *w, const double ext[3], char *buf, size_t len)
{
  PetscFunctionBeginUser;
  buf[0] = 0;
  if (w->s.kind != SURFACE_PLANE) PetscFunctionReturn(PETSC_SUCCESS);
  for (int k = 0; k < 3; k++) {
    double o[3] = {dem->insert.lat_origin[0], dem->insert.lat_origin[1], dem->insert.lat_origin[2]};
    if (PetscAbsReal(w->s.n[k]) <= 1 - 1e-12) continue;
    o[k] = w->s.n[k] > 0 ? w->s.p[k] : w->s.p[k] - ext[k];
    PetscCall(PetscSNPrintf(buf, len, " (e.g. -dem_lattice_origin %.6g,%.6g,%.6g puts it on the wall)", o[0], o[1], o[2]));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Where particle i is, a ghost's periodic image wrapped back into the domain. */
static void dem_place_position(const Dem dem, PetscInt i, double x[3])
{
  const Domain *dom = dem->dom;
  for (int k = 0; k < 3; k++) {
    x[k] = dem->p.x[3 * i + k];
    if (dom->periodic[k] && (x[k] < dom->lo[k] || x[k] >= dom->hi[k])) x[k] -= dom->len[k] * floor((x[k] - dom->lo[k]) / dom->len[k]);
  }
}

/* The message of the finding f (on the rank that made it). */
static PetscErrorCode DemPlaceMessage(Dem dem, const DemPlaceFind *f, double limit, char *msg)
{
  const DemPlaceKind kind  = (DemPlaceKind)f->key[0];
  const double       depth = f->key[1];
  PetscInt           i = f->i, j = f->j;
  char               lat[320], wall[96], hint[128], how[160], lim[256];
  double             ext[3];

  PetscFunctionBeginUser;
  if (dem->insert.lat_count > 0) PetscCall(DemPlaceLatticeText(dem, lat, sizeof lat, ext));
  if (kind == FIND_LATTICE_FILE && dem_origin(dem, dem->p.id[i]) != PLACE_LATTICE) { /* the lattice particle first */
    i = f->j;
    j = f->i;
  }
  if (j >= 0 && kind != FIND_LATTICE_FILE && dem->p.id[j] < dem->p.id[i]) { /* a pair of one kind: by id */
    i = f->j;
    j = f->i;
  }
  double xi[3], xj[3] = {0, 0, 0};
  dem_place_position(dem, i, xi);
  if (j >= 0) dem_place_position(dem, j, xj);
  PetscCall(PetscSNPrintf(lim, sizeof lim, "more than a contact reaches (limit %.3g radii, -dem_init_file_overlap_max%s)", limit, dem->insert.init_overlap_max > 0 ? "" : ": by default twice the contact design's overlap at -dem_impact_velocity, at least 0.05"));
  if (f->wall >= 0) {
    PetscCall(DemPlaceWallText(dem, f->wall, wall, sizeof wall));
    if (depth >= 2) PetscCall(PetscSNPrintf(how, sizeof how, "lies wholly on the wrong side of %s", wall));
    else PetscCall(PetscSNPrintf(how, sizeof how, "overlaps %s by %.3g radii", wall, depth));
  }
  switch (kind) {
  case FIND_LATTICE_WALL:
    hint[0] = 0;
    if (f->wall < dem->walls.nwall) PetscCall(DemPlaceOriginHint(dem, &dem->walls.wall[f->wall], ext, hint, sizeof hint));
    PetscCall(PetscSNPrintf(msg, DEM_PLACE_MSG, "lattice particle id %" PetscInt_FMT " at (%.6g, %.6g, %.6g) %s: the lattice (%s) crosses that wall; move -dem_lattice_origin so that the whole block, %.6g x %.6g x %.6g m from the origin, lies on the wall's granular side%s, or use fewer sites", dem->p.id[i], xi[0], xi[1], xi[2], how, lat, ext[0], ext[1], ext[2], hint));
    break;
  case FIND_LATTICE_LATTICE:
    PetscCall(PetscSNPrintf(msg, DEM_PLACE_MSG, "lattice particles id %" PetscInt_FMT " at (%.6g, %.6g, %.6g) and id %" PetscInt_FMT " at (%.6g, %.6g, %.6g) overlap by %.3g radii: the lattice (%s) is longer than the periodic domain along an axis (-domain_lo/-domain_hi), so its last layer meets the periodic image of the first; use fewer sites or a smaller spacing", dem->p.id[i], xi[0], xi[1], xi[2], dem->p.id[j], xj[0], xj[1], xj[2], depth, lat));
    break;
  case FIND_LATTICE_FILE:
    PetscCall(PetscSNPrintf(msg, DEM_PLACE_MSG, "lattice particle id %" PetscInt_FMT " at (%.6g, %.6g, %.6g) overlaps particle id %" PetscInt_FMT " at (%.6g, %.6g, %.6g) of -dem_init_file %s by %.3g radii: the lattice (%s) is inserted in addition to the file's particles; to restart from the file alone give -dem_lattice 0,0,0, or move the lattice clear of them with -dem_lattice_origin", dem->p.id[i], xi[0], xi[1], xi[2], dem->p.id[j], xj[0], xj[1], xj[2], dem->insert.init_file, depth, lat));
    break;
  case FIND_FILE_WALL:
    PetscCall(PetscSNPrintf(msg, DEM_PLACE_MSG, "-dem_init_file %s: particle id %" PetscInt_FMT " at (%.6g, %.6g, %.6g) %s, %s: the file's particles do not fit this run's walls; give the walls of the run that wrote it", dem->insert.init_file, dem->p.id[i], xi[0], xi[1], xi[2], how, lim));
    break;
  default:
    PetscCall(PetscSNPrintf(msg, DEM_PLACE_MSG, "-dem_init_file %s: particles id %" PetscInt_FMT " at (%.6g, %.6g, %.6g) and id %" PetscInt_FMT " at (%.6g, %.6g, %.6g) overlap by %.3g radii, %s: no run reaches that state (an edited or merged file, or a diverged run); rebuild the file, or raise -dem_init_file_overlap_max knowingly", dem->insert.init_file, dem->p.id[i], xi[0], xi[1], xi[2], dem->p.id[j], xj[0], xj[1], xj[2], depth, lim));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. Stops with one message when an inserted particle overlaps a wall or another. */
PetscErrorCode DemCheckPlacement(Dem dem)
{
  DemPlaceFind best = {{(double)FIND_NONE, 0, 0}, -1, -1, -1};
  double      *all;
  PetscMPIInt  size, rank, winner = -1;
  char         msg[DEM_PLACE_MSG];
  const double limit = DemPlaceFileLimit(dem);

  PetscFunctionBeginUser;
  if (dem->insert.lat_count <= 0 && dem->insert.file_end <= 0) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscLogEventBegin(DEM_Placement, 0, 0, 0, 0));
  PetscCall(DemPlaceScan(dem, limit, &best));
  PetscCallMPI(MPI_Comm_size(dem->comm, &size));
  PetscCallMPI(MPI_Comm_rank(dem->comm, &rank));
  PetscCall(PetscMalloc1(3 * (size_t)size, &all));
  PetscCallMPI(MPI_Allgather(best.key, 3, MPI_DOUBLE, all, 3, MPI_DOUBLE, dem->comm));
  for (PetscMPIInt r = 0; r < size; r++)
    if (all[3 * r] < FIND_NONE && (winner < 0 || dem_place_worse(all + 3 * r, all + 3 * winner))) winner = r;
  PetscCall(PetscFree(all));
  PetscCall(PetscLogEventEnd(DEM_Placement, 0, 0, 0, 0));
  if (winner < 0) PetscFunctionReturn(PETSC_SUCCESS);
  if (rank == winner) PetscCall(DemPlaceMessage(dem, &best, limit, msg));
  PetscCallMPI(MPI_Bcast(msg, DEM_PLACE_MSG, MPI_CHAR, winner, dem->comm));
  SETERRQ(dem->comm, PETSC_ERR_ARG_OUTOFRANGE, "%s", msg);
}
