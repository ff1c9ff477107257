/* Restart on another rank count: a checkpoint written by R ranks read by a run of P != R ranks.
 * The writer's per-rank state (checkpoint.c) is translated into what does not depend on the
 * decomposition: the owned particles with their state (each writing rank's first n rows of the
 * per-particle datasets, those of the field table, dem_fields.h; its ghosts are skipped), and
 * every tangential spring keyed by ids: (id_i, id_j, xi) for an entry of a rank's Verlet list, in a half list the reverse
 * (id_j, id_i, -xi) as well for a pair of two owned particles (each particle takes its own side
 * along, as DemSpringsSave does), (id, wall) for an entry of a wall list, and a mesh's loaded
 * slots as the two records of DemMeshesSaveSprings (spring, normal); a mesh's pose is a function
 * of the time, its local triangles and candidates are rebuilt with the lists. Reading rank k
 * takes the contiguous block of writing ranks [kR/P, (k+1)R/P), one slab per dataset; the DEM's
 * global migration (redistribute.c) sends every particle with its springs to the rank whose box
 * holds its centre (periodic positions wrapped); each rank orders its particles by id, so the
 * result does not depend on how the rows were split; the rebuild from the migration on
 * (rebuild.c) creates the ghosts, lists the pairs and re-attaches the springs by ids. The forces
 * and torques of the last step travel with the particles (velocity Verlet's first half step
 * reads them); the scalars (time, step, next id, list builds, particle count, id checksum) are
 * the file's; afterwards the count and the id checksum must be the file's (every id once).
 * The same rank count with other boxes (another process grid, other cuts) takes this way too:
 * its ranks' particles, each in its writer's box at the last list build (x0), are not all in
 * this run's boxes (DemCheckpointNeedsRemap).
 * Memory: a rank holds its block's rows of one dataset at a time, their ids and their lists,
 * about ceil(R/P) writing ranks' state (all of it on one rank for a 1-rank checkpoint). */
#include "dem/dem_core.h"
#include "dem/dem_walls.h"
#include "dem/dem_checkpoint.h"
#include <stddef.h>
#include "dem/dem_fields.h"

#define CNT(b, r, k) ((b)->cnt[DEM_CKPT_NCOUNT * (r) + (k)])

/* What this rank reads: the writing ranks [r0, r1) of R. */
typedef struct {
  IoCkpt      ck;
  const char *path;
  PetscInt    R, r0, r1;
  PetscInt   *cnt;  /* DEM_CKPT_NCOUNT counters per writing rank: n, ng, ... */
  PetscInt    nown; /* owned particles of the block */
  PetscInt   *gid;  /* ids of the block's rows, owned and ghosts, writer after writer */
  PetscInt   *goff; /* start of writer r's rows in gid, r - r0 */
} DemRemap;

/* The block's rows of a dataset: v, and off[r - r0] where writer r's rows start (r1 - r0 + 1). */
typedef struct {
  void     *v;
  PetscInt *off;
} DemSlab;

