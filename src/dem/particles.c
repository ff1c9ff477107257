/* Particle store: structure of arrays, xyz interleaved per particle, grown geometrically.
 * Permutation (re-sort by cell for memory locality) moves every per-particle array together;
 * the neighbour module carries the contact springs across (neighbours.c). */
#include "dem/dem_impl.h"

/* every real per-particle array and its width (the coupling arrays only when switched on) */
static int DemRealArrays(Dem dem, double ***a, int *m)
{
  double **p[] = {&dem->x, &dem->v, &dem->w, &dem->f, &dem->tq, &dem->q, &dem->x0, &dem->fext, &dem->kdrag, &dem->udrag, &dem->jdrag};
  int      w[] = {3, 3, 3, 3, 3, 4, 3, 3, 1, 3, 3};
  int      na  = dem->external ? 11 : 7;
  for (int k = 0; k < na; k++) {
    a[k] = p[k];
    m[k] = w[k];
  }
  return na;
}

PetscErrorCode DemParticlesReserve(Dem dem, PetscInt n)
{
  PetscInt cap;
  double **a[12];
  int      m[12], na;

  PetscFunctionBeginUser;
  if (n <= dem->cap) PetscFunctionReturn(PETSC_SUCCESS);
  cap = PetscMax(n, dem->cap + dem->cap / 4 + 64);
  na  = DemRealArrays(dem, a, m);
  for (int k = 0; k < na; k++) PetscCall(PetscRealloc(sizeof(double) * m[k] * (size_t)cap, a[k]));
  PetscCall(PetscRealloc(sizeof(PetscInt) * (size_t)cap, &dem->id));
  PetscCall(PetscRealloc(sizeof(PetscInt) * (size_t)cap, &dem->shape));
  dem->cap = cap;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* new[i] = old[perm[i]] for every per-particle array */
PetscErrorCode DemParticlesPermute(Dem dem, const PetscInt *perm)
{
  double   *tmp;
  PetscInt *itmp;
  PetscInt  n = dem->n;
  double  **a[12];
  int       m[12], na = DemRealArrays(dem, a, m);

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(4 * (size_t)n + 1, &tmp));
  PetscCall(PetscMalloc1((size_t)n + 1, &itmp));
  for (int c = 0; c < na; c++) {
    double *src = *a[c];
    for (PetscInt i = 0; i < n; i++)
      for (int k = 0; k < m[c]; k++) tmp[m[c] * i + k] = src[m[c] * perm[i] + k];
    PetscCall(PetscArraycpy(src, tmp, m[c] * n));
  }
  for (PetscInt i = 0; i < n; i++) itmp[i] = dem->id[perm[i]];
  PetscCall(PetscArraycpy(dem->id, itmp, n));
  for (PetscInt i = 0; i < n; i++) itmp[i] = dem->shape[perm[i]];
  PetscCall(PetscArraycpy(dem->shape, itmp, n));
  PetscCall(PetscFree(tmp));
  PetscCall(PetscFree(itmp));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemAddParticle(Dem dem, const DemParticle *p)
{
  PetscInt i = dem->n;

  PetscFunctionBeginUser;
  dem->state++;
  PetscCheck(p->shape >= 0 && p->shape < dem->nshape, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "particle %" PetscInt_FMT ": shape %" PetscInt_FMT " not in [0, %" PetscInt_FMT ")", p->id, p->shape, dem->nshape);
  for (int k = 0; k < 3; k++)
    PetscCheck(PetscIsNormalReal(p->x[k]) || p->x[k] == 0, PETSC_COMM_SELF, PETSC_ERR_FP, "particle %" PetscInt_FMT ": position is not finite", p->id);
  PetscCall(DemParticlesReserve(dem, i + 1));
  for (int k = 0; k < 3; k++) {
    dem->x[3 * i + k] = dem->x0[3 * i + k] = p->x[k];
    dem->v[3 * i + k]                      = p->v[k];
    dem->w[3 * i + k]                      = p->w[k];
    dem->f[3 * i + k] = dem->tq[3 * i + k] = 0;
  }
  for (int k = 0; k < 4; k++) dem->q[4 * i + k] = p->q[k];
  if (dem->external) {
    dem->kdrag[i] = 0;
    for (int k = 0; k < 3; k++) dem->fext[3 * i + k] = dem->udrag[3 * i + k] = dem->jdrag[3 * i + k] = 0;
  }
  if (p->q[0] == 0 && p->q[1] == 0 && p->q[2] == 0 && p->q[3] == 0) dem->q[4 * i] = 1; /* identity */
  dem->id[i]    = p->id;
  dem->shape[i] = p->shape;
  dem->n++;
  dem->next_id    = PetscMax(dem->next_id, p->id + 1);
  dem->need_build = PETSC_TRUE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemGetLocalCount(Dem dem, PetscInt *n)
{
  PetscFunctionBeginUser;
  *n = dem->n;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemGetParticle(Dem dem, PetscInt i, DemParticle *p)
{
  PetscFunctionBeginUser;
  PetscCheck(i >= 0 && i < dem->n, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "particle index %" PetscInt_FMT " not in [0, %" PetscInt_FMT ")", i, dem->n);
  p->id    = dem->id[i];
  p->shape = dem->shape[i];
  for (int k = 0; k < 3; k++) {
    p->x[k] = dem->x[3 * i + k];
    p->v[k] = dem->v[3 * i + k];
    p->w[k] = dem->w[3 * i + k];
  }
  for (int k = 0; k < 4; k++) p->q[k] = dem->q[4 * i + k];
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemSetParticle(Dem dem, PetscInt i, const DemParticle *p)
{
  PetscFunctionBeginUser;
  dem->state++;
  PetscCheck(i >= 0 && i < dem->n, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "particle index %" PetscInt_FMT " not in [0, %" PetscInt_FMT ")", i, dem->n);
  for (int k = 0; k < 3; k++) {
    dem->x[3 * i + k] = p->x[k];
    dem->v[3 * i + k] = p->v[k];
    dem->w[3 * i + k] = p->w[k];
  }
  for (int k = 0; k < 4; k++) dem->q[4 * i + k] = p->q[k];
  dem->need_build = PETSC_TRUE;
  PetscFunctionReturn(PETSC_SUCCESS);
}
