/* Particle sources: any number of inserters -dem_insert_<k>_* (k = 0..9), each a region (a box,
 * a cylinder, or a rectangle patch from which a stream leaves), a rate (particles/s or kg/s)
 * and/or a total (count or mass), start and stop times, an initial velocity with a uniform
 * spread, random orientations, a shape and a size distribution (psd.h); their options and set-up
 * checks are in sources_options.c.
 * Batches: source k places a batch at start + j P (P = -dem_insert_<k>_period), holding what is
 * due by the end of its window, floor(rate (t_b + P - start)) particles (or, by mass, while the
 * inserted mass is below mass_rate (t_b + P - start)), capped by the total; what could not be
 * placed is carried (the target is cumulative) and reported: one note when a batch leaves some
 * to the next ones, one warning when the source does not catch up (DemSourceShortfall).
 * Placement is the same on any rank count: the diameter of the n-th particle of source k is a
 * function of (seed, k, n) only, a candidate c's position, velocity and orientation of (seed, k,
 * c) and that diameter (dem_uniform), so a blocked candidate never changes the size drawn (no
 * size bias where the region is crowded); each rank tests the candidates centred in its box
 * against its particles and ghosts (the halo covers r_cand + r_max) and the walls, one reduction
 * gives the blocked set, then every rank accepts the same candidates in candidate order
 * (rejecting one that overlaps an earlier accepted one; sizes of their own: in rounds, each
 * particle's candidates in turn, DemSourceBatch), ids following the largest id so far; the owner
 * adds them at the rebuild that DemStep runs at every batch step (sources change the particle
 * set only at rebuilds).
 * A particle placed at the step ending at t is there at t with the set velocity: x is not
 * drifted, and v0 - g dt/2 before the step's last half kick gives v0 (no contact can act on it).
 * Units SI. The state (counts, mass, candidate counter, batch, shortfall) is checkpointed. */
#include "dem/dem_core.h"
#include "dem/dem_walls.h"
#include "dem/dem_sources.h"

#define DEM_SRC_STREAM        16     /* the sources' hash streams start here (the lattice's are 0-6) */
#define DEM_SRC_MAX_CANDIDATE 200000 /* per batch: bounds the memory (about 30 MB) */

/* The batch time, the end of its window (capped at stop) and whether the source is done. */
static double DemSourceBatchTime(const DemSource *s)
{
  return s->start + (double)s->batch * s->period;
}

static PetscBool DemSourceDone(const DemSource *s)
{
  return (PetscBool)((s->count >= 0 && s->inserted >= s->count) || (s->mass >= 0 && s->m_inserted >= s->mass) || (s->stop > 0 && DemSourceBatchTime(s) >= s->stop));
}

/* Not collective; the same on every rank (a function of the clock and the sources' state). */
static PetscBool DemSourceDue(Dem dem, const DemSource *s)
{
  return (PetscBool)(!DemSourceDone(s) && dem->clock.t + dem->clock.dt >= DemSourceBatchTime(s) - 0.5 * dem->clock.dt);
}

PetscBool DemSourcesDue(Dem dem)
{
  for (PetscInt i = 0; i < dem->src.n; i++)
    if (DemSourceDue(dem, &dem->src.s[i])) return PETSC_TRUE;
  return PETSC_FALSE;
}

/* The cumulative targets by the end of the batch's window: count and mass (1e300: none). */
static void DemSourceTargets(const DemSource *s, double *ntgt, double *mtgt)
{
  double w = DemSourceBatchTime(s) + s->period;
  if (s->stop > 0) w = PetscMin(w, s->stop);
  w -= s->start;
  *ntgt = *mtgt = 1e300;
  if (s->rate > 0) *ntgt = PetscFloorReal(s->rate * w + 1e-9);
  if (s->count >= 0) *ntgt = PetscMin(*ntgt, (double)s->count);
  if (s->mass_rate > 0) *mtgt = s->mass_rate * w;
  if (s->mass >= 0) *mtgt = PetscMin(*mtgt, s->mass);
}

/* A small linked-cell grid of spheres (centre, radius) over a box, for the placement tests: cells
 * at least as wide as the largest centre distance that can overlap, coordinates clamped. */
