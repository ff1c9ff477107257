/* The per-particle fields (dem_fields.h): one row per array of the particle store, and the
 * packing of a particle's rows into a message of doubles and back. The rows' order is the order
 * of the values in a record, of the frames' particle datasets (position, velocity,
 * angular_velocity, quaternion, radius, id, shape) and of the arrays' allocation. Ids and shapes travel as doubles, exact
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
  {"dem/f", DEM_FIELD_REAL, 3, DEM_FIELD_AT(p.f), DEM_FIELD_ALWAYS, STATE | DEM_FIELD_CKPT_GHOSTS, NULL, DEM_FRAME_STORED, NULL},
  {"dem/tq", DEM_FIELD_REAL, 3, DEM_FIELD_AT(p.tq), DEM_FIELD_ALWAYS, STATE | DEM_FIELD_CKPT_GHOSTS, NULL, DEM_FRAME_STORED, NULL},
  {"dem/q", DEM_FIELD_REAL, 4, DEM_FIELD_AT(p.q), DEM_FIELD_ALWAYS, ALL_MSG, "quaternion", DEM_FRAME_STORED, NULL},
  {"dem/x0", DEM_FIELD_REAL, 3, DEM_FIELD_AT(p.x0), DEM_FIELD_ALWAYS, DEM_FIELD_PERMUTE | DEM_FIELD_CKPT, NULL, DEM_FRAME_STORED, NULL}, /* set from x on arrival and at list builds */
  {"dem/ext_fext", DEM_FIELD_REAL, 3, DEM_FIELD_AT(ext.fext), DEM_FIELD_COUPLED, STATE, NULL, DEM_FRAME_STORED, NULL},
  {"dem/ext_k", DEM_FIELD_REAL, 1, DEM_FIELD_AT(ext.kdrag), DEM_FIELD_COUPLED, STATE, NULL, DEM_FRAME_STORED, NULL},
  {"dem/ext_u", DEM_FIELD_REAL, 3, DEM_FIELD_AT(ext.udrag), DEM_FIELD_COUPLED, STATE, NULL, DEM_FRAME_STORED, NULL},
  {"dem/ext_j", DEM_FIELD_REAL, 3, DEM_FIELD_AT(ext.jdrag), DEM_FIELD_COUPLED, STATE, NULL, DEM_FRAME_STORED, NULL},
  {"dem/radius", DEM_FIELD_REAL, 1, DEM_FIELD_AT(p.rad), DEM_FIELD_POLY, OWNED, "radius", DEM_FRAME_RADIUS, DemFieldSizesArrive},
  {"dem/mass", DEM_FIELD_REAL, 1, DEM_FIELD_AT(p.m), DEM_FIELD_POLY, DEM_FIELD_PERMUTE | DEM_FIELD_CKPT | DEM_FIELD_CKPT_GHOSTS, NULL, DEM_FRAME_STORED, NULL}, /* from the radius */
  {"dem/inv_mass", DEM_FIELD_REAL, 1, DEM_FIELD_AT(p.invm), DEM_FIELD_POLY, DEM_FIELD_PERMUTE | DEM_FIELD_CKPT | DEM_FIELD_CKPT_GHOSTS, NULL, DEM_FRAME_STORED, NULL},
  {"dem/inv_inertia", DEM_FIELD_REAL, 1, DEM_FIELD_AT(p.invi), DEM_FIELD_POLY, DEM_FIELD_PERMUTE | DEM_FIELD_CKPT | DEM_FIELD_CKPT_GHOSTS, NULL, DEM_FRAME_STORED, NULL},
  {"dem/id", DEM_FIELD_INT, 1, DEM_FIELD_AT(p.id), DEM_FIELD_ALWAYS, OWNED, "id", DEM_FRAME_STORED, NULL},
  {"dem/shape", DEM_FIELD_INT, 1, DEM_FIELD_AT(p.shape), DEM_FIELD_ALWAYS, OWNED, "shape", DEM_FRAME_STORED, NULL},
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
    DemRefKind kind = DEM_REF_ANY;
    if (f->flags & DEM_FIELD_SHIFT) kind = DEM_REF_SHIFT3;
    else if (f->type == DEM_FIELD_INT) kind = f->width == 1 ? DEM_REF_INT1 : DEM_REF_ANY;
    else if (f->width == 1) kind = DEM_REF_REAL1;
    else if (f->width == 3) kind = DEM_REF_REAL3;
    else if (f->width == 4) kind = DEM_REF_REAL4;
    ref[nf] = (DemFieldRef){*DemFieldPtr(dem, f), f->width, kind, f};
    *width += (size_t)f->width;
    nf++;
  }
  return nf;
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

