/* Contact forces for convex particles (pairs over the half Verlet list, and plane walls).
 *
 * The narrow phase (convex.h: libccd MPR for depth and normal, the contact features for the
 * point) gives for a touching pair the overlap delta, the unit normal n from i to its partner j
 * and the world contact point p. The same laws as for spheres (contact_laws.h) act at p:
 *   r_i = p - x_i, r_j = p - x_j,  v_rel = (v_j + w_j x r_j) - (v_i + w_i x r_i),
 *   v_n = v_rel . n,  v_t = v_rel - v_n n,  F_i = -F_n n - F_t,  F_j = -F_i,
 *   T_i = r_i x F_i,  T_j = r_j x F_j   (the lever arm gives torque even without friction).
 * A wall is a partner of infinite mass with velocity v_wall and no spin; its contact comes from
 * ConvexCollidePlane (n = -wall normal). Bounding spheres that do not overlap are rejected
 * before libccd; a pair that does not touch has its tangential spring reset (as for spheres).
 * Separating-axis cache: most pairs of the list whose bounding spheres overlap do not touch,
 * and a body pair apart along some axis u, (x_j - x_i).u > h_i(u) + h_j(-u) (h: support
 * extent about the centre), usually stays apart along it for many steps. Each list entry keeps
 * the last such axis (tried first), the centre line is tried next, and only then libccd; when
 * libccd finds no contact, the face directions of both bodies and the cross products of their
 * edge directions (the complete set of separating-axis candidates) are searched for one to keep.
 * A test costs two support scans (about a tenth of an MPR call). The cache is exact (an axis
 * either separates or the full test runs) and is cleared at every list build. An entry also
 * flags a pair that touched at the last step: a separating-axis pair then goes to its test
 * directly (the centre-line probe usually fails). A particle's rotation matrix is formed at most
 * once per pass of the pair loop (dem->narrow.rot).
 * Few-axis pairs (box-box: 3 + 3 face normals and 3 x 3 edge-edge axes; -dem_convex_sat_axes
 * sets the limit, 16 by default; two boxes in closed form, geom/sat_box.c) skip libccd: the
 * separating-axis test over all candidates gives the exact minimum penetration (depth and normal
 * of the least overlap, for convex polyhedra the minimum translation), continuous in the poses,
 * where MPR's portal depth jumps; the contact point follows (ConvexBodiesContactPoint, the model of
 * -dem_convex_contact_point), and MPR is the fallback if that point fails. With the support
 * point, pairs left to MPR take MPR's depth and normal and the support features' point.
 * The contact laws use R = d_eq/2 per shape (shapes.c). Units SI. */
#include "dem/dem_core.h"
#include "dem/dem_walls.h"

typedef struct {
  DemLaw               law;
  const DemPairParams *p;
  const ConvexContact *c;
  const double        *xi, *vi, *wi; /* particle i */
  const double        *xj, *vj, *wj; /* partner j (a wall: its point, velocity, zero spin) */
  double               dt;
} DemConvexIn;

/* Force on i and torques on i and j of one contact. xi_t: the pair's spring or NULL. */
static inline void dem_convex_force(const DemConvexIn *in, double *xi_t, double Fi[3], double Ti[3], double Tj[3])
{
  const double *nrm = in->c->normal;
  double        ri[3], rj[3], ui[3], uj[3], vr[3], kt, gt;

  for (int k = 0; k < 3; k++) {
    ri[k] = in->c->point[k] - in->xi[k];
    rj[k] = in->c->point[k] - in->xj[k];
  }
  dem_cross(in->wi, ri, ui);
  dem_cross(in->wj, rj, uj);
  for (int k = 0; k < 3; k++) vr[k] = in->vj[k] + uj[k] - in->vi[k] - ui[k];
  const double vn = dem_dot(vr, nrm);
  const double fn = dem_normal_force(in->law, in->p, in->c->depth, vn, &kt, &gt);
  for (int k = 0; k < 3; k++) Fi[k] = -fn * nrm[k];
  if (in->p->mu > 0) {
    double vt[3], ft[3];
    for (int k = 0; k < 3; k++) vt[k] = vr[k] - vn * nrm[k];
    dem_tangential_force(in->p, fn, kt, gt, nrm, vt, xi_t, in->dt, ft); /* ft acts on j */
    for (int k = 0; k < 3; k++) Fi[k] -= ft[k];
  } else if (xi_t) xi_t[0] = xi_t[1] = xi_t[2] = 0;
  dem_cross(ri, Fi, Ti);
  dem_cross(Fi, rj, Tj); /* r_j x (-F_i) */
}

