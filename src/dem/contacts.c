/* Particle-particle contact forces over the half Verlet list (each pair once; Newton's third
 * law adds the opposite force to a local partner; in the full list (-dem_deterministic) and for
 * ghost partners only the row particle receives its force, the partner's rank computes the
 * other half). Every expression is antisymmetric under exchanging i and j, so both sides of a
 * pair computed on two ranks get exactly opposite forces. Spheres: n = (x_j - x_i)/|x_j - x_i|, overlap
 * delta = r_i + r_j - |x_j - x_i|, contact point at r_i - delta/2 from i along n. The spring of
 * a pair that is not touching is reset to zero (a new contact starts unloaded). Torques only
 * when the scene has friction (dem->rotation).
 * Speed (the pair loop is most of a dense step): a scene of one shape reads its radius and pair
 * parameters once, not per pair; the arrays are restrict-qualified so that the row
 * particle's state and sums stay in registers. The arithmetic is the same, expression by expression, so
 * the forces are bitwise those of the general path. */
#include "dem/dem_impl.h"

/* Rows 0..n-1: forces and torques of their pairs, added to the row particle and (half list)
 * to local partners (j < nhalf). With one shape (mono) the partner's shape is never read: the
 * radius and the parameters are those of shape 0 (a loop-invariant test, predicted). */
static void dem_pair_rows(const Dem dem, PetscBool mono)
{
  const double *restrict   x = dem->x, *restrict v = dem->v, *restrict w = dem->w;
  double *restrict         f = dem->f, *restrict tq = dem->tq, *restrict hist = dem->nl.hist;
  const PetscInt *restrict shape = dem->shape, *restrict start = dem->nl.start, *restrict nbr = dem->nl.nbr;
  const PetscInt           n = dem->n, ns = dem->nshape, nhalf = dem->full_list ? 0 : dem->n;
  const DemLaw             law = dem->law;
  const PetscBool          rot = dem->rotation;
  const double             dt = dem->dt;
  const DemPairParams      p1 = dem->pp[0]; /* local copies: no store in the loop can change them */
  double                   rad[DEM_MAX_SHAPES];

  for (PetscInt s = 0; s < ns; s++) rad[s] = dem->shp[s].r;
  for (PetscInt i = 0; i < n; i++) {
    const double         xi[3] = {x[3 * i], x[3 * i + 1], x[3 * i + 2]};
    const double         vi[3] = {v[3 * i], v[3 * i + 1], v[3 * i + 2]};
    const double         wi[3] = {w[3 * i], w[3 * i + 1], w[3 * i + 2]};
    const double         ri    = mono ? rad[0] : rad[shape[i]];
    const DemPairParams *row   = mono ? NULL : dem->pp + shape[i] * ns;
    double               fi[3] = {0, 0, 0}, ti[3] = {0, 0, 0};

    for (PetscInt a = start[i]; a < start[i + 1]; a++) {
      const PetscInt j  = nbr[a];
      const double  *xj = x + 3 * j;
      const double   rj = mono ? rad[0] : rad[shape[j]], rs = ri + rj;
      const double   d[3] = {xj[0] - xi[0], xj[1] - xi[1], xj[2] - xi[2]};
      const double   d2 = dem_dot(d, d);
      double        *xi_t = hist ? hist + 3 * a : NULL;
      if (d2 >= rs * rs) { /* not touching: no square root, no division, no spring */
        if (xi_t) xi_t[0] = xi_t[1] = xi_t[2] = 0;
        continue;
      }
      const DemPairParams *p    = mono ? &p1 : row + shape[j];
      const double         dist = sqrt(d2), inv = 1.0 / dist, delta = rs - dist;
      const double         nrm[3] = {d[0] * inv, d[1] * inv, d[2] * inv};
      const double        *vj = v + 3 * j, *wj = w + 3 * j;
      const double         li = ri - 0.5 * delta, lj = rj - 0.5 * delta; /* lever arms */
      double               vr[3], kt, gt, F[3], c[3] = {0, 0, 0}; /* c: n x ft, the torque's direction */
      /* partner's contact-point velocity relative to i's: v_j - v_i + (w_j l_j + w_i l_i) x (-n)... */
      {
        double wsum[3], c[3];
        for (int k = 0; k < 3; k++) wsum[k] = li * wi[k] + lj * wj[k];
        dem_cross(wsum, nrm, c); /* w_i x (l_i n) - w_j x (-l_j n) = (l_i w_i + l_j w_j) x n */
        for (int k = 0; k < 3; k++) vr[k] = vj[k] - vi[k] - c[k];
      }
      const double vn = dem_dot(vr, nrm);
      const double fn = dem_normal_force(law, p, delta, vn, &kt, &gt);
      for (int k = 0; k < 3; k++) F[k] = -fn * nrm[k]; /* on i */
      if (p->mu > 0) {
        double vt[3], ft[3];
        for (int k = 0; k < 3; k++) vt[k] = vr[k] - vn * nrm[k];
        dem_tangential_force(p, fn, kt, gt, nrm, vt, xi_t, dt, ft); /* ft acts on the partner */
        if (rot) {
          dem_cross(nrm, ft, c); /* torque on i: (l_i n) x (-ft); on j: (-l_j n) x ft */
          for (int k = 0; k < 3; k++) ti[k] -= li * c[k];
        }
        for (int k = 0; k < 3; k++) F[k] -= ft[k];
      }
      for (int k = 0; k < 3; k++) fi[k] += F[k];
      if (j < nhalf)
        for (int k = 0; k < 3; k++) {
          f[3 * j + k] -= F[k];
          tq[3 * j + k] -= lj * c[k];
        }
    }
    for (int k = 0; k < 3; k++) {
      f[3 * i + k] += fi[k];
      tq[3 * i + k] += ti[k];
    }
  }
}

PetscErrorCode DemContactsPairs(Dem dem)
{
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(DEM_Contacts, 0, 0, 0, 0));
  dem_pair_rows(dem, (PetscBool)(dem->nshape == 1));
  PetscCall(PetscLogEventEnd(DEM_Contacts, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}
