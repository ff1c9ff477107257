/* The vessel: the walls that bound the gas of a coupled run, given to the fluid as one level
 * function phi(x) > 0 in the gas, < 0 in the solid (DemVesselLevel; the fluid's FAVOR fractions
 * come from it). phi is the minimum over the walls that bound the gas of their signed distance,
 * the gas side positive: the gas is the intersection of their gas sides.
 *
 * Which walls bound the gas (DemVesselSetUp, one start-up line each): a cylinder (-dem_cylinder,
 * the gas inside, R - |rho|; one turning about its own axis is geometrically still and bounds the
 * gas as a still wall) unless -dem_cylinder_fluid no; its caps with -dem_cylinder_caps_fluid yes;
 * a plane (-dem_plane_<k>, (x - p).n) with -dem_plane_<k>_fluid yes, never a moving or removable
 * one; a still closed triangle mesh (-dem_mesh_<k>_fluid inside, the default, or outside: an
 * immersed obstacle). Planes, the box and caps let the gas through by default: in a bed they are
 * the distributor (the floor sits at the first cell face over the inlet's row) and the lid.
 * Rectangles, polygons, the hopper and moving meshes bound the particles only.
 *
 * A mesh's signed distance: the distance to the nearest triangle (TriClosestPoint), exact within
 * a band of two fluid cells' largest side and clamped to +-band beyond it (the fluid needs the
 * zero set and the values near it), the sign from the nearest triangle's outward normal when the
 * nearest point is inside a face, else from a parity ray cast along a grid axis (Schneider &
 * Eberly, Geometric Tools for Computer Graphics, 13.1: inside iff a ray crosses the surface an
 * odd number of times). The mesh must be closed: after welding vertices closer than 1e-9 of its
 * extent, every edge shared by exactly two triangles (else refused, naming the count of open
 * edges). Each connected shell is oriented by one ray cast from just off one of its faces.
 * Triangles lying in a face of the domain (not a periodic one) are that face: the fluid's own
 * condition holds there (a cylinder's cap on the inlet face lets the gas in), so the distance
 * skips them; the sign's ray casts still count them.
 * Acceleration: a bin grid over the mesh's box grown by the band, bins of half the band; a bin
 * keeps the triangles that can be the nearest to one of its points within the band, sorted by
 * their distance from its centre, so a query stops at the first triangle that cannot be nearer
 * than the best so far; a bin holding none lies wholly on one side, its sign computed once.
 * Units: m. */
#include "dem/dem_walls.h"

struct _DemVesselMesh {
  const double *v;           /* the mesh's vertices at rest (9 per triangle) */
  double       *nout;        /* outward unit normal per triangle (valid when oriented) */
  double       *pn;          /* per triangle the pseudonormals of its edges AB, BC, CA and vertices A, B, C */
  PetscBool     oriented;    /* every shell consistently oriented: the face sign is usable */
  double        sgn;         /* +1: the gas inside (phi = inside distance), -1: outside */
  double        band;        /* |phi| is exact below band, band beyond it (m) */
  double        lo[3], b;    /* the bin grid: origin and bin size (m) */
  PetscInt      nb[3];       /* bins per axis */
  PetscInt     *start, *tri; /* per bin its triangles (CSR), nearest to its centre first */
  double       *dc;          /* their distances from the bin's centre (m) */
  signed char  *side;        /* a bin with no triangle: +1 inside the mesh, -1 outside */
  PetscInt      nopen, ntri; /* edges not shared by exactly two triangles; triangles */
  PetscBool    *onface;      /* triangles lying in a non-periodic domain face (NULL: none) */
  PetscInt      nface;       /* how many */
  double        tol;         /* a point this near a face triangle lies on the box's face (m) */
};

static inline double vm_dist2(const double *a, const double *b)
{
  return (a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]);
}

/* The bin of x along axis d (may lie outside 0..nb[d]-1). */
static inline PetscInt vm_bin(const struct _DemVesselMesh *vm, const double *x, int d)
{
  return (PetscInt)floor((x[d] - vm->lo[d]) / vm->b);
}

/* Crossings of the ray from x along +-axis a (dir +1 or -1) with the mesh, walked through the bins
 * of x's row; a crossing counts in the bin holding its point only, so a triangle listed in several
 * bins counts once. Returns -1 when the ray meets an edge or a vertex (ambiguous), else the count. */