/* Support extent of a shape about its centre along the body-frame direction d. */
static inline double dem_extent(const ConvexShape *c, const double d[3])
{
  if (c->kind == CONVEX_CYLINDER) return c->radius * sqrt(d[0] * d[0] + d[1] * d[1]) + 0.5 * c->height * fabs(d[2]);
  double best = -PETSC_MAX_REAL;
  for (PetscInt k = 0; k < c->nv; k++) {
    const double t = c->v[3 * k] * d[0] + c->v[3 * k + 1] * d[1] + c->v[3 * k + 2] * d[2];
    best           = t > best ? t : best;
  }
  return best;
}

/* The same for a shape of the table: a box in closed form, sum_k h_k |a_k . d|. */
static inline double dem_shape_extent(const DemShape *s, const double d[3])
{
  if (s->ax.box) return s->ax.bh[0] * PetscAbsReal(dem_dot(s->ax.fn, d)) + s->ax.bh[1] * PetscAbsReal(dem_dot(s->ax.fn + 3, d)) + s->ax.bh[2] * PetscAbsReal(dem_dot(s->ax.fn + 6, d));
  return dem_extent(s->cvx, d);
}

/* Body i at the origin, body j at d: are they apart along the world axis u (either sense)? */
static inline PetscBool dem_apart(const DemBody *bi, const DemBody *bj, const double d[3], const double u[3])
{
  const double  du = dem_dot(d, u), s = du >= 0 ? 1.0 : -1.0;
  const double *Ri = bi->R, *Rj = bj->R;
  double        ui[3], uj[3];
  for (int k = 0; k < 3; k++) { /* R^T (s u) and R^T (-s u) */
    ui[k] = s * (Ri[k] * u[0] + Ri[3 + k] * u[1] + Ri[6 + k] * u[2]);
    uj[k] = -s * (Rj[k] * u[0] + Rj[3 + k] * u[1] + Rj[6 + k] * u[2]);
  }
  return (PetscBool)(s * du > dem_shape_extent(bi->s, ui) + dem_shape_extent(bj->s, uj));
}

static inline void dem_rotation(const double *q, double *R)
{
  const double w = q[0], x = q[1], y = q[2], z = q[3];
  R[0] = 1 - 2 * (y * y + z * z), R[1] = 2 * (x * y - w * z), R[2] = 2 * (x * z + w * y);
  R[3] = 2 * (x * y + w * z), R[4] = 1 - 2 * (x * x + z * z), R[5] = 2 * (y * z - w * x);
  R[6] = 2 * (x * z - w * y), R[7] = 2 * (y * z + w * x), R[8] = 1 - 2 * (x * x + y * y);
}

static inline PetscBool dem_sat_pair(const Dem dem, const DemShape *si, const DemShape *sj)
{
  return (PetscBool)(dem->narrow.convex_sat && si->ax.nfn > 0 && sj->ax.nfn > 0 && si->ax.nfn + sj->ax.nfn + si->ax.nen * sj->ax.nen <= dem->narrow.convex_sat_axes);
}

/* Least overlap of i (at the origin) and j (at d) along the unit world axis u: returns it, and
 * in n the axis oriented from i to j. */
