/* Sphere pair forces of a scene of spheres of their own sizes (-dem_insert_<k>_psd, or
 * -dem_init_file_radii own): the loop of contacts.c (two passes over blocks of the list, the
 * same order of every sum), with the radii and masses read per particle and the pair's m*, R*
 * and linear stiffness and damping formed per contact (dem_pair_sized). A file of its own so
 * that each file calls the pair kernel (contact_pair.h) once, which the compiler then inlines. */
#include "dem/contact_pair.h"

/* Entries a0..a1-1 of the list, as dem_pair_block of contacts.c: the radii and masses of the two
 * particles, m* and R* per contact (dem_pair_sized); a function of its own so that that loop
 * stays the one every other scene runs. */
void dem_pair_block_sized(const DemPairPass *P, PetscInt a0, PetscInt a1, DemRowSum *sum)
{
  DemRowSum S              = *sum; /* a local copy, kept in registers */
  const double *restrict x = P->pt->x, *restrict v = P->pt->v, *restrict w = P->pt->w;
  double *restrict f = P->pt->f, *restrict tq = P->pt->tq, *restrict hist = P->nl->hist;
  const PetscInt *restrict shape = P->pt->shape, *restrict nbr = P->nl->nbr, *restrict own = P->nl->own;
  const PetscInt       ns     = P->ns;
  const DemPairLaw     L      = {P->cm->law, P->cm->rotation, P->cm->roll, P->dt, P->nl->full_list ? 0 : P->pt->n};
  const PetscBool      mono   = P->mono;
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
    const double         ri = prad[i], rj = prad[j];
    const DemPairParams *p = mono ? pp : pp + shape[i] * ns + shape[j];
    DemPairParams        sized;
    dem_pair_sized(L.law, p, pmass[i], ri, pmass[j], rj, &sized); /* m* and R* of the two spheres */
    const DemPair q = {&sized, dem_pair_inertia(pmass[i], ri, pmass[j], rj), ri, rj, {td[t][0], td[t][1], td[t][2]}, td[t][3], v + 3 * i, w + 3 * i, v + 3 * j, w + 3 * j, hist ? hist + 3 * a : NULL, j};
    if (i != S.cur) dem_row_flush(&S, i, f, tq); /* the previous row is complete */
    dem_pair_force(&L, &q, &S, f, tq);
  }
  *sum = S;
}
