/* Particle store: structure of arrays, xyz interleaved per particle, grown geometrically; its
 * arrays are the rows of the field table (dem_fields.h, fields.c), which growth, permutation and
 * a new particle's slot walk. Permutation (re-sort by cell for memory locality) moves every
 * per-particle array together; the neighbour module carries the contact springs across
 * (neighbours.c). In a scene of spheres of their own sizes (DemShapeTable.poly) each particle
 * also has its radius, mass, 1/m and 1/I (I = 2/5 m r^2, m = rho 4/3 pi r^3 with its shape's
 * density), set from the radius in one place (DemParticleSetSize, fields.c); other scenes
 * allocate none of them. */
#include "dem/dem_core.h"
#include "dem/dem_fields.h"

PetscErrorCode DemParticlesReserve(Dem dem, PetscInt n)
{
  PetscInt  cap     = dem->p.cap;
  PetscBool missing = PETSC_FALSE; /* a scene that became poly: its size arrays */

  PetscFunctionBeginUser;
  for (int k = 0; k < dem_nfields && cap > 0; k++) missing |= (PetscBool)(DemFieldOn(dem, &dem_fields[k]) && !*DemFieldPtr(dem, &dem_fields[k]));
  if (n <= cap && !missing) PetscFunctionReturn(PETSC_SUCCESS);
  if (n > cap) cap = PetscMax(n, cap + cap / 4 + 64);
  for (int k = 0; k < dem_nfields; k++) {
    const DemField *f = &dem_fields[k];
    if (DemFieldOn(dem, f)) PetscCall(PetscRealloc((f->type == DEM_FIELD_INT ? sizeof(PetscInt) : sizeof(double)) * (size_t)f->width * (size_t)cap, DemFieldPtr(dem, f)));
  }
  dem->p.cap = cap;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* new[i] = old[perm[i]] for every per-particle array */
PetscErrorCode DemParticlesPermute(Dem dem, const PetscInt *perm)
{
  const PetscInt n    = dem->p.n;
  int            wmax = 1;
  double        *tmp;
  PetscInt      *itmp;

  PetscFunctionBeginUser;
  for (int k = 0; k < dem_nfields; k++) wmax = PetscMax(wmax, dem_fields[k].width);
  PetscCall(PetscMalloc1((size_t)wmax * (size_t)n + 1, &tmp));
  PetscCall(PetscMalloc1((size_t)wmax * (size_t)n + 1, &itmp));
  for (int c = 0; c < dem_nfields; c++) {
    const DemField *f = &dem_fields[c];
    const int       m = f->width;
    if (!(f->flags & DEM_FIELD_PERMUTE) || !DemFieldOn(dem, f)) continue;
    if (f->type == DEM_FIELD_INT) {
      PetscInt *src = (PetscInt *)*DemFieldPtr(dem, f);
      for (PetscInt i = 0; i < n; i++)
        for (int k = 0; k < m; k++) itmp[m * i + k] = src[m * perm[i] + k];
      PetscCall(PetscArraycpy(src, itmp, m * n));
    } else {
      double *src = (double *)*DemFieldPtr(dem, f);
      for (PetscInt i = 0; i < n; i++)
        for (int k = 0; k < m; k++) tmp[m * i + k] = src[m * perm[i] + k];
      PetscCall(PetscArraycpy(src, tmp, m * n));
    }
  }
  PetscCall(PetscFree(tmp));
  PetscCall(PetscFree(itmp));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemParticlesDestroy(Dem dem)
{
  PetscFunctionBeginUser;
  for (int k = 0; k < dem_nfields; k++) PetscCall(PetscFree(*DemFieldPtr(dem, &dem_fields[k])));
  PetscFunctionReturn(PETSC_SUCCESS);
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

/* The checks of a new particle: its shape, its radius (r: 0 its shape's), a finite position. */
static PetscErrorCode DemParticleCheck(Dem dem, const DemParticle *p, double *r)
{
  PetscFunctionBeginUser;
  *r = 0;
  PetscCheck(p->shape >= 0 && p->shape < dem->shapes.nshape, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "particle %" PetscInt_FMT ": shape %" PetscInt_FMT " not in [0, %" PetscInt_FMT ")", p->id, p->shape, dem->shapes.nshape);
  if (dem->shapes.poly) PetscCall(DemParticleRadius(dem, p, r));
  for (int k = 0; k < 3; k++)
    PetscCheck(PetscIsNormalReal(p->x[k]) || p->x[k] == 0, PETSC_COMM_SELF, PETSC_ERR_FP, "particle %" PetscInt_FMT ": position is not finite", p->id);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Slot i = n, its rows ref (nf) filled, joins the locals: a zero quaternion becomes the
 * identity, x0 = x, the rows' arrival rules (DemFieldsArrive), the counters. */
static void DemParticleJoin(Dem dem, const DemFieldRef *ref, int nf)
{
  const PetscInt i = dem->p.n;
  double        *q = dem->p.q + 4 * i;

  dem->state++;
  if (q[0] == 0 && q[1] == 0 && q[2] == 0 && q[3] == 0) q[0] = 1; /* identity */
  for (int k = 0; k < 3; k++) dem->p.x0[3 * i + k] = dem->p.x[3 * i + k];
  DemFieldsArrive(dem, ref, nf, i);
  dem->p.n++;
  dem->p.next_id  = PetscMax(dem->p.next_id, dem->p.id[i] + 1);
  dem->need_build = PETSC_TRUE;
}

PetscErrorCode DemAddParticle(Dem dem, const DemParticle *p)
{
  const PetscInt i = dem->p.n;
  double         r;
  DemFieldRef    ref[DEM_MAX_FIELDS];
  size_t         w;

  PetscFunctionBeginUser;
  PetscCall(DemParticleCheck(dem, p, &r));
  PetscCall(DemParticlesReserve(dem, i + 1));
  DemFieldsClear(dem, i); /* force, torque, the coupling's arrays */
  for (int k = 0; k < 3; k++) {
    dem->p.x[3 * i + k] = p->x[k];
    dem->p.v[3 * i + k] = p->v[k];
    dem->p.w[3 * i + k] = p->w[k];
  }
  for (int k = 0; k < 4; k++) dem->p.q[4 * i + k] = p->q[k];
  dem->p.id[i]    = p->id;
  dem->p.shape[i] = p->shape;
  if (dem->shapes.poly) dem->p.rad[i] = r;
  DemParticleJoin(dem, ref, DemFieldsResolve(dem, 0, ref, &w));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemParticleArrive(Dem dem, const DemFieldRef *ref, int nf)
{
  const PetscInt i = dem->p.n;
  DemParticle    p = {0};
  double         r;

  PetscFunctionBeginUser;
  p.id    = dem->p.id[i];
  p.shape = dem->p.shape[i];
  p.r     = dem->shapes.poly ? dem->p.rad[i] : 0;
  for (int k = 0; k < 3; k++) p.x[k] = dem->p.x[3 * i + k];
  PetscCall(DemParticleCheck(dem, &p, &r));
  DemParticleJoin(dem, ref, nf);
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