static inline double dem_sat_overlap(const DemBody *bi, const DemBody *bj, const double d[3], const double u[3], double n[3])
{
  const double  du = dem_dot(d, u), s = du >= 0 ? 1.0 : -1.0;
  const double *Ri = bi->R, *Rj = bj->R;
  double        ui[3], uj[3];
  for (int k = 0; k < 3; k++) {
    n[k]  = s * u[k];
    ui[k] = s * (Ri[k] * u[0] + Ri[3 + k] * u[1] + Ri[6 + k] * u[2]);
    uj[k] = -s * (Rj[k] * u[0] + Rj[3 + k] * u[1] + Rj[6 + k] * u[2]);
  }
  return dem_shape_extent(bi->s, ui) + dem_shape_extent(bj->s, uj) - s * du;
}

/* One candidate axis a (unit, world): PETSC_TRUE when it separates the pair (u = a); otherwise
 * m keeps the least overlap so far and its axis oriented from i to j. */
static inline PetscBool dem_sat_axis(const DemBody *bi, const DemBody *bj, const double d[3], const double a[3], ConvexSatMin *m, double u[3])
{
  double       n[3];
  const double ov = dem_sat_overlap(bi, bj, d, a, n);
  if (ov < 0) {
    for (int k = 0; k < 3; k++) u[k] = a[k];
    return PETSC_TRUE;
  }
  if (ov < m->depth) {
    m->depth = ov;
    for (int k = 0; k < 3; k++) m->n[k] = n[k];
  }
  return PETSC_FALSE;
}

/* Separating-axis test of two polyhedra over the face normals of both and the cross products of
 * their edge directions (the complete candidate set): PETSC_FALSE with the separating axis in u,
 * or PETSC_TRUE with the least overlap and its axis (i to j) in m. After libccd found no contact
 * it also finds the axis the cache keeps (u = 0 if rounding left none). */
static PetscBool dem_sat(const DemBody *bi, const DemBody *bj, const double d[3], ConvexSatMin *m, double u[3])
{
  const DemBody  *b2[2] = {bi, bj};
  const double   *Ri = bi->R, *Rj = bj->R;
  const DemShape *si = bi->s, *sj = bj->s;
  double          a[3];
  m->depth = PETSC_MAX_REAL;
  if (si->ax.box && sj->ax.box) { /* the same axes in closed form (geom/sat_box.c) */
    const ConvexSatBody gi = {&si->ax, Ri}, gj = {&sj->ax, Rj};
    return ConvexSatBox(&gi, &gj, d, m, u);
  }
  for (int b = 0; b < 2; b++)
    for (PetscInt f = 0; f < b2[b]->s->ax.nfn; f++) {
      const double *fn = b2[b]->s->ax.fn + 3 * f, *R = b2[b]->R;
      for (int k = 0; k < 3; k++) a[k] = R[3 * k] * fn[0] + R[3 * k + 1] * fn[1] + R[3 * k + 2] * fn[2];
      if (dem_sat_axis(bi, bj, d, a, m, u)) return PETSC_FALSE;
    }
  for (PetscInt e = 0; e < si->ax.nen; e++) {
    double ei[3], ej[3];
    for (int k = 0; k < 3; k++) ei[k] = Ri[3 * k] * si->ax.en[3 * e] + Ri[3 * k + 1] * si->ax.en[3 * e + 1] + Ri[3 * k + 2] * si->ax.en[3 * e + 2];
    for (PetscInt g = 0; g < sj->ax.nen; g++) {
      for (int k = 0; k < 3; k++) ej[k] = Rj[3 * k] * sj->ax.en[3 * g] + Rj[3 * k + 1] * sj->ax.en[3 * g + 1] + Rj[3 * k + 2] * sj->ax.en[3 * g + 2];
      dem_cross(ei, ej, a);
      const double l2 = dem_dot(a, a);
      if (l2 < 1e-12) continue; /* parallel edges: the face axes cover them */
      const double il = 1 / sqrt(l2);
      for (int k = 0; k < 3; k++) a[k] *= il;
      if (dem_sat_axis(bi, bj, d, a, m, u)) return PETSC_FALSE;
    }
  }
  u[0] = u[1] = u[2] = 0;
  return PETSC_TRUE;
}

