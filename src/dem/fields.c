/* The per-particle fields (dem_fields.h): one row per array of the particle store, and the
 * packing of a particle's rows into a message of doubles and back. The rows' order is the order
 * of the values in a record and of the frames' particle datasets (position, velocity,
 * angular_velocity, quaternion, radius, id, shape). Ids and shapes travel as doubles, exact
 * below 2^53. A particle of its own size sends only its radius: mass, 1/m and 1/I follow from
 * it on arrival (DemParticleSetSize), the same bits as the sender's. */
#include "dem/dem_fields.h"
#include <string.h>

#define ALL_MSG (DEM_FIELD_PERMUTE | DEM_FIELD_MIGRATE | DEM_FIELD_GHOST | DEM_FIELD_UPDATE | DEM_FIELD_CKPT | DEM_FIELD_CKPT_GHOSTS)
#define OWNED   (DEM_FIELD_PERMUTE | DEM_FIELD_MIGRATE | DEM_FIELD_GHOST | DEM_FIELD_CKPT | DEM_FIELD_CKPT_GHOSTS)
#define STATE   (DEM_FIELD_PERMUTE | DEM_FIELD_MIGRATE | DEM_FIELD_CKPT)

static void DemFieldSizesArrive(Dem dem, PetscInt i)
{
  DemParticleSetSize(dem, i, dem->p.rad[i]);
}

const DemField dem_fields[] = {
  /* checkpoint, type, width, storage, scenes, operations, frame */
  {"dem/x", DEM_FIELD_REAL, 3, DEM_FIELD_AT(p.x), DEM_FIELD_ALWAYS, ALL_MSG | DEM_FIELD_SHIFT, "position", DEM_FRAME_WRAPPED, NULL},
  {"dem/v", DEM_FIELD_REAL, 3, DEM_FIELD_AT(p.v), DEM_FIELD_ALWAYS, ALL_MSG, "velocity", DEM_FRAME_STORED, NULL},
  {"dem/w", DEM_FIELD_REAL, 3, DEM_FIELD_AT(p.w), DEM_FIELD_ALWAYS, ALL_MSG, "angular_velocity", DEM_FRAME_STORED, NULL},
  {"dem/q", DEM_FIELD_REAL, 4, DEM_FIELD_AT(p.q), DEM_FIELD_ALWAYS, ALL_MSG, "quaternion", DEM_FRAME_STORED, NULL},
  {"dem/radius", DEM_FIELD_REAL, 1, DEM_FIELD_AT(p.rad), DEM_FIELD_POLY, OWNED, "radius", DEM_FRAME_RADIUS, DemFieldSizesArrive},
  {"dem/id", DEM_FIELD_INT, 1, DEM_FIELD_AT(p.id), DEM_FIELD_ALWAYS, OWNED, "id", DEM_FRAME_STORED, NULL},
  {"dem/shape", DEM_FIELD_INT, 1, DEM_FIELD_AT(p.shape), DEM_FIELD_ALWAYS, OWNED, "shape", DEM_FRAME_STORED, NULL},
  {"dem/f", DEM_FIELD_REAL, 3, DEM_FIELD_AT(p.f), DEM_FIELD_ALWAYS, STATE | DEM_FIELD_CKPT_GHOSTS, NULL, DEM_FRAME_STORED, NULL},
  {"dem/tq", DEM_FIELD_REAL, 3, DEM_FIELD_AT(p.tq), DEM_FIELD_ALWAYS, STATE | DEM_FIELD_CKPT_GHOSTS, NULL, DEM_FRAME_STORED, NULL},
  {"dem/x0", DEM_FIELD_REAL, 3, DEM_FIELD_AT(p.x0), DEM_FIELD_ALWAYS, DEM_FIELD_PERMUTE | DEM_FIELD_CKPT, NULL, DEM_FRAME_STORED, NULL}, /* set from x on arrival and at list builds */
  {"dem/ext_fext", DEM_FIELD_REAL, 3, DEM_FIELD_AT(ext.fext), DEM_FIELD_COUPLED, STATE, NULL, DEM_FRAME_STORED, NULL},
  {"dem/ext_k", DEM_FIELD_REAL, 1, DEM_FIELD_AT(ext.kdrag), DEM_FIELD_COUPLED, STATE, NULL, DEM_FRAME_STORED, NULL},
  {"dem/ext_u", DEM_FIELD_REAL, 3, DEM_FIELD_AT(ext.udrag), DEM_FIELD_COUPLED, STATE, NULL, DEM_FRAME_STORED, NULL},
  {"dem/ext_j", DEM_FIELD_REAL, 3, DEM_FIELD_AT(ext.jdrag), DEM_FIELD_COUPLED, STATE, NULL, DEM_FRAME_STORED, NULL},
  {"dem/mass", DEM_FIELD_REAL, 1, DEM_FIELD_AT(p.m), DEM_FIELD_POLY, DEM_FIELD_PERMUTE | DEM_FIELD_CKPT | DEM_FIELD_CKPT_GHOSTS, NULL, DEM_FRAME_STORED, NULL}, /* from the radius */
  {"dem/inv_mass", DEM_FIELD_REAL, 1, DEM_FIELD_AT(p.invm), DEM_FIELD_POLY, DEM_FIELD_PERMUTE | DEM_FIELD_CKPT | DEM_FIELD_CKPT_GHOSTS, NULL, DEM_FRAME_STORED, NULL},
  {"dem/inv_inertia", DEM_FIELD_REAL, 1, DEM_FIELD_AT(p.invi), DEM_FIELD_POLY, DEM_FIELD_PERMUTE | DEM_FIELD_CKPT | DEM_FIELD_CKPT_GHOSTS, NULL, DEM_FRAME_STORED, NULL},
};
const int dem_nfields = (int)(sizeof dem_fields / sizeof dem_fields[0]);