typedef struct {
  double   lo[3], inv[3];
  PetscInt nc[3], n, cap, *head, *next;
  double  *xr; /* x, y, z, r per item */
} DemSrcGrid;

static PetscErrorCode DemSrcGridCreate(const double lo[3], const double hi[3], double cell, DemSrcGrid *g)
{
  PetscInt ncell = 1;

  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(g, sizeof *g));
  for (int d = 0; d < 3; d++) {
    const double len = PetscMax(hi[d] - lo[d], cell);
    g->nc[d]         = (PetscInt)PetscMin(64.0, PetscMax(1.0, PetscFloorReal(len / cell)));
    g->lo[d]         = lo[d];
    g->inv[d]        = g->nc[d] / len;
    ncell *= g->nc[d];
  }
  PetscCall(PetscMalloc1(ncell, &g->head));
  for (PetscInt c = 0; c < ncell; c++) g->head[c] = -1;
  PetscFunctionReturn(PETSC_SUCCESS);
}

static inline PetscInt dem_src_coord(const DemSrcGrid *g, const double *x, int d)
{
  const PetscInt c = (PetscInt)PetscFloorReal((x[d] - g->lo[d]) * g->inv[d]);
  return c < 0 ? 0 : (c >= g->nc[d] ? g->nc[d] - 1 : c);
}

static PetscErrorCode DemSrcGridAdd(DemSrcGrid *g, const double x[3], double r)
{
  PetscFunctionBeginUser;
  if (g->n == g->cap) {
    g->cap = 2 * g->cap + 64;
    PetscCall(PetscRealloc(sizeof(double) * 4 * (size_t)g->cap, &g->xr));
    PetscCall(PetscRealloc(sizeof(PetscInt) * (size_t)g->cap, &g->next));
  }
  const PetscInt c = dem_src_coord(g, x, 0) + g->nc[0] * (dem_src_coord(g, x, 1) + g->nc[1] * dem_src_coord(g, x, 2));
  for (int d = 0; d < 3; d++) g->xr[4 * g->n + d] = x[d];
  g->xr[4 * g->n + 3] = r;
  g->next[g->n]       = g->head[c];
  g->head[c]          = g->n++;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Whether a sphere (x, r) overlaps an item of the grid. */
static PetscBool DemSrcGridHits(const DemSrcGrid *g, const double x[3], double r)
{
  PetscInt c[3];
  for (int d = 0; d < 3; d++) c[d] = dem_src_coord(g, x, d);
  for (PetscInt k = PetscMax(c[2] - 1, 0); k <= PetscMin(c[2] + 1, g->nc[2] - 1); k++)
    for (PetscInt j = PetscMax(c[1] - 1, 0); j <= PetscMin(c[1] + 1, g->nc[1] - 1); j++)
      for (PetscInt i = PetscMax(c[0] - 1, 0); i <= PetscMin(c[0] + 1, g->nc[0] - 1); i++)
        for (PetscInt a = g->head[i + g->nc[0] * (j + g->nc[1] * k)]; a >= 0; a = g->next[a]) {
          const double *y = g->xr + 4 * a, dx[3] = {x[0] - y[0], x[1] - y[1], x[2] - y[2]}, s = r + y[3];
          if (dem_dot(dx, dx) < s * s) return PETSC_TRUE;
        }
  return PETSC_FALSE;
}

static PetscErrorCode DemSrcGridDestroy(DemSrcGrid *g)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree(g->head));
  PetscCall(PetscFree(g->next));
  PetscCall(PetscFree(g->xr));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Diameter (m) of the n-th particle source s inserts (n from 0): a function of (seed, k, n) only.
 * A blocked candidate is replaced by another position for the same particle, never by another
 * size: redrawing the size too would let small sizes win where the region is crowded, and the
 * inserted set would no longer follow the distribution. */
static double DemSourceDiameter(const DemSource *s, PetscInt n)
{
  return DemPsdSample(&s->psd, dem_uniform(s->seed, n, DEM_SRC_STREAM + 16 * (int)s->k));
}

