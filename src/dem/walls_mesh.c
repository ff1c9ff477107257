/* Triangle-mesh walls (options: walls_mesh_options.c): contacts of spheres with a soup of
 * triangles, two-sided, with the same kernels as the analytic walls (walls.c).
 * Contact rule (no double counting): for a sphere (centre x, radius r) take every candidate
 * triangle's closest point q (geom/trimesh.h TriClosestPoint) with d = |q - x| < r, nearest
 * first, and accept q unless, for a contact a accepted before it (unit normal n_a from x to q_a,
 * distance d_a), (q - x).n_a >= d_a - 1e-10 r: q lies on or beyond the tangent plane of a. A
 * shared edge or vertex gives the same point to every triangle that holds it and counts once;
 * a coplanar or convex-joined neighbour's point lies on or behind the accepted plane and is
 * dropped, so a sphere crossing its edge feels exactly one plane; a concave corner's second
 * face lies in front of it and is felt. The rule holds within one mesh; two meshes are two
 * walls. Normal from x to q, overlap r - d, contact point x + (r - overlap/2) n; surface velocity
 * v + omega u x (c - a(t)) of the mesh's rigid motion. Convex particles (DemMeshTouchConvex):
 * the polygon walls' face rule per triangle, a plane counted once; a triangle's edge pressing
 * into a particle's face is not seen (a convex ridge does not hold a convex particle).
 * Tangential springs: per particle and mesh DEM_MESH_SLOTS slots (normal, spring), each contact
 * taking the slot whose normal of the last step is closest (cosine > 0.7), so a sphere rolling
 * over an edge keeps its spring; slots are saved across list builds as id-keyed records and in
 * checkpoints (on another rank count as the same records: checkpoint_remap.c). Lists: at each
 * build, the triangles whose box meets this rank's box grown by the largest radius + skin are
 * binned, and each local particle lists those within r + skin; a moving mesh counts its travel
 * bound (|v| dt + |dtheta| raxis) as a wall's (dem.c). */
#include "dem/dem_core.h"
#include "dem/dem_walls.h"

/* The integral of the table's piecewise-linear omega from its first time to t (omega
 * constant outside the table), and omega(t) in *w. */
static double dem_mesh_table_integral(const double *tab, PetscInt n, double t, double *w)
{
  double acc = 0;
  if (t <= tab[0]) {
    *w = tab[1];
    return tab[1] * (t - tab[0]);
  }
  for (PetscInt j = 0; j + 1 < n; j++) {
    const double ta = tab[2 * j], wa = tab[2 * j + 1], tb = tab[2 * j + 2], wb = tab[2 * j + 3];
    if (t <= tb) {
      const double s = t - ta, wt = wa + (wb - wa) * s / (tb - ta);
      *w = wt;
      return acc + 0.5 * (wa + wt) * s;
    }
    acc += 0.5 * (wa + wb) * (tb - ta);
  }
  *w = tab[2 * n - 1];
  return acc + tab[2 * n - 1] * (t - tab[2 * n - 2]);
}

/* The angle (rad) turned from 0 to t and omega(t). */
static double dem_mesh_angle(const DemMesh *m, double t, double *w)
{
  double w0;
  if (!m->tab) {
    *w = m->omega;
    return m->omega * t;
  }
  return dem_mesh_table_integral(m->tab, m->ntab, t, w) - dem_mesh_table_integral(m->tab, m->ntab, 0, &w0);
}

/* The vertices of the cnt triangles of list (the first cnt when list is NULL) at the pose
 * (theta, tpose). */
static void dem_mesh_place(DemMesh *m, const PetscInt *list, PetscInt cnt)
{
  const double c = cos(m->theta), s = sin(m->theta), *u = m->ax_u;
  const double sh[3] = {m->vel[0] * m->tpose, m->vel[1] * m->tpose, m->vel[2] * m->tpose};
  for (PetscInt a = 0; a < cnt; a++) {
    const PetscInt t = list ? list[a] : a;
    for (int j = 0; j < 3; j++) {
      const double *x = m->ref.v + 9 * t + 3 * j, d[3] = {x[0] - m->ax_p[0], x[1] - m->ax_p[1], x[2] - m->ax_p[2]};
      double        ux[3], *y                          = m->cur + 9 * t + 3 * j;
      dem_cross(u, d, ux);
      const double ud = dem_dot(u, d) * (1 - c);
      for (int k = 0; k < 3; k++) y[k] = m->ax_p[k] + sh[k] + c * d[k] + s * ux[k] + ud * u[k]; /* Rodrigues */
    }
  }
}

/* Not collective. The pose of every moving mesh at time t (its local triangles placed), the
 * travel since the last build accumulated; *moved: the largest (NULL: not accumulated). */