void DemParticleSetSize(Dem dem, PetscInt i, double r)
{
  const double m = dem_sphere_mass(dem->shapes.shp[dem->p.shape[i]].rho, r), inertia = 0.4 * m * r * r;
  dem->p.rad[i]  = r;
  dem->p.m[i]    = m;
  dem->p.invm[i] = 1.0 / m;
  dem->p.invi[i] = 1.0 / inertia;
}

int DemFieldsResolve(Dem dem, unsigned flags, DemFieldRef ref[DEM_MAX_FIELDS], size_t *width)
{
  int nf = 0;
  *width = 0;
  for (int k = 0; k < dem_nfields; k++) {
    const DemField *f = &dem_fields[k];
    if ((f->flags & flags) != flags || !DemFieldOn(dem, f)) continue;
    ref[nf] = (DemFieldRef){*DemFieldPtr(dem, f), f->width, (f->flags & DEM_FIELD_SHIFT) != 0, f->type == DEM_FIELD_INT, f};
    *width += (size_t)f->width;
    nf++;
  }
  return nf;
}

double *DemFieldsPack(const DemFieldRef *ref, int nf, PetscInt i, const double shift[3], double *b)
{
  for (int f = 0; f < nf; f++) {
    const int w = ref[f].width;
    if (ref[f].isint) {
      const PetscInt *s = (const PetscInt *)ref[f].a + (size_t)w * i;
      for (int k = 0; k < w; k++) b[k] = (double)s[k];
    } else {
      const double *s = (const double *)ref[f].a + (size_t)w * i;
      if (ref[f].shift)
        for (int k = 0; k < 3; k++) b[k] = s[k] + shift[k];
      else if (w == 3) {
        b[0] = s[0];
        b[1] = s[1];
        b[2] = s[2];
      } else
        for (int k = 0; k < w; k++) b[k] = s[k];
    }
    b += w;
  }
  return b;
}

const double *DemFieldsUnpack(const DemFieldRef *ref, int nf, PetscInt i, const double *b)
{
  for (int f = 0; f < nf; f++) {
    const int w = ref[f].width;
    if (ref[f].isint) {
      PetscInt *d = (PetscInt *)ref[f].a + (size_t)w * i;
      for (int k = 0; k < w; k++) d[k] = (PetscInt)b[k];
    } else if (w == 3) {
      double *d = (double *)ref[f].a + (size_t)w * i;
      d[0]      = b[0];
      d[1]      = b[1];
      d[2]      = b[2];
    } else {
      double *d = (double *)ref[f].a + (size_t)w * i;
      for (int k = 0; k < w; k++) d[k] = b[k];
    }
    b += w;
  }
  return b;
}

