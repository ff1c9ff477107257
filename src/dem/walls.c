/* Walls: the store and the sphere contacts. A wall is an infinite plane given by a point p and a
 * unit normal n pointing into the granular side, optionally translating at a constant velocity;
 * or a finite rectangle, a convex polygon (walls_polygon.c), a cylinder with particles inside,
 * rotating about its axis (walls_cylinder.c). The options that make them are read in
 * walls_options.c, which calls the readers of those files; they add walls here (DemWallAdd).
 * A sphere touches a wall when its overlap (dem_walls.h: dem_wall_sphere; each kind's kernels, written
 * once, are in geom/surface_<kind>.h) is positive: for a plane r - (x - p).n; for a cylinder r + |rho| - R. The contact uses the same kernels as a
 * particle pair, with the wall as a partner of infinite mass and radius (m* = m, R* = r) whose
 * surface velocity at the contact point c is v + omega u x (c - a) (dem_wall_velocity: a
 * translating plane, a rotating drum), so a moving wall drags particles by friction. Each wall
 * keeps a list of the particles within r + skin, rebuilt with the Verlet list, and their
 * tangential springs. A plane may be removed at a time (-dem_plane_<k>_remove_time: a silo's
 * plate under the orifice): from the step whose forces act at that time on (dem.c, DemStep) it
 * has no list, no contacts and no travel (removed). Rolling resistance against a wall takes
 * w_rel = w_i - omega u (a turning drum's angular velocity; 0 for the other walls).
 * Edges: a rectangle or a polygon is touched only where the sphere's centre (the contact point)
 * projects inside it and lies in front of it; a sphere overhanging a joint edge feels no force
 * from that face (the neighbouring face takes over, as in a box corner or a hopper's corners).
 * Only edges marked as free rims (the hopper's orifice) are touched as segments. At most
 * DEM_MAX_WALLS walls in all. A wall's list keeps the particles its kind's gap puts within reach
 * (surface_near). A domain face is closed (DemWallsCloseFace) by a wall whose kind says so
 * (surface_closes_face: at the face or inside before it), or by a mesh at rest whose triangles
 * tile the face itself. */
#include "dem/dem_core.h"
#include "dem/dem_walls.h"