static PetscInt vm_ray(const struct _DemVesselMesh *vm, const double *x, int a, int dir)
{
  const int u = (a + 1) % 3, w = (a + 2) % 3;
  PetscInt  i[3], count        = 0;
  for (int d = 0; d < 3; d++) i[d] = vm_bin(vm, x, d);
  if (i[u] < 0 || i[u] >= vm->nb[u] || i[w] < 0 || i[w] >= vm->nb[w]) return 0;
  for (PetscInt j = PetscMax(0, PetscMin(i[a], vm->nb[a] - 1)); j >= 0 && j < vm->nb[a]; j += dir) {
    PetscInt c[3];
    c[a] = j, c[u] = i[u], c[w] = i[w];
    if (dir > 0 && j < i[a]) continue;
    const PetscInt bin = c[0] + vm->nb[0] * (c[1] + vm->nb[1] * c[2]);
    for (PetscInt q = vm->start[bin]; q < vm->start[bin + 1]; q++) {
      const double *p0 = vm->v + 9 * vm->tri[q], *p1 = p0 + 3, *p2 = p0 + 6;
      /* signed areas of the projections on the (u, w) plane: barycentric weights of x's foot */
      const double e0 = (p1[u] - x[u]) * (p2[w] - x[w]) - (p2[u] - x[u]) * (p1[w] - x[w]);
      const double e1 = (p2[u] - x[u]) * (p0[w] - x[w]) - (p0[u] - x[u]) * (p2[w] - x[w]);
      const double e2 = (p0[u] - x[u]) * (p1[w] - x[w]) - (p1[u] - x[u]) * (p0[w] - x[w]);
      if (e0 + e1 + e2 == 0) continue;                                            /* the triangle contains the ray's direction: its neighbours decide */
      if ((e0 < 0 || e1 < 0 || e2 < 0) && (e0 > 0 || e1 > 0 || e2 > 0)) continue; /* the foot is outside */
      if (e0 == 0 || e1 == 0 || e2 == 0) return -1;                               /* on an edge or a vertex */
      const double h = (e0 * p0[a] + e1 * p1[a] + e2 * p2[a]) / (e0 + e1 + e2);
      if ((h - x[a]) * dir <= 0) continue;
      const double hx[3] = {a == 0 ? h : x[0], a == 1 ? h : x[1], a == 2 ? h : x[2]};
      if (vm_bin(vm, hx, a) == j) count++;
    }
  }
  return count;
}

/* The parity of the crossings of the ray x + t r (t > 0) with every triangle (Moeller & Trumbore,
 * J. Graphics Tools 2 (1997) 21); -1 when it meets an edge, a vertex or a triangle's plane. */
static PetscInt vm_ray_all(const struct _DemVesselMesh *vm, const double *x, const double *r)
{
  PetscInt count = 0;
  for (PetscInt t = 0; t < vm->ntri; t++) {
    const double *a = vm->v + 9 * t, *b = a + 3, *c = a + 6;
    const double  e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const double  pv[3] = {r[1] * e2[2] - r[2] * e2[1], r[2] * e2[0] - r[0] * e2[2], r[0] * e2[1] - r[1] * e2[0]};
    const double  det   = e1[0] * pv[0] + e1[1] * pv[1] + e1[2] * pv[2];
    if (det == 0) continue; /* parallel: the neighbours decide */
    const double tv[3] = {x[0] - a[0], x[1] - a[1], x[2] - a[2]};
    const double u     = (tv[0] * pv[0] + tv[1] * pv[1] + tv[2] * pv[2]) / det;
    const double qv[3] = {tv[1] * e1[2] - tv[2] * e1[1], tv[2] * e1[0] - tv[0] * e1[2], tv[0] * e1[1] - tv[1] * e1[0]};
    const double w     = (r[0] * qv[0] + r[1] * qv[1] + r[2] * qv[2]) / det;
    const double h     = (e2[0] * qv[0] + e2[1] * qv[1] + e2[2] * qv[2]) / det;
    if (u < 0 || w < 0 || u + w > 1 || h < 0) continue;
    if (u == 0 || w == 0 || u + w == 1 || h == 0) return -1;
    count++;
  }
  return count;
}

/* Whether x is inside the mesh by a parity ray cast: the shortest half-rows first, the next one
 * when a ray meets an edge or a vertex (a grid node on the mesh's own grid lines often does); then
 * rays in directions off every axis and plane, over all triangles. *ok false when every ray did. */
