/* Particle-particle contact forces over the half Verlet list (each pair once; Newton's third
 * law adds the opposite force to a local partner; in the full list (-dem_deterministic) and for
 * ghost partners only the row particle receives its force, the partner's rank computes the
 * other half). Every expression is antisymmetric under exchanging i and j, so both sides of a
 * pair computed on two ranks get exactly opposite forces. Spheres: n = (x_j - x_i)/|x_j - x_i|, overlap
 * delta = r_i + r_j - |x_j - x_i|, contact point at r_i - delta/2 from i along n. The spring of
 * a pair that is not touching is reset to zero (a new contact starts unloaded). Torques only
 * when the scene has friction (dem->contact.rotation).
 * Speed (the pair loop is most of a dense step): in a settled bed only about a third of the
 * list entries touch, in no predictable pattern, so the loop screens the entries of a block
 * first (branch-free, flat over rows: DemNeigh.own gives each entry's row) and then computes the
 * touching pairs. That halves the mispredicted branches of a dense step (callgrind) and cuts its
 * time by about a quarter. A scene of one shape reads its radius and parameters once; the
 * arithmetic is the same, expression by expression, as a row-by-row loop, and so are the order
 * of every sum and therefore the forces, to the bit. Spheres of their own sizes (poly) run a loop
 * of their own, the same but for the radii and masses read per particle and the pair's m*, R*
 * and linear stiffness and damping formed per contact (dem_pair_sized) from the (shape, shape)
 * material table: a shared body with a constant flag was not specialised by the compiler for
 * the other scenes, whose loop must stay the one it was. Rolling resistance (-dem_rolling_model,
 * contact_laws.h) adds a torque on i and the opposite on j, behind one branch on the model. */
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

/* One touching sphere pair (d = x_j - x_i, d2 = |d|^2 < (ri + rj)^2), shared by the loops of one
 * size per shape and of own sizes: the force and torques on i go to its row sums S, the opposite
 * ones on j (a local particle of the half list, j < nhalf) straight to f and tq. */
static inline __attribute__((always_inline)) void dem_pair_force(DemLaw law, const DemPairParams *p, double ieff, PetscBool rot, DemRoll roll, double dt, double ri, double rj, const double d[3], double d2, const double *vi, const double *wi, const double *vj, const double *wj, double *xi_t, DemRowSum *S, PetscInt j, PetscInt nhalf, double *f, double *tq)
{
  const double dist = sqrt(d2), inv = 1.0 / dist, delta = ri + rj - dist;
  const double nrm[3] = {d[0] * inv, d[1] * inv, d[2] * inv};
  const double li = ri - 0.5 * delta, lj = rj - 0.5 * delta; /* lever arms */
  double       vr[3], kt, gt, F[3], c[3] = {0, 0, 0};        /* c: n x ft, the torque's direction */
  /* partner's contact-point velocity relative to i's: v_j - v_i + (w_j l_j + w_i l_i) x (-n)... */
  {
    double wsum[3], cw[3];
    for (int k = 0; k < 3; k++) wsum[k] = li * wi[k] + lj * wj[k];
    dem_cross(wsum, nrm, cw); /* w_i x (l_i n) - w_j x (-l_j n) = (l_i w_i + l_j w_j) x n */
    for (int k = 0; k < 3; k++) vr[k] = vj[k] - vi[k] - cw[k];
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
      for (int k = 0; k < 3; k++) S->ti[k] -= li * c[k];
    }
    for (int k = 0; k < 3; k++) F[k] -= ft[k];
  }
  if (roll) { /* rolling resistance: a torque on i, the opposite on j */
    double mr[3];
    dem_rolling_pair(roll, p, fn, ieff, wi, wj, ri, rj, nrm, dt, mr);
    for (int k = 0; k < 3; k++) S->ti[k] += mr[k];
    if (j < nhalf)
      for (int k = 0; k < 3; k++) tq[3 * j + k] -= mr[k];
  }
  for (int k = 0; k < 3; k++) S->fi[k] += F[k];
  if (j < nhalf)
    for (int k = 0; k < 3; k++) {
      f[3 * j + k] -= F[k];
      tq[3 * j + k] -= lj * c[k];
    }
}

