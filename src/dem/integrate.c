/* Time integration: velocity Verlet for translation, the same half-kicks for the spin, and a
 * quaternion update for orientation.
 *   v(n+1/2) = v(n) + dt/2 F(n)/m,  x(n+1) = x(n) + dt v(n+1/2),
 *   v(n+1)   = v(n+1/2) + dt/2 F(n+1)/m  (forces use v(n+1/2), as LAMMPS and LIGGGHTS do);
 *   w likewise with T/I (spheres: isotropic inertia, so Euler's equations reduce to this;
 *   convex shapes: Euler's equations with the full inertia tensor, rotation.c);
 *   dq/dt = 1/2 (0, w) q  (w in the world frame, q maps body to world), renormalised each
 *   step by one Newton step of 1/sqrt(|q|^2), exact to O((w dt)^4) since |q| stays 1 + O((w dt)^2).
 * The first half also tracks the largest displacement since the last list build.
 * With a coupling attached (external.c) the translational kicks are DemExternalKick's (drag
 * implicit); a frozen DEM (-dem_frozen) moves nothing. Spheres of their own sizes take their own
 * 1/m and 1/I (DemParticles.invm, invi). */
#include "dem/dem_core.h"

#define DEM_INTEGRATE_BLOCK 256 /* particles per block of the first half step */

/* Spin half kick and quaternion step of particle i (spheres: isotropic inertia, 1/I = ii). */
static inline void dem_spin_first_half(double *restrict wi, double *restrict qi, const double *restrict ti, double ii, double h)
{
  double dq[4];
  for (int k = 0; k < 3; k++) wi[k] += h * ti[k] * ii;
  /* (0, w) q */
  dq[0]    = -(wi[0] * qi[1] + wi[1] * qi[2] + wi[2] * qi[3]);
  dq[1]    = wi[0] * qi[0] + wi[1] * qi[3] - wi[2] * qi[2];
  dq[2]    = wi[1] * qi[0] + wi[2] * qi[1] - wi[0] * qi[3];
  dq[3]    = wi[2] * qi[0] + wi[0] * qi[2] - wi[1] * qi[1];
  double s = 0;
  for (int k = 0; k < 4; k++) {
    qi[k] += h * dq[k];
    s += qi[k] * qi[k];
  }
  /* |q|^2 = 1 + O((w dt)^2): one Newton step for 1/sqrt(s) renormalises to O((w dt)^4) */
  s = 1.5 - 0.5 * s;
  for (int k = 0; k < 4; k++) qi[k] *= s;
}

/* Half kick and drift (with one shape a flat loop over the 3n components, which vectorises)
 * and the largest displacement since the list build, block by block, and for spheres with
 * friction (rotation) the spin half kick and quaternion step. Writes the local particles' x, v,
 * w, q (and the coupling's impulse); reads f, tq, x0 and the shapes' masses and inertias. */
