/* The table of per-particle fields (src/dem/dem_fields.h) against the particle store it
 * describes and the packers that walk it.
 *   storage: every pointer-sized word of DemParticles and DemExternalState that is not one of
 *     their counters or flags is the array of exactly one row, and every row's array lies in one
 *     of them (a new array without its row, or a row twice, fails); a control: the same check
 *     on the table without its dem/x0 row must find that word uncovered;
 *   rows: integer rows have width 1, the shifted row is the 3 doubles of the position, names of
 *     datasets are unique, a frame row is a checkpoint row, a row of the forward update is a
 *     ghost row, every row moves with the permutation;
 *   allocation: after set-up of a scene of own sizes with a coupling, every row's array exists;
 *   records: the migration record of a particle (no springs) is the migration rows' widths plus
 *     its spring count (DemMigSize, DemMigPack), and unpacked (DemMigUnpack) every value of those
 *     rows arrives bitwise, the id 2^31 - 2 included (a float would make it 2^31), the mass and inertia from the radius too;
 *     the ghost rows' record likewise, one particle (DemFieldsPack, DemFieldsUnpack) and a list
 *     (DemFieldsPackList, DemFieldsUnpackRange, as the ghost messages). */
#include "dem_common.h"
#include "dem/dem_fields.h"

/* Whether every word of the struct at [base, base + size) of struct _p_Dem outside the scalars
 * (offset, size pairs relative to base) is the offset of exactly one row of rows (skip: a row
 * left out), and every row inside it is such a word; the first offending offset in *bad. */
static PetscBool Covered(size_t base, size_t size, const size_t (*scal)[2], int nscal, int skip, size_t *bad)
{
  for (size_t o = 0; o + sizeof(void *) <= size; o += sizeof(void *)) {
    int hits = 0, scalar = 0;
    for (int s = 0; s < nscal; s++) scalar |= scal[s][0] < o + sizeof(void *) && o < scal[s][0] + scal[s][1];
    if (scalar) continue;
    for (int k = 0; k < dem_nfields; k++) hits += k != skip && dem_fields[k].at == base + o;
    if (hits != 1) {
      *bad = o;
      return PETSC_FALSE;
    }
  }
  return PETSC_TRUE;
}