static void dem_pair_block(const DemPairPass *P, PetscInt a0, PetscInt a1, DemRowSum *sum)
{
  DemRowSum S              = *sum; /* a local copy, kept in registers */
  const double *restrict x = P->pt->x, *restrict v = P->pt->v, *restrict w = P->pt->w;
  double *restrict f = P->pt->f, *restrict tq = P->pt->tq, *restrict hist = P->nl->hist;
  const PetscInt *restrict shape = P->pt->shape, *restrict nbr = P->nl->nbr, *restrict own = P->nl->own;
  const PetscInt       ns = P->ns, nhalf = P->nl->full_list ? 0 : P->pt->n;
  const DemLaw         law = P->cm->law;
  const PetscBool      rot = P->cm->rotation, mono = P->mono;
  const DemRoll        roll = P->cm->roll;
  const double         dt = P->dt, *rad = P->rad;
  const DemPairParams *pp = P->cm->pp;
  PetscInt             m = 0, mn = 0, ta[DEM_PAIR_BLOCK], tn[DEM_PAIR_BLOCK];
  double               td[DEM_PAIR_BLOCK][4];

  for (PetscInt a = a0; a < a1; a++) { /* pass 1 */
    const PetscInt i = own[a], j = nbr[a];
    const double  *xi = x + 3 * i, *xj = x + 3 * j;
    const double   rs    = mono ? rad[0] + rad[0] : rad[shape[i]] + rad[shape[j]];
    const double   d[3]  = {xj[0] - xi[0], xj[1] - xi[1], xj[2] - xi[2]};
    const double   d2    = dem_dot(d, d);
    const int      touch = d2 < rs * rs;
    for (int k = 0; k < 3; k++) td[m][k] = d[k];
    td[m][3] = d2;
    ta[m]    = a;
    tn[mn]   = a;
    m += touch;
    mn += !touch;
  }
  if (hist)
    for (PetscInt t = 0; t < mn; t++) dem_spring_reset(hist + 3 * tn[t]);
  for (PetscInt t = 0; t < m; t++) { /* pass 2 */
    const PetscInt       a = ta[t], i = own[a], j = nbr[a];
    const double         d[3] = {td[t][0], td[t][1], td[t][2]}, d2 = td[t][3];
    const double         ri = mono ? rad[0] : rad[shape[i]], rj = mono ? rad[0] : rad[shape[j]];
    const DemPairParams *p    = mono ? pp : pp + shape[i] * ns + shape[j];
    double              *xi_t = hist ? hist + 3 * a : NULL;
    if (i != S.cur) dem_row_flush(&S, i, f, tq); /* the previous row is complete */
    dem_pair_force(law, p, p->ieff, rot, roll, dt, ri, rj, d, d2, v + 3 * i, w + 3 * i, v + 3 * j, w + 3 * j, xi_t, &S, j, nhalf, f, tq);
  }
  *sum = S;
}

/* The same for spheres of their own sizes: the radii and masses of the two particles, m* and R*
 * per contact (dem_pair_sized); a function of its own so that the loop above stays the one every
 * other scene runs. */
