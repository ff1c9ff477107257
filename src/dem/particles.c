/* Particle store: structure of arrays, xyz interleaved per particle, grown geometrically.
 * Permutation (re-sort by cell for memory locality) moves every per-particle array together;
 * the neighbour module carries the contact springs across (neighbours.c). In a scene of spheres
 * of their own sizes (DemShapeTable.poly) each particle also has its radius, mass, 1/m and 1/I
 * (I = 2/5 m r^2, m = rho 4/3 pi r^3 with its shape's density), set from the radius in one place
 * (DemParticleSetSize); other scenes allocate none of them. */
#include "dem/dem_core.h"

/* every real per-particle array and its width (the coupling arrays only when switched on) */
static int DemRealArrays(Dem dem, double ***a, int *m)
{
  double **p[] = {&dem->p.x, &dem->p.v, &dem->p.w, &dem->p.f, &dem->p.tq, &dem->p.q, &dem->p.x0, &dem->ext.fext, &dem->ext.kdrag, &dem->ext.udrag, &dem->ext.jdrag};
  int      w[] = {3, 3, 3, 3, 3, 4, 3, 3, 1, 3, 3};
  double **s[] = {&dem->p.rad, &dem->p.m, &dem->p.invm, &dem->p.invi};
  int      na  = dem->ext.on ? 11 : 7;
  for (int k = 0; k < na; k++) {
    a[k] = p[k];
    m[k] = w[k];
  }
  for (int k = 0; k < 4 && dem->shapes.poly; k++, na++) {
    a[na] = s[k];
    m[na] = 1;
  }
  return na;
}

PetscErrorCode DemParticlesReserve(Dem dem, PetscInt n)
{
  PetscInt cap;
  double **a[16];
  int      m[16], na;

  PetscFunctionBeginUser;
  if (n <= dem->p.cap && (!dem->shapes.poly || dem->p.rad)) PetscFunctionReturn(PETSC_SUCCESS);
  cap = n <= dem->p.cap ? dem->p.cap : PetscMax(n, dem->p.cap + dem->p.cap / 4 + 64); /* a scene that became poly: its size arrays */
  na  = DemRealArrays(dem, a, m);
  for (int k = 0; k < na; k++) PetscCall(PetscRealloc(sizeof(double) * m[k] * (size_t)cap, a[k]));
  PetscCall(PetscRealloc(sizeof(PetscInt) * (size_t)cap, &dem->p.id));
  PetscCall(PetscRealloc(sizeof(PetscInt) * (size_t)cap, &dem->p.shape));
  dem->p.cap = cap;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* new[i] = old[perm[i]] for every per-particle array */
PetscErrorCode DemParticlesPermute(Dem dem, const PetscInt *perm)
{
  double   *tmp;
  PetscInt *itmp;
  PetscInt  n = dem->p.n;
  double  **a[16];
  int       m[16], na = DemRealArrays(dem, a, m);

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(4 * (size_t)n + 1, &tmp));
  PetscCall(PetscMalloc1((size_t)n + 1, &itmp));
  for (int c = 0; c < na; c++) {
    double *src = *a[c];
    for (PetscInt i = 0; i < n; i++)
      for (int k = 0; k < m[c]; k++) tmp[m[c] * i + k] = src[m[c] * perm[i] + k];
    PetscCall(PetscArraycpy(src, tmp, m[c] * n));
  }
  for (PetscInt i = 0; i < n; i++) itmp[i] = dem->p.id[perm[i]];
  PetscCall(PetscArraycpy(dem->p.id, itmp, n));
  for (PetscInt i = 0; i < n; i++) itmp[i] = dem->p.shape[perm[i]];
  PetscCall(PetscArraycpy(dem->p.shape, itmp, n));
  PetscCall(PetscFree(tmp));
  PetscCall(PetscFree(itmp));
  PetscFunctionReturn(PETSC_SUCCESS);
}

void DemParticleSetSize(Dem dem, PetscInt i, double r)
{
  const double m = dem_sphere_mass(dem->shapes.shp[dem->p.shape[i]].rho, r), inertia = 0.4 * m * r * r;
  dem->p.rad[i]  = r;
  dem->p.m[i]    = m;
  dem->p.invm[i] = 1.0 / m;
  dem->p.invi[i] = 1.0 / inertia;
}

/* A poly scene's particle radius: its own (p->r > 0) or its shape's (p->r = 0), within the
 * largest radius the reach was made for. */