static PetscErrorCode DemSlabFree(DemSlab *s)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree(s->v));
  PetscCall(PetscFree(s->off));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. The block's rows of dataset name (all of them if all), writing rank r having
 * written rows[r] values (rows NULL: whatever the file's counts say). */
static PetscErrorCode DemRemapSlab(const DemRemap *b, const char *name, IoCkptType type, const PetscInt *rows, PetscBool all, DemSlab *s)
{
  long long *cnt, start = 0, len = 0;
  PetscInt   r0 = all ? 0 : b->r0, r1 = all ? b->R : b->r1;

  PetscFunctionBeginUser;
  PetscCall(IoCkptReadCounts(b->ck, name, &cnt));
  for (PetscInt r = 0; rows && r < b->R; r++) PetscCheck(cnt[r] == rows[r], PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "-restart %s: the dataset %s has %lld entries of rank %" PetscInt_FMT ", expected %" PetscInt_FMT " from its counters", b->path, name, cnt[r], r, rows[r]);
  PetscCall(PetscMalloc1(r1 - r0 + 1, &s->off));
  for (PetscInt r = 0; r < r0; r++) start += cnt[r];
  for (PetscInt r = r0; r < r1; r++) {
    s->off[r - r0] = (PetscInt)len;
    len += cnt[r];
  }
  s->off[r1 - r0] = (PetscInt)len;
  PetscCall(PetscFree(cnt));
  PetscCall(PetscMalloc(IoCkptTypeSize(type) * ((size_t)len + 1), &s->v));
  PetscCall(IoCkptReadSlabAll(b->ck, name, type, start, len, s->v));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. Every writing rank's counters, the scalars (which they agree on), the clock and
 * the walls' positions (rank 0's). */
static PetscErrorCode DemRemapCounters(Dem dem, DemRemap *b)
{
  PetscInt   *rows, nsum = 0;
  double      clk[3], *wd;
  PetscMPIInt rank, size;
  int         R;
  DemSlab     s;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(dem->comm, &rank));
  PetscCallMPI(MPI_Comm_size(dem->comm, &size));
  PetscCall(IoCkptGetRanks(b->ck, &R));
  b->R  = R;
  b->r0 = (PetscInt)(((long long)rank * R) / size);
  b->r1 = (PetscInt)(((long long)(rank + 1) * R) / size);
  PetscCall(PetscMalloc1(R, &rows));
  for (PetscInt r = 0; r < R; r++) rows[r] = DEM_CKPT_NCOUNT;
  PetscCall(DemRemapSlab(b, "dem/counters", IO_CKPT_INT, rows, PETSC_TRUE, &s));
  b->cnt = (PetscInt *)s.v;
  PetscCall(PetscFree(s.off));
  PetscCall(PetscFree(rows));
  for (PetscInt r = 0; r < R; r++) {
    PetscCheck(CNT(b, r, CK_NWALL) == dem->walls.nwall, dem->comm, PETSC_ERR_FILE_UNEXPECTED, "-restart %s: the dataset dem/counters gives %" PetscInt_FMT " walls, the case's options make %" PetscInt_FMT, b->path, CNT(b, r, CK_NWALL), dem->walls.nwall);
    PetscCheck(CNT(b, r, CK_STEP) == CNT(b, 0, CK_STEP) && CNT(b, r, CK_INITIAL_N) == CNT(b, 0, CK_INITIAL_N) && CNT(b, r, CK_N) >= 0 && CNT(b, r, CK_NG) >= 0, dem->comm, PETSC_ERR_FILE_UNEXPECTED, "-restart %s: the dataset dem/counters of rank %" PetscInt_FMT " disagrees with rank 0's (step, particle count) or has a negative count", b->path, r);
    nsum += CNT(b, r, CK_N);
    dem->p.next_id = PetscMax(dem->p.next_id, CNT(b, r, CK_NEXT_ID));
  }
  /* the run's count: initial + inserted - removed (dem->flow, read before the remap) */
  PetscCheck(nsum == CNT(b, 0, CK_INITIAL_N) + dem->flow.inserted - dem->flow.removed, dem->comm, PETSC_ERR_FILE_UNEXPECTED, "-restart %s: the dataset dem/counters gives %" PetscInt_FMT " particles owned by the ranks that wrote it, and a run of %" PetscInt_FMT, b->path, nsum, CNT(b, 0, CK_INITIAL_N) + dem->flow.inserted - dem->flow.removed);
  b->nown = 0;
  for (PetscInt r = b->r0; r < b->r1; r++) b->nown += CNT(b, r, CK_N);
  dem->nl.builds   = CNT(b, 0, CK_BUILDS);
  dem->nl.sorts    = CNT(b, 0, CK_SORTS);
  dem->clock.step  = CNT(b, 0, CK_STEP);
  dem->state       = CNT(b, 0, CK_STATE);
  dem->initial.n   = CNT(b, 0, CK_INITIAL_N);
  dem->ex.migrated = 0;
  PetscCall(IoCkptReadSlabAll(b->ck, "dem/clock", IO_CKPT_REAL, 0, 3, clk));
  dem->clock.t          = clk[0];
  dem->initial.checksum = clk[1];
  PetscCall(PetscMalloc1(4 * dem->walls.nwall + 1, &wd));
  PetscCall(IoCkptReadSlabAll(b->ck, "dem/wall_state", IO_CKPT_REAL, 0, 4 * dem->walls.nwall, wd));
  for (PetscInt w = 0; w < dem->walls.nwall; w++)
    for (int k = 0; k < 3; k++) dem->walls.wall[w].s.p[k] = wd[4 * w + k];
  PetscCall(PetscFree(wd));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. The block's ids (owned and ghosts) and its owned particles' per-particle state. */
static PetscErrorCode DemRemapParticles(Dem dem, DemRemap *b)
{
  PetscInt *rows;
  DemSlab   s;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(b->R, &rows));
  for (PetscInt r = 0; r < b->R; r++) rows[r] = CNT(b, r, CK_N) + CNT(b, r, CK_NG);
  PetscCall(DemRemapSlab(b, "dem/id", IO_CKPT_INT, rows, PETSC_FALSE, &s));
  b->gid  = (PetscInt *)s.v;
  b->goff = s.off;
  PetscCall(DemParticlesReserve(dem, b->nown));
  dem->p.n  = b->nown;
  dem->p.ng = 0;
  for (int f = 0; f < dem_nfields; f++) { /* the owned rows of every dataset of the field table (dem/id again) */
    const DemField  *fd   = &dem_fields[f];
    const IoCkptType type = fd->type == DEM_FIELD_INT ? IO_CKPT_INT : IO_CKPT_REAL;
    const size_t     sz   = IoCkptTypeSize(type) * (size_t)fd->width;
    char            *o;
    if (!(fd->flags & DEM_FIELD_CKPT) || !DemFieldOn(dem, fd)) continue;
    o = *(char **)DemFieldPtr(dem, fd);
    for (PetscInt r = 0; r < b->R; r++) rows[r] = fd->width * (CNT(b, r, CK_N) + (fd->flags & DEM_FIELD_CKPT_GHOSTS ? CNT(b, r, CK_NG) : 0));
    PetscCall(DemRemapSlab(b, fd->ckpt, type, rows, PETSC_FALSE, &s));
    for (PetscInt r = b->r0; r < b->r1; r++) { /* the owned rows come first */
      PetscCall(PetscMemcpy(o, (char *)s.v + IoCkptTypeSize(type) * (size_t)s.off[r - b->r0], sz * (size_t)CNT(b, r, CK_N)));
      o += sz * (size_t)CNT(b, r, CK_N);
    }
    PetscCall(DemSlabFree(&s));
  }
  PetscCall(PetscFree(rows));
  for (PetscInt i = 0; i < dem->p.n; i++) PetscCheck(dem->p.shape[i] >= 0 && dem->p.shape[i] < dem->shapes.nshape, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "-restart %s: the dataset dem/shape gives particle %" PetscInt_FMT " shape %" PetscInt_FMT ", the case has shapes [0, %" PetscInt_FMT ")", b->path, dem->p.id[i], dem->p.shape[i], dem->shapes.nshape);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Appends a spring record (not a zero one: a pair without a record starts unloaded). */
static PetscErrorCode DemRemapPush(DemSpring **recs, PetscInt *n, PetscInt *cap, PetscInt owner, PetscInt partner, double sign, const double *h)
{
  PetscFunctionBeginUser;
  if (h[0] == 0 && h[1] == 0 && h[2] == 0) PetscFunctionReturn(PETSC_SUCCESS);
  if (*n == *cap) {
    *cap = 2 * *cap + 64;
    PetscCall(PetscRealloc(sizeof(DemSpring) * (size_t)*cap, recs));
  }
  (*recs)[(*n)++] = (DemSpring){owner, partner, {sign * h[0], sign * h[1], sign * h[2]}};
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. The springs of the block's Verlet lists as id-keyed records. */
static PetscErrorCode DemRemapPairSprings(Dem dem, const DemRemap *b, DemSpring **recs, PetscInt *n, PetscInt *cap)
{
  PetscInt *rows;
  DemSlab   st, nb, hs;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(b->R, &rows));
  for (PetscInt r = 0; r < b->R; r++) rows[r] = CNT(b, r, CK_N) ? CNT(b, r, CK_N) + 1 : 0;
  PetscCall(DemRemapSlab(b, "dem/nl_start", IO_CKPT_INT, rows, PETSC_FALSE, &st));
  PetscCall(PetscFree(rows));
  PetscCall(DemRemapSlab(b, "dem/nl_nbr", IO_CKPT_INT, NULL, PETSC_FALSE, &nb));
  PetscCall(DemRemapSlab(b, "dem/nl_hist", IO_CKPT_REAL, NULL, PETSC_FALSE, &hs));
  for (PetscInt r = b->r0; r < b->r1; r++) {
    const PetscInt  k = r - b->r0, nr = CNT(b, r, CK_N), Nr = nr + CNT(b, r, CK_NG);
    const PetscInt *start = (PetscInt *)st.v + st.off[k], *nbr = (PetscInt *)nb.v + nb.off[k], *id = b->gid + b->goff[k];
    const double   *hist = (double *)hs.v + hs.off[k];
    const PetscInt  m    = nr ? start[nr] : 0;
    PetscCheck(nb.off[k + 1] - nb.off[k] == m && hs.off[k + 1] - hs.off[k] == 3 * m, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "-restart %s: the datasets dem/nl_nbr, dem/nl_hist of rank %" PetscInt_FMT " have %" PetscInt_FMT ", %" PetscInt_FMT " entries, its dem/nl_start says %" PetscInt_FMT " pairs", b->path, r, nb.off[k + 1] - nb.off[k], hs.off[k + 1] - hs.off[k], m);
    for (PetscInt i = 0; i < nr; i++) {
      PetscCheck(start[i] >= 0 && start[i] <= start[i + 1] && start[i + 1] <= m, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "-restart %s: the dataset dem/nl_start of rank %" PetscInt_FMT " is not ascending in [0, %" PetscInt_FMT "]", b->path, r, m);
      for (PetscInt a = start[i]; a < start[i + 1]; a++) {
        const PetscInt j = nbr[a];
        PetscCheck(j >= 0 && j < Nr && j != i, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "-restart %s: the dataset dem/nl_nbr of rank %" PetscInt_FMT " lists row %" PetscInt_FMT ", not another of its %" PetscInt_FMT " rows", b->path, r, j, Nr);
        PetscCall(DemRemapPush(recs, n, cap, id[i], id[j], 1, hist + 3 * a));
        if (!dem->nl.full_list && j < nr) PetscCall(DemRemapPush(recs, n, cap, id[j], id[i], -1, hist + 3 * a));
      }
    }
  }
  PetscCall(DemSlabFree(&st));
  PetscCall(DemSlabFree(&nb));
  PetscCall(DemSlabFree(&hs));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. The springs of the block's wall lists as records (id, -1 - wall). */
static PetscErrorCode DemRemapWallSprings(Dem dem, const DemRemap *b, DemSpring **recs, PetscInt *n, PetscInt *cap)
{
  const PetscInt nw = dem->walls.nwall;
  PetscInt      *rows;
  DemSlab        wc, wi, wh;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(b->R, &rows));
  for (PetscInt r = 0; r < b->R; r++) rows[r] = nw;
  PetscCall(DemRemapSlab(b, "dem/wall_cnt", IO_CKPT_INT, rows, PETSC_FALSE, &wc));
  PetscCall(PetscFree(rows));
  PetscCall(DemRemapSlab(b, "dem/wall_idx", IO_CKPT_INT, NULL, PETSC_FALSE, &wi));
  PetscCall(DemRemapSlab(b, "dem/wall_hist", IO_CKPT_REAL, NULL, PETSC_FALSE, &wh));
  for (PetscInt r = b->r0; r < b->r1; r++) {
    const PetscInt  k = r - b->r0, nr = CNT(b, r, CK_N), *cnt = (PetscInt *)wc.v + wc.off[k], *idx = (PetscInt *)wi.v + wi.off[k];
    const PetscInt *id   = b->gid + b->goff[k];
    const double   *hist = (double *)wh.v + wh.off[k];
    PetscInt        e    = 0;
    for (PetscInt w = 0; w < nw; w++) e += cnt[w];
    PetscCheck(wi.off[k + 1] - wi.off[k] == e && wh.off[k + 1] - wh.off[k] == 3 * e, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "-restart %s: the datasets dem/wall_idx, dem/wall_hist of rank %" PetscInt_FMT " do not hold the %" PetscInt_FMT " entries its dem/wall_cnt says", b->path, r, e);
    e = 0;
    for (PetscInt w = 0; w < nw; w++)
      for (PetscInt a = 0; a < cnt[w]; a++, e++) {
        PetscCheck(idx[e] >= 0 && idx[e] < nr, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "-restart %s: the dataset dem/wall_idx of rank %" PetscInt_FMT " lists row %" PetscInt_FMT ", not one of its %" PetscInt_FMT " particles", b->path, r, idx[e], nr);
        PetscCall(DemRemapPush(recs, n, cap, id[idx[e]], -1 - w, 1, hist + 3 * e));
      }
  }
  PetscCall(DemSlabFree(&wc));
  PetscCall(DemSlabFree(&wi));
  PetscCall(DemSlabFree(&wh));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. The springs of the block's mesh slots (dem/mesh_slot: per writer, mesh after mesh,
 * DEM_MESH_SLOTS slots (normal, spring) per owned particle) as the records DemMeshesSaveSprings
 * makes, two per loaded slot: (id, DEM_MESH_PARTNER(k, s, 0)) the spring, (.., 1) its normal. */
static PetscErrorCode DemRemapMeshSprings(Dem dem, const DemRemap *b, DemSpring **recs, PetscInt *n, PetscInt *cap)
{
  const PetscInt nm = dem->meshes.n, ns = 6 * DEM_MESH_SLOTS;
  PetscInt      *rows;
  DemSlab        sl;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(b->R, &rows));
  for (PetscInt r = 0; r < b->R; r++) rows[r] = nm * ns * CNT(b, r, CK_N);
  PetscCall(DemRemapSlab(b, "dem/mesh_slot", IO_CKPT_REAL, rows, PETSC_FALSE, &sl));
  PetscCall(PetscFree(rows));
  for (PetscInt r = b->r0; r < b->r1; r++) {
    const PetscInt k = r - b->r0, nr = CNT(b, r, CK_N), *id = b->gid + b->goff[k];
    const double  *v = (double *)sl.v + sl.off[k];
    for (PetscInt m = 0; m < nm; m++)
      for (PetscInt i = 0; i < nr; i++)
        for (int t = 0; t < DEM_MESH_SLOTS; t++) {
          const double *e = v + m * ns * nr + 6 * (DEM_MESH_SLOTS * i + t);
          if (e[3] == 0 && e[4] == 0 && e[5] == 0) continue; /* an unloaded slot: no record (as DemMeshesSaveSprings) */
          PetscCall(DemRemapPush(recs, n, cap, id[i], DEM_MESH_PARTNER(m, t, 0), 1, e + 3));
          PetscCall(DemRemapPush(recs, n, cap, id[i], DEM_MESH_PARTNER(m, t, 1), 1, e));
        }
  }
  PetscCall(DemSlabFree(&sl));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. Every particle must lie where a rank's box can take it: finite, and within a
 * radius of the domain across a closed side (as DemCheckInDomain asks of a running scene) or
 * within a period across a periodic one. The first offender (lowest id) is named by every rank. */
static PetscErrorCode DemRemapCheckMap(Dem dem, const DemRemap *b)
{
  const Domain *dom      = dem->dom;
  PetscInt      bad      = PETSC_MAX_INT, gbad;
  double        where[4] = {-PETSC_MAX_REAL, -PETSC_MAX_REAL, -PETSC_MAX_REAL, -PETSC_MAX_REAL}, gwhere[4];

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < dem->p.n; i++)
    for (int k = 0; k < 3; k++) {
      const double x = dem->p.x[3 * i + k], r = dom->periodic[k] ? dom->len[k] : DemRadius(&dem->p, &dem->shapes, i);
      if ((x >= dom->lo[k] - r && x <= dom->hi[k] + r) || dem->p.id[i] >= bad) continue; /* a NaN fails the test */
      bad = dem->p.id[i];
      for (int c = 0; c < 3; c++) where[c] = dem->p.x[3 * i + c];
      where[3] = k;
    }
  PetscCallMPI(MPI_Allreduce(&bad, &gbad, 1, MPIU_INT, MPI_MIN, dem->comm));
  if (gbad == PETSC_MAX_INT) PetscFunctionReturn(PETSC_SUCCESS);
  if (bad != gbad)
    for (int c = 0; c < 4; c++) where[c] = -PETSC_MAX_REAL;
  PetscCallMPI(MPI_Allreduce(where, gwhere, 4, MPI_DOUBLE, MPI_MAX, dem->comm));
  const int k = (int)gwhere[3];
  SETERRQ(dem->comm, PETSC_ERR_FILE_UNEXPECTED, "-restart %s: the dataset dem/x puts particle %" PetscInt_FMT " at (%g, %g, %g) m, outside this run's domain along %c ([%g, %g] m): the checkpoint cannot be mapped onto the ranks' boxes", b->path, gbad, gwhere[0], gwhere[1], gwhere[2], "xyz"[k], (double)dom -> lo[k], (double)dom -> hi[k]);
}