PetscErrorCode DemIntegrateFirstHalf(DemParticles *p, const DemShapeTable *st, DemExternalState *e, PetscBool rotation, double dt, double *maxdisp2)
{
  const double h     = 0.5 * dt;
  double *restrict x = p->x, *restrict v = p->v, *restrict w = p->w, *restrict q = p->q;
  const double *restrict f = p->f, *restrict tq = p->tq, *restrict x0 = p->x0;
  const PetscInt n = p->n, *restrict shape = p->shape;
  double         d2max = 0, d2sum = 0;

  PetscFunctionBeginUser;
  *maxdisp2 = 0;
  if (e->frozen) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscLogEventBegin(DEM_Integrate, 0, 0, 0, 0));
  if (e->on) DemExternalKick(p, st, e, h);
  /* blocks of particles small enough to stay in L1 between the kick-drift and the displacement */
  for (PetscInt b0 = 0; b0 < n; b0 += DEM_INTEGRATE_BLOCK) {
    const PetscInt b1 = PetscMin(b0 + DEM_INTEGRATE_BLOCK, n);
    if (p->invm) /* spheres of their own sizes */
      for (PetscInt i = b0; i < b1; i++) {
        const double im = e->on ? 0 : p->invm[i];
        for (int k = 0; k < 3; k++) {
          v[3 * i + k] += h * f[3 * i + k] * im;
          x[3 * i + k] += dt * v[3 * i + k];
        }
      }
    else if (st->nshape == 1) {
      const double im = e->on ? 0 : st->shp[0].invm;
      for (PetscInt k = 3 * b0; k < 3 * b1; k++) {
        v[k] += h * f[k] * im;
        x[k] += dt * v[k];
      }
    } else
      for (PetscInt i = b0; i < b1; i++) {
        const double im = e->on ? 0 : st->shp[shape[i]].invm;
        for (int k = 0; k < 3; k++) {
          v[3 * i + k] += h * f[3 * i + k] * im;
          x[3 * i + k] += dt * v[3 * i + k];
        }
      }
    for (PetscInt i = b0; i < b1; i++) {
      double d2 = 0;
      for (int k = 0; k < 3; k++) {
        const double d = x[3 * i + k] - x0[3 * i + k];
        d2 += d * d;
      }
      d2max = d2 > d2max ? d2 : d2max;
      d2sum += d2; /* a NaN, which the max drops, survives a sum (one add: the loop still vectorises) */
    }
  }
  if (d2sum != d2sum) d2max = d2sum;                        /* DemStep stops on a non-finite displacement */
  if (st->convex) PetscCall(DemRotateFirstHalf(p, st, dt)); /* full inertia tensor (rotation.c) */
  else if (rotation)
    for (PetscInt i = 0; i < n; i++) {
      const double ii = p->invi ? p->invi[i] : st->nshape == 1 ? st->shp[0].invi
                                                               : st->shp[shape[i]].invi;
      dem_spin_first_half(w + 3 * i, q + 4 * i, tq + 3 * i, ii, h);
    }
  *maxdisp2 = d2max;
  PetscCall(PetscLogFlops(12.0 * n));
  PetscCall(PetscLogEventEnd(DEM_Integrate, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Half kicks of v and (spheres) w; with one shape a flat loop over the 3n components. */
PetscErrorCode DemIntegrateSecondHalf(DemParticles *p, const DemShapeTable *st, DemExternalState *e, PetscBool rotation, double dt)
{
  const double h     = 0.5 * dt;
  double *restrict v = p->v, *restrict w = p->w;
  const double *restrict f = p->f, *restrict tq = p->tq;
  const PetscInt  n = p->n, *restrict shape = p->shape;
  const PetscBool spin = (PetscBool)(rotation && !st->convex);

  PetscFunctionBeginUser;
  if (e->frozen) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscLogEventBegin(DEM_Integrate, 0, 0, 0, 0));
  if (e->on) DemExternalKick(p, st, e, h);
  else if (p->invm)
    for (PetscInt i = 0; i < n; i++)
      for (int k = 0; k < 3; k++) v[3 * i + k] += h * f[3 * i + k] * p->invm[i];
  else if (st->nshape == 1) {
    const double im = st->shp[0].invm;
    for (PetscInt k = 0; k < 3 * n; k++) v[k] += h * f[k] * im;
  } else
    for (PetscInt i = 0; i < n; i++) {
      const double im = st->shp[shape[i]].invm;
      for (int k = 0; k < 3; k++) v[3 * i + k] += h * f[3 * i + k] * im;
    }
  if (st->convex) PetscCall(DemRotateSecondHalf(p, st, dt)); /* full inertia tensor (rotation.c) */
  else if (spin && p->invi)
    for (PetscInt i = 0; i < n; i++)
      for (int k = 0; k < 3; k++) w[3 * i + k] += h * tq[3 * i + k] * p->invi[i];
  else if (spin && st->nshape == 1) {
    const double ii = st->shp[0].invi;
    for (PetscInt k = 0; k < 3 * n; k++) w[k] += h * tq[k] * ii;
  } else if (spin)
    for (PetscInt i = 0; i < n; i++) {
      const double ii = st->shp[shape[i]].invi;
      for (int k = 0; k < 3; k++) w[3 * i + k] += h * tq[3 * i + k] * ii;
    }
  PetscCall(PetscLogEventEnd(DEM_Integrate, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}