static PetscErrorCode DemParticleRadius(Dem dem, const DemParticle *p, double *r)
{
  double rlim = dem->shapes.r_source_max;

  PetscFunctionBeginUser;
  for (PetscInt s = 0; s < dem->shapes.nshape; s++) rlim = PetscMax(rlim, dem->shapes.shp[s].r);
  *r = p->r > 0 ? p->r : dem->shapes.shp[p->shape].r;
  PetscCheck(p->r >= 0 && *r <= rlim, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "particle %" PetscInt_FMT ": radius %g m must be in (0, %g] (the largest a source declared, r_source_max, or a shape's radius)", p->id, (double)p->r, rlim);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemAddParticle(Dem dem, const DemParticle *p)
{
  PetscInt i = dem->p.n;
  double   r = 0;

  PetscFunctionBeginUser;
  dem->state++;
  PetscCheck(p->shape >= 0 && p->shape < dem->shapes.nshape, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "particle %" PetscInt_FMT ": shape %" PetscInt_FMT " not in [0, %" PetscInt_FMT ")", p->id, p->shape, dem->shapes.nshape);
  if (dem->shapes.poly) PetscCall(DemParticleRadius(dem, p, &r));
  for (int k = 0; k < 3; k++)
    PetscCheck(PetscIsNormalReal(p->x[k]) || p->x[k] == 0, PETSC_COMM_SELF, PETSC_ERR_FP, "particle %" PetscInt_FMT ": position is not finite", p->id);
  PetscCall(DemParticlesReserve(dem, i + 1));
  for (int k = 0; k < 3; k++) {
    dem->p.x[3 * i + k] = dem->p.x0[3 * i + k] = p->x[k];
    dem->p.v[3 * i + k]                        = p->v[k];
    dem->p.w[3 * i + k]                        = p->w[k];
    dem->p.f[3 * i + k] = dem->p.tq[3 * i + k] = 0;
  }
  for (int k = 0; k < 4; k++) dem->p.q[4 * i + k] = p->q[k];
  if (dem->ext.on) {
    dem->ext.kdrag[i] = 0;
    for (int k = 0; k < 3; k++) dem->ext.fext[3 * i + k] = dem->ext.udrag[3 * i + k] = dem->ext.jdrag[3 * i + k] = 0;
  }
  if (p->q[0] == 0 && p->q[1] == 0 && p->q[2] == 0 && p->q[3] == 0) dem->p.q[4 * i] = 1; /* identity */
  dem->p.id[i]    = p->id;
  dem->p.shape[i] = p->shape;
  if (dem->shapes.poly) DemParticleSetSize(dem, i, r);
  dem->p.n++;
  dem->p.next_id  = PetscMax(dem->p.next_id, p->id + 1);
  dem->need_build = PETSC_TRUE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemGetLocalCount(Dem dem, PetscInt *n)
{
  PetscFunctionBeginUser;
  *n = dem->p.n;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemGetParticle(Dem dem, PetscInt i, DemParticle *p)
{
  PetscFunctionBeginUser;
  PetscCheck(i >= 0 && i < dem->p.n, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "particle index %" PetscInt_FMT " not in [0, %" PetscInt_FMT ")", i, dem->p.n);
  p->id    = dem->p.id[i];
  p->shape = dem->p.shape[i];
  p->r     = dem->p.rad ? dem->p.rad[i] : 0;
  for (int k = 0; k < 3; k++) {
    p->x[k] = dem->p.x[3 * i + k];
    p->v[k] = dem->p.v[3 * i + k];
    p->w[k] = dem->p.w[3 * i + k];
  }
  for (int k = 0; k < 4; k++) p->q[k] = dem->p.q[4 * i + k];
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemSetParticle(Dem dem, PetscInt i, const DemParticle *p)
{
  PetscFunctionBeginUser;
  dem->state++;
  PetscCheck(i >= 0 && i < dem->p.n, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "particle index %" PetscInt_FMT " not in [0, %" PetscInt_FMT ")", i, dem->p.n);
  for (int k = 0; k < 3; k++) {
    dem->p.x[3 * i + k] = p->x[k];
    dem->p.v[3 * i + k] = p->v[k];
    dem->p.w[3 * i + k] = p->w[k];
  }
  for (int k = 0; k < 4; k++) dem->p.q[4 * i + k] = p->q[k];
  if (dem->shapes.poly && p->r > 0 && p->r != dem->p.rad[i]) { /* a new size (its shape stays) */
    DemParticle t = *p;
    double      r;
    t.shape = dem->p.shape[i];
    PetscCall(DemParticleRadius(dem, &t, &r));
    DemParticleSetSize(dem, i, r);
  }
  dem->need_build = PETSC_TRUE;
  PetscFunctionReturn(PETSC_SUCCESS);
}