/* The messages' loops. Particles go in blocks of DEM_PACK_BLOCK whose records stay in the first
 * level cache; within a block row after row, each by a loop of its width known to the compiler
 * (the position with its shift; 1, 3, 4), so the loops are the hand-written layout's. */
#define DEM_PACK_BLOCK 64
#define DEM_PACK_LOOP(W, EXPR) \
  for (PetscInt a = 0; a < cnt; a++) \
    for (int k = 0; k < (W); k++) d[stride * (size_t)a + k] = (EXPR)
#define DEM_UNPACK_LOOP(W, T) \
  for (PetscInt a = 0; a < cnt; a++) \
    for (int k = 0; k < (W); k++) ((T *)r->a)[(size_t)(W) * (g0 + a) + k] = (T)e[stride * (size_t)a + k]

static void dem_pack_rows(const DemFieldRef *ref, int nf, const PetscInt *idx, PetscInt cnt, const double shift[3], double *b, size_t stride)
{
  double *d = b;
  for (int f = 0; f < nf; d += ref[f].width, f++) {
    const DemFieldRef *r = &ref[f];
    const double      *s = (const double *)r->a;
    switch (r->kind) {
    case DEM_REF_SHIFT3:
      DEM_PACK_LOOP(3, s[3 * idx[a] + k] + shift[k]);
      break;
    case DEM_REF_REAL1:
      DEM_PACK_LOOP(1, s[idx[a]]);
      break;
    case DEM_REF_REAL3:
      DEM_PACK_LOOP(3, s[3 * idx[a] + k]);
      break;
    case DEM_REF_REAL4:
      DEM_PACK_LOOP(4, s[4 * idx[a] + k]);
      break;
    case DEM_REF_INT1:
      DEM_PACK_LOOP(1, (double)((const PetscInt *)r->a)[idx[a]]);
      break;
    default:
      DEM_PACK_LOOP(r->width, s[(size_t)r->width * idx[a] + k]);
    }
  }
}

static void dem_unpack_rows(const DemFieldRef *ref, int nf, PetscInt g0, PetscInt cnt, const double *b, size_t stride)
{
  const double *e = b;
  for (int f = 0; f < nf; e += ref[f].width, f++) {
    const DemFieldRef *r = &ref[f];
    switch (r->kind) {
    case DEM_REF_SHIFT3:
    case DEM_REF_REAL3:
      DEM_UNPACK_LOOP(3, double);
      break;
    case DEM_REF_REAL1:
      DEM_UNPACK_LOOP(1, double);
      break;
    case DEM_REF_REAL4:
      DEM_UNPACK_LOOP(4, double);
      break;
    case DEM_REF_INT1:
      DEM_UNPACK_LOOP(1, PetscInt);
      break;
    default:
      DEM_UNPACK_LOOP(r->width, double);
    }
  }
}

void DemFieldsPackList(const DemFieldRef *ref, int nf, const PetscInt *idx, PetscInt cnt, const double shift[3], double *b, size_t stride)
{
  for (PetscInt a0 = 0; a0 < cnt; a0 += DEM_PACK_BLOCK) dem_pack_rows(ref, nf, idx + a0, PetscMin(DEM_PACK_BLOCK, cnt - a0), shift, b + stride * (size_t)a0, stride);
}

void DemFieldsUnpackRange(const DemFieldRef *ref, int nf, PetscInt g0, PetscInt cnt, const double *b, size_t stride)
{
  for (PetscInt a0 = 0; a0 < cnt; a0 += DEM_PACK_BLOCK) dem_unpack_rows(ref, nf, g0 + a0, PetscMin(DEM_PACK_BLOCK, cnt - a0), b + stride * (size_t)a0, stride);
}

double *DemFieldsPack(const DemFieldRef *ref, int nf, PetscInt i, const double shift[3], double *b)
{
  size_t w = 0;
  for (int f = 0; f < nf; f++) w += (size_t)ref[f].width;
  dem_pack_rows(ref, nf, &i, 1, shift, b, w);
  return b + w;
}

const double *DemFieldsUnpack(const DemFieldRef *ref, int nf, PetscInt i, const double *b)
{
  size_t w = 0;
  for (int f = 0; f < nf; f++) w += (size_t)ref[f].width;
  dem_unpack_rows(ref, nf, i, 1, b, w);
  return b + w;
}