/* Candidate c of source s for a particle of diameter d: centre (wholly inside the region),
 * velocity, orientation; a function of (seed, k, c, d) only. Streams of source k:
 * DEM_SRC_STREAM + 16 k + 0..9 (0: the sizes, by particle). */
static void DemSourceCandidate(Dem dem, const DemSource *s, PetscInt c, double d, DemParticle *p)
{
  const int    b    = DEM_SRC_STREAM + 16 * (int)s->k;
  const double r    = 0.5 * d;
  const double u[3] = {dem_uniform(s->seed, c, b + 1), dem_uniform(s->seed, c, b + 2), dem_uniform(s->seed, c, b + 3)};

  memset(p, 0, sizeof *p);
  p->shape = s->shape;
  p->r     = dem->shapes.poly ? r : 0;
  geom_region_sample(&s->reg, u, r, p->x); /* wholly inside */
  for (int k = 0; k < 3; k++) p->v[k] = s->v[k] + s->vspread * (2 * dem_uniform(s->seed, c, b + 7 + k) - 1);
  p->q[0] = 1;
  if (s->random_orient) { /* Shoemake, Graphics Gems III (1992) */
    const double u1 = dem_uniform(s->seed, c, b + 4), a1 = 2 * PETSC_PI * dem_uniform(s->seed, c, b + 5), a2 = 2 * PETSC_PI * dem_uniform(s->seed, c, b + 6);
    const double q1 = sqrt(1 - u1), q2 = sqrt(u1);
    p->q[0] = q2 * cos(a2);
    p->q[1] = q1 * sin(a1);
    p->q[2] = q1 * cos(a1);
    p->q[3] = q2 * sin(a2);
  }
}

/* Radius (m) of the candidate p (its own, or its shape's). */
static inline double dem_src_radius(Dem dem, const DemParticle *p)
{
  return p->r > 0 ? p->r : dem->shapes.shp[p->shape].r;
}

/* Collective. blk[i] = 1 where candidate i overlaps a particle (local or ghost), a wall or a mesh
 * triangle (its bounding sphere, for a convex shape): each
 * rank tests the candidates centred in its box, one reduction joins them. */
static PetscErrorCode DemSourceBlocked(Dem dem, const DemSource *s, PetscInt K, const DemParticle *cand, unsigned char *blk)
{
  double     dmin, dmax, rp = dem->shapes.r_source_max, lo[3], hi[3], nrm[3];
  DemSrcGrid g;

  PetscFunctionBeginUser;
  DemPsdRange(&s->psd, &dmin, &dmax);
  for (PetscInt t = 0; t < dem->shapes.nshape; t++) rp = PetscMax(rp, dem->shapes.shp[t].r);
  for (int d = 0; d < 3; d++) {
    lo[d] = s->lo[d] - 0.5 * dmax - rp;
    hi[d] = s->hi[d] + 0.5 * dmax + rp;
  }
  PetscCall(DemSrcGridCreate(lo, hi, 0.5 * dmax + rp, &g));
  for (PetscInt j = 0; j < dem->p.n + dem->p.ng; j++) {
    const double *x = dem->p.x + 3 * j;
    if (x[0] < lo[0] || x[1] < lo[1] || x[2] < lo[2] || x[0] > hi[0] || x[1] > hi[1] || x[2] > hi[2]) continue;
    PetscCall(DemSrcGridAdd(&g, x, DemRadius(&dem->p, &dem->shapes, j)));
  }
  for (PetscInt i = 0; i < K; i++) {
    const double r = dem_src_radius(dem, &cand[i]);
    blk[i]         = 0;
    if (!dem_in_box(dem->dom, cand[i].x)) continue;
    if (DemSrcGridHits(&g, cand[i].x, r)) blk[i] = 1;
    for (PetscInt w = 0; w < dem->walls.nwall && !blk[i]; w++)
      if (!dem->walls.wall[w].removed && dem_wall_sphere(&dem->walls.wall[w], cand[i].x, r, nrm) > 0) blk[i] = 1;
    if (!blk[i] && dem->meshes.n && DemMeshesBlock(dem, cand[i].x, r)) blk[i] = 1; /* walls_mesh.c */
  }
  PetscCall(DemSrcGridDestroy(&g));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, blk, (PetscMPIInt)K, MPI_UNSIGNED_CHAR, MPI_MAX, dem->comm));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Accepted candidates of this step, all sources, on every rank (x, y, z, r; volume), and the next id. */