static PetscBool vm_inside_ray(const struct _DemVesselMesh *vm, const double *x, PetscBool *ok)
{
  int      order[6];
  PetscInt len[6];
  for (int a = 0; a < 3; a++) {
    const PetscInt i = PetscMax(0, PetscMin(vm_bin(vm, x, a), vm->nb[a] - 1));
    len[2 * a] = vm->nb[a] - i, len[2 * a + 1] = i + 1, order[2 * a] = 2 * a, order[2 * a + 1] = 2 * a + 1;
  }
  for (int s = 1; s < 6; s++) /* insertion sort by length */
    for (int t = s; t > 0 && len[order[t]] < len[order[t - 1]]; t--) {
      const int o = order[t];
      order[t] = order[t - 1], order[t - 1] = o;
    }
  *ok = PETSC_TRUE;
  for (int s = 0; s < 6; s++) {
    const PetscInt c = vm_ray(vm, x, order[s] / 2, order[s] % 2 ? -1 : 1);
    if (c >= 0) return (PetscBool)(c % 2);
  }
  for (int s = 0; s < 3; s++) {
    static const double dir[3][3] = {{0.5773502691896258, 0.5150380749100542, 0.6334158633590218}, {-0.3141592653589793, 0.8414709848078965, 0.4396926207859084}, {0.7071067811865476, -0.2718281828459045, -0.6527036446661393}};
    const PetscInt      c         = vm_ray_all(vm, x, dir[s]);
    if (c >= 0) return (PetscBool)(c % 2);
  }
  *ok = PETSC_FALSE;
  return PETSC_FALSE;
}

/* The signed distance of x from the mesh, positive inside, clamped to +-band. */
static double vm_inside_distance(const struct _DemVesselMesh *vm, const double *x)
{
  PetscInt i[3];
  for (int d = 0; d < 3; d++) {
    i[d] = vm_bin(vm, x, d);
    if (i[d] < 0 || i[d] >= vm->nb[d]) return -vm->band; /* beyond the grown box: outside, far */
  }
  const PetscInt bin = i[0] + vm->nb[0] * (i[1] + vm->nb[1] * i[2]);
  if (vm->start[bin] == vm->start[bin + 1]) return vm->side[bin] * vm->band;
  const double hd   = 0.5 * sqrt(3.0) * vm->b;
  double       best = vm->band * vm->band, q[3], qb[3] = {0, 0, 0};
  PetscInt     tb    = -1;
  TriFeature   fb    = TRI_FACE;
  PetscBool    onbox = PETSC_FALSE; /* x lies on a triangle in the box's face: in the gas's domain */
  for (PetscInt k = vm->start[bin]; k < vm->start[bin + 1]; k++) {
    const double lb = vm->dc[k] - hd;
    if (lb > 0 && lb * lb >= best) break;       /* no later triangle can be nearer */
    if (vm->onface && vm->onface[vm->tri[k]]) { /* the box's face: not a wall of the gas */
      const double *p = vm->v + 9 * vm->tri[k];
      if (!onbox) TriClosestPoint(p, p + 3, p + 6, x, q), onbox = (PetscBool)(vm_dist2(x, q) <= vm->tol * vm->tol);
      continue;
    }
    const double    *p  = vm->v + 9 * vm->tri[k];
    const TriFeature f  = TriClosestPoint(p, p + 3, p + 6, x, q);
    const double     d2 = vm_dist2(x, q);
    if (d2 < best) best = d2, tb = vm->tri[k], fb = f, qb[0] = q[0], qb[1] = q[1], qb[2] = q[2];
  }
  const double d = tb < 0 ? vm->band : sqrt(best);
  if (tb >= 0 && d == 0) return 0;
  if (onbox) return d;
  if (tb >= 0 && vm->oriented) { /* the nearest feature's (pseudo)normal decides */
    const double *n = fb == TRI_FACE ? vm->nout + 3 * tb : vm->pn + 18 * tb + 3 * (fb - TRI_EDGE_AB);
    const double  s = (x[0] - qb[0]) * n[0] + (x[1] - qb[1]) * n[1] + (x[2] - qb[2]) * n[2];
    if (s != 0) return s < 0 ? d : -d;
  }
  PetscBool ok, in = vm_inside_ray(vm, x, &ok);
  if (!ok && tb >= 0) { /* every ray grazed an edge: the nearest face's side, its normal as written */
    const double *n = vm->nout + 3 * tb;
    in              = (PetscBool)((x[0] - qb[0]) * n[0] + (x[1] - qb[1]) * n[1] + (x[2] - qb[2]) * n[2] < 0);
  }
  return in ? d : -d;
}

PetscReal DemVesselLevel(const PetscReal x[3], void *ctx)
{
  Dem       dem = (Dem)ctx;
  PetscReal phi = PETSC_MAX_REAL;
  for (PetscInt k = 0; k < dem->walls.nwall; k++) {
    const DemWall *w = &dem->walls.wall[k];
    if (w->gas) phi = PetscMin(phi, surface_gap(&w->s, x));
  }
  for (PetscInt k = 0; k < dem->meshes.n; k++) {
    const struct _DemVesselMesh *vm = dem->meshes.m[k].vm;
    if (vm) phi = PetscMin(phi, vm->sgn * vm_inside_distance(vm, x));
  }
  return phi;
}