static PetscErrorCode CheckStorage(void)
{
  const size_t ps[4][2] = {{offsetof(DemParticles, n), sizeof(PetscInt)}, {offsetof(DemParticles, ng), sizeof(PetscInt)}, {offsetof(DemParticles, cap), sizeof(PetscInt)}, {offsetof(DemParticles, next_id), sizeof(PetscInt)}};
  const size_t es[2][2] = {{offsetof(DemExternalState, on), sizeof(PetscBool)}, {offsetof(DemExternalState, frozen), sizeof(PetscBool)}};
  const size_t pb = DEM_FIELD_AT(p), eb = DEM_FIELD_AT(ext);
  size_t       bad    = 0;
  int          inside = 0, x0 = -1;
  PetscBool    ok;

  PetscFunctionBeginUser;
  ok = Covered(pb, sizeof(DemParticles), ps, 4, -1, &bad);
  PetscCall(CheckTrue("every array of DemParticles is one row of the table", ok, ok ? "yes" : CheckName("the word at offset %zu is in %s rows", bad, "0 or 2+")));
  ok = Covered(eb, sizeof(DemExternalState), es, 2, -1, &bad);
  PetscCall(CheckTrue("every array of DemExternalState is one row of the table", ok, ok ? "yes" : CheckName("the word at offset %zu is in %s rows", bad, "0 or 2+")));
  for (int k = 0; k < dem_nfields; k++) {
    const size_t a = dem_fields[k].at;
    inside += (a >= pb && a < pb + sizeof(DemParticles)) || (a >= eb && a < eb + sizeof(DemExternalState));
    if (dem_fields[k].ckpt && !strcmp(dem_fields[k].ckpt, "dem/x0")) x0 = k;
  }
  PetscCall(CheckEqual("rows whose array lies in DemParticles or DemExternalState", inside, dem_nfields));
  ok = (PetscBool)(x0 >= 0 && !Covered(pb, sizeof(DemParticles), ps, 4, x0, &bad) && bad == dem_fields[x0].at - pb);
  PetscCall(CheckTrue("control: the table without dem/x0 leaves the word of p.x0 uncovered", ok, ok ? CheckName("offset %zu found", bad) : "not found"));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode CheckRows(void)
{
  int bad_int = 0, bad_shift = 0, bad_frame = 0, bad_update = 0, bad_perm = 0, dup = 0;

  PetscFunctionBeginUser;
  for (int k = 0; k < dem_nfields; k++) {
    const DemField *f = &dem_fields[k];
    bad_int += f->type == DEM_FIELD_INT && f->width != 1;
    bad_shift += (f->flags & DEM_FIELD_SHIFT) && (f->type != DEM_FIELD_REAL || f->width != 3 || f->at != DEM_FIELD_AT(p.x));
    bad_frame += f->frame && !(f->flags & DEM_FIELD_CKPT);
    bad_update += (f->flags & DEM_FIELD_UPDATE) && !(f->flags & DEM_FIELD_GHOST);
    bad_perm += !(f->flags & DEM_FIELD_PERMUTE);
    for (int j = 0; j < k; j++) dup += (f->ckpt && dem_fields[j].ckpt && !strcmp(f->ckpt, dem_fields[j].ckpt)) || (f->frame && dem_fields[j].frame && !strcmp(f->frame, dem_fields[j].frame));
  }
  PetscCall(CheckEqual("integer rows of width other than 1", bad_int, 0));
  PetscCall(CheckEqual("shifted rows other than the position's 3 doubles", bad_shift, 0));
  PetscCall(CheckEqual("frame rows that are not checkpoint rows", bad_frame, 0));
  PetscCall(CheckEqual("forward-update rows that are not ghost rows", bad_update, 0));
  PetscCall(CheckEqual("rows the permutation does not move", bad_perm, 0));
  PetscCall(CheckEqual("dataset names used twice", dup, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Whether row f of particles i and j holds the same bits. */
static PetscBool SameRow(Dem dem, const DemField *f, PetscInt i, PetscInt j)
{
  const size_t sz = (f->type == DEM_FIELD_INT ? sizeof(PetscInt) : sizeof(double)) * (size_t)f->width;
  const char  *a  = (const char *)*DemFieldPtr(dem, f);
  return (PetscBool)!memcmp(a + sz * (size_t)i, a + sz * (size_t)j, sz);
}

static PetscErrorCode CheckRecords(PetscBool poly)
{
  const char *what = poly ? "own sizes, coupled" : "one size, dry";
  Domain      dom;
  Dem         dem;
  DemExternal ext;
  DemFieldRef ref[DEM_MAX_FIELDS];
  size_t      w, used = 0;
  double     *b;
  DemSpring  *recs = NULL;
  PetscInt    nrec = 0, cap = 0, n, missing = 0, differ = 0;
  int         nf;

  PetscFunctionBeginUser;
  PetscCall(TestDemCreate("-domain_lo 0,0,0 -domain_hi 0.1,0.1,0.1 -dem_radius 0.005 -dem_kn 1e4 -dem_friction 0.3 -dem_contact_law linear -dem_dt 1e-5 -dem_gravity 0,0,-9.81", &dom, &dem));
  if (poly) PetscCall(DemSetOwnSizes(dem, 0.002, 0.005));
  for (PetscInt k = 0; k < 3; k++) {
    DemParticle p = {.id = k ? k : 2147483646, .shape = 0, .x = {0.02 + 0.03 * k, 0.05 + 1e-17 * k, 0.0500000001}, .v = {0.1, -0.3 / 7, 1e-300}, .w = {1.0 / 3, 0, -2}, .q = {0.6, 0.8, 0, 0}, .r = poly ? 0.0021 + 1e-4 * k / 3 : 0};
    PetscCall(DemAddParticle(dem, &p));
  }
  if (poly) PetscCall(DemSetExternal(dem, PETSC_TRUE));
  PetscCall(DemSetUp(dem));
  PetscCall(DemStep(dem)); /* forces and torques set */
  for (int k = 0; k < dem_nfields; k++) missing += DemFieldOn(dem, &dem_fields[k]) && !*DemFieldPtr(dem, &dem_fields[k]);
  PetscCall(CheckEqual(CheckName("rows of the scene (%s) without their array after set-up", what), missing, 0));
  if (poly) {
    PetscCall(DemGetExternal(dem, &ext));
    for (int k = 0; k < 3; k++) ext.fext[k] = ext.u[k] = ext.j[k] = 1.0 / (3 + k);
    ext.k[0] = 0.1;
  }
  PetscCall(DemGetLocalCount(dem, &n));
  PetscInt i = TestFind(dem, 2147483646);
  nf         = DemFieldsResolve(dem, DEM_FIELD_MIGRATE, ref, &w);
  PetscCall(PetscMalloc1(w + 64, &b));
  const size_t sz = DemMigSize(dem, i, recs, nrec), packed = DemMigPack(dem, i, recs, nrec, (double[3]){0, 0, 0}, b);
  PetscCall(CheckEqual(CheckName("migration record (%s): DemMigSize = the migration rows' widths + 1", what), (PetscInt)sz, (PetscInt)w + 1));
  PetscCall(CheckEqual(CheckName("migration record (%s): DemMigPack writes DemMigSize doubles", what), (PetscInt)packed, (PetscInt)sz));
  PetscCall(DemMigUnpack(dem, b, &recs, &nrec, &cap, &used));
  PetscCall(CheckEqual(CheckName("migration record (%s): DemMigUnpack reads them", what), (PetscInt)used, (PetscInt)sz));
  for (int k = 0; k < dem_nfields; k++) {
    const DemField *f = &dem_fields[k];
    if (!DemFieldOn(dem, f) || f->at == DEM_FIELD_AT(p.x0)) continue; /* x0: the position on arrival */
    if (!SameRow(dem, f, i, n)) differ++;
  }
  PetscCall(CheckEqual(CheckName("migration (%s): rows of the arrived copy not bitwise the particle's (id 2^31-2)", what), differ, 0));
  nf        = DemFieldsResolve(dem, DEM_FIELD_GHOST, ref, &w);
  double *e = DemFieldsPack(ref, nf, i, (double[3]){0, 0, 0}, b);
  PetscCall(DemParticlesReserve(dem, n + 3));
  nf              = DemFieldsResolve(dem, DEM_FIELD_GHOST, ref, &w);
  const double *r = DemFieldsUnpack(ref, nf, n + 1, b);
  DemFieldsArrive(dem, ref, nf, n + 1);
  DemFieldsPackList(ref, nf, (PetscInt[2]){i, i}, 2, (double[3]){0, 0, 0}, b, w); /* the messages' way */
  DemFieldsUnpackRange(ref, nf, n + 2, 1, b + w, w);
  DemFieldsArrive(dem, ref, nf, n + 2);
  differ = 0;
  for (int k = 0; k < dem_nfields; k++) {
    const DemField *f = &dem_fields[k];
    if (DemFieldOn(dem, f) && (f->flags & DEM_FIELD_GHOST || (poly && f->when == DEM_FIELD_POLY))) differ += !SameRow(dem, f, i, n + 1) + !SameRow(dem, f, i, n + 2);
  }
  PetscCall(CheckEqual(CheckName("ghost record (%s): packed and read = the ghost rows' widths", what), (PetscInt)(e - b) + (PetscInt)(r - b), 2 * (PetscInt)w));
  PetscCall(CheckEqual(CheckName("ghost record (%s): rows of the ghost (and its mass, 1/m, 1/I) not bitwise the owner's", what), differ, 0));
  PetscCall(PetscFree(b));
  PetscCall(PetscFree(recs));
  PetscCall(TestDemDestroy(&dom, &dem));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(CheckStorage());
  PetscCall(CheckRows());
  PetscCall(CheckRecords(PETSC_FALSE));
  PetscCall(CheckRecords(PETSC_TRUE));
  PetscCall(PetscFinalize());
  return check_failures ? 1 : 0;
}