static void dem_pair_block_poly(const DemPairPass *P, PetscInt a0, PetscInt a1, DemRowSum *sum)
{
  DemRowSum S              = *sum; /* a local copy, kept in registers */
  const double *restrict x = P->pt->x, *restrict v = P->pt->v, *restrict w = P->pt->w;
  double *restrict f = P->pt->f, *restrict tq = P->pt->tq, *restrict hist = P->nl->hist;
  const PetscInt *restrict shape = P->pt->shape, *restrict nbr = P->nl->nbr, *restrict own = P->nl->own;
  const PetscInt       ns = P->ns, nhalf = P->nl->full_list ? 0 : P->pt->n;
  const DemLaw         law = P->cm->law;
  const PetscBool      rot = P->cm->rotation, mono = P->mono;
  const DemRoll        roll   = P->cm->roll;
  const double         dt     = P->dt;
  const DemPairParams *pp     = P->cm->pp;
  const double *restrict prad = P->pt->rad, *restrict pmass = P->pt->m;
  PetscInt m = 0, mn = 0, ta[DEM_PAIR_BLOCK], tn[DEM_PAIR_BLOCK];
  double   td[DEM_PAIR_BLOCK][4];

  for (PetscInt a = a0; a < a1; a++) { /* pass 1 */
    const PetscInt i = own[a], j = nbr[a];
    const double  *xi = x + 3 * i, *xj = x + 3 * j;
    const double   rs    = prad[i] + prad[j];
    const double   d[3]  = {xj[0] - xi[0], xj[1] - xi[1], xj[2] - xi[2]};
    const double   d2    = dem_dot(d, d);
    const int      touch = d2 < rs * rs;
    for (int k = 0; k < 3; k++) td[m][k] = d[k];
    td[m][3] = d2;
    ta[m]    = a;
    tn[mn]   = a;
    m += touch;
    mn += !touch;
  }
  if (hist)
    for (PetscInt t = 0; t < mn; t++) dem_spring_reset(hist + 3 * tn[t]);
  for (PetscInt t = 0; t < m; t++) { /* pass 2 */
    const PetscInt       a = ta[t], i = own[a], j = nbr[a];
    const double         d[3] = {td[t][0], td[t][1], td[t][2]}, d2 = td[t][3];
    const double         ri = prad[i], rj = prad[j];
    const DemPairParams *p = mono ? pp : pp + shape[i] * ns + shape[j];
    DemPairParams        sized;
    dem_pair_sized(law, p, pmass[i], ri, pmass[j], rj, &sized); /* m* and R* of the two spheres */
    p            = &sized;
    double *xi_t = hist ? hist + 3 * a : NULL;
    if (i != S.cur) dem_row_flush(&S, i, f, tq); /* the previous row is complete */
    dem_pair_force(law, p, dem_pair_inertia(pmass[i], ri, pmass[j], rj), rot, roll, dt, ri, rj, d, d2, v + 3 * i, w + 3 * i, v + 3 * j, w + 3 * j, xi_t, &S, j, nhalf, f, tq);
  }
  *sum = S;
}

/* Pair forces over the list: adds to f and tq of the local particles, resets or advances the
 * springs of the list; reads x, v, w of the particles and ghosts, the radii and the contact model. */
PetscErrorCode DemContactsPairs(DemParticles *p, const DemShapeTable *st, const DemContactModel *cm, DemNeigh *nl, double dt)
{
  const PetscInt    ne = nl->start[p->n];
  double            rad[DEM_MAX_SHAPES];
  DemRowSum         sum = {.cur = -1};
  const DemPairPass P   = {p, nl, cm, rad, st->nshape, (PetscBool)(st->nshape == 1), dt};

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(DEM_Contacts, 0, 0, 0, 0));
  for (PetscInt s = 0; s < st->nshape; s++) rad[s] = st->shp[s].r;
  if (p->rad)
    for (PetscInt a0 = 0; a0 < ne; a0 += DEM_PAIR_BLOCK) dem_pair_block_poly(&P, a0, PetscMin(a0 + DEM_PAIR_BLOCK, ne), &sum);
  else
    for (PetscInt a0 = 0; a0 < ne; a0 += DEM_PAIR_BLOCK) dem_pair_block(&P, a0, PetscMin(a0 + DEM_PAIR_BLOCK, ne), &sum);
  if (sum.cur >= 0)
    for (int k = 0; k < 3; k++) {
      p->f[3 * sum.cur + k] += sum.fi[k];
      p->tq[3 * sum.cur + k] += sum.ti[k];
    }
  PetscCall(PetscLogEventEnd(DEM_Contacts, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}
