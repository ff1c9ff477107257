/* External forces on the particles, for a fluid coupling (the DEM never sees the fluid).
 * A coupling writes, per local particle, a constant force fext (e.g. buoyancy), a drag
 * coefficient k and a fluid velocity u; each translational half kick of length h then solves
 *   m dv/dt = F + fext + k (u - v)
 * with the drag backward-Euler (implicit in v), so any k h/m is stable:
 *   v' = (v + h ((F + fext)/m + k u/m)) / (1 + h k/m),
 * and adds the impulse actually received, h k (u - v'), to j. The arrays live beside the other
 * per-particle arrays (particles.c permutes them on re-sorts) and exist only while switched on.
 * A frozen DEM (-dem_frozen) integrates nothing: its particles are fixed obstacles. A checkpoint
 * holds the arrays of the local particles (dem/ext_fext, ext_k, ext_u, ext_j: the first rows of
 * the particle arrays, in the same local order). */
#include "dem/dem_core.h"
#include "dem/dem_fields.h"

/* The translational half kick of length h with the coupling's forces: writes the local
 * particles' v and the impulse j; reads f, the coupling's fext, k, u and the shapes' masses. */
void DemExternalKick(DemParticles *p, const DemShapeTable *st, DemExternalState *e, double h)
{
  double        *v = p->v, *j = e->jdrag;
  const double  *f = p->f, *fe = e->fext, *kd = e->kdrag, *u = e->udrag;
  const PetscInt n = p->n, *shape = p->shape;

  for (PetscInt i = 0; i < n; i++) {
    const double im = p->invm ? p->invm[i] : st->shp[shape[i]].invm, hk = h * kd[i];
    const double den = 1.0 / (1.0 + hk * im);
    for (int k = 0; k < 3; k++) {
      const double vn = (v[3 * i + k] + h * (f[3 * i + k] + fe[3 * i + k]) * im + hk * im * u[3 * i + k]) * den;
      v[3 * i + k]    = vn;
      j[3 * i + k] += hk * (u[3 * i + k] - vn);
    }
  }
}

PetscErrorCode DemSetExternal(Dem dem, PetscBool on)
{
  PetscFunctionBeginUser;
  if (on == dem->ext.on) PetscFunctionReturn(PETSC_SUCCESS);
  for (int k = 0; k < dem_nfields; k++) { /* the coupled rows of the field table */
    const DemField *f = &dem_fields[k];
    if (f->when != DEM_FIELD_COUPLED) continue;
    if (on) PetscCall(PetscCalloc((f->type == DEM_FIELD_INT ? sizeof(PetscInt) : sizeof(double)) * ((size_t)f->width * (size_t)dem->p.cap + 1), DemFieldPtr(dem, f)));
    else PetscCall(PetscFree(*DemFieldPtr(dem, f)));
  }
  dem->ext.on = on;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. A coupled run's checkpoint holds the coupling's arrays (dem/ext_*, rows of the
 * checkpoint table, checkpoint.c) and a dry one does not: neither continues the other. */
PetscErrorCode DemExternalCheckpointCheck(Dem dem, IoCkpt ck)
{
  const char *path;
  PetscBool   has;

  PetscFunctionBeginUser;
  PetscCall(IoCkptGetPath(ck, &path));
  PetscCall(IoCkptHas(ck, "dem/ext_k", &has));
  PetscCheck(has || !dem->ext.on, dem->comm, PETSC_ERR_FILE_UNEXPECTED, "-restart %s: the dataset dem/ext_k is missing: a dry run's checkpoint cannot continue a coupled run (this case has -fluid_ or -cpl_ options)", path);
  PetscCheck(!has || dem->ext.on, dem->comm, PETSC_ERR_FILE_UNEXPECTED, "-restart %s: the dataset dem/ext_k shows a coupled run's checkpoint; this case is dry (give the coupled case's -fluid_ and -cpl_ options)", path);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemGetExternal(Dem dem, DemExternal *e)
{
  PetscFunctionBeginUser;
  PetscCheck(dem->ext.on, PETSC_COMM_SELF, PETSC_ERR_ORDER, "call DemSetExternal(dem, PETSC_TRUE) before DemGetExternal");
  e->fext = dem->ext.fext;
  e->k    = dem->ext.kdrag;
  e->u    = dem->ext.udrag;
  e->j    = dem->ext.jdrag;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemGetState(Dem dem, PetscInt *state)
{
  PetscFunctionBeginUser;
  *state = dem->state;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemGetArrays(Dem dem, DemArrays *a)
{
  PetscFunctionBeginUser;
  a->nlocal = dem->p.n;
  a->nghost = dem->p.ng;
  a->x      = dem->p.x;
  a->v      = dem->p.v;
  a->id     = dem->p.id;
  a->shape  = dem->p.shape;
  a->r      = dem->p.rad;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemGetShape(Dem dem, PetscInt s, PetscReal *radius, PetscReal *mass)
{
  PetscFunctionBeginUser;
  PetscCheck(s >= 0 && s < dem->shapes.nshape, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "shape %" PetscInt_FMT " not in [0, %" PetscInt_FMT ")", s, dem->shapes.nshape);
  if (radius) *radius = dem->shapes.shp[s].r;
  if (mass) *mass = dem->shapes.shp[s].m;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemGetShapeCount(Dem dem, PetscInt *n)
{
  PetscFunctionBeginUser;
  *n = dem->shapes.nshape;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemGetGravity(Dem dem, PetscReal g[3])
{
  PetscFunctionBeginUser;
  for (int k = 0; k < 3; k++) g[k] = dem->g[k];
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemExternalSetFromOptions(Dem dem)
{
  PetscFunctionBeginUser;
  PetscOptionsBegin(dem->comm, NULL, "DEM frozen bed", NULL);
  PetscCall(SableOptionsBool("-dem_frozen", "Integrate no particles (fixed obstacles, e.g. a packed bed)", dem->ext.frozen, &dem->ext.frozen, NULL));
  PetscOptionsEnd();
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemSetFrozen(Dem dem, PetscBool frozen)
{
  PetscFunctionBeginUser;
  dem->ext.frozen = frozen;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemGetFrozen(Dem dem, PetscBool *frozen)
{
  PetscFunctionBeginUser;
  *frozen = dem->ext.frozen;
  PetscFunctionReturn(PETSC_SUCCESS);
}
