/* Diagnostics and output of convex particles.
 * Statistics: translational energy 1/2 m v^2, rotational energy 1/2 W.(J W) with W = R^T w the
 * body-frame spin, gravity, and for every touching pair or wall contact (narrow phase as in
 * convex_contacts.c) the elastic energy of the law (linear 1/2 kn delta^2 + 1/2 kt |xi|^2, hertz
 * 8/15 E* sqrt(R*) delta^(5/2)) and the overlap over the equivalent radius d_eq/2.
 * Output: besides the per-particle arrays (position, quaternion, ...), every particle's surface
 * in the world frame, x + R v for the shape's hull vertices v, as one triangle mesh that ParaView
 * draws directly (XDMF grid "surface"; a cylinder is drawn as a 24-sided prism). */
#include "dem/dem_core.h"
#include "dem/dem_walls.h"
#include "geom/quat.h"

#define DEM_CYL_SIDES 24

static double dem_elastic(const Dem dem, const DemPairParams *p, double delta, const double *xi)
{
  double e = dem->contact.law == DEM_LAW_HERTZ ? 8.0 / 15.0 * p->es * sqrt(p->reff) * pow(delta, 2.5) : 0.5 * p->kn * delta * delta;
  if (xi && dem->contact.law == DEM_LAW_LINEAR) e += 0.5 * p->kt * dem_dot(xi, xi);
  return e;
}

