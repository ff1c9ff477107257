/* The sphere pair kernel of the pair loops (contacts.c: one size per shape; contacts_sized.c:
 * spheres of their own sizes): the types one pass works on (DemPairPass, the row sums
 * DemRowSum), the contact model as a pass applies it (DemPairLaw) and one touching pair
 * (DemPair), and the force of one pair (dem_pair_force). Private to those two files; the laws
 * themselves are contact_laws.h. */
#pragma once
#include <string.h>
#include "dem/dem_core.h"

#define DEM_PAIR_BLOCK 256 /* list entries screened per block (10 kB of buffers on the stack) */

/* Resets a spring to +0 unless it is already +0 (bit pattern 0): in a bed most pairs that do not
 * touch have no spring, and their cache lines then stay clean. */
static inline void dem_spring_reset(double *h)
{
  uint64_t b[3];
  memcpy(b, h, sizeof b);
  if (b[0] | b[1] | b[2]) h[0] = h[1] = h[2] = 0;
}

/* Entries a0..a1-1 of the list, flat over rows (own[a] is the row). Pass 1 screens every entry
 * and keeps the touching ones in list order, without a branch on the answer (close to a coin
 * toss in a dense bed, so a branch would be mispredicted often), and the others, whose springs
 * are reset. Pass 2 computes the touching pairs. The row sums (fi, ti of row cur) carry over from
 * block to block and are added to the row particle when the next touching pair belongs to
 * another row, so every force is summed in the order of a row-by-row loop (a row without a
 * touching pair adds nothing; the row loop added +0, which changes no force that can occur:
 * sums that start at +0 never become -0). */
typedef struct {
  PetscInt cur;
  double   fi[3], ti[3];
} DemRowSum;

/* What one pass of the pair loop works on: the particles (x, v, w read; f, tq added to), the list
 * (springs written), the contact model, the radius of each shape and the time step. */
typedef struct {
  DemParticles          *pt;
  DemNeigh              *nl;
  const DemContactModel *cm;
  const double          *rad;
  PetscInt               ns;   /* shapes */
  PetscBool              mono; /* one shape: its radius and parameters are read once */
  double                 dt;
} DemPairPass;

/* A row's sums are complete: add them to its particle and start row i. */
static inline void dem_row_flush(DemRowSum *S, PetscInt i, double *f, double *tq)
{
  if (S->cur >= 0)
    for (int k = 0; k < 3; k++) {
      f[3 * S->cur + k] += S->fi[k];
      tq[3 * S->cur + k] += S->ti[k];
    }
  S->cur = i;
  for (int k = 0; k < 3; k++) S->fi[k] = S->ti[k] = 0;
}

/* The contact model as a pass of the pair loop applies it, the same for every pair. */
typedef struct {
  DemLaw    law;
  PetscBool rot;   /* torques (the scene has friction) */
  DemRoll   roll;  /* rolling resistance */
  double    dt;    /* s */
  PetscInt  nhalf; /* partners j < nhalf are local particles of the half list: they get the opposite force */
} DemPairLaw;

/* One touching sphere pair: d = x_j - x_i, d2 = |d|^2 < (ri + rj)^2; its parameters (p, and ieff
 * for rolling resistance), the velocities and angular velocities of both, its spring (NULL:
 * none) and the partner's index j. */
typedef struct {
  const DemPairParams *p;
  double               ieff;
  double               ri, rj, d[3], d2;
  const double        *vi, *wi, *vj, *wj;
  double              *xi_t;
  PetscInt             j;
} DemPair;

/* One touching sphere pair q under the law L, shared by the loops of one size per shape and of
 * own sizes: the force and torques on i go to its row sums S, the opposite ones on j (a local
 * particle of the half list, j < L->nhalf) straight to f and tq. Each file calls it once (the
 * compiler then inlines it, a static function called once, and keeps L and q in registers;
 * objdump of contacts.o and contacts_sized.o shows no call to it): a second call in one file
 * would leave it out of line, above GCC's size limit for inlining. */
static inline void dem_pair_force(const DemPairLaw *L, const DemPair *q, DemRowSum *S, double *f, double *tq)
{
  const DemPairParams *p = q->p;
  const double        *d = q->d, *vi = q->vi, *wi = q->wi, *vj = q->vj, *wj = q->wj;
  const double         ri = q->ri, rj = q->rj, d2 = q->d2, dt = L->dt;
  const PetscInt       j    = q->j;
  const double         dist = sqrt(d2), inv = 1.0 / dist, delta = ri + rj - dist;
  const double         nrm[3] = {d[0] * inv, d[1] * inv, d[2] * inv};
  const double         li = ri - 0.5 * delta, lj = rj - 0.5 * delta; /* lever arms */
  double               vr[3], kt, gt, F[3], c[3] = {0, 0, 0};        /* c: n x ft, the torque's direction */
  /* partner's contact-point velocity relative to i's: v_j - v_i + (w_j l_j + w_i l_i) x (-n)... */
  {
    double wsum[3], cw[3];
    for (int k = 0; k < 3; k++) wsum[k] = li * wi[k] + lj * wj[k];
    dem_cross(wsum, nrm, cw); /* w_i x (l_i n) - w_j x (-l_j n) = (l_i w_i + l_j w_j) x n */
    for (int k = 0; k < 3; k++) vr[k] = vj[k] - vi[k] - cw[k];
  }
  const double vn = dem_dot(vr, nrm);
  const double fn = dem_normal_force(L->law, p, delta, vn, &kt, &gt);
  for (int k = 0; k < 3; k++) F[k] = -fn * nrm[k]; /* on i */
  if (p->mu > 0) {
    double vt[3], ft[3];
    for (int k = 0; k < 3; k++) vt[k] = vr[k] - vn * nrm[k];
    dem_tangential_force(p, fn, kt, gt, nrm, vt, q->xi_t, dt, ft); /* ft acts on the partner */
    if (L->rot) {
      dem_cross(nrm, ft, c); /* torque on i: (l_i n) x (-ft); on j: (-l_j n) x ft */
      for (int k = 0; k < 3; k++) S->ti[k] -= li * c[k];
    }
    for (int k = 0; k < 3; k++) F[k] -= ft[k];
  }
  if (L->roll) { /* rolling resistance: a torque on i, the opposite on j */
    double mr[3];
    dem_rolling_pair(L->roll, p, fn, q->ieff, wi, wj, ri, rj, nrm, dt, mr);
    for (int k = 0; k < 3; k++) S->ti[k] += mr[k];
    if (j < L->nhalf)
      for (int k = 0; k < 3; k++) tq[3 * j + k] -= mr[k];
  }
  for (int k = 0; k < 3; k++) S->fi[k] += F[k];
  if (j < L->nhalf)
    for (int k = 0; k < 3; k++) {
      f[3 * j + k] -= F[k];
      tq[3 * j + k] -= lj * c[k];
    }
}

/* Entries a0..a1-1 of the list of spheres of their own sizes (contacts_sized.c). */
void dem_pair_block_sized(const DemPairPass *P, PetscInt a0, PetscInt a1, DemRowSum *sum);