/* Adds a plane wall; name is the option that made it (messages name the wall by it). */
PetscErrorCode DemWallAdd(Dem dem, const char *name, const double p[3], const double n[3], const double v[3])
{
  DemWall *w;
  double   nn = sqrt(dem_dot(n, n));

  PetscFunctionBeginUser;
  PetscCheck(dem->walls.nwall < DEM_MAX_WALLS, dem->comm, PETSC_ERR_ARG_OUTOFRANGE, "at most %d walls", DEM_MAX_WALLS);
  PetscCheck(nn > 0, dem->comm, PETSC_ERR_ARG_OUTOFRANGE, "wall %" PetscInt_FMT ": the normal must be non-zero", dem->walls.nwall);
  w = &dem->walls.wall[dem->walls.nwall++];
  PetscCall(PetscMemzero(w, sizeof *w));
  w->mu       = -1;             /* the wall material's friction */
  w->t_remove = PETSC_MAX_REAL; /* never removed */
  w->fluid    = -1;             /* the kind's default (vessel.c) */
  PetscCall(PetscStrncpy(w->name, name, sizeof w->name));
  for (int k = 0; k < 3; k++) {
    w->s.p[k] = p[k];
    w->s.n[k] = n[k] / nn;
    w->s.v[k] = v[k];
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Per-wall friction override: n values for walls first.. (a box: xlo,ylo,zlo,xhi,yhi,zhi).
 * Called inside the walls' options block. */
PetscErrorCode DemWallFrictionOption(PetscOptionItems *PetscOptionsObject, Dem dem, const char *opt, PetscInt n, PetscInt first)
{
  PetscReal mu[6];
  PetscBool set;

  PetscFunctionBeginUser;
  PetscCheck(n >= 1 && n <= 6, dem->comm, PETSC_ERR_PLIB, "%s: %" PetscInt_FMT " walls, at most 6", opt, n);
  for (int k = 0; k < 6; k++) mu[k] = dem->contact.wmat.mu; /* the default -help shows */
  /* exactly n values (another count is an error naming the option); the sign checked below */
  PetscCall(SableOptionsRealN(opt, "Friction coefficient of this wall, overriding -dem_wall_friction (box: xlo,ylo,zlo,xhi,yhi,zhi)", NULL, mu, n, n, &set));
  if (!set || first < 0) PetscFunctionReturn(PETSC_SUCCESS); /* first < 0: -help lists it, no wall */
  for (PetscInt k = 0; k < n; k++) {
    PetscCheck(mu[k] >= 0, dem->comm, PETSC_ERR_ARG_OUTOFRANGE, "%s %g must be >= 0", opt, (double)mu[k]);
    /* box walls were added as xlo, xhi, ylo, yhi, zlo, zhi */
    dem->walls.wall[first + (n == 6 ? 2 * (k % 3) + k / 3 : k)].mu = mu[k];
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemWallsCloseFace(Dem dem, int d, int side, PetscBool *closed)
{
  const Domain *dom = dem->dom;
  const int     a = (d + 1) % 3, b = (d + 2) % 3;
  const double  tol = 1e-9 * PetscMax(dom->len[0], PetscMax(dom->len[1], dom->len[2]));
  double        c[4][3]; /* the face's corners */

  PetscFunctionBeginUser;
  for (int q = 0; q < 4; q++) {
    c[q][d] = side ? dom->hi[d] : dom->lo[d];
    c[q][a] = q & 1 ? dom->hi[a] : dom->lo[a];
    c[q][b] = q & 2 ? dom->hi[b] : dom->lo[b];
  }
  *closed = PETSC_FALSE;
  for (PetscInt wi = 0; wi < dem->walls.nwall && !*closed; wi++) {
    const DemWall *w = &dem->walls.wall[wi];
    if (w->t_remove < PETSC_MAX_REAL) continue; /* a gate that opens closes nothing */
    *closed = surface_closes_face(&w->s, d, side, (const double(*)[3])c, tol);
  }
  if (!*closed && dem->meshes.n) PetscCall(DemMeshesCloseFace(dem, d, side, tol, closed)); /* walls_mesh.c */
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Lists of the local particles within r + skin of each wall; springs restored from the id-keyed
 * records (partner = -1 - wall index). */
PetscErrorCode DemWallsBuildLists(DemWalls *walls, const DemParticles *pt, const DemShapeTable *st, double skin, const DemSpring *recs, PetscInt nrec)
{
  PetscFunctionBeginUser;
  for (PetscInt wi = 0; wi < walls->nwall; wi++) {
    DemWall *w = &walls->wall[wi];
    w->cnt     = 0;
    for (PetscInt i = 0; i < pt->n && !w->removed; i++) {
      if (!surface_near(&w->s, pt->x + 3 * i, DemRadius(pt, st, i) + skin, skin)) continue;
      if (w->cnt == w->cap) {
        w->cap = 2 * w->cap + 256;
        PetscCall(PetscRealloc(sizeof(PetscInt) * (size_t)w->cap, &w->idx));
        PetscCall(PetscRealloc(3 * sizeof(double) * (size_t)w->cap, &w->hist));
      }
      const DemSpring *r = nrec ? DemSpringFind(recs, nrec, pt->id[i], -1 - wi) : NULL;
      w->idx[w->cnt]     = i;
      for (int k = 0; k < 3; k++) w->hist[3 * w->cnt + k] = r ? r->xi[k] : 0;
      w->cnt++;
    }
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The walls' contact forces on the spheres (DemStep has moved the walls): adds to f and tq of the
 * particles in the wall lists, advances or resets the walls' springs; reads x, v, w, the radii
 * and the contact model. */
static inline void dem_walls_body(DemParticles *pt, const double *rad, const DemContactModel *cm, DemWalls *walls, double dt, const PetscBool poly)
{
  for (PetscInt wi = 0; wi < walls->nwall; wi++) {
    DemWall      *w = &walls->wall[wi];
    DemPairParams pwl;
    for (PetscInt a = 0; a < w->cnt; a++) {
      const PetscInt       i  = w->idx[a];
      const double        *xi = pt->x + 3 * i;
      const double         r  = poly ? pt->rad[i] : rad[pt->shape[i]];
      double               nrm[3]; /* from the particle to the wall */
      const double         delta = dem_wall_sphere(w, xi, r, nrm);
      double              *xi_t  = cm->law != DEM_LAW_LINEAR_NOHIST ? w->hist + 3 * a : NULL;
      const DemPairParams *p     = DemWallParams(cm, w, pt->shape[i], &pwl);
      DemPairParams        sized;
      if (poly && delta > 0) { /* m* = m, R* = r of the sphere */
        dem_pair_sized(cm->law, p, pt->m[i], r, 0, 0, &sized);
        p = &sized;
      }
      if (delta <= 0) {
        if (xi_t) xi_t[0] = xi_t[1] = xi_t[2] = 0;
        continue;
      }
      const double l     = r - 0.5 * delta;
      const double pc[3] = {xi[0] + l * nrm[0], xi[1] + l * nrm[1], xi[2] + l * nrm[2]}; /* contact point */
      const double ww[3] = {w->s.omega * w->s.ax_u[0], w->s.omega * w->s.ax_u[1], w->s.omega * w->s.ax_u[2]};
      double       vw[3];
      dem_wall_velocity(w, pc, vw);
      dem_sphere_wall_force(pt, i, r, delta, nrm, vw, ww, p, cm, poly ? dem_pair_inertia(pt->m[i], r, 0, 0) : p->ieff, xi_t, dt);
    }
  }
}

PetscErrorCode DemContactsWalls(DemParticles *pt, const DemShapeTable *st, const DemContactModel *cm, DemWalls *walls, double dt)
{
  double rad[DEM_MAX_SHAPES]; /* the radii, side by side (as in the pair loop) */

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(DEM_Walls, 0, 0, 0, 0));
  for (PetscInt s = 0; s < st->nshape; s++) rad[s] = st->shp[s].r;
  if (pt->rad) dem_walls_body(pt, rad, cm, walls, dt, PETSC_TRUE); /* spheres of their own sizes */
  else dem_walls_body(pt, rad, cm, walls, dt, PETSC_FALSE);
  PetscCall(PetscLogEventEnd(DEM_Walls, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}