/* Particle i as a body of the pair tests, its rotation matrix in R (9). */
static inline void dem_body(const Dem dem, PetscInt i, const double *R, DemBody *b)
{
  b->s = &dem->shapes.shp[dem->p.shape[i]];
  b->x = dem->p.x + 3 * i;
  b->q = dem->p.q + 4 * i;
  b->R = R;
}

static inline ConvexBody dem_convex_body(const DemBody *b)
{
  ConvexBody c = {.s = b->s->cvx};
  for (int k = 0; k < 3; k++) c.x[k] = b->x[k];
  for (int k = 0; k < 9; k++) c.R[k] = b->R[k];
  return c;
}

/* The narrow phase of one pair whose bounding spheres overlap, d = x_j - x_i. u: the pair's
 * cache entry (updated): u[0..2] a separating axis (0: none), u[3] = 1 if the pair touched at
 * the last step; NULL for none. A pair of the separating-axis test that touched skips the
 * centre-line probe (it usually fails, and the test is complete without it: the same answer);
 * a pair left to MPR always takes it, as the statistics do. The forces and the statistics
 * (convex_diag.c) both call it, so the elastic energy is that of the depth the forces used. */
static PetscErrorCode dem_convex_narrow(const Dem dem, const DemBody *bi, const DemBody *bj, const double d[3], double *u, ConvexContact *c)
{
  double       none[4] = {0, 0, 0, 0};
  ConvexSatMin m;

  PetscFunctionBeginUser;
  if (!u) u = none;
  c->overlap          = PETSC_FALSE;
  const PetscBool sat = dem_sat_pair(dem, bi->s, bj->s);
  if (u[3] == 0 || !sat) {
    if ((u[0] != 0 || u[1] != 0 || u[2] != 0) && dem_apart(bi, bj, d, u)) PetscFunctionReturn(PETSC_SUCCESS);
    if (dem_apart(bi, bj, d, d)) {
      for (int k = 0; k < 3; k++) u[k] = d[k];
      PetscFunctionReturn(PETSC_SUCCESS);
    }
  }
  u[3] = 0;
  if (sat) {
    if (!dem_sat(bi, bj, d, &m, u)) PetscFunctionReturn(PETSC_SUCCESS); /* u: the separating axis found */
    if (m.depth > 0) {
      const ConvexBody A = dem_convex_body(bi), B = dem_convex_body(bj);
      if (ConvexBodiesContactPoint(&A, &B, m.n, m.depth, dem->narrow.convex_point, c)) {
        u[3] = 1;
        PetscFunctionReturn(PETSC_SUCCESS);
      }
    }
    /* touching at 0 depth, or no supporting feature: MPR below (u is 0) */
  }
  const ConvexPose pi = DemPose(bi->x, bi->q), pj = DemPose(bj->x, bj->q);
  PetscCall(ConvexCollideWith(bi->s->cvx, &pi, bj->s->cvx, &pj, dem->narrow.convex_point, c)); /* MPR's depth and normal */
  if (c->overlap) u[0] = u[1] = u[2] = 0, u[3] = 1;
  else if (!sat) (void)dem_sat(bi, bj, d, &m, u); /* the axis to keep, or u = 0 */
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Contact of the pair (i, j) for the statistics: the narrow phase of the forces, no cache. */
PetscErrorCode DemConvexPairContact(Dem dem, PetscInt i, PetscInt j, ConvexContact *c)
{
  const DemShape *si = &dem->shapes.shp[dem->p.shape[i]], *sj = &dem->shapes.shp[dem->p.shape[j]];
  const double    rs   = si->r + sj->r;
  const double    d[3] = {dem->p.x[3 * j] - dem->p.x[3 * i], dem->p.x[3 * j + 1] - dem->p.x[3 * i + 1], dem->p.x[3 * j + 2] - dem->p.x[3 * i + 2]};
  double          Ri[9], Rj[9];
  DemBody         bi, bj;

  PetscFunctionBeginUser;
  c->overlap = PETSC_FALSE;
  if (dem_dot(d, d) >= rs * rs) PetscFunctionReturn(PETSC_SUCCESS);
  dem_rotation(dem->p.q + 4 * i, Ri);
  dem_rotation(dem->p.q + 4 * j, Rj);
  dem_body(dem, i, Ri, &bi);
  dem_body(dem, j, Rj, &bj);
  PetscCall(dem_convex_narrow(dem, &bi, &bj, d, NULL, c));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The rotation matrices of the particles, local and ghost, for one pass of the pair loop:
 * room for all (dem->narrow.rot), each formed when a pair first needs it (a particle whose stamp is
 * not this pass's), so a dilute scene forms few; when the last pass had at least half as many
 * pairs with overlapping bounding spheres as particles, all are formed at once (a dense bed: a
 * sequential sweep, measured 4% faster on the settled icosahedra than forming them on demand). */
static PetscErrorCode dem_rotations_begin(Dem dem)
{
  const PetscInt nt = dem->p.n + dem->p.ng;

  PetscFunctionBeginUser;
  if (nt > dem->narrow.rot_cap) {
    PetscCall(PetscFree2(dem->narrow.rot, dem->narrow.rot_stamp));
    dem->narrow.rot_cap = nt + nt / 4 + 64;
    PetscCall(PetscMalloc2(9 * (size_t)dem->narrow.rot_cap, &dem->narrow.rot, dem->narrow.rot_cap, &dem->narrow.rot_stamp));
    dem->narrow.rot_pass = PETSC_MAX_INT - 1; /* the stamps are reset below */
  }
  if (++dem->narrow.rot_pass == PETSC_MAX_INT) {
    for (PetscInt i = 0; i < dem->narrow.rot_cap; i++) dem->narrow.rot_stamp[i] = -1;
    dem->narrow.rot_pass = 0;
  }
  if (2 * dem->narrow.rot_pairs >= nt)
    for (PetscInt i = 0; i < nt; i++) {
      dem_rotation(dem->p.q + 4 * i, dem->narrow.rot + 9 * i);
      dem->narrow.rot_stamp[i] = dem->narrow.rot_pass;
    }
  PetscFunctionReturn(PETSC_SUCCESS);
}

static inline const double *dem_rot(Dem dem, PetscInt i)
{
  if (dem->narrow.rot_stamp[i] != dem->narrow.rot_pass) {
    dem_rotation(dem->p.q + 4 * i, dem->narrow.rot + 9 * i);
    dem->narrow.rot_stamp[i] = dem->narrow.rot_pass;
  }
  return dem->narrow.rot + 9 * i;
}

PetscErrorCode DemContactsPairsConvex(Dem dem)
{
  const DemNeigh *nl = &dem->nl;
  double         *f = dem->p.f, *tq = dem->p.tq, *hist = nl->hist, *ax;
  DemConvexIn     in    = {.law = dem->contact.law, .dt = dem->clock.dt};
  PetscInt        pairs = 0; /* with overlapping bounding spheres: the next pass's choice */

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(DEM_Contacts, 0, 0, 0, 0));
  if (!dem->narrow.sepax || dem->narrow.sepax_build != nl->builds) { /* a new list: a new, empty cache */
    PetscCall(PetscFree(dem->narrow.sepax));
    PetscCall(PetscCalloc1(4 * (size_t)nl->start[dem->p.n] + 4, &dem->narrow.sepax));
    dem->narrow.sepax_build = nl->builds;
  }
  ax = dem->narrow.sepax;
  PetscCall(dem_rotations_begin(dem));
  for (PetscInt i = 0; i < dem->p.n; i++) {
    const DemShape *si = &dem->shapes.shp[dem->p.shape[i]];
    DemBody         bi, bj;
    double          fi[3] = {0, 0, 0}, ti[3] = {0, 0, 0};
    PetscBool       has_i = PETSC_FALSE;
    in.xi                 = dem->p.x + 3 * i;
    in.vi                 = dem->p.v + 3 * i;
    in.wi                 = dem->p.w + 3 * i;
    for (PetscInt a = nl->start[i]; a < nl->start[i + 1]; a++) {
      const PetscInt  j    = nl->nbr[a];
      const DemShape *sj   = &dem->shapes.shp[dem->p.shape[j]];
      const double    rs   = si->r + sj->r;
      const double    d[3] = {dem->p.x[3 * j] - in.xi[0], dem->p.x[3 * j + 1] - in.xi[1], dem->p.x[3 * j + 2] - in.xi[2]};
      double         *xi_t = hist ? hist + 3 * a : NULL;
      ConvexContact   c;
      double          F[3], Ti[3], Tj[3];
      if (dem_dot(d, d) >= rs * rs) { /* bounding spheres apart: libccd is not called */
        if (xi_t) xi_t[0] = xi_t[1] = xi_t[2] = 0;
        continue;
      }
      pairs++;
      if (!has_i) {
        dem_body(dem, i, dem_rot(dem, i), &bi);
        has_i = PETSC_TRUE;
      }
      dem_body(dem, j, dem_rot(dem, j), &bj);
      PetscCall(dem_convex_narrow(dem, &bi, &bj, d, ax + 4 * a, &c));
      if (!c.overlap) {
        if (xi_t) xi_t[0] = xi_t[1] = xi_t[2] = 0;
        continue;
      }
      in.p  = dem->contact.pp + dem->p.shape[i] * dem->shapes.nshape + dem->p.shape[j];
      in.c  = &c;
      in.xj = dem->p.x + 3 * j;
      in.vj = dem->p.v + 3 * j;
      in.wj = dem->p.w + 3 * j;
      dem_convex_force(&in, xi_t, F, Ti, Tj);
      for (int k = 0; k < 3; k++) {
        fi[k] += F[k];
        ti[k] += Ti[k];
      }
      if (!dem->nl.full_list && j < dem->p.n) /* a ghost's rank (or the full list) computes j's side */
        for (int k = 0; k < 3; k++) {
          f[3 * j + k] -= F[k];
          tq[3 * j + k] += Tj[k];
        }
    }
    for (int k = 0; k < 3; k++) {
      f[3 * i + k] += fi[k];
      tq[3 * i + k] += ti[k];
    }
  }
  dem->narrow.rot_pairs = pairs;
  PetscCall(PetscLogEventEnd(DEM_Contacts, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemContactsWallsConvex(Dem dem)
{
  static const double zero[3] = {0, 0, 0};
  DemConvexIn         in      = {.law = dem->contact.law, .dt = dem->clock.dt, .wj = zero};

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(DEM_Walls, 0, 0, 0, 0));
  for (PetscInt wi = 0; wi < dem->walls.nwall; wi++) {
    DemWall      *w = &dem->walls.wall[wi];
    DemPairParams pwl;
    in.xj = w->s.p;
    in.vj = w->s.v;
    for (PetscInt a = 0; a < w->cnt; a++) {
      const PetscInt i    = w->idx[a];
      double        *xi_t = dem->contact.law != DEM_LAW_LINEAR_NOHIST ? w->hist + 3 * a : NULL;
      const double  *x    = dem->p.x + 3 * i;
      ConvexPose     pose = DemPose(x, dem->p.q + 4 * i);
      ConvexContact  c;
      double         F[3], Ti[3], Tj[3];
      PetscCall(ConvexCollidePlane(dem->shapes.shp[dem->p.shape[i]].cvx, &pose, w->s.p, w->s.n, &c));
      if (!c.overlap || !DemWallCovers(w, c.point, x)) {
        if (xi_t) xi_t[0] = xi_t[1] = xi_t[2] = 0;
        continue;
      }
      in.p  = DemWallParams(&dem->contact, w, dem->p.shape[i], &pwl);
      in.c  = &c;
      in.xi = dem->p.x + 3 * i;
      in.vi = dem->p.v + 3 * i;
      in.wi = dem->p.w + 3 * i;
      dem_convex_force(&in, xi_t, F, Ti, Tj);
      for (int k = 0; k < 3; k++) {
        dem->p.f[3 * i + k] += F[k];
        dem->p.tq[3 * i + k] += Ti[k];
      }
    }
  }
  PetscCall(PetscLogEventEnd(DEM_Walls, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Not collective. The meshes' forces and torques on the local convex particles (the face rule of
 * DemMeshTouchConvex, walls_mesh.c); the springs in the mesh's slots, matched by normal as for
 * spheres; the surface velocity of the mesh's rigid motion at the contact point. */
PetscErrorCode DemContactsMeshesConvex(Dem dem)
{
  static const double zero[3] = {0, 0, 0};
  DemConvexIn         in      = {.law = dem->contact.law, .dt = dem->clock.dt, .wj = zero};

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(DEM_Walls, 0, 0, 0, 0));
  for (PetscInt k = 0; k < dem->meshes.n; k++) {
    DemMesh     *m      = &dem->meshes.m[k];
    const double axp[3] = {m->ax_p[0] + m->vel[0] * m->tpose, m->ax_p[1] + m->vel[1] * m->tpose, m->ax_p[2] + m->vel[2] * m->tpose};
    if (!m->cstart) continue;
    for (PetscInt i = 0; i < dem->p.n; i++) {
      ConvexContact cc[DEM_MESH_MAXC];
      double        an[DEM_MESH_MAXC][3], *sl = m->slot ? m->slot + 6 * DEM_MESH_SLOTS * i : NULL;
      int           na, match[DEM_MESH_MAXC];
      if (m->cstart[i] == m->cstart[i + 1]) continue;
      PetscCall(DemMeshTouchConvex(dem, m, i, cc, &na));
      for (int a = 0; a < na; a++)
        for (int j = 0; j < 3; j++) an[a][j] = cc[a].normal[j];
      if (sl) DemMeshMatchSlots(sl, na, an, match);
      in.p  = &m->pw[dem->p.shape[i]];
      in.xi = dem->p.x + 3 * i;
      in.vi = dem->p.v + 3 * i;
      in.wi = dem->p.w + 3 * i;
      for (int a = 0; a < na; a++) {
        double vw[3], d[3], none[3] = {0, 0, 0}, *xi_t = NULL, F[3], Ti[3], Tj[3];
        if (sl && match[a] >= 0) {
          xi_t = sl + 6 * match[a] + 3;
          for (int j = 0; j < 3; j++) sl[6 * match[a] + j] = an[a][j];
        } else if (sl) xi_t = none; /* more contacts than slots: this one without history */
        for (int j = 0; j < 3; j++) d[j] = cc[a].point[j] - axp[j];
        dem_cross(m->ax_u, d, vw);
        for (int j = 0; j < 3; j++) vw[j] = m->vel[j] + m->w_now * vw[j];
        in.c  = &cc[a];
        in.xj = cc[a].point; /* a partner without spin: only its velocity enters */
        in.vj = vw;
        dem_convex_force(&in, xi_t, F, Ti, Tj);
        for (int j = 0; j < 3; j++) {
          dem->p.f[3 * i + j] += F[j];
          dem->p.tq[3 * i + j] += Ti[j];
        }
      }
    }
  }
  PetscCall(PetscLogEventEnd(DEM_Walls, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}