void DemFieldsArrive(Dem dem, const DemFieldRef *ref, int nf, PetscInt i)
{
  for (int f = 0; f < nf; f++)
    if (ref[f].f->arrive) ref[f].f->arrive(dem, i);
}

void DemFieldsClear(Dem dem, PetscInt i)
{
  for (int k = 0; k < dem_nfields; k++) {
    const DemField *f = &dem_fields[k];
    if (!DemFieldOn(dem, f)) continue;
    const size_t sz = f->type == DEM_FIELD_INT ? sizeof(PetscInt) : sizeof(double);
    memset((char *)*DemFieldPtr(dem, f) + sz * (size_t)f->width * (size_t)i, 0, sz * (size_t)f->width);
  }
}

/* The list's rows, one row at a time over the particles (the inner loop of one width). */
void DemFieldsPackList(const DemFieldRef *ref, int nf, const PetscInt *idx, PetscInt cnt, const double shift[3], double *b, size_t stride)
{
  size_t o = 0;
  for (int f = 0; f < nf; o += (size_t)ref[f].width, f++) {
    const int w = ref[f].width;
    double   *d = b + o;
    if (ref[f].isint) {
      const PetscInt *s = (const PetscInt *)ref[f].a;
      for (PetscInt a = 0; a < cnt; a++)
        for (int k = 0; k < w; k++) d[stride * (size_t)a + k] = (double)s[(size_t)w * idx[a] + k];
    } else if (ref[f].shift) {
      const double *s = (const double *)ref[f].a;
      for (PetscInt a = 0; a < cnt; a++)
        for (int k = 0; k < 3; k++) d[stride * (size_t)a + k] = s[3 * idx[a] + k] + shift[k];
    } else if (w == 3) {
      const double *s = (const double *)ref[f].a;
      for (PetscInt a = 0; a < cnt; a++)
        for (int k = 0; k < 3; k++) d[stride * (size_t)a + k] = s[3 * idx[a] + k];
    } else if (w == 4) {
      const double *s = (const double *)ref[f].a;
      for (PetscInt a = 0; a < cnt; a++)
        for (int k = 0; k < 4; k++) d[stride * (size_t)a + k] = s[4 * idx[a] + k];
    } else {
      const double *s = (const double *)ref[f].a;
      for (PetscInt a = 0; a < cnt; a++)
        for (int k = 0; k < w; k++) d[stride * (size_t)a + k] = s[(size_t)w * idx[a] + k];
    }
  }
}

void DemFieldsUnpackRange(const DemFieldRef *ref, int nf, PetscInt g0, PetscInt cnt, const double *b, size_t stride)
{
  size_t o = 0;
  for (int f = 0; f < nf; o += (size_t)ref[f].width, f++) {
    const int     w = ref[f].width;
    const double *e = b + o;
    if (ref[f].isint) {
      PetscInt *d = (PetscInt *)ref[f].a + (size_t)w * g0;
      for (PetscInt a = 0; a < cnt; a++)
        for (int k = 0; k < w; k++) d[(size_t)w * a + k] = (PetscInt)e[stride * (size_t)a + k];
    } else if (w == 3) {
      double *d = (double *)ref[f].a + 3 * g0;
      for (PetscInt a = 0; a < cnt; a++)
        for (int k = 0; k < 3; k++) d[3 * a + k] = e[stride * (size_t)a + k];
    } else if (w == 4) {
      double *d = (double *)ref[f].a + 4 * g0;
      for (PetscInt a = 0; a < cnt; a++)
        for (int k = 0; k < 4; k++) d[4 * a + k] = e[stride * (size_t)a + k];
    } else {
      double *d = (double *)ref[f].a + (size_t)w * g0;
      for (PetscInt a = 0; a < cnt; a++)
        for (int k = 0; k < w; k++) d[(size_t)w * a + k] = e[stride * (size_t)a + k];
    }
  }
}
