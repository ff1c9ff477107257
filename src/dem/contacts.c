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
 * the other scenes, whose loop must stay the one it was. That loop lives in contacts_sized.c, so
 * that each file calls the pair kernel (contact_pair.h) once and the compiler inlines it there as
 * a function called once, with no attribute (two calls in one file are not inlined: too large). Rolling resistance (-dem_rolling_model,
 * contact_laws.h) adds a torque on i and the opposite on j, behind one branch on the model. */
#include <string.h>
#include "dem/dem_core.h"

#include "dem/contact_pair.h"

static void dem_pair_block(const DemPairPass *P, PetscInt a0, PetscInt a1, DemRowSum *sum)
{
  DemRowSum S              = *sum; /* a local copy, kept in registers */
  const double *restrict x = P->pt->x, *restrict v = P->pt->v, *restrict w = P->pt->w;
  double *restrict f = P->pt->f, *restrict tq = P->pt->tq, *restrict hist = P->nl->hist;
  const PetscInt *restrict shape = P->pt->shape, *restrict nbr = P->nl->nbr, *restrict own = P->nl->own;
  const PetscInt       ns   = P->ns;
  const DemPairLaw     L    = {P->cm->law, P->cm->rotation, P->cm->roll, P->dt, P->nl->full_list ? 0 : P->pt->n};
  const PetscBool      mono = P->mono;
  const double        *rad  = P->rad;
  const DemPairParams *pp   = P->cm->pp;
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
    const DemPairParams *p = mono ? pp : pp + shape[i] * ns + shape[j];
    const DemPair        q = {p, p->ieff, mono ? rad[0] : rad[shape[i]], mono ? rad[0] : rad[shape[j]], {td[t][0], td[t][1], td[t][2]}, td[t][3], v + 3 * i, w + 3 * i, v + 3 * j, w + 3 * j, hist ? hist + 3 * a : NULL, j};
    if (i != S.cur) dem_row_flush(&S, i, f, tq); /* the previous row is complete */
    dem_pair_force(&L, &q, &S, f, tq);
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
    for (PetscInt a0 = 0; a0 < ne; a0 += DEM_PAIR_BLOCK) dem_pair_block_sized(&P, a0, PetscMin(a0 + DEM_PAIR_BLOCK, ne), &sum);
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