/* r: ke, ke_rot, pe_grav, pe_spring, checksum (added to); c[1], c[2]: pair and wall contacts. */
PetscErrorCode DemConvexStatsLocal(Dem dem, double r[5], PetscInt c[3], double *rmax)
{
  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < dem->p.n; i++) {
    const DemShape *s = &dem->shapes.shp[dem->p.shape[i]];
    double          R[9], wb[3];
    convex_quat_to_matrix(dem->p.q + 4 * i, R);
    convex_mat_tvec(R, dem->p.w + 3 * i, wb);
    r[0] += 0.5 * s->m * dem_dot(dem->p.v + 3 * i, dem->p.v + 3 * i);
    for (int k = 0; k < 3; k++) r[1] += 0.5 * s->J[k] * wb[k] * wb[k];
    r[2] -= s->m * dem_dot(dem->g, dem->p.x + 3 * i);
    r[4] += (double)dem->p.id[i];
    for (PetscInt a = dem->nl.start[i]; a < dem->nl.start[i + 1]; a++) {
      const PetscInt  j = dem->nl.nbr[a];
      const DemShape *t = &dem->shapes.shp[dem->p.shape[j]];
      ConvexContact   cc;
      PetscCall(DemConvexPairContact(dem, i, j, &cc));
      if (!cc.overlap) continue;
      /* a pair seen from both sides (full list, or a ghost partner) counts half on each */
      const PetscBool both = (PetscBool)(dem->nl.full_list || j >= dem->p.n);
      if (!both || dem->p.id[i] < dem->p.id[j]) c[1]++;
      r[3] += (both ? 0.5 : 1.0) * dem_elastic(dem, &dem->contact.pp[dem->p.shape[i] * dem->shapes.nshape + dem->p.shape[j]], cc.depth, dem->nl.hist ? dem->nl.hist + 3 * a : NULL);
      *rmax = PetscMax(*rmax, cc.depth / PetscMin(s->req, t->req));
    }
  }
  for (PetscInt w = 0; w < dem->walls.nwall; w++) {
    const DemWall *wl = &dem->walls.wall[w];
    for (PetscInt a = 0; a < wl->cnt; a++) {
      const PetscInt   i  = wl->idx[a];
      const DemShape  *s  = &dem->shapes.shp[dem->p.shape[i]];
      const ConvexPose pi = DemPose(dem->p.x + 3 * i, dem->p.q + 4 * i);
      ConvexContact    cc;
      PetscCall(ConvexCollidePlane(s->cvx, &pi, wl->s.p, wl->s.n, &cc));
      if (!cc.overlap || !DemWallCovers(wl, cc.point, pi.x)) continue;
      c[2]++;
      r[3] += dem_elastic(dem, &dem->contact.pw[dem->p.shape[i]], cc.depth, dem->contact.law != DEM_LAW_LINEAR_NOHIST ? wl->hist + 3 * a : NULL);
      *rmax = PetscMax(*rmax, cc.depth / s->req);
    }
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The drawing mesh of a shape (body frame): its hull, or a prism for a cylinder. */
static void dem_draw_mesh(const ConvexShape *c, PetscInt *nv, const double **v, PetscInt *nf, const PetscInt **f, double *cv, PetscInt *cf)
{
  if (c->kind == CONVEX_POLYHEDRON) {
    *nv = c->nv, *v = c->v, *nf = c->nf, *f = c->f;
    return;
  }
  const int m = DEM_CYL_SIDES;
  for (int k = 0; k < m; k++) {
    const double a = 2 * PETSC_PI * k / m;
    for (int e = 0; e < 2; e++) {
      cv[3 * (2 * k + e)]     = c->radius * cos(a);
      cv[3 * (2 * k + e) + 1] = c->radius * sin(a);
      cv[3 * (2 * k + e) + 2] = (e ? 0.5 : -0.5) * c->height;
    }
  }
  PetscInt t = 0;
  for (int k = 0; k < m; k++) { /* side quads: two triangles each */
    const PetscInt a0 = 2 * k, a1 = 2 * k + 1, b0 = 2 * ((k + 1) % m), b1 = b0 + 1;
    const PetscInt tri[6] = {a0, b0, b1, a0, b1, a1};
    for (int e = 0; e < 6; e++) cf[t++] = tri[e];
  }
  for (int k = 1; k + 1 < m; k++) { /* caps: fans */
    const PetscInt bot[3] = {0, 2 * (k + 1), 2 * k}, top[3] = {1, 2 * k + 1, 2 * (k + 1) + 1};
    for (int e = 0; e < 3; e++) cf[t++] = bot[e];
    for (int e = 0; e < 3; e++) cf[t++] = top[e];
  }
  *nv = 2 * m, *v = cv, *nf = t / 3, *f = cf;
}

PetscErrorCode DemConvexWriteSurface(Dem dem, const double *x, Io io)
{
  double          cv[6 * DEM_CYL_SIDES], *xyz;
  PetscInt        cf[12 * DEM_CYL_SIDES], np = 0, nt = 0, *tri, *pid;
  PetscInt        nv, nf;
  const double   *v;
  const PetscInt *f;

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < dem->p.n; i++) {
    dem_draw_mesh(dem->shapes.shp[dem->p.shape[i]].cvx, &nv, &v, &nf, &f, cv, cf);
    np += nv;
    nt += nf;
  }
  PetscCall(PetscMalloc3(3 * np + 3, &xyz, np + 1, &pid, 3 * nt + 3, &tri));
  np = nt = 0;
  for (PetscInt i = 0; i < dem->p.n; i++) {
    double R[9];
    dem_draw_mesh(dem->shapes.shp[dem->p.shape[i]].cvx, &nv, &v, &nf, &f, cv, cf);
    convex_quat_to_matrix(dem->p.q + 4 * i, R);
    for (PetscInt a = 0; a < nf; a++)
      for (int k = 0; k < 3; k++) tri[3 * (nt + a) + k] = np + f[3 * a + k];
    for (PetscInt a = 0; a < nv; a++) {
      convex_mat_vec(R, v + 3 * a, xyz + 3 * (np + a));
      for (int k = 0; k < 3; k++) xyz[3 * (np + a) + k] += x[3 * i + k];
      pid[np + a] = dem->p.id[i];
    }
    np += nv;
    nt += nf;
  }
  PetscCall(IoWriteSurface(io, np, xyz, pid, nt, tri));
  PetscCall(PetscFree3(xyz, pid, tri));
  PetscFunctionReturn(PETSC_SUCCESS);
}