/* Union-find root with path halving. */
static PetscInt vm_root(PetscInt *par, PetscInt i)
{
  while (par[i] != i) i = par[i] = par[par[i]];
  return i;
}

typedef struct {
  PetscInt a, b, t, s; /* welded vertex ids (a < b), the triangle (t < 0: the edge runs b -> a, in
                          triangle -1 - t) and the edge's place in it (0: AB, 1: BC, 2: CA) */
} VmEdge;

static int vm_edge_cmp(const void *x, const void *y)
{
  const VmEdge *e = x, *f = y;
  if (e->a != f->a) return e->a < f->a ? -1 : 1;
  if (e->b != f->b) return e->b < f->b ? -1 : 1;
  return 0;
}

typedef struct {
  long long k[3];
  PetscInt  i;
} VmKey;

static int vm_key_cmp(const void *x, const void *y)
{
  const VmKey *e = x, *f = y;
  for (int d = 0; d < 3; d++)
    if (e->k[d] != f->k[d]) return e->k[d] < f->k[d] ? -1 : 1;
  return 0;
}

/* The topology of the mesh: vertices welded within 1e-9 of its extent (id: the welded vertex of
 * each corner), its edges sorted (e, *ne), the count of edges not shared by exactly two
 * triangles, and (closed meshes) whether each shell's triangles agree in orientation; par: the
 * shell of each triangle (union-find roots). The caller frees id and e. */
static PetscErrorCode VmTopology(struct _DemVesselMesh *vm, const double lo[3], double ext, PetscInt *par, PetscBool *consistent, PetscInt **id_, VmEdge **e_, PetscInt *ne_)
{
  const PetscInt nv = 3 * vm->ntri;
  VmKey         *key;
  VmEdge        *e;
  PetscInt      *id, ne = 0;
  const double   tol = 1e-9 * ext;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(nv, &key));
  PetscCall(PetscMalloc1(nv, &id));
  PetscCall(PetscMalloc1(nv, &e));
  for (PetscInt j = 0; j < nv; j++) {
    for (int d = 0; d < 3; d++) key[j].k[d] = llround((vm->v[3 * j + d] - lo[d]) / tol);
    key[j].i = j;
  }
  qsort(key, (size_t)nv, sizeof *key, vm_key_cmp);
  for (PetscInt j = 0, w = -1; j < nv; j++) {
    if (j == 0 || vm_key_cmp(&key[j], &key[j - 1])) w++;
    id[key[j].i] = w;
  }
  for (PetscInt t = 0; t < vm->ntri; t++) {
    par[t]            = t;
    const PetscInt *c = id + 3 * t;
    if (c[0] == c[1] || c[1] == c[2] || c[2] == c[0]) continue; /* welded flat: no edges */
    for (int s = 0; s < 3; s++) {
      const PetscInt p = c[s], q = c[(s + 1) % 3];
      e[ne++] = p < q ? (VmEdge){p, q, t, s} : (VmEdge){q, p, -1 - t, s};
    }
  }
  qsort(e, (size_t)ne, sizeof *e, vm_edge_cmp);
  vm->nopen   = 0;
  *consistent = PETSC_TRUE;
  for (PetscInt j = 0; j < ne;) {
    PetscInt m = j + 1;
    while (m < ne && !vm_edge_cmp(&e[m], &e[j])) m++;
    if (m - j != 2) vm->nopen++;
    else {
      const PetscInt t0 = e[j].t < 0 ? -1 - e[j].t : e[j].t, t1 = e[j + 1].t < 0 ? -1 - e[j + 1].t : e[j + 1].t;
      if ((e[j].t < 0) == (e[j + 1].t < 0)) *consistent = PETSC_FALSE; /* both run the same way */
      par[vm_root(par, t0)] = vm_root(par, t1);
    }
    j = m;
  }
  PetscCall(PetscFree(key));
  *id_ = id, *e_ = e, *ne_ = ne;
  PetscFunctionReturn(PETSC_SUCCESS);
}

typedef struct {
  double   d;
  PetscInt t;
} VmCand;

static int vm_cand_cmp(const void *x, const void *y)
{
  const VmCand *e = x, *f = y;
  if (e->d != f->d) return e->d < f->d ? -1 : 1;
  return e->t < f->t ? -1 : e->t > f->t;
}