typedef struct {
  double  *xr, *vol;
  PetscInt n, cap, next_id;
} DemSrcAccepted;

/* Not collective (the same on every rank). Candidate p becomes the next particle of source s:
 * counted, given the next id, and kept for its owner's rebuild. */
static PetscErrorCode DemSourceAccept(Dem dem, DemSource *s, DemParticle *p, DemSrcAccepted *acc)
{
  const double r = dem_src_radius(dem, p), m = DemSourceMass(dem, s, 2 * r);

  PetscFunctionBeginUser;
  if (acc->n == acc->cap) {
    acc->cap = 2 * acc->cap + 64;
    PetscCall(PetscRealloc(sizeof(double) * 4 * (size_t)acc->cap, &acc->xr));
    PetscCall(PetscRealloc(sizeof(double) * (size_t)acc->cap, &acc->vol));
  }
  for (int d = 0; d < 3; d++) acc->xr[4 * acc->n + d] = p->x[d];
  acc->xr[4 * acc->n + 3] = r;
  acc->vol[acc->n++]      = m / dem->shapes.shp[s->shape].rho;
  p->id                   = acc->next_id++;
  s->inserted++;
  s->m_inserted += m;
  dem->flow.inserted++;
  dem->flow.m_inserted += m;
  dem->flow.id_inserted += (PetscReal)p->id;
  if (!dem_in_box(dem->dom, p->x)) PetscFunctionReturn(PETSC_SUCCESS);
  /* the step's last half kick adds g dt/2: the particle leaves with the set velocity */
  for (int d = 0; d < 3; d++) p->v[d] -= 0.5 * dem->clock.dt * dem->g[d];
  if (dem->src.npend == dem->src.cappend) {
    dem->src.cappend = 2 * dem->src.cappend + 64;
    PetscCall(PetscRealloc(sizeof(DemParticle) * (size_t)dem->src.cappend, &dem->src.pend));
  }
  dem->src.pend[dem->src.npend++] = *p;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* One placement round of a source: J slots, slot t the particle inserted + t (own sizes: its
 * diameter DemSourceDiameter) with candidates A0 (slot 0) or A (the others), in slot order;
 * one size: a single slot of A0 candidates that serves every particle of the batch. */
typedef struct {
  PetscBool own;
  PetscInt  J, A0, A, K;
  double    ntgt, mtgt; /* the batch's cumulative targets */
} DemSrcRound;

static inline PetscInt dem_src_slot(const DemSrcRound *r, PetscInt i)
{
  return i < r->A0 ? 0 : 1 + (i - r->A0) / r->A;
}

/* Collective. One round (above): draws the candidates, finds the blocked ones, accepts in
 * candidate order up to the targets (own sizes: the first free candidate of each slot, the round
 * ending at a slot with none). *tried: the candidates used; *failed: the slot where it ended,
 * none placed (-1: it did not). */
static PetscErrorCode DemSourceRound(Dem dem, DemSource *s, const DemSrcRound *r, DemSrcAccepted *acc, PetscInt *tried, PetscInt *failed)
{
  DemParticle   *cand;
  unsigned char *blk;
  DemSrcGrid     g;
  double         dmin, dmax, lo[3], hi[3], d = 0;
  PetscInt       i = 0, n0 = s->inserted;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc2(r->K + 1, &cand, r->K + 1, &blk));
  for (PetscInt c = 0, tcur = -1; c < r->K; c++) { /* a slot's candidates share its particle's diameter */
    const PetscInt t = r->own ? dem_src_slot(r, c) : 0;
    if (t != tcur) d = DemSourceDiameter(s, n0 + (tcur = t));
    DemSourceCandidate(dem, s, s->cand + c, d, &cand[c]);
  }
  PetscCall(DemSourceBlocked(dem, s, r->K, cand, blk));
  DemPsdRange(&s->psd, &dmin, &dmax);
  const double reach = 0.5 * dmax + dem->shapes.r_source_max; /* this source's and any source's radii */
  for (int k = 0; k < 3; k++) {
    lo[k] = s->lo[k] - reach;
    hi[k] = s->hi[k] + reach;
  }
  PetscCall(DemSrcGridCreate(lo, hi, reach, &g)); /* the accepted of earlier sources and rounds too */
  for (PetscInt a = 0; a < acc->n; a++) PetscCall(DemSrcGridAdd(&g, acc->xr + 4 * a, acc->xr[4 * a + 3]));
  *failed = -1;
  while (i < r->K && s->inserted < r->ntgt && s->m_inserted < r->mtgt) {
    DemParticle   *p = &cand[i];
    const PetscInt t = dem_src_slot(r, i);
    if (!blk[i] && !DemSrcGridHits(&g, p->x, dem_src_radius(dem, p))) {
      PetscCall(DemSrcGridAdd(&g, p->x, dem_src_radius(dem, p)));
      PetscCall(DemSourceAccept(dem, s, p, acc));
      if (r->own) { /* on to the next slot's candidates */
        i = t == 0 ? r->A0 : r->A0 + t * r->A;
        continue;
      }
    }
    i++;
    if (r->own && (i == r->K || dem_src_slot(r, i) != t)) {
      *failed = t;
      break;
    }
  }
  *tried = PetscMin(i, r->K);
  PetscCall(DemSrcGridDestroy(&g));
  PetscCall(PetscFree2(cand, blk));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. One batch of source s up to its targets. One size: nwant x attempts candidates
 * that serve every particle due, in rounds of at most DEM_SRC_MAX_CANDIDATE (the same as one
 * list: a round sees the earlier rounds' accepted). Own sizes: rounds of J particles with A
 * candidates each, A starting at 1 and doubling whenever a round ends at a particle with no free
 * candidate, up to -attempts; the batch ends once a particle has had -attempts candidates (the
 * rest is carried). *dstop: the diameter of the particle the batch ended at (0: none). */
static PetscErrorCode DemSourceBatch(Dem dem, DemSource *s, DemSrcAccepted *acc, double *dstop)
{
  double      dmin, dmax;
  DemSrcRound r;
  PetscInt    used = 0, tried, failed;

  PetscFunctionBeginUser;
  DemSourceTargets(s, &r.ntgt, &r.mtgt);
  DemPsdRange(&s->psd, &dmin, &dmax);
  r.own  = (PetscBool)(dmax > dmin);
  *dstop = 0;
  if (!r.own) {
    double nwant = r.ntgt - s->inserted;
    if (r.mtgt < 1e300) nwant = PetscMin(nwant, PetscCeilReal((r.mtgt - s->m_inserted) / s->m_mean) + 1);
    double budget = nwant > 0 ? nwant * (double)s->attempts : 0;
    r.J           = 1;
    while (budget >= 1 && s->inserted < r.ntgt && s->m_inserted < r.mtgt) {
      r.A = r.A0 = r.K = (PetscInt)PetscMin((double)DEM_SRC_MAX_CANDIDATE, budget);
      PetscCall(DemSourceRound(dem, s, &r, acc, &tried, &failed));
      s->cand += tried;
      budget -= (double)tried;
    }
    if (s->inserted < r.ntgt && s->m_inserted < r.mtgt) *dstop = dmin;
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  r.A = 1;
  for (;;) {
    double m = s->m_inserted; /* the slots: the particles due, their own masses against the mass target */
    r.A0     = PetscMin(r.A, s->attempts - used);
    for (r.J = 0; s->inserted + r.J < r.ntgt && m < r.mtgt && r.A0 + r.J * r.A <= DEM_SRC_MAX_CANDIDATE; r.J++) m += DemSourceMass(dem, s, DemSourceDiameter(s, s->inserted + r.J));
    if (!r.J) break;
    r.K = r.A0 + (r.J - 1) * r.A;
    PetscCall(DemSourceRound(dem, s, &r, acc, &tried, &failed));
    s->cand += tried;
    if (failed < 0) used = 0;
    else {
      used = failed == 0 ? used + r.A0 : r.A;
      if (used >= s->attempts) {
        *dstop = DemSourceDiameter(s, s->inserted);
        break;
      }
      r.A = PetscMin(2 * r.A, s->attempts);
    }
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. The solids volume fraction of source s's region: the particles whose centres lie in
 * it (the locals, and this step's accepted of every source when acc is given). */
static PetscErrorCode DemSourceFill(Dem dem, const DemSource *s, const DemSrcAccepted *acc, double *fill)
{
  double v = 0;

  PetscFunctionBeginUser;
  for (PetscInt j = 0; j < dem->p.n; j++)
    if (geom_region_inside(&s->reg, dem->p.x + 3 * j)) v += DemMass(&dem->p, &dem->shapes, j) / dem->shapes.shp[dem->p.shape[j]].rho;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &v, 1, MPI_DOUBLE, MPI_SUM, dem->comm));
  for (PetscInt a = 0; acc && a < acc->n; a++)
    if (geom_region_inside(&s->reg, acc->xr + 4 * a)) v += acc->vol[a];
  *fill = v / s->vol;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. After a batch that placed `placed` particles and ended at a particle of diameter
 * dstop (0: none), with its region's solids fraction `before` it (< 0: not measured, nothing was
 * carried): the shortfall (particles due and not placed, carried by the cumulative target) and
 * what the log says of it, each at most once per source. A batch that leaves particles due after
 * placing others prints a note: random placement ran out of candidates for one particle (a
 * crowded region, not necessarily a full one: a large sphere among many), and the rest follow at
 * the next batches as the region empties. A warning says the source is not catching up: a batch
 * placed none of the particles carried while no particle left the region since the last batch
 * (the region is full and stays so), or a rate's shortfall grew past two batches' worth (the
 * region does not clear as fast as the rate fills it). The summary (DemViewSources) gives the end
 * state and refers to them. */
static PetscErrorCode DemSourceShortfall(Dem dem, DemSource *s, PetscInt placed, double dstop, double before, const DemSrcAccepted *acc)
{
  double         ntgt, mtgt, sh = 0, fill = 0, dmin, dmax;
  const PetscInt prev = s->shortfall;
  const double   t = dem->clock.t + dem->clock.dt, per = s->rate > 0 ? s->rate * s->period : s->mass_rate * s->period / s->m_mean;
  const int      k = (int)s->k;
  char           why[256];

  PetscFunctionBeginUser;
  DemSourceTargets(s, &ntgt, &mtgt);
  if (ntgt < 1e300) sh = ntgt - s->inserted;
  if (mtgt < 1e300 && s->m_inserted < mtgt) sh = PetscMax(sh, PetscCeilReal((mtgt - s->m_inserted) / s->m_mean));
  s->shortfall = (PetscInt)sh;
  s->sh_max    = PetscMax(s->sh_max, s->shortfall);
  s->t_caught  = s->shortfall > 0 ? -1 : (prev > 0 ? t : s->t_caught);
  s->batch++;
  if (!s->shortfall) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(DemSourceFill(dem, s, acc, &fill));
  const PetscBool full  = (PetscBool)(prev > 0 && placed == 0 && before >= s->fill * (1 - 1e-12));
  const PetscBool grows = (PetscBool)(prev > 0 && per > 0 && s->shortfall > prev && s->shortfall > 2 * per);
  s->fill               = fill;
  DemPsdRange(&s->psd, &dmin, &dmax);
  if (dstop > 0 && dmax > dmin) PetscCall(PetscSNPrintf(why, sizeof why, "the %" PetscInt_FMT " candidates (-dem_insert_%d_attempts) of a particle of %.3g mm were all blocked, the region being %.1f%% full by volume", s->attempts, k, 1e3 * dstop, 100 * fill));
  else PetscCall(PetscSNPrintf(why, sizeof why, "its %" PetscInt_FMT " candidates per particle due (-dem_insert_%d_attempts) ran out, the region being %.1f%% full by volume", s->attempts, k, 100 * fill));
  if ((full || grows) && !(s->said & 2)) {
    PetscCall(PetscPrintf(dem->comm, "warning: t = %g s: source -dem_insert_%d is %" PetscInt_FMT " particles behind its rate or total and not catching up (%s; %s): enlarge the region, lower the rate, or give more -dem_insert_%d_attempts\n", t, k, s->shortfall, full ? "this batch placed none, and no particle left the region since the last one" : "the shortfall grew past two batches' worth", why, k));
    s->said |= 2;
  } else if (!(s->said & 3)) {
    PetscCall(PetscPrintf(dem->comm, "source -dem_insert_%d: t = %g s: placed %" PetscInt_FMT " of the %" PetscInt_FMT " particles due (%s); the other %" PetscInt_FMT " are carried to the next batches, every %g s\n", k, t, placed, placed + s->shortfall, why, s->shortfall, (double)s->period));
    s->said |= 1;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemSourcesPlace(Dem dem)
{
  DemSrcAccepted acc = {NULL, NULL, 0, 0, 0};

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(DEM_Placement, 0, 0, 0, 0));
  PetscCall(DemGhostsUpdate(dem)); /* the ghosts where they are now, as the locals */
  PetscCallMPI(MPI_Allreduce(&dem->p.next_id, &acc.next_id, 1, MPIU_INT, MPI_MAX, dem->comm));
  for (PetscInt i = 0; i < dem->src.n; i++) {
    DemSource *s  = &dem->src.s[i];
    PetscInt   n0 = s->inserted;
    double     dstop, before = -1;
    if (!DemSourceDue(dem, s)) continue;
    if (s->shortfall > 0) PetscCall(DemSourceFill(dem, s, &acc, &before)); /* did the region empty since the last batch? */
    PetscCall(DemSourceBatch(dem, s, &acc, &dstop));
    PetscCall(DemSourceShortfall(dem, s, s->inserted - n0, dstop, before, &acc));
  }
  PetscCall(PetscFree(acc.xr));
  PetscCall(PetscFree(acc.vol));
  PetscCall(PetscLogEventEnd(DEM_Placement, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemSourcesAddPending(Dem dem)
{
  PetscFunctionBeginUser;
  if (!dem->src.npend) PetscFunctionReturn(PETSC_SUCCESS);
  dem->p.ng = 0; /* the ghosts go (the rebuild makes them again): locals are appended */
  for (PetscInt a = 0; a < dem->src.npend; a++) PetscCall(DemAddParticle(dem, &dem->src.pend[a]));
  dem->src.npend = 0;
  { /* the cell grid was sized for the particles of its set-up (at most 8 cells per particle +
       1000, neighbours.c): a run that starts empty would bin thousands of particles in cells many
       reaches wide. Once the count would allow 4 times the cells, the grid is sized again at this
       rebuild (a function of the count and the grid, so a restart does the same). */
    double ideal = 1;
    for (int k = 0; k < 3; k++) ideal *= PetscMax(1.0, PetscFloorReal((dem->dom->subhi[k] - dem->dom->sublo[k] + 2 * dem->nl.reach) / dem->nl.reach));
    if (dem->nl.cstart && dem->nl.ncell < ideal && 8.0 * dem->p.n + 1000 > 4.0 * dem->nl.ncell) PetscCall(DemNeighResetCells(dem));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. The sources' state and the inserted totals of the flow, dataset dem/sources (the
 * same on every rank): n, inserted, m_inserted, id_inserted, then per source inserted,
 * candidates, batch, shortfall, the log's lines said, mass, largest shortfall, catch-up time,
 * region's solids fraction after the last batch. */
#define DEM_SRC_CKPT 9
PetscErrorCode DemSourcesCheckpoint(Dem dem, IoCkpt ck, PetscBool write)
{
  double         v[4 + DEM_SRC_CKPT * DEM_MAX_SOURCES];
  const PetscInt nv = 4 + DEM_SRC_CKPT * dem->src.n;

  PetscFunctionBeginUser;
  if (!dem->src.n) PetscFunctionReturn(PETSC_SUCCESS);
  if (write) {
    v[0] = (double)dem->src.n;
    v[1] = (double)dem->flow.inserted;
    v[2] = dem->flow.m_inserted;
    v[3] = dem->flow.id_inserted;
    for (PetscInt i = 0; i < dem->src.n; i++) {
      const DemSource *s               = &dem->src.s[i];
      const double     w[DEM_SRC_CKPT] = {(double)s->inserted, (double)s->cand, (double)s->batch, (double)s->shortfall, (double)s->said, s->m_inserted, (double)s->sh_max, s->t_caught, s->fill};
      for (int a = 0; a < DEM_SRC_CKPT; a++) v[4 + DEM_SRC_CKPT * i + a] = w[a];
    }
    PetscCall(IoCkptWriteShared(ck, "dem/sources", IO_CKPT_REAL, nv, v));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  { /* a checkpoint of Sable before the log's figures held 6 numbers a source (the 6th the mass) */
    long long total;
    PetscCall(IoCkptGetSize(ck, "dem/sources", &total));
    if (total == 4 + 6 * dem->src.n) {
      PetscCall(IoCkptReadShared(ck, "dem/sources", IO_CKPT_REAL, total, v));
      for (PetscInt i = dem->src.n - 1; i >= 0; i--) { /* spread to 9 a source, from the last */
        const double *o = v + 4 + 6 * i, w[DEM_SRC_CKPT] = {o[0], o[1], o[2], o[3], 0, o[5], o[3], -1, 0};
        for (int a = 0; a < DEM_SRC_CKPT; a++) v[4 + DEM_SRC_CKPT * i + a] = w[a];
      }
    } else PetscCall(IoCkptReadShared(ck, "dem/sources", IO_CKPT_REAL, nv, v));
  }
  PetscCheck(v[0] == (double)dem->src.n, dem->comm, PETSC_ERR_FILE_UNEXPECTED, "-restart: the checkpoint has %g particle sources, the case's options make %" PetscInt_FMT, v[0], dem->src.n);
  dem->flow.inserted    = (PetscInt)v[1];
  dem->flow.m_inserted  = v[2];
  dem->flow.id_inserted = v[3];
  for (PetscInt i = 0; i < dem->src.n; i++) {
    DemSource    *s = &dem->src.s[i];
    const double *w = v + 4 + DEM_SRC_CKPT * i;
    s->inserted     = (PetscInt)w[0];
    s->cand         = (PetscInt)w[1];
    s->batch        = (PetscInt)w[2];
    s->shortfall    = (PetscInt)w[3];
    s->said         = (PetscInt)w[4];
    s->m_inserted   = w[5];
    s->sh_max       = (PetscInt)w[6];
    s->t_caught     = w[7];
    s->fill         = w[8];
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. One line per source: what it inserted and its shortfall at the end; a source that
 * was behind says how far and when it caught up, or, still behind, how full its region is. */
PetscErrorCode DemViewSources(Dem dem, PetscViewer v)
{
  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < dem->src.n; i++) {
    const DemSource *s        = &dem->src.s[i];
    char             how[256] = "";
    if (s->shortfall > 0) {
      double fill = 0;
      PetscCall(DemSourceFill(dem, s, NULL, &fill));
      PetscCall(PetscSNPrintf(how, sizeof how, " (due and not placed: its region is %.1f%% full by volume at the end%s)", 100 * fill, s->said & 2 ? "; it stopped catching up, see the warning" : ", and it was still placing the carried ones"));
    } else if (s->sh_max > 0) PetscCall(PetscSNPrintf(how, sizeof how, " (placed over several batches: up to %" PetscInt_FMT " carried, all placed by t = %g s)", s->sh_max, (double)s->t_caught));
    PetscCall(PetscViewerASCIIPrintf(v, "source -dem_insert_%d (%s): %" PetscInt_FMT " particles, %.6g kg inserted in %" PetscInt_FMT " batches; shortfall %" PetscInt_FMT " particles%s\n", (int)s->k, GeomRegionKinds[s->reg.kind], s->inserted, (double)s->m_inserted, s->batch, s->shortfall, how));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemSourcesDestroy(Dem dem)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree(dem->src.pend));
  dem->src.npend = dem->src.cappend = 0;
  PetscFunctionReturn(PETSC_SUCCESS);
}
