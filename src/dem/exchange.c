/* Parallel exchange of particles between the ranks of the shared DMDA decomposition, after
 * Grains3D's tailored scheme (Part II §3): a particle within the halo (width = reach = 2 r_max +
 * skin) of its box faces is sent only to the neighbours whose halo it lies in — 1 near a face,
 * 3 near an edge, 7 near a corner — one message of doubles per direction, non-blocking. Three
 * named operations:
 *   migration (at list rebuilds): a particle whose centre left the box goes to the neighbour that
 *     owns it, with its full state, its tangential springs and, when a coupling is attached, its
 *     external force, drag and received impulse; periodic axes wrap positions;
 *   ghost creation (at list rebuilds): copies of halo particles, positions shifted across periodic
 *     boundaries; the send lists are kept;
 *   forward update (every other step): the owners' kinematics overwrite the ghosts' in place.
 * There is no reverse communication: a local-ghost pair is computed on both ranks, each applying
 * the force to its own particle only; the kernels are written so that both sides get exactly
 * opposite forces. With one rank along a periodic axis the neighbour is the rank itself (a
 * message to self with a shift), so periodicity has one code path. A box thinner than the halo
 * along a split or periodic axis is an error (a particle could then reach past a neighbour). */
#include "dem/dem_core.h"
#include "dem/dem_fields.h"

/* The records are the field table's rows (dem_fields.h): migration all of a particle's state
 * (DEM_FIELD_MIGRATE), then the number of its springs and the springs (partner, xi: 4 each);
 * ghost creation the rows of DEM_FIELD_GHOST, the forward update those of DEM_FIELD_UPDATE. */

static void dem_dir_offsets(int d, int o[3])
{
  o[0] = d % 3 - 1;
  o[1] = (d / 3) % 3 - 1;
  o[2] = d / 9 - 1;
}