/* The bin grid: each bin's triangles within band + hd of its centre (hd: half its diagonal) and
 * within dmin + 2 hd of it (dmin: the nearest's distance; no farther one can be nearest to a
 * point of the bin), sorted by that distance. */
static PetscErrorCode VmBins(struct _DemVesselMesh *vm)
{
  const PetscInt nbin = vm->nb[0] * vm->nb[1] * vm->nb[2];
  const double   hd = 0.5 * sqrt(3.0) * vm->b, reach = vm->band + hd;
  PetscInt      *cnt, cap = 0, n = 0;
  VmCand        *all   = NULL;
  PetscInt      *owner = NULL;

  PetscFunctionBeginUser;
  PetscCall(PetscCalloc1(nbin + 1, &cnt));
  for (PetscInt t = 0; t < vm->ntri; t++) {
    const double *p = vm->v + 9 * t;
    PetscInt      i0[3], i1[3];
    for (int d = 0; d < 3; d++) {
      const double a = PetscMin(p[d], PetscMin(p[3 + d], p[6 + d])), z = PetscMax(p[d], PetscMax(p[3 + d], p[6 + d]));
      i0[d] = PetscMax(0, (PetscInt)floor((a - reach - vm->lo[d]) / vm->b));
      i1[d] = PetscMin(vm->nb[d] - 1, (PetscInt)floor((z + reach - vm->lo[d]) / vm->b));
    }
    for (PetscInt k = i0[2]; k <= i1[2]; k++)
      for (PetscInt j = i0[1]; j <= i1[1]; j++)
        for (PetscInt i = i0[0]; i <= i1[0]; i++) {
          const double c[3] = {vm->lo[0] + (i + 0.5) * vm->b, vm->lo[1] + (j + 0.5) * vm->b, vm->lo[2] + (k + 0.5) * vm->b};
          double       q[3];
          TriClosestPoint(p, p + 3, p + 6, c, q);
          const double d = sqrt(vm_dist2(c, q));
          if (d > reach) continue;
          if (n == cap) {
            cap = PetscMax(2 * cap, 1024);
            PetscCall(PetscRealloc(sizeof *all * (size_t)cap, &all));
            PetscCall(PetscRealloc(sizeof *owner * (size_t)cap, &owner));
          }
          all[n] = (VmCand){d, t}, owner[n++] = i + vm->nb[0] * (j + vm->nb[1] * k);
        }
  }
  for (PetscInt q = 0; q < n; q++) cnt[owner[q] + 1]++;
  for (PetscInt b = 0; b < nbin; b++) cnt[b + 1] += cnt[b];
  {
    VmCand  *srt;
    PetscInt m = 0, *pos;
    PetscCall(PetscMalloc2(n, &srt, nbin, &pos));
    for (PetscInt b = 0; b < nbin; b++) pos[b] = cnt[b];
    for (PetscInt q = 0; q < n; q++) srt[pos[owner[q]]++] = all[q];
    PetscCall(PetscMalloc1(nbin + 1, &vm->start));
    PetscCall(PetscMalloc2(n, &vm->tri, n, &vm->dc));
    vm->start[0] = 0;
    for (PetscInt b = 0; b < nbin; b++) { /* kept: those that can be nearest to a point of the bin */
      qsort(srt + cnt[b], (size_t)(cnt[b + 1] - cnt[b]), sizeof *srt, vm_cand_cmp);
      for (PetscInt q = cnt[b]; q < cnt[b + 1] && srt[q].d <= srt[cnt[b]].d + 2 * hd; q++) vm->tri[m] = srt[q].t, vm->dc[m++] = srt[q].d;
      vm->start[b + 1] = m;
    }
    PetscCall(PetscFree2(srt, pos));
  }
  PetscCall(PetscFree(cnt));
  PetscCall(PetscFree(all));
  PetscCall(PetscFree(owner));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The angle-weighted pseudonormals of the edges (the sum of the two faces' normals) and vertices
 * (the faces' normals weighted by their angles there) of a closed, outward-oriented mesh: the sign
 * of (x - q).n with n the pseudonormal of the feature holding x's nearest point q is the side of x
 * (Baerentzen & Aanaes, IEEE TVCG 11 (2005) 243, doi:10.1109/TVCG.2005.49). */
static PetscErrorCode VmPseudonormals(struct _DemVesselMesh *vm, const PetscInt *id, const VmEdge *e, PetscInt ne)
{
  PetscInt nid = 0;
  double  *vs;

  PetscFunctionBeginUser;
  for (PetscInt j = 0; j < 3 * vm->ntri; j++) nid = PetscMax(nid, id[j] + 1);
  PetscCall(PetscCalloc1(3 * nid, &vs));
  PetscCall(PetscCalloc1(18 * vm->ntri, &vm->pn));
  for (PetscInt t = 0; t < vm->ntri; t++)
    for (int j = 0; j < 3; j++) {
      const double *p = vm->v + 9 * t, *a = p + 3 * j, *b = p + 3 * ((j + 1) % 3), *c = p + 3 * ((j + 2) % 3);
      const double  u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
      const double  cs  = (u[0] * w[0] + u[1] * w[1] + u[2] * w[2]) / sqrt(vm_dist2(b, a) * vm_dist2(c, a));
      const double  ang = acos(PetscMax(-1.0, PetscMin(1.0, cs)));
      for (int d = 0; d < 3; d++) vs[3 * id[3 * t + j] + d] += ang * vm->nout[3 * t + d];
    }
  for (PetscInt t = 0; t < vm->ntri; t++)
    for (int j = 0; j < 3; j++)
      for (int d = 0; d < 3; d++) vm->pn[18 * t + 9 + 3 * j + d] = vs[3 * id[3 * t + j] + d];
  for (PetscInt j = 0; j + 1 < ne; j++) { /* closed: the edges come in pairs */
    if (vm_edge_cmp(&e[j], &e[j + 1])) continue;
    const PetscInt t0 = e[j].t < 0 ? -1 - e[j].t : e[j].t, t1 = e[j + 1].t < 0 ? -1 - e[j + 1].t : e[j + 1].t;
    for (int d = 0; d < 3; d++) vm->pn[18 * t0 + 3 * e[j].s + d] = vm->pn[18 * t1 + 3 * e[j + 1].s + d] = vm->nout[3 * t0 + d] + vm->nout[3 * t1 + d];
    j++;
  }
  PetscCall(PetscFree(vs));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Builds the vessel's view of mesh m (at rest): topology, orientation, bins, the far bins' sides. */
/* The triangles of the mesh lying in a face of the domain (its three vertices within 1e-9 of the
 * domain's extent of the face's plane), but on periodic axes (there the mesh is a wall). */
static PetscErrorCode VmFaceTriangles(struct _DemVesselMesh *vm, const Domain *dom)
{
  const double tol = 1e-9 * PetscMax(dom->len[0], PetscMax(dom->len[1], dom->len[2]));

  PetscFunctionBeginUser;
  vm->tol = tol;
  for (PetscInt t = 0; t < vm->ntri; t++) {
    const double *p  = vm->v + 9 * t;
    PetscBool     on = PETSC_FALSE;
    for (int d = 0; d < 3 && !on; d++)
      for (int side = 0; side < 2 && !on && !dom->periodic[d]; side++) {
        const double z = side ? dom->hi[d] : dom->lo[d];
        on             = (PetscBool)(PetscAbsReal(p[d] - z) <= tol && PetscAbsReal(p[3 + d] - z) <= tol && PetscAbsReal(p[6 + d] - z) <= tol);
      }
    if (!on) continue;
    if (!vm->onface) PetscCall(PetscCalloc1(vm->ntri, &vm->onface));
    vm->onface[t] = PETSC_TRUE;
    vm->nface++;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode VmCreate(const DemMesh *m, const Domain *dom, double band, struct _DemVesselMesh **out)
{
  struct _DemVesselMesh *vm;
  double                 lo[3], hi[3], ext = 0;
  PetscInt              *par;
  PetscBool              consistent = PETSC_FALSE;
  PetscInt              *id = NULL, ne = 0;
  VmEdge                *e = NULL;

  PetscFunctionBeginUser;
  PetscCall(PetscNew(&vm));
  vm->v = m->ref.v, vm->ntri = m->ref.ntri, vm->band = band, vm->b = 0.5 * band, vm->sgn = 1;
  for (int d = 0; d < 3; d++) lo[d] = PETSC_MAX_REAL, hi[d] = -PETSC_MAX_REAL;
  for (PetscInt j = 0; j < 3 * vm->ntri; j++)
    for (int d = 0; d < 3; d++) lo[d] = PetscMin(lo[d], vm->v[3 * j + d]), hi[d] = PetscMax(hi[d], vm->v[3 * j + d]);
  for (int d = 0; d < 3; d++) ext = PetscMax(ext, hi[d] - lo[d]);
  PetscCall(PetscMalloc1(vm->ntri, &par));
  PetscCall(PetscMalloc1(3 * vm->ntri, &vm->nout));
  PetscCall(VmFaceTriangles(vm, dom));
  PetscCall(VmTopology(vm, lo, ext, par, &consistent, &id, &e, &ne));
  /* bins of half the band over the box grown by band + one bin, at most 128 a side */
  for (int d = 0; d < 3; d++) vm->b = PetscMax(vm->b, (hi[d] - lo[d] + 2 * band) / 126);
  for (int d = 0; d < 3; d++) {
    vm->lo[d] = lo[d] - band - vm->b;
    vm->nb[d] = (PetscInt)ceil((hi[d] + band + vm->b - vm->lo[d]) / vm->b);
  }
  PetscCall(VmBins(vm));
  PetscCall(PetscArraycpy(vm->nout, m->ref.n, 3 * vm->ntri));
  vm->oriented = (PetscBool)(consistent && vm->nopen == 0);
  if (vm->oriented) { /* each shell's normals outward: a ray from just off one face decides */
    PetscInt *flip;
    PetscCall(PetscMalloc1(vm->ntri, &flip));
    for (PetscInt t = 0; t < vm->ntri; t++) flip[t] = -1;
    for (PetscInt t = 0; t < vm->ntri && vm->oriented; t++) {
      const PetscInt r = vm_root(par, t);
      if (flip[r] >= 0) continue;
      const double *p = vm->v + 9 * t, *n = vm->nout + 3 * t;
      double        x[3], l2              = 0;
      for (int d = 0; d < 3; d++) l2 = PetscMax(l2, vm_dist2(p + 3 * d, p + 3 * ((d + 1) % 3)));
      for (int d = 0; d < 3; d++) x[d] = (p[d] + p[3 + d] + p[6 + d]) / 3 + 1e-6 * sqrt(l2) * n[d];
      PetscBool ok, in = vm_inside_ray(vm, x, &ok);
      if (!ok) vm->oriented = PETSC_FALSE; /* every ray grazed: signs by rays only */
      flip[r] = in;
    }
    for (PetscInt t = 0; t < vm->ntri && vm->oriented; t++)
      if (flip[vm_root(par, t)])
        for (int d = 0; d < 3; d++) vm->nout[3 * t + d] = -vm->nout[3 * t + d];
    PetscCall(PetscFree(flip));
  }
  if (vm->oriented) PetscCall(VmPseudonormals(vm, id, e, ne));
  PetscCall(PetscFree(id));
  PetscCall(PetscFree(e));
  { /* the side of each bin holding no triangle: a ray from its centre */
    const PetscInt nbin = vm->nb[0] * vm->nb[1] * vm->nb[2];
    PetscCall(PetscMalloc1(nbin, &vm->side));
    for (PetscInt b = 0; b < nbin; b++) {
      const PetscInt i = b % vm->nb[0], j = (b / vm->nb[0]) % vm->nb[1], k = b / (vm->nb[0] * vm->nb[1]);
      vm->side[b] = 0;
      if (vm->start[b] < vm->start[b + 1] || vm->nopen) continue;
      const double c[3] = {vm->lo[0] + (i + 0.5) * vm->b, vm->lo[1] + (j + 0.5) * vm->b, vm->lo[2] + (k + 0.5) * vm->b};
      PetscBool    ok;
      vm->side[b] = vm_inside_ray(vm, c, &ok) ? 1 : -1;
    }
  }
  PetscCall(PetscFree(par));
  *out = vm;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemVesselMeshDestroy(DemMesh *m)
{
  PetscFunctionBeginUser;
  if (!m->vm) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscFree(m->vm->start));
  PetscCall(PetscFree2(m->vm->tri, m->vm->dc));
  PetscCall(PetscFree(m->vm->side));
  PetscCall(PetscFree(m->vm->nout));
  PetscCall(PetscFree(m->vm->pn));
  PetscCall(PetscFree(m->vm->onface));
  PetscCall(PetscFree(m->vm));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The start-up line of wall w, and whether it bounds the gas (refusing a moving one asked to). */
static PetscErrorCode DemVesselWall(Dem dem, DemWall *w)
{
  const PetscBool moving = (PetscBool)(w->s.v[0] != 0 || w->s.v[1] != 0 || w->s.v[2] != 0 || w->t_remove < PETSC_MAX_REAL);
  const char     *what   = "";
  char            opt[64];

  PetscFunctionBeginUser;
  w->gas = PETSC_FALSE;
  if (w->s.kind == SURFACE_CYLINDER || !strncmp(w->name, "-dem_cylinder_caps", 18)) {
    const PetscBool cap = (PetscBool)(w->s.kind != SURFACE_CYLINDER);
    w->gas              = (PetscBool)(w->fluid == 1);
    if (!w->gas) what = cap ? " (-dem_cylinder_caps_fluid no: they let the gas through)" : " (-dem_cylinder_fluid no)";
    else if (w->s.omega != 0) what = cap ? " (they turn about the cylinder's axis: the gas sees them still)" : " (it turns about its own axis: the gas sees it still)";
  } else if (w->s.kind == SURFACE_PLANE) {
    PetscCall(PetscStrncpy(opt, w->name, sizeof opt));
    PetscCheck(w->fluid != 1 || !moving, dem->comm, PETSC_ERR_SUP, "%s_fluid yes: the plane %s, and the gas sees still walls only; leave %s_fluid out (it then bounds the particles only)", opt, w->t_remove < PETSC_MAX_REAL ? "is removed at a time" : "moves", opt);
    w->gas = (PetscBool)(w->fluid == 1);
    if (!w->gas) what = moving ? (w->t_remove < PETSC_MAX_REAL ? " (it is removed at a time)" : " (it moves)") : !strncmp(w->name, "-dem_box", 8) ? " (a plane lets the gas through)"
                                                                                                                                                  : " (a plane lets the gas through: give its _fluid yes to make it bound the gas)";
  } else what = " (a finite wall: the gas passes around it)";
  PetscCall(PetscPrintf(dem->comm, "vessel: %s bounds %s%s\n", w->name, w->gas ? "particles and gas" : "the particles only", what));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemVesselSetUp(Dem dem, PetscBool *any)
{
  const Domain *dom  = dem->dom;
  const double  band = 2 * PetscMax(dom->h[0], PetscMax(dom->h[1], dom->h[2]));

  PetscFunctionBeginUser;
  *any = PETSC_FALSE;
  for (PetscInt k = 0; k < dem->walls.nwall; k++) {
    PetscCall(DemVesselWall(dem, &dem->walls.wall[k]));
    *any = (PetscBool)(*any || dem->walls.wall[k].gas);
  }
  for (PetscInt k = 0; k < dem->meshes.n; k++) {
    DemMesh       *m    = &dem->meshes.m[k];
    const int      mode = m->fluid >= 0 ? m->fluid : m->moving ? DEM_MESH_FLUID_NONE
                                                               : DEM_MESH_FLUID_INSIDE;
    PetscLogDouble t0, t1;
    char           face[128] = "";
    PetscCall(DemVesselMeshDestroy(m));
    if (mode == DEM_MESH_FLUID_NONE) {
      PetscCall(PetscPrintf(dem->comm, "vessel: %s (%s) %s: it bounds the particles only\n", m->name, m->file, m->moving ? "moves" : "has _fluid none"));
      continue;
    }
    PetscCall(PetscTime(&t0));
    PetscCall(VmCreate(m, dem->dom, band, &m->vm));
    PetscCall(PetscTime(&t1));
    m->vm->sgn = mode == DEM_MESH_FLUID_INSIDE ? 1 : -1;
    PetscCheck(m->vm->nopen == 0, dem->comm, PETSC_ERR_ARG_WRONG, "%s_fluid %s: %s (%s) is not closed: %" PetscInt_FMT " edges are not shared by exactly two triangles, and the gas needs a closed surface (close it, e.g. tools/make_stl cylinder --caps, its ends on or beyond the box faces where the gas enters and leaves), or give %s_fluid none (it then bounds the particles only)", m->name,
               mode == DEM_MESH_FLUID_INSIDE ? "inside" : "outside", m->name, m->file, m->vm->nopen, m->name);
    if (m->vm->nface) PetscCall(PetscSNPrintf(face, sizeof face, "; %" PetscInt_FMT " of them lie in the box's faces and leave them to the fluid's conditions there", m->vm->nface));
    PetscCall(PetscPrintf(dem->comm, "vessel: %s (%s) bounds particles and gas (%s: closed, %" PetscInt_FMT " triangles%s%s; %" PetscInt_FMT " x %" PetscInt_FMT " x %" PetscInt_FMT " bins of %g m, set up in %.3f s)\n", m->name, m->file, mode == DEM_MESH_FLUID_INSIDE ? "the gas inside it" : "the gas outside it, an immersed obstacle", m->ref.ntri,
                          m->vm->oriented ? "" : ", orientation mixed: signs by ray casts", face, m->vm->nb[0], m->vm->nb[1], m->vm->nb[2], m->vm->b, t1 - t0));
    *any = PETSC_TRUE;
  }
  dem->walls.vessel = *any;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemVesselGetActive(Dem dem, PetscBool *any)
{
  PetscFunctionBeginUser;
  *any = dem->walls.vessel;
  PetscFunctionReturn(PETSC_SUCCESS);
}