PetscErrorCode DemCheckpointNeedsRemap(Dem dem, IoCkpt ck, PetscBool *remap)
{
  const Domain *dom = dem->dom;
  const char   *path;
  PetscInt      c[DEM_CKPT_NCOUNT], n;
  double       *x0;
  int           R, out = 0, any;
  PetscMPIInt   size;

  PetscFunctionBeginUser;
  PetscCall(IoCkptGetRanks(ck, &R));
  PetscCallMPI(MPI_Comm_size(dem->comm, &size));
  *remap = (PetscBool)(R != size);
  if (*remap) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(IoCkptGetPath(ck, &path));
  PetscCall(IoCkptReadRowsInto(ck, "dem/counters", IO_CKPT_INT, DEM_CKPT_NCOUNT, c));
  PetscCall(IoCkptReadRows(ck, "dem/x0", IO_CKPT_REAL, &n, (void **)&x0));
  PetscCheck(n == 3 * c[CK_N], PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "-restart %s: the dataset dem/x0 has %" PetscInt_FMT " entries on this rank, expected %" PetscInt_FMT, path, n, 3 * c[CK_N]);
  for (int k = 0; k < 3; k++) { /* the box as the migration sees it (exchange.c): open towards the domain's closed sides */
    const PetscBool first = (PetscBool)(dom->cstart[k] == 0 && !dom->periodic[k]), last = (PetscBool)(dom->cstart[k] + dom->ccount[k] == dom->cells[k] && !dom->periodic[k]);
    for (PetscInt i = 0; i < c[CK_N]; i++) out |= (x0[3 * i + k] < dom->sublo[k] && !first) || (x0[3 * i + k] >= dom->subhi[k] && !last);
  }
  PetscCall(PetscFree(x0));
  PetscCallMPI(MPI_Allreduce(&out, &any, 1, MPI_INT, MPI_LOR, dem->comm));
  *remap = (PetscBool)any;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemCheckpointReadRemap(Dem dem, IoCkpt ck)
{
  DemRemap   b = {ck, NULL, 0, 0, 0, NULL, 0, NULL, NULL};
  DemSpring *recs;
  PetscInt   nrec = 0, cap = 64, *perm, *key;
  DemStats   st;

  PetscFunctionBeginUser;
  PetscCall(IoCkptGetPath(ck, &b.path));
  PetscCall(DemRemapCounters(dem, &b));
  PetscCall(DemRemapParticles(dem, &b));
  PetscCall(PetscMalloc1(cap, &recs));
  if (dem->contact.law != DEM_LAW_LINEAR_NOHIST) {
    PetscCall(DemRemapPairSprings(dem, &b, &recs, &nrec, &cap));
    PetscCall(DemRemapWallSprings(dem, &b, &recs, &nrec, &cap));
    if (dem->meshes.n) PetscCall(DemRemapMeshSprings(dem, &b, &recs, &nrec, &cap));
  }
  PetscCall(DemSpringsSort(recs, nrec));
  PetscCall(PetscFree(b.cnt));
  PetscCall(PetscFree(b.gid));
  PetscCall(PetscFree(b.goff));
  PetscCall(DemRemapCheckMap(dem, &b));
  if (dem->meshes.n) PetscCall(DemMeshesMove(dem, dem->clock.t, NULL)); /* the pose of the restored time (walls_mesh.c) */
  /* every particle to the rank whose box holds it, then in id order there */
  PetscCall(DemNeighResetCells(dem)); /* the cell grid is sized for the particles the rank now has */
  PetscCall(PetscLogEventBegin(DEM_Neighbours, 0, 0, 0, 0));
  PetscCall(DemMigrateGlobal(dem, &recs, &nrec, &cap));
  PetscCall(PetscMalloc2(dem->p.n + 1, &perm, dem->p.n + 1, &key));
  for (PetscInt i = 0; i < dem->p.n; i++) {
    perm[i] = i;
    key[i]  = dem->p.id[i];
  }
  PetscCall(PetscSortIntWithArray(dem->p.n, key, perm));
  PetscCall(DemParticlesPermute(dem, perm));
  PetscCall(PetscFree2(perm, key));
  dem->ex.remap = PETSC_FALSE; /* the neighbour migration of the rebuild then moves none */
  PetscCall(DemRebuildFrom(dem, recs, nrec, cap));
  PetscCall(PetscLogEventEnd(DEM_Neighbours, 0, 0, 0, 0));
  dem->stop_sig = 0;
  PetscCall(PetscPrintf(dem->comm, "restart: the particles of the checkpoint's %" PetscInt_FMT " rank(s) redistributed over this run's boxes (the run continues to round-off, bitwise with -dem_deterministic)\n", b.R));
  PetscCall(DemGetStats(dem, &st));
  /* the run's count: initial + inserted - removed (dem->flow, read before the remap) */
  const PetscInt n0 = dem->initial.n + dem->flow.inserted - dem->flow.removed;
  const double   c0 = dem->initial.checksum + dem->flow.id_inserted - dem->flow.id_removed;
  PetscCheck(st.n == n0 && st.checksum == c0, dem->comm, PETSC_ERR_FILE_UNEXPECTED, "-restart %s: the dataset dem/id gives %" PetscInt_FMT " particles with id checksum %.17g after the redistribution, the run had %" PetscInt_FMT " and %.17g: an id is missing or repeated", b.path, st.n, st.checksum, n0, c0);
  PetscFunctionReturn(PETSC_SUCCESS);
}