PetscErrorCode DemExchangeSetUp(Dem dem)
{
  const Domain   *dom = dem->dom;
  DemExchange    *ex  = &dem->ex;
  PetscInt        c[3];
  const PetscInt *l[3];
  PetscMPIInt     me;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(dem->comm, &me));
  PetscCall(DMDAGetOwnershipRanges(dom->da, &l[0], &l[1], &l[2]));
  for (int k = 0; k < 3; k++) { /* my coordinate in the process grid */
    PetscInt s = 0;
    for (c[k] = 0; s < dom->cstart[k]; c[k]++) s += l[k][c[k]];
    const double w = dom->subhi[k] - dom->sublo[k];
    PetscCheck(!(dom->nranks[k] > 1 || dom->periodic[k]) || w >= dem->nl.reach, dem->comm, PETSC_ERR_ARG_OUTOFRANGE,
               "rank box width %g m along axis %d is thinner than the halo %g m (2 r_max + skin): use fewer ranks along that axis (-da_processors_%c) or a larger domain", w, k, (double)dem->nl.reach, "xyz"[k]);
  }
  ex->active = PETSC_FALSE;
  for (int d = 0; d < 27; d++) {
    int      o[3];
    PetscInt nb[3], ok = 1;
    dem_dir_offsets(d, o);
    for (int k = 0; k < 3; k++) {
      nb[k]           = c[k] + o[k];
      ex->shift[d][k] = 0;
      if (nb[k] < 0 || nb[k] >= dom->nranks[k]) {
        if (!dom->periodic[k]) ok = 0;
        nb[k]           = (nb[k] + dom->nranks[k]) % dom->nranks[k];
        ex->shift[d][k] = o[k] > 0 ? -dom->len[k] : dom->len[k];
      }
    }
    ex->rank[d] = (ok && d != 13) ? (PetscMPIInt)(nb[0] + dom->nranks[0] * (nb[1] + dom->nranks[1] * nb[2])) : -1;
    if (ex->rank[d] >= 0) ex->active = PETSC_TRUE;
  }
  (void)me;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemExchangeDestroy(Dem dem)
{
  PetscFunctionBeginUser;
  for (int d = 0; d < 27; d++) PetscCall(PetscFree(dem->ex.send[d]));
  PetscCall(PetscFree(dem->ex.sbuf));
  PetscCall(PetscFree(dem->ex.rbuf));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemBufReserve(double **buf, size_t *cap, size_t n)
{
  PetscFunctionBeginUser;
  if (n > *cap) {
    *cap = 2 * n + 1024;
    PetscCall(PetscFree(*buf));
    PetscCall(PetscMalloc1(*cap, buf));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Variable-size exchange: sizes first, then the doubles; returns receive offsets per direction. */
static PetscErrorCode DemExchangeVariable(Dem dem, const size_t soff[28], size_t roff[28])
{
  DemExchange *ex = &dem->ex;
  MPI_Request  req[54];
  long long    ssz[27], rsz[27];
  int          nr = 0;

  PetscFunctionBeginUser;
  for (int d = 0; d < 27; d++) {
    ssz[d] = (long long)(soff[d + 1] - soff[d]);
    rsz[d] = 0;
    if (ex->rank[d] < 0) continue;
    /* from the neighbour at offset d, a message it sent in direction 26-d */
    PetscCallMPI(MPI_Irecv(&rsz[d], 1, MPI_LONG_LONG, ex->rank[d], 26 - d, dem->comm, &req[nr++]));
    PetscCallMPI(MPI_Isend(&ssz[d], 1, MPI_LONG_LONG, ex->rank[d], d, dem->comm, &req[nr++]));
  }
  PetscCallMPI(MPI_Waitall(nr, req, MPI_STATUSES_IGNORE));
  roff[0] = 0;
  for (int d = 0; d < 27; d++) roff[d + 1] = roff[d] + (size_t)rsz[d];
  PetscCall(DemBufReserve(&ex->rbuf, &ex->caprbuf, roff[27] + 1));
  nr = 0;
  for (int d = 0; d < 27; d++) {
    if (ex->rank[d] < 0) continue;
    if (rsz[d]) PetscCallMPI(MPI_Irecv(ex->rbuf + roff[d], (PetscMPIInt)rsz[d], MPI_DOUBLE, ex->rank[d], 26 - d, dem->comm, &req[nr++]));
    if (ssz[d]) PetscCallMPI(MPI_Isend(ex->sbuf + soff[d], (PetscMPIInt)ssz[d], MPI_DOUBLE, ex->rank[d], d, dem->comm, &req[nr++]));
  }
  PetscCallMPI(MPI_Waitall(nr, req, MPI_STATUSES_IGNORE));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Direction along axis k in which x leaves the box (0: stays). */
static int dem_leave(const Dem dem, const double *x, int k)
{
  const Domain *dom   = dem->dom;
  const int     first = dom->cstart[k] == 0, last = dom->cstart[k] + dom->ccount[k] == dom->cells[k];
  if (x[k] < dom->sublo[k] && (!first || dom->periodic[k])) return -1;
  if (x[k] >= dom->subhi[k] && (!last || dom->periodic[k])) return 1;
  return 0;
}

/* The springs of particle id in recs (sorted by owner): first record and count. */
static const DemSpring *dem_springs_of(const DemSpring *recs, PetscInt nrec, PetscInt id, PetscInt *ns)
{
  const DemSpring *s = DemSpringFind(recs, nrec, id, PETSC_MIN_INT), *s0 = s;
  *ns = 0;
  for (; s && s < recs + nrec && s->owner == id; s++) (*ns)++;
  return s0;
}

size_t DemMigSize(Dem dem, PetscInt i, const DemSpring *recs, PetscInt nrec)
{
  DemFieldRef ref[DEM_MAX_FIELDS];
  size_t      w;
  PetscInt    ns;

  (void)dem_springs_of(recs, nrec, dem->p.id[i], &ns);
  (void)DemFieldsResolve(dem, DEM_FIELD_MIGRATE, ref, &w);
  return w + 1 + 4 * (size_t)ns;
}

size_t DemMigPack(Dem dem, PetscInt i, const DemSpring *recs, PetscInt nrec, const double shift[3], double *b)
{
  DemFieldRef      ref[DEM_MAX_FIELDS];
  size_t           w;
  PetscInt         ns;
  const DemSpring *s0 = dem_springs_of(recs, nrec, dem->p.id[i], &ns);
  const int        nf = DemFieldsResolve(dem, DEM_FIELD_MIGRATE, ref, &w);
  double          *e  = DemFieldsPack(ref, nf, i, shift, b);

  e[0] = (double)ns;
  for (PetscInt a = 0; a < ns; a++) {
    e[1 + 4 * a] = (double)s0[a].partner;
    for (int k = 0; k < 3; k++) e[2 + 4 * a + k] = s0[a].xi[k];
  }
  return w + 1 + 4 * (size_t)ns;
}

PetscErrorCode DemMigUnpack(Dem dem, const double *b, DemSpring **recs, PetscInt *nrec, PetscInt *caprec, size_t *used)
{
  DemFieldRef    ref[DEM_MAX_FIELDS];
  size_t         w;
  const PetscInt i = dem->p.n;
  const double  *e;
  PetscInt       ns, id;
  int            nf;

  PetscFunctionBeginUser;
  PetscCall(DemParticlesReserve(dem, i + 1));
  nf = DemFieldsResolve(dem, DEM_FIELD_MIGRATE, ref, &w);
  DemFieldsClear(dem, i);
  e  = DemFieldsUnpack(ref, nf, i, b);
  ns = (PetscInt)e[0];
  id = dem->p.id[i];
  PetscCall(DemParticleArrive(dem, ref, nf));
  if (*nrec + ns > *caprec) {
    *caprec = 2 * (*nrec + ns) + 64;
    PetscCall(PetscRealloc(sizeof(DemSpring) * (size_t)*caprec, recs));
  }
  for (PetscInt a = 0; a < ns; a++) {
    DemSpring *r = *recs + (*nrec)++;
    r->owner     = id;
    r->partner   = (PetscInt)e[1 + 4 * a];
    for (int k = 0; k < 3; k++) r->xi[k] = e[2 + 4 * a + k];
  }
  *used = w + 1 + 4 * (size_t)ns;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Not collective (called at every list build). A particle wholly outside the domain across a side that is not periodic has
 * nowhere to go (Sable has no outlet region that deletes particles): an error naming it, not a
 * particle silently drifting away. */
PetscErrorCode DemCheckInDomain(Dem dem)
{
  const Domain *dom = dem->dom;

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < dem->p.n; i++)
    for (int k = 0; k < 3; k++) {
      const double x = dem->p.x[3 * i + k], r = DemRadius(&dem->p, &dem->shapes, i);
      PetscCheck(PetscIsInfOrNanReal(x) == PETSC_FALSE, PETSC_COMM_SELF, PETSC_ERR_FP, "t = %g s: particle %" PetscInt_FMT " has a non-finite position; the run is diverging: lower -dem_dt (now %g s)", (double)dem->clock.t, dem->p.id[i], (double)dem->clock.dt);
      if (dom->periodic[k] || (x >= dom->lo[k] - r && x <= dom->hi[k] + r)) continue;
      for (PetscInt w = 0; w < dem->walls.nwall; w++) { /* wholly behind an unbounded plane: it went through, the step cannot resolve the contact */
        const DemWall *wl = &dem->walls.wall[w];
        double         s  = 0;
        if (wl->s.kind != SURFACE_PLANE || wl->removed) continue;
        for (int c = 0; c < 3; c++) s += (dem->p.x[3 * i + c] - wl->s.p[c]) * wl->s.n[c];
        PetscCheck(s >= -r, PETSC_COMM_SELF, PETSC_ERR_NOT_CONVERGED, "t = %g s: particle %" PetscInt_FMT " went through wall %s and left the domain (%c = %g m): the run is diverging; lower -dem_dt (now %g s) or raise -dem_kn", (double)dem->clock.t, dem->p.id[i], wl->name, "xyz"[k], x, (double)dem -> clock.dt);
      }
      SETERRQ(PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "t = %g s: particle %" PetscInt_FMT " left the domain across its %s %c side (%c = %g m, domain [%g, %g] m); close that side with walls (-dem_box, -dem_plane_k) or enlarge -domain_lo/-domain_hi", (double)dem->clock.t, dem->p.id[i], x < dom->lo[k] ? "lower" : "upper", "xyz"[k], "xyz"[k], x, (double)dom -> lo[k], (double)dom -> hi[k]);
    }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. Sends every local particle that left the box to its new owner with its state and
 * springs (recs, sorted by owner id on entry and on exit; received springs are appended). */
PetscErrorCode DemMigrate(Dem dem, DemSpring **recs, PetscInt *nrec, PetscInt *caprec)
{
  DemExchange *ex = &dem->ex;
  PetscInt    *dir, *keep, nkeep = 0;
  size_t       soff[28], roff[28], pos[27];

  PetscFunctionBeginUser;
  if (!ex->active) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscMalloc2(dem->p.n + 1, &dir, dem->p.n + 1, &keep));
  for (int d = 0; d < 27; d++) soff[d] = 0;
  size_t total = 0;
  for (PetscInt i = 0; i < dem->p.n; i++) {
    const double *x = dem->p.x + 3 * i;
    dir[i]          = (dem_leave(dem, x, 0) + 1) + 3 * (dem_leave(dem, x, 1) + 1) + 9 * (dem_leave(dem, x, 2) + 1);
    if (dir[i] == 13) {
      keep[nkeep++] = i;
      continue;
    }
    const size_t sz = DemMigSize(dem, i, *recs, *nrec);
    soff[dir[i]] += sz;
    total += sz;
  }
  for (int d = 0, acc = 0; d < 27; d++) { /* prefix sums */
    const size_t sz = soff[d];
    soff[d]         = (size_t)acc;
    pos[d]          = (size_t)acc;
    acc += (int)sz;
  }
  soff[27] = total;
  PetscCall(DemBufReserve(&ex->sbuf, &ex->capsbuf, total + 1));
  for (PetscInt i = 0; i < dem->p.n; i++)
    if (dir[i] != 13) pos[dir[i]] += DemMigPack(dem, i, *recs, *nrec, ex->shift[dir[i]], ex->sbuf + pos[dir[i]]);
  ex->migrated = dem->p.n - nkeep;
  dem->p.n     = nkeep;
  PetscCall(DemParticlesPermute(dem, keep));
  PetscCall(PetscFree2(dir, keep));
  PetscCall(DemExchangeVariable(dem, soff, roff));
  for (size_t o = 0, used; o < roff[27]; o += used) PetscCall(DemMigUnpack(dem, ex->rbuf + o, recs, nrec, caprec, &used));
  PetscCall(DemSpringsSort(*recs, *nrec));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. Ghost copies of the halo particles of every neighbour, appended after the locals. */
PetscErrorCode DemGhostsCreate(Dem dem)
{
  DemExchange  *ex  = &dem->ex;
  const Domain *dom = dem->dom;
  const double  h   = dem->nl.reach;
  size_t        soff[28], roff[28], GW;
  DemFieldRef   ref[DEM_MAX_FIELDS];
  int           nf = DemFieldsResolve(dem, DEM_FIELD_GHOST, ref, &GW);

  PetscFunctionBeginUser;
  dem->p.ng = 0;
  if (!ex->active) PetscFunctionReturn(PETSC_SUCCESS);
  for (int d = 0; d < 27; d++) ex->nsend[d] = 0;
  for (PetscInt i = 0; i < dem->p.n; i++) {
    const double *x = dem->p.x + 3 * i;
    int           lo[3], hi[3];
    for (int k = 0; k < 3; k++) {
      lo[k] = x[k] < dom->sublo[k] + h;
      hi[k] = x[k] >= dom->subhi[k] - h;
    }
    if (!(lo[0] | hi[0] | lo[1] | hi[1] | lo[2] | hi[2])) continue;
    for (int d = 0; d < 27; d++) { /* the 1, 3 or 7 directions whose halo holds x */
      int o[3], in = 1;
      dem_dir_offsets(d, o);
      for (int k = 0; k < 3; k++) in &= o[k] == 0 || (o[k] < 0 ? lo[k] : hi[k]);
      if (!in || d == 13 || ex->rank[d] < 0) continue;
      if (ex->nsend[d] == ex->capsend[d]) {
        ex->capsend[d] = 2 * ex->capsend[d] + 64;
        PetscCall(PetscRealloc(sizeof(PetscInt) * (size_t)ex->capsend[d], &ex->send[d]));
      }
      ex->send[d][ex->nsend[d]++] = i;
    }
  }
  soff[0] = 0;
  for (int d = 0; d < 27; d++) soff[d + 1] = soff[d] + GW * (size_t)ex->nsend[d];
  PetscCall(DemBufReserve(&ex->sbuf, &ex->capsbuf, soff[27] + 1));
  for (int d = 0; d < 27; d++) DemFieldsPackList(ref, nf, ex->send[d], ex->nsend[d], ex->shift[d], ex->sbuf + soff[d], GW);
  PetscCall(DemExchangeVariable(dem, soff, roff));
  PetscCall(DemParticlesReserve(dem, dem->p.n + (PetscInt)(roff[27] / GW)));
  nf = DemFieldsResolve(dem, DEM_FIELD_GHOST, ref, &GW); /* the arrays may have moved */
  for (int d = 0; d < 27; d++) {
    ex->recvstart[d] = dem->p.n + dem->p.ng;
    ex->nrecv[d]     = (PetscInt)((roff[d + 1] - roff[d]) / GW);
    DemFieldsUnpackRange(ref, nf, ex->recvstart[d], ex->nrecv[d], ex->rbuf + roff[d], GW);
    for (PetscInt a = 0; a < ex->nrecv[d]; a++) DemFieldsArrive(dem, ref, nf, dem->p.n + dem->p.ng++); /* the owner's mass and inertia, to the bit */
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. Forward communication: ghosts take their owners' current kinematics. */
PetscErrorCode DemGhostsUpdate(Dem dem)
{
  DemExchange *ex = &dem->ex;
  DemFieldRef  ref[DEM_MAX_FIELDS];
  size_t       W;
  const int    nf = DemFieldsResolve(dem, DEM_FIELD_UPDATE, ref, &W);
  MPI_Request  req[54];
  int          nr = 0;
  size_t       so = 0, ro = 0, soff[27], roff[27];

  PetscFunctionBeginUser;
  if (!ex->active) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscLogEventBegin(DEM_Exchange, 0, 0, 0, 0));
  for (int d = 0; d < 27; d++) {
    soff[d] = so;
    roff[d] = ro;
    so += W * (size_t)ex->nsend[d];
    ro += W * (size_t)ex->nrecv[d];
  }
  PetscCall(DemBufReserve(&ex->sbuf, &ex->capsbuf, so + 1));
  PetscCall(DemBufReserve(&ex->rbuf, &ex->caprbuf, ro + 1));
  for (int d = 0; d < 27; d++)
    if (ex->rank[d] >= 0 && ex->nrecv[d]) PetscCallMPI(MPI_Irecv(ex->rbuf + roff[d], (PetscMPIInt)W * (PetscMPIInt)ex->nrecv[d], MPI_DOUBLE, ex->rank[d], 26 - d, dem->comm, &req[nr++]));
  for (int d = 0; d < 27; d++) {
    if (ex->rank[d] < 0 || !ex->nsend[d]) continue;
    DemFieldsPackList(ref, nf, ex->send[d], ex->nsend[d], ex->shift[d], ex->sbuf + soff[d], W);
    PetscCallMPI(MPI_Isend(ex->sbuf + soff[d], (PetscMPIInt)W * (PetscMPIInt)ex->nsend[d], MPI_DOUBLE, ex->rank[d], d, dem->comm, &req[nr++]));
  }
  PetscCallMPI(MPI_Waitall(nr, req, MPI_STATUSES_IGNORE));
  for (int d = 0; d < 27; d++) DemFieldsUnpackRange(ref, nf, ex->recvstart[d], ex->nrecv[d], ex->rbuf + roff[d], W);
  PetscCall(PetscLogEventEnd(DEM_Exchange, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}
