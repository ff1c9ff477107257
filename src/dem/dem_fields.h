/* The table of per-particle fields (fields.c): every array of the particle store, one row each,
 * with its type, width, storage and the operations that carry it. The store's growth and
 * permutation (particles.c), the migration record and the ghost messages (exchange.c,
 * redistribute.c), the checkpoint datasets (checkpoint.c, checkpoint_remap.c) and the frames'
 * particle datasets (diag.c) walk it, so a new per-particle quantity is one row plus its physics
 * (and its pointer in DemParticles or DemExternalState).
 * Messages are doubles: a real field is copied as it is, an integer field converted to double and
 * back, exact for |value| < 2^53 (a PetscInt of 32 bits always; ids and shapes of 64 bits are far
 * below). A row's values sit in the record in the table's order, the position (DEM_FIELD_SHIFT)
 * with the periodic shift of the direction added.
 * Invariants (tests/dem/test_fields.c): every pointer of DemParticles and DemExternalState is one
 * row; an integer row has width 1; a frame row is a checkpoint row too. */
#pragma once
#include "dem/dem_core.h"
#include <stddef.h>

typedef enum {
  DEM_FIELD_REAL, /* double */
  DEM_FIELD_INT   /* PetscInt */
} DemFieldType;

/* Which scenes have the array: every one, a coupled run (DemSetExternal), spheres of their own
 * sizes (DemShapeTable.poly). An absent array is NULL and no operation carries it. */
typedef enum {
  DEM_FIELD_ALWAYS,
  DEM_FIELD_COUPLED,
  DEM_FIELD_POLY
} DemFieldWhen;

/* What a row takes part in (flags). Permutation moves the local particles (re-sort, removal,
 * migration); migration is the record of a particle that changes rank; ghost the message that
 * creates a ghost at a list build; update the forward update of the ghosts at every other step;
 * a checkpoint dataset holds the locals' rows, and the ghosts' too with DEM_FIELD_CKPT_GHOSTS. */
enum {
  DEM_FIELD_PERMUTE     = 1 << 0,
  DEM_FIELD_MIGRATE     = 1 << 1,
  DEM_FIELD_GHOST       = 1 << 2,
  DEM_FIELD_UPDATE      = 1 << 3,
  DEM_FIELD_SHIFT       = 1 << 4, /* the position: a message adds its direction's periodic shift */
  DEM_FIELD_CKPT        = 1 << 5,
  DEM_FIELD_CKPT_GHOSTS = 1 << 6
};

/* What a frame's particle dataset holds: the stored array of the locals, the positions wrapped
 * into the box along periodic axes (DemWrapPeriodic), or every particle's radius (its own in a
 * scene of own sizes, else its shape's: written in every scene). */
typedef enum {
  DEM_FRAME_STORED,
  DEM_FRAME_WRAPPED,
  DEM_FRAME_RADIUS
} DemFrameFrom;

typedef struct {
  const char  *ckpt;  /* checkpoint dataset (dem/...), NULL: none */
  DemFieldType type;  /* double or PetscInt */
  int          width; /* values per particle */
  size_t       at;    /* offset of the array's pointer in struct _p_Dem (DEM_FIELD_AT) */
  DemFieldWhen when;
  unsigned     flags;
  const char  *frame; /* frame dataset (particles/...), NULL: none; the frames' order is the table's */
  DemFrameFrom frame_from;
  /* after a message put the row's values of particle i in place (migration, ghosts): the
     values that follow from them (the radius: mass, 1/m, 1/I); NULL: none */
  void (*arrive)(Dem dem, PetscInt i);
} DemField;
#define DEM_FIELD_AT(member) offsetof(struct _p_Dem, member)

extern const DemField dem_fields[];
extern const int      dem_nfields;

/* Whether the scene has row f's array. */
static inline PetscBool DemFieldOn(Dem dem, const DemField *f)
{
  return (PetscBool)(f->when == DEM_FIELD_ALWAYS || (f->when == DEM_FIELD_COUPLED && dem->ext.on) || (f->when == DEM_FIELD_POLY && dem->shapes.poly));
}
/* The address of row f's array pointer in dem. */
static inline void **DemFieldPtr(Dem dem, const DemField *f)
{
  return (void **)((char *)dem + f->at);
}

/* A row as a message packer sees it, its array resolved (once per message, after any growth). */
typedef enum {
  DEM_REF_SHIFT3, /* the position: 3 doubles, the shift added */
  DEM_REF_REAL1,
  DEM_REF_REAL3,
  DEM_REF_REAL4,
  DEM_REF_INT1,
  DEM_REF_ANY /* doubles of another width (an integer row has width 1) */
} DemRefKind;
typedef struct {
  void           *a;
  int             width;
  DemRefKind      kind;
  const DemField *f;
} DemFieldRef;
#define DEM_MAX_FIELDS 32

/* The scene's rows with all of flags set, in the table's order: their count, and the doubles
 * of one particle's record (*width). */
int DemFieldsResolve(Dem dem, unsigned flags, DemFieldRef ref[DEM_MAX_FIELDS], size_t *width);
/* Particle i's values of the rows into b (the shift added to the position); returns b's end. */
double *DemFieldsPack(const DemFieldRef *ref, int nf, PetscInt i, const double shift[3], double *b);
/* The record b into particle i's slot; returns b's end. */
const double *DemFieldsUnpack(const DemFieldRef *ref, int nf, PetscInt i, const double *b);
/* The same for many particles (the ghost messages): particles idx[0..cnt) into records of
 * stride doubles from b; records into the slots g0..g0+cnt. */
void DemFieldsPackList(const DemFieldRef *ref, int nf, const PetscInt *idx, PetscInt cnt, const double shift[3], double *b, size_t stride);
void DemFieldsUnpackRange(const DemFieldRef *ref, int nf, PetscInt g0, PetscInt cnt, const double *b, size_t stride);
/* The rows' arrival rules for particle i (DemField.arrive). */
void DemFieldsArrive(Dem dem, const DemFieldRef *ref, int nf, PetscInt i);
/* Every array of the scene set to 0 for particle i. */
void DemFieldsClear(Dem dem, PetscInt i);

/* particles.c: the store's arrays freed; slot n, its rows ref (nf) filled from a message, checked
 * as a new particle and joined to the locals (x0 = x, arrival rules, counters) */
PetscErrorCode DemParticlesDestroy(Dem dem);
PetscErrorCode DemParticleArrive(Dem dem, const DemFieldRef *ref, int nf);