PetscErrorCode DemMeshesMove(Dem dem, double t, double *moved)
{
  PetscFunctionBeginUser;
  if (moved) *moved = 0;
  for (PetscInt k = 0; k < dem->meshes.n; k++) {
    DemMesh *m = &dem->meshes.m[k];
    double   w;
    if (!m->moving) continue;
    const double th = dem_mesh_angle(m, t, &w);
    if (moved) {
      m->moved += PetscAbsReal(th - m->theta) * m->raxis + sqrt(dem_dot(m->vel, m->vel)) * PetscAbsReal(t - m->tpose);
      *moved = PetscMax(*moved, m->moved);
    }
    m->theta = th;
    m->w_now = w;
    m->tpose = t;
    dem_mesh_place(m, m->loc, m->nloc);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The triangles of mesh m whose box meets lo..hi (this rank's box grown by g). */
static PetscErrorCode DemMeshLocal(DemMesh *m, const double lo[3], const double hi[3])
{
  PetscFunctionBeginUser;
  m->nloc = 0;
  for (PetscInt t = 0; t < m->ref.ntri; t++) {
    const double *v  = m->cur + 9 * t;
    PetscBool     in = PETSC_TRUE;
    for (int k = 0; k < 3; k++) in = (PetscBool)(in && PetscMin(v[k], PetscMin(v[3 + k], v[6 + k])) <= hi[k] && PetscMax(v[k], PetscMax(v[3 + k], v[6 + k])) >= lo[k]);
    if (!in) continue;
    if (m->nloc == m->caploc) {
      m->caploc = 2 * m->caploc + 64;
      PetscCall(PetscRealloc(sizeof(PetscInt) * (size_t)m->caploc, &m->loc));
    }
    m->loc[m->nloc++] = t;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

typedef struct { /* the bins of a mesh's local triangles over this rank's box */
  PetscInt nc[3], *start, *tri;
  double   lo[3], inv[3];
} DemMeshBins;

static inline PetscInt dem_mesh_bin(const DemMeshBins *b, int k, double x)
{
  const PetscInt c = (PetscInt)floor((x - b->lo[k]) * b->inv[k]);
  return c < 0 ? 0 : (c >= b->nc[k] ? b->nc[k] - 1 : c);
}

/* Bins of cell size >= 2 g (at most 32 a side), each triangle in every bin its box grown by g
 * meets: a particle within g of a triangle finds it in its own bin. */
static PetscErrorCode DemMeshBin(const DemMesh *m, const double lo[3], const double hi[3], double g, DemMeshBins *b)
{
  PetscInt ncell = 1;

  PetscFunctionBeginUser;
  for (int k = 0; k < 3; k++) {
    b->nc[k]  = PetscMax(1, PetscMin(32, (PetscInt)((hi[k] - lo[k]) / (2 * g))));
    b->lo[k]  = lo[k];
    b->inv[k] = b->nc[k] / (hi[k] - lo[k]);
    ncell *= b->nc[k];
  }
  PetscCall(PetscCalloc1(ncell + 1, &b->start));
  for (int pass = 0; pass < 2; pass++) {
    if (pass) {
      for (PetscInt c = 0; c < ncell; c++) b->start[c + 1] += b->start[c];
      PetscCall(PetscMalloc1(b->start[ncell] + 1, &b->tri));
    }
    for (PetscInt a = 0; a < m->nloc; a++) {
      const double *v = m->cur + 9 * m->loc[a];
      PetscInt      c0[3], c1[3];
      for (int k = 0; k < 3; k++) {
        c0[k] = dem_mesh_bin(b, k, PetscMin(v[k], PetscMin(v[3 + k], v[6 + k])) - g);
        c1[k] = dem_mesh_bin(b, k, PetscMax(v[k], PetscMax(v[3 + k], v[6 + k])) + g);
      }
      for (PetscInt z = c0[2]; z <= c1[2]; z++)
        for (PetscInt y = c0[1]; y <= c1[1]; y++)
          for (PetscInt x = c0[0]; x <= c1[0]; x++) {
            const PetscInt c = x + b->nc[0] * (y + b->nc[1] * z);
            if (pass) b->tri[b->start[c]++] = m->loc[a];
            else b->start[c + 1]++;
          }
    }
  }
  for (PetscInt c = ncell; c > 0; c--) b->start[c] = b->start[c - 1]; /* the fill advanced each start */
  b->start[0] = 0;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The candidate triangles of each local particle: those within r + skin, from its bin. */
static PetscErrorCode DemMeshCandidates(Dem dem, DemMesh *m, const DemMeshBins *b)
{
  const DemParticles *pt  = &dem->p;
  PetscInt            cnt = 0;

  PetscFunctionBeginUser;
  if (pt->n + 1 > m->capstart) {
    m->capstart = pt->n + 1;
    PetscCall(PetscRealloc(sizeof(PetscInt) * (size_t)m->capstart, &m->cstart));
  }
  for (PetscInt i = 0; i < pt->n; i++) {
    const double  *x = pt->x + 3 * i, reach = DemRadius(pt, &dem->shapes, i) + dem->nl.skin;
    const PetscInt c = dem_mesh_bin(b, 0, x[0]) + b->nc[0] * (dem_mesh_bin(b, 1, x[1]) + b->nc[1] * dem_mesh_bin(b, 2, x[2]));
    m->cstart[i]     = cnt;
    for (PetscInt e = b->start[c]; e < b->start[c + 1]; e++) {
      const double *v = m->cur + 9 * b->tri[e];
      double        q[3];
      TriClosestPoint(v, v + 3, v + 6, x, q);
      const double d[3] = {q[0] - x[0], q[1] - x[1], q[2] - x[2]};
      if (dem_dot(d, d) >= reach * reach) continue;
      if (cnt == m->capc) {
        m->capc = 2 * m->capc + 256;
        PetscCall(PetscRealloc(sizeof(PetscInt) * (size_t)m->capc, &m->ctri));
      }
      m->ctri[cnt++] = b->tri[e];
    }
  }
  m->cstart[pt->n] = cnt;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The springs of mesh k's slots from the id-keyed records (partners DEM_MESH_PARTNER(k, s, .)). */
static PetscErrorCode DemMeshRestoreSlots(Dem dem, PetscInt k, DemMesh *m, const DemSpring *recs, PetscInt nrec)
{
  const PetscInt n = dem->p.n, hi = DEM_MESH_PARTNER(k, 0, 0), lo = DEM_MESH_PARTNER(k, DEM_MESH_SLOTS - 1, 1);

  PetscFunctionBeginUser;
  if (dem->contact.law == DEM_LAW_LINEAR_NOHIST) PetscFunctionReturn(PETSC_SUCCESS);
  if (n > m->capslot) {
    PetscCall(PetscFree(m->slot));
    m->capslot = n;
    PetscCall(PetscMalloc1(6 * DEM_MESH_SLOTS * (size_t)n, &m->slot));
  }
  if (n) PetscCall(PetscArrayzero(m->slot, 6 * DEM_MESH_SLOTS * n));
  for (PetscInt i = 0; i < n && nrec; i++) {
    const DemSpring *r = DemSpringFind(recs, nrec, dem->p.id[i], PETSC_MIN_INT);
    for (; r && r < recs + nrec && r->owner == dem->p.id[i]; r++) {
      if (r->partner < lo || r->partner > hi) continue;
      const PetscInt e = -1 - DEM_MAX_WALLS - r->partner - 2 * k * DEM_MESH_SLOTS, s = e / 2, half = e % 2;
      for (int j = 0; j < 3; j++) m->slot[6 * (DEM_MESH_SLOTS * i + s) + 3 * (1 - half) + j] = r->xi[j];
    }
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Not collective. At a list build: the meshes' local triangles (at the current pose), their
 * bins, the candidates of every local particle, and the springs from the records. */
PetscErrorCode DemMeshesBuildLists(Dem dem, const DemSpring *recs, PetscInt nrec)
{
  const double g = 0.5 * (dem->nl.reach - dem->nl.skin) + dem->nl.skin; /* largest radius + skin */
  double       lo[3], hi[3];

  PetscFunctionBeginUser;
  for (int k = 0; k < 3; k++) {
    lo[k] = dem->dom->sublo[k] - g;
    hi[k] = dem->dom->subhi[k] + g;
  }
  for (PetscInt k = 0; k < dem->meshes.n; k++) {
    DemMesh    *m = &dem->meshes.m[k];
    DemMeshBins b;
    PetscCall(PetscMemzero(&b, sizeof b));
    if (m->moving) dem_mesh_place(m, NULL, m->ref.ntri);
    PetscCall(DemMeshLocal(m, lo, hi));
    PetscCall(DemMeshBin(m, lo, hi, g, &b));
    PetscCall(DemMeshCandidates(dem, m, &b));
    PetscCall(PetscFree(b.start));
    PetscCall(PetscFree(b.tri));
    PetscCall(DemMeshRestoreSlots(dem, k, m, recs, nrec));
    m->moved = 0;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The touching triangles' points of particle i, nearest first, reduced by the contact rule:
 * the accepted contacts' unit normals and distances. Returns their count. */
static inline int dem_mesh_touch(const DemMesh *m, PetscInt i, const double *x, double r, double an[][3], double ad[])
{
  double dq[DEM_MESH_MAXC], qq[DEM_MESH_MAXC][3];
  int    nc = 0, na = 0;
  for (PetscInt a = m->cstart[i]; a < m->cstart[i + 1]; a++) {
    const double *v = m->cur + 9 * m->ctri[a];
    double        q[3];
    TriClosestPoint(v, v + 3, v + 6, x, q);
    const double d2 = (q[0] - x[0]) * (q[0] - x[0]) + (q[1] - x[1]) * (q[1] - x[1]) + (q[2] - x[2]) * (q[2] - x[2]);
    if (!(d2 < r * r && d2 > 0)) continue;
    const double d = sqrt(d2);
    if (nc == DEM_MESH_MAXC && d >= dq[nc - 1]) continue; /* the farthest are dropped */
    int j = nc < DEM_MESH_MAXC ? nc++ : nc - 1;
    for (; j > 0 && dq[j - 1] > d; j--) {
      dq[j] = dq[j - 1];
      for (int k = 0; k < 3; k++) qq[j][k] = qq[j - 1][k];
    }
    dq[j] = d;
    for (int k = 0; k < 3; k++) qq[j][k] = q[k];
  }
  const double tol = 1e-10 * r;
  for (int c = 0; c < nc; c++) {
    const double rel[3] = {qq[c][0] - x[0], qq[c][1] - x[1], qq[c][2] - x[2]};
    PetscBool    ok     = PETSC_TRUE;
    for (int a = 0; a < na && ok; a++) ok = (PetscBool)(dem_dot(rel, an[a]) < ad[a] - tol);
    if (!ok) continue;
    for (int k = 0; k < 3; k++) an[na][k] = rel[k] / dq[c];
    ad[na++] = dq[c];
  }
  return na;
}

/* Whether the point q of the plane of triangle (a, b, c) (unit normal n) lies in the triangle,
 * edges included to tol. */
static inline PetscBool dem_tri_covers(const double *a, const double *b, const double *c, const double n[3], const double q[3], double tol)
{
  const double *v[3] = {a, b, c};
  for (int e = 0; e < 3; e++) {
    const double *p = v[e], *r = v[(e + 1) % 3];
    const double  d[3] = {r[0] - p[0], r[1] - p[1], r[2] - p[2]}, w[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]};
    double        en[3]; /* n x d points into the triangle for a right-handed (a, b, c) */
    dem_cross(n, d, en);
    if (dem_dot(w, en) < -tol * sqrt(dem_dot(en, en))) return PETSC_FALSE;
  }
  return PETSC_TRUE;
}

/* Not collective. The contacts of convex particle i (pose) with mesh m by the face rule of the
 * polygon walls: for each candidate triangle, the contact with its plane (ConvexCollidePlane,
 * the normal turned towards the particle's centre: two-sided) counts where its point lies in
 * the triangle (edges included to 1e-10 of the bounding radius); a plane counts once (a later
 * triangle of a plane already accepted, normal and offset equal to 1e-10, is dropped), so
 * coplanar neighbours sharing the point's edge or vertex give one contact. A triangle's edge or
 * vertex pressing into a particle's face is not seen (a ridge: see the README). Returns the
 * count in *nc (at most DEM_MESH_MAXC). */
PetscErrorCode DemMeshTouchConvex(Dem dem, const DemMesh *m, PetscInt i, ConvexContact cc[], int *nc)
{
  const DemShape  *s = &dem->shapes.shp[dem->p.shape[i]];
  const double    *x = dem->p.x + 3 * i, tol = 1e-10 * s->r;
  const ConvexPose pose = DemPose(x, dem->p.q + 4 * i);
  double           off[DEM_MESH_MAXC];

  PetscFunctionBeginUser;
  *nc = 0;
  for (PetscInt a = m->cstart[i]; a < m->cstart[i + 1] && *nc < DEM_MESH_MAXC; a++) {
    const double *v = m->cur + 9 * m->ctri[a], e1[3] = {v[3] - v[0], v[4] - v[1], v[5] - v[2]}, e2[3] = {v[6] - v[0], v[7] - v[1], v[8] - v[2]};
    const double  d[3] = {x[0] - v[0], x[1] - v[1], x[2] - v[2]};
    double        nr[3], n[3]; /* the right-handed normal, and the one towards the centre */
    ConvexContact c;
    dem_cross(e1, e2, nr);
    const double nn = sqrt(dem_dot(nr, nr)), h = dem_dot(d, nr) / nn;
    if (!(nn > 0) || h == 0 || PetscAbsReal(h) >= s->r) continue;
    for (int k = 0; k < 3; k++) nr[k] /= nn, n[k] = h > 0 ? nr[k] : -nr[k];
    PetscCall(ConvexCollidePlane(s->cvx, &pose, v, n, &c));
    if (!c.overlap || !dem_tri_covers(v, v + 3, v + 6, nr, c.point, tol)) continue;
    const double o   = dem_dot(v, n);
    PetscBool    dup = PETSC_FALSE;
    for (int b = 0; b < *nc && !dup; b++) dup = (PetscBool)(dem_dot(cc[b].normal, n) < -1 + 1e-10 && PetscAbsReal(off[b] - o) <= tol);
    if (dup) continue;
    off[*nc]    = o;
    cc[(*nc)++] = c;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The slot of each accepted contact (normals an): the unused slot whose normal is closest
 * (cosine > 0.7), else a free one, else -1 (no history); the slots left over are freed. */
static inline void dem_mesh_match(double *sl, int na, const double an[][3], int match[])
{
  PetscBool used[DEM_MESH_SLOTS] = {PETSC_FALSE};
  for (int a = 0; a < na; a++) {
    double best = 0.7;
    match[a]    = -1;
    for (int s = 0; s < DEM_MESH_SLOTS; s++) {
      const double *n = sl + 6 * s, c = dem_dot(n, an[a]);
      if (!used[s] && c > best) best = c, match[a] = s;
    }
    if (match[a] >= 0) used[match[a]] = PETSC_TRUE;
  }
  for (int a = 0; a < na; a++) {
    if (match[a] >= 0) continue;
    for (int s = 0; s < DEM_MESH_SLOTS && match[a] < 0; s++) {
      const double *n = sl + 6 * s;
      if (!used[s] && n[0] == 0 && n[1] == 0 && n[2] == 0) match[a] = s, used[s] = PETSC_TRUE;
    }
  }
  for (int s = 0; s < DEM_MESH_SLOTS; s++)
    if (!used[s])
      for (int k = 0; k < 6; k++) sl[6 * s + k] = 0;
}

/* Not collective. The same for the convex particles (convex_contacts.c). */
void DemMeshMatchSlots(double *sl, int na, const double an[][3], int match[])
{
  dem_mesh_match(sl, na, an, match);
}

/* The forces of mesh m on local particle i (as dem_walls_body in walls.c). */
static inline void dem_mesh_particle(Dem dem, DemMesh *m, PetscInt i, const PetscBool poly)
{
  DemParticles          *pt = &dem->p;
  const DemContactModel *cm = &dem->contact;
  const double          *xi = pt->x + 3 * i, dt = dem->clock.dt;
  const double           r = poly ? pt->rad[i] : dem->shapes.shp[pt->shape[i]].r;
  double                 an[DEM_MESH_MAXC][3], ad[DEM_MESH_MAXC], none[3];
  int                    match[DEM_MESH_MAXC];
  double                *sl     = m->slot ? m->slot + 6 * DEM_MESH_SLOTS * i : NULL;
  const int              na     = dem_mesh_touch(m, i, xi, r, an, ad);
  const double           axp[3] = {m->ax_p[0] + m->vel[0] * m->tpose, m->ax_p[1] + m->vel[1] * m->tpose, m->ax_p[2] + m->vel[2] * m->tpose};

  if (sl) dem_mesh_match(sl, na, an, match);
  for (int a = 0; a < na; a++) {
    const double        *nrm = an[a], delta = r - ad[a];
    const DemPairParams *p = &m->pw[pt->shape[i]];
    DemPairParams        sized;
    double              *xi_t = NULL;
    if (sl && match[a] >= 0) {
      xi_t = sl + 6 * match[a] + 3;
      for (int k = 0; k < 3; k++) sl[6 * match[a] + k] = nrm[k];
    } else if (sl) { /* more contacts than slots: this one without history */
      none[0] = none[1] = none[2] = 0;
      xi_t                        = none;
    }
    if (poly) { /* m* = m, R* = r of the sphere */
      dem_pair_sized(cm->law, p, pt->m[i], r, 0, 0, &sized);
      p = &sized;
    }
    const double l     = r - 0.5 * delta;
    const double pc[3] = {xi[0] + l * nrm[0], xi[1] + l * nrm[1], xi[2] + l * nrm[2]}; /* contact point */
    const double ww[3] = {m->w_now * m->ax_u[0], m->w_now * m->ax_u[1], m->w_now * m->ax_u[2]};
    double       vw[3], d[3];
    for (int k = 0; k < 3; k++) d[k] = pc[k] - axp[k];
    dem_cross(m->ax_u, d, vw);
    for (int k = 0; k < 3; k++) vw[k] = m->vel[k] + m->w_now * vw[k];
    dem_sphere_wall_force(pt, i, r, delta, nrm, vw, ww, p, cm, poly ? dem_pair_inertia(pt->m[i], r, 0, 0) : p->ieff, xi_t, dt);
  }
}

/* Not collective. The meshes' forces and torques on the local spheres; advances their springs. */
PetscErrorCode DemContactsMeshes(Dem dem)
{
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(DEM_Walls, 0, 0, 0, 0));
  for (PetscInt k = 0; k < dem->meshes.n; k++) {
    DemMesh *m = &dem->meshes.m[k];
    if (!m->cstart) continue;
    for (PetscInt i = 0; i < dem->p.n; i++) {
      if (m->cstart[i] == m->cstart[i + 1]) continue;
      if (dem->p.rad) dem_mesh_particle(dem, m, i, PETSC_TRUE);
      else dem_mesh_particle(dem, m, i, PETSC_FALSE);
    }
  }
  PetscCall(PetscLogEventEnd(DEM_Walls, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Not collective. Appends the loaded slots to the id-keyed records of DemSpringsSave (springs.c),
 * two per slot (spring, normal), and sorts them again. */
PetscErrorCode DemMeshesSaveSprings(Dem dem, DemSpring **recs, PetscInt *nrec, PetscInt *cap)
{
  PetscInt n = *nrec;

  PetscFunctionBeginUser;
  if (dem->contact.law == DEM_LAW_LINEAR_NOHIST) PetscFunctionReturn(PETSC_SUCCESS);
  for (PetscInt k = 0; k < dem->meshes.n; k++) {
    const DemMesh *m = &dem->meshes.m[k];
    if (!m->slot || !m->cstart) continue;
    for (PetscInt i = 0; i < dem->p.n; i++)
      for (int s = 0; s < DEM_MESH_SLOTS; s++) {
        const double *sl = m->slot + 6 * (DEM_MESH_SLOTS * i + s);
        if (sl[3] == 0 && sl[4] == 0 && sl[5] == 0) continue;
        if (n + 2 > *cap) {
          *cap = 2 * *cap + 64;
          PetscCall(PetscRealloc(sizeof(DemSpring) * (size_t)*cap, recs));
        }
        (*recs)[n++] = (DemSpring){dem->p.id[i], DEM_MESH_PARTNER(k, s, 0), {sl[3], sl[4], sl[5]}};
        (*recs)[n++] = (DemSpring){dem->p.id[i], DEM_MESH_PARTNER(k, s, 1), {sl[0], sl[1], sl[2]}};
      }
  }
  if (n > *nrec) PetscCall(DemSpringsSort(*recs, n));
  *nrec = n;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective, same rank count. The meshes' travel (shared), local triangles and candidates
 * (dem/mesh_lists: per mesh nloc, loc, n + 1 starts, the candidates) and slots (dem/mesh_slot);
 * on reading, the pose at the restored time. */
PetscErrorCode DemMeshesCheckpoint(Dem dem, IoCkpt ck, PetscBool write)
{
  const PetscInt nm = dem->meshes.n, n = dem->p.n, ns = 6 * DEM_MESH_SLOTS * n;
  double         moved[DEM_MAX_MESHES];
  PetscInt      *li = NULL, nli = 0, o = 0, nsl = 0;
  double        *sd = NULL;

  PetscFunctionBeginUser;
  if (!nm) PetscFunctionReturn(PETSC_SUCCESS);
  if (write) {
    for (PetscInt k = 0; k < nm; k++) {
      const DemMesh *m = &dem->meshes.m[k];
      moved[k]         = m->moved;
      nli += 1 + m->nloc + n + 1 + m->cstart[n];
    }
    PetscCall(PetscMalloc1(nli + 1, &li));
    PetscCall(PetscCalloc1(nm * ns + 1, &sd));
    for (PetscInt k = 0; k < nm; k++) {
      const DemMesh *m = &dem->meshes.m[k];
      li[o++]          = m->nloc;
      for (PetscInt a = 0; a < m->nloc; a++) li[o++] = m->loc[a];
      for (PetscInt a = 0; a <= n; a++) li[o++] = m->cstart[a];
      for (PetscInt a = 0; a < m->cstart[n]; a++) li[o++] = m->ctri[a];
      if (m->slot) PetscCall(PetscArraycpy(sd + k * ns, m->slot, ns));
    }
    PetscCall(IoCkptWriteShared(ck, "dem/mesh_moved", IO_CKPT_REAL, nm, moved));
    PetscCall(IoCkptWriteRows(ck, "dem/mesh_lists", IO_CKPT_INT, nli, li));
    PetscCall(IoCkptWriteRows(ck, "dem/mesh_slot", IO_CKPT_REAL, nm * ns, sd));
    PetscCall(PetscFree(li));
    PetscCall(PetscFree(sd));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(IoCkptReadShared(ck, "dem/mesh_moved", IO_CKPT_REAL, nm, moved));
  PetscCall(IoCkptReadRows(ck, "dem/mesh_lists", IO_CKPT_INT, &nli, (void **)&li));
  PetscCall(IoCkptReadRows(ck, "dem/mesh_slot", IO_CKPT_REAL, &nsl, (void **)&sd));
  { /* the rows' lengths against their counts, on every rank before any rank stops */
    PetscBool ok = (PetscBool)(nsl == nm * ns), all;
    for (PetscInt k = 0, q = 0; k < nm && ok; k++) {
      ok = (PetscBool)(q < nli && li[q] >= 0 && q + 1 + li[q] + n + 1 <= nli);
      if (!ok) break;
      q += 1 + li[q];
      const PetscInt nc = li[q + n];
      q += n + 1;
      ok = (PetscBool)(nc >= 0 && q + nc <= nli);
      q += nc;
    }
    PetscCall(MPIU_Allreduce(&ok, &all, 1, MPIU_BOOL, MPI_LAND, dem->comm));
    PetscCheck(all, dem->comm, PETSC_ERR_FILE_UNEXPECTED, "-restart: the checkpoint's mesh springs (datasets dem/mesh_lists, dem/mesh_slot) do not match its particles on some rank: the file is damaged or was written by another build");
  }
  for (PetscInt k = 0; k < nm; k++) {
    DemMesh *m = &dem->meshes.m[k];
    PetscCall(PetscFree(m->loc));
    m->nloc   = li[o++];
    m->caploc = m->nloc + 1;
    PetscCall(PetscMalloc1(m->caploc, &m->loc));
    PetscCall(PetscArraycpy(m->loc, li + o, m->nloc));
    o += m->nloc;
    PetscCall(PetscFree(m->cstart));
    m->capstart = n + 1;
    PetscCall(PetscMalloc1(n + 1, &m->cstart));
    PetscCall(PetscArraycpy(m->cstart, li + o, n + 1));
    o += n + 1;
    PetscCall(PetscFree(m->ctri));
    m->capc = m->cstart[n] + 1;
    PetscCall(PetscMalloc1(m->capc, &m->ctri));
    PetscCall(PetscArraycpy(m->ctri, li + o, m->cstart[n]));
    o += m->cstart[n];
    if (dem->contact.law != DEM_LAW_LINEAR_NOHIST) {
      PetscCall(PetscFree(m->slot));
      m->capslot = n;
      PetscCall(PetscMalloc1(ns + 1, &m->slot));
      PetscCall(PetscArraycpy(m->slot, sd + k * ns, ns));
    }
  }
  PetscCall(PetscFree(li));
  PetscCall(PetscFree(sd));
  PetscCall(DemMeshesMove(dem, dem->clock.t, NULL)); /* the pose of the restored time */
  for (PetscInt k = 0; k < nm; k++) dem->meshes.m[k].moved = moved[k];
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Not collective. The meshes' contacts for DemGetStats (diag.c): c[2] counts them, r[3] adds
 * their normal elastic energy (linear 1/2 kn delta^2, hertz 8/15 E* sqrt(R*) delta^(5/2); the
 * springs' share left out), *rmax the largest overlap over the radius. */
PetscErrorCode DemMeshesStatsLocal(Dem dem, double r[5], PetscInt c[3], double *rmax)
{
  PetscFunctionBeginUser;
  for (PetscInt k = 0; k < dem->meshes.n; k++) {
    const DemMesh *m = &dem->meshes.m[k];
    if (!m->cstart) continue;
    for (PetscInt i = 0; i < dem->p.n; i++) {
      double        depth[DEM_MESH_MAXC], an[DEM_MESH_MAXC][3], ad[DEM_MESH_MAXC], rr;
      int           na = 0;
      DemPairParams p  = m->pw[dem->p.shape[i]];
      if (m->cstart[i] == m->cstart[i + 1]) continue;
      if (dem->shapes.convex) {
        ConvexContact cc[DEM_MESH_MAXC];
        PetscCall(DemMeshTouchConvex(dem, m, i, cc, &na));
        for (int a = 0; a < na; a++) depth[a] = cc[a].depth;
        rr = dem->shapes.shp[dem->p.shape[i]].req;
      } else {
        rr = DemRadius(&dem->p, &dem->shapes, i);
        na = dem_mesh_touch(m, i, dem->p.x + 3 * i, rr, an, ad);
        for (int a = 0; a < na; a++) depth[a] = rr - ad[a];
        if (dem->p.rad) dem_pair_sized(dem->contact.law, &m->pw[dem->p.shape[i]], dem->p.m[i], rr, 0, 0, &p);
      }
      for (int a = 0; a < na; a++) {
        r[3] += dem->contact.law == DEM_LAW_HERTZ ? 8.0 / 15.0 * p.es * sqrt(p.reff) * pow(depth[a], 2.5) : 0.5 * p.kn * depth[a] * depth[a];
        *rmax = PetscMax(*rmax, depth[a] / rr);
      }
      c[2] += na;
    }
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Not collective (every rank holds every mesh). Whether a mesh at rest closes the domain face
 * (d, side): its triangles in the face's plane (to tol) and within its rectangle have areas
 * summing to the face's (1e-9 relative; a soup that tiles the face: no triangle counted twice,
 * as the reader skips exact duplicates). Only the face's own plane: a mesh is two-sided, so a
 * plane of triangles inside the domain has particles on either side, and those between it and
 * the face would reach the face. A moving mesh closes nothing. */
PetscErrorCode DemMeshesCloseFace(Dem dem, int d, int side, double tol, PetscBool *closed)
{
  const Domain *dom = dem->dom;
  const int     a = (d + 1) % 3, b = (d + 2) % 3;
  const double  face = dom->len[a] * dom->len[b], at = side ? dom->hi[d] : dom->lo[d];

  PetscFunctionBeginUser;
  *closed = PETSC_FALSE;
  for (PetscInt k = 0; k < dem->meshes.n && !*closed; k++) {
    const DemMesh *m   = &dem->meshes.m[k];
    double         sum = 0;
    if (m->moving) continue;
    for (PetscInt t = 0; t < m->ref.ntri; t++) {
      const double *v = m->ref.v + 9 * t, c = v[d];
      PetscBool     in = (PetscBool)(PetscAbsReal(v[3 + d] - c) <= tol && PetscAbsReal(v[6 + d] - c) <= tol && PetscAbsReal(c - at) <= tol);
      for (int j = 0; j < 3 && in; j++) in = (PetscBool)(v[3 * j + a] >= dom->lo[a] - tol && v[3 * j + a] <= dom->hi[a] + tol && v[3 * j + b] >= dom->lo[b] - tol && v[3 * j + b] <= dom->hi[b] + tol);
      if (!in) continue;
      sum += 0.5 * PetscAbsReal((v[3 + a] - v[a]) * (v[6 + b] - v[b]) - (v[6 + a] - v[a]) * (v[3 + b] - v[b]));
    }
    *closed = (PetscBool)(sum >= face * (1 - 1e-9));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Not collective. The deepest contact of local particle i with mesh k over its radius (spheres:
 * r; convex: d_eq/2), 0 when clear: the placement check (placement.c). */
PetscErrorCode DemMeshDepth(Dem dem, PetscInt k, PetscInt i, double *depth)
{
  const DemMesh *m = &dem->meshes.m[k];

  PetscFunctionBeginUser;
  *depth = 0;
  if (!m->cstart || m->cstart[i] == m->cstart[i + 1]) PetscFunctionReturn(PETSC_SUCCESS);
  if (dem->shapes.convex) {
    ConvexContact cc[DEM_MESH_MAXC];
    int           na;
    PetscCall(DemMeshTouchConvex(dem, m, i, cc, &na));
    for (int a = 0; a < na; a++) *depth = PetscMax(*depth, cc[a].depth / dem->shapes.shp[dem->p.shape[i]].req);
  } else {
    const double r = DemRadius(&dem->p, &dem->shapes, i);
    double       an[DEM_MESH_MAXC][3], ad[DEM_MESH_MAXC];
    const int    na = dem_mesh_touch(m, i, dem->p.x + 3 * i, r, an, ad);
    for (int a = 0; a < na; a++) *depth = PetscMax(*depth, (r - ad[a]) / r);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Not collective. Whether a sphere (centre x in this rank's box, radius r <= the largest
 * radius) meets a triangle of a mesh: a source's candidate (sources.c). The rank's triangles of
 * the last list build cover it (they meet the box grown by the largest radius + skin, and a
 * mesh moves less than skin/2 between builds); their vertices are at the current pose. */
PetscBool DemMeshesBlock(Dem dem, const double x[3], double r)
{
  for (PetscInt k = 0; k < dem->meshes.n; k++) {
    const DemMesh *m = &dem->meshes.m[k];
    for (PetscInt a = 0; a < m->nloc; a++) {
      const double *v    = m->cur + 9 * m->loc[a];
      PetscBool     near = PETSC_TRUE;
      double        q[3];
      for (int j = 0; j < 3 && near; j++) near = (PetscBool)(PetscMin(v[j], PetscMin(v[3 + j], v[6 + j])) < x[j] + r && PetscMax(v[j], PetscMax(v[3 + j], v[6 + j])) > x[j] - r);
      if (!near) continue;
      TriClosestPoint(v, v + 3, v + 6, x, q);
      const double d[3] = {q[0] - x[0], q[1] - x[1], q[2] - x[2]};
      if (dem_dot(d, d) < r * r) return PETSC_TRUE;
    }
  }
  return PETSC_FALSE;
}
