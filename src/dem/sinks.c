/* Outlets: regions that take particles out of the run, and the mass balance they keep.
 * An outlet is a region (geom/region.h): a box (a particle whose centre is inside it is
 * removed), a plane patch (the rectangle of corners p0, p1, p2: a particle whose centre crossed
 * it, in either direction, since the last list build is removed; the crossing point is taken on
 * the straight segment x0 -> x, which is shorter than skin/2), or a domain side (a particle whose centre
 * left the domain across that side is removed instead of stopping the run, DemCheckInDomain);
 * each is active for start <= t <= stop (t at the end of the step). Options
 * -dem_outlet_<k>_{box,patch,side,start,stop}, k = 0..9; a coupled run adds the fluid's outlet
 * faces as side outlets (DemAddOutletSide, -cpl_outlet_remove).
 * Removal changes the particle set at list rebuilds only: DemStep marks the owner's particles
 * (ghosts never: their owner marks them), asks every rank for a rebuild through its reduction,
 * and the rebuild (DemSinksRemove, before the migration) compacts every per-particle array with
 * DemParticlesPermute; the springs of a removed particle find no partner and vanish with the
 * rebuild. Counts, masses and id sums are reduced to global totals per outlet and into
 * dem->flow, equal on every rank. The balance initial + inserted - removed = present holds in
 * count and in the id checksum (DemCheckBalance, -dem_check_every); ids sum exactly in doubles
 * below 2^53. */
#include "dem/dem_core.h"
#include "dem/dem_sources.h"

static const char *const DemSideNames[] = {"xlo", "xhi", "ylo", "yhi", "zlo", "zhi", "DemSide", "DEM_SIDE_", NULL};
/* the indexed options whose values are words, listed for the option checks (tools/gen-options.sh) */
static const char *const DemOutletSideOption[DEM_MAX_OUTLETS] = {"-dem_outlet_0_side", "-dem_outlet_1_side", "-dem_outlet_2_side", "-dem_outlet_3_side", "-dem_outlet_4_side", "-dem_outlet_5_side", "-dem_outlet_6_side", "-dem_outlet_7_side", "-dem_outlet_8_side", "-dem_outlet_9_side"};

static PetscErrorCode DemOutletNew(Dem dem, const char *name, DemOutletKind kind, DemOutlet **o)
{
  PetscFunctionBeginUser;
  PetscCheck(dem->sinks.nout < DEM_MAX_OUTLETS + 6, dem->comm, PETSC_ERR_ARG_OUTOFRANGE, "%s: at most %d outlets", name, DEM_MAX_OUTLETS + 6);
  *o = &dem->sinks.out[dem->sinks.nout++];
  PetscCall(PetscMemzero(*o, sizeof **o));
  PetscCall(PetscStrncpy((*o)->name, name, sizeof(*o)->name));
  (*o)->kind   = kind;
  (*o)->t_stop = PETSC_MAX_REAL;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The region r of option opt: a box must overlap the domain, a patch lie inside it. */
static PetscErrorCode DemOutletRegion(Dem dem, const char *opt, const GeomRegion *r)
{
  const Domain    *dom = dem->dom;
  const PetscReal *g   = r->g;
  DemOutlet       *o   = NULL;

  PetscFunctionBeginUser;
  for (int k = 0; k < 3 && r->kind == GEOM_REGION_BOX; k++) PetscCheck(g[k] < dom->hi[k] && g[k + 3] > dom->lo[k], dem->comm, PETSC_ERR_ARG_OUTOFRANGE, "%s: the box is outside the domain along %c ([%g, %g] against -domain_lo/-domain_hi [%g, %g] m)", opt, "xyz"[k], (double)g[k], (double)g[k + 3], (double)dom -> lo[k], (double)dom -> hi[k]);
  for (int c = 0; c < 4 && r->kind == GEOM_REGION_PATCH; c++)
    for (int k = 0; k < 3; k++) {
      const double x = g[k] + (c & 1 ? g[3 + k] : 0) + (c & 2 ? g[6 + k] : 0), tol = 1e-9 * dom->len[k];
      PetscCheck(x >= dom->lo[k] - tol && x <= dom->hi[k] + tol, dem->comm, PETSC_ERR_ARG_OUTOFRANGE, "%s: corner %d of the patch has %c = %g m, outside the domain [%g, %g] m (-domain_lo/-domain_hi)", opt, c, "xyz"[k], x, (double)dom -> lo[k], (double)dom -> hi[k]);
    }
  PetscCall(DemOutletNew(dem, opt, DEM_OUTLET_REGION, &o));
  o->reg = *r;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemAddOutletSide(Dem dem, int d, int s, const char *name)
{
  DemOutlet *o = NULL;

  PetscFunctionBeginUser;
  PetscCheck(d >= 0 && d < 3 && (s == 0 || s == 1), dem->comm, PETSC_ERR_ARG_OUTOFRANGE, "%s: side (%d, %d) is not a domain side", name, d, s);
  PetscCheck(!dem->dom->periodic[d], dem->comm, PETSC_ERR_ARG_INCOMP, "%s: the %c axis is periodic (-domain_periodic_%c): nothing leaves across %s", name, "xyz"[d], "xyz"[d], DemSideNames[2 * d + s]);
  PetscCall(DemOutletNew(dem, name, DEM_OUTLET_SIDE, &o));
  o->axis = d;
  o->side = s;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Outlet k: its region (one of box, patch, side) and its time window. */
static PetscErrorCode DemOutletOptions(PetscOptionItems *PetscOptionsObject, Dem dem, int k)
{
  char           opt[64], ob[64], op[64], os[64], o0[64], o1[64];
  PetscReal      t0 = 0, t1 = PETSC_MAX_REAL;
  PetscInt       side = 0, nout = dem->sinks.nout;
  PetscBool      rset, sset, s0, s1, help;
  GeomRegion     reg;
  GeomRegionSpec spec = {{ob, NULL, op}, {"Outlet box: particles whose centre enters it are removed: lo_x,lo_y,lo_z,hi_x,hi_y,hi_z", NULL, "Outlet patch: particles whose centre crosses the rectangle of corners p0, p1, p2 (p1-p0 perpendicular to p2-p0) are removed: p0x,p0y,p0z,p1x,p1y,p1z,p2x,p2y,p2z"}};

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsHasHelp(NULL, &help)); /* -help: an outlet left incomplete is no error */
  PetscCall(PetscSNPrintf(opt, sizeof opt, "-dem_outlet_%d", k));
  PetscCall(PetscSNPrintf(ob, sizeof ob, "-dem_outlet_%d_box", k));
  PetscCall(PetscSNPrintf(op, sizeof op, "-dem_outlet_%d_patch", k));
  PetscCall(PetscSNPrintf(o0, sizeof o0, "-dem_outlet_%d_start", k));
  PetscCall(PetscSNPrintf(o1, sizeof o1, "-dem_outlet_%d_stop", k));
  PetscCall(PetscStrncpy(os, DemOutletSideOption[k], sizeof os));
  PetscCall(GeomRegionOptions(&spec, &reg, &rset)); /* box or patch (geom/region.h) */
  PetscCall(SableOptionsEnum(DemOutletSideOption[k], "Outlet side: a particle leaving the domain across it is removed instead of stopping the run", DemSideNames, 6, 0, &side, &sset));
  PetscCall(SableOptionsReal(o0, "Time the outlet starts removing particles", "s", "[0,inf)", t0, &t0, &s0));
  PetscCall(SableOptionsReal(o1, "Time the outlet stops removing particles; default: never", "s", "[0,inf)", -1, &t1, &s1));
  PetscCheck((int)rset + (int)sset <= 1, dem->comm, PETSC_ERR_ARG_INCOMP, "%s: give one of %s, %s, %s", opt, ob, op, os);
  PetscCheck(rset || sset || !(s0 || s1) || help, dem->comm, PETSC_ERR_ARG_WRONG, "%s given without %s, %s or %s", s0 ? o0 : o1, ob, op, os);
  if (!s1) t1 = PETSC_MAX_REAL;
  PetscCheck(t0 <= t1, dem->comm, PETSC_ERR_ARG_OUTOFRANGE, "%s %g s is after %s %g s: the outlet would never remove anything", o0, (double)t0, o1, (double)t1);
  if (rset) PetscCall(DemOutletRegion(dem, reg.kind == GEOM_REGION_BOX ? ob : op, &reg));
  if (sset) {
    PetscCall(PetscSNPrintf(opt, sizeof opt, "%s %s", os, DemSideNames[side]));
    PetscCall(DemAddOutletSide(dem, (int)side / 2, (int)side % 2, opt));
  }
  if (dem->sinks.nout == nout) PetscFunctionReturn(PETSC_SUCCESS);
  dem->sinks.out[nout].t_start = t0;
  dem->sinks.out[nout].t_stop  = t1;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemSinksSetFromOptions(Dem dem)
{
  PetscFunctionBeginUser;
  PetscOptionsBegin(dem->comm, NULL, "DEM outlets", NULL);
  for (int k = 0; k < DEM_MAX_OUTLETS; k++) PetscCall(DemOutletOptions(PetscOptionsObject, dem, k));
  PetscOptionsEnd();
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Whether outlet o takes the particle now at x, at x0 at the last list build. */
static inline PetscBool dem_outlet_takes(const DemOutlet *o, const Domain *dom, const double *x, const double *x0)
{
  if (o->kind == DEM_OUTLET_SIDE) return (PetscBool)(o->side ? x[o->axis] > dom->hi[o->axis] : x[o->axis] < dom->lo[o->axis]);
  return o->reg.kind == GEOM_REGION_PATCH ? geom_region_crossed(&o->reg, x0, x) : geom_region_inside(&o->reg, x);
}

PetscErrorCode DemSinksMark(Dem dem)
{
  DemSinks    *sk = &dem->sinks;
  const double t  = dem->clock.t + dem->clock.dt;

  PetscFunctionBeginUser;
  sk->ngone = 0;
  for (PetscInt i = 0; i < dem->p.n; i++)
    for (PetscInt k = 0; k < sk->nout; k++) {
      const DemOutlet *o = &sk->out[k];
      if (t < o->t_start || t > o->t_stop || !dem_outlet_takes(o, dem->dom, dem->p.x + 3 * i, dem->p.x0 + 3 * i)) continue;
      if (sk->ngone == sk->capgone) {
        sk->capgone = 2 * sk->capgone + 64;
        PetscCall(PetscRealloc(sizeof(PetscInt) * (size_t)sk->capgone, &sk->gone));
        PetscCall(PetscRealloc(sizeof(PetscInt) * (size_t)sk->capgone, &sk->gone_out));
      }
      sk->gone[sk->ngone]       = i;
      sk->gone_out[sk->ngone++] = k; /* the first outlet that takes it: counted once */
      break;
    }
  if (sk->ngone) dem->need_build = PETSC_TRUE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemSinksRemove(Dem dem)
{
  DemSinks *sk = &dem->sinks;
  PetscInt *perm, nk = 0, nr = 0, n = dem->p.n;
  double   *loc, *glob;
  const int nv = 3 * (int)sk->nout;

  PetscFunctionBeginUser;
  PetscCall(PetscCalloc2(nv + 1, &loc, nv + 1, &glob));
  if (sk->ngone) {
    PetscCall(PetscMalloc1(n + 1, &perm));
    for (PetscInt a = 0; a < sk->ngone; a++) {
      const PetscInt i = sk->gone[a], k = sk->gone_out[a];
      const double   m = DemMass(&dem->p, &dem->shapes, i); /* its own size's, or its shape's */
      loc[3 * k] += 1;
      loc[3 * k + 1] += m;
      loc[3 * k + 2] += (double)dem->p.id[i];
      perm[n - sk->ngone + nr++] = i; /* the removed ones go last */
    }
    for (PetscInt i = 0, a = 0; i < n; i++) {
      if (a < sk->ngone && sk->gone[a] == i) a++; /* marked in increasing order */
      else perm[nk++] = i;
    }
    PetscCall(DemParticlesPermute(dem, perm));
    dem->p.n -= sk->ngone;
    sk->ngone = 0;
    PetscCall(PetscFree(perm));
  }
  PetscCallMPI(MPI_Allreduce(loc, glob, nv, MPI_DOUBLE, MPI_SUM, dem->comm));
  for (PetscInt k = 0; k < sk->nout; k++) {
    DemOutlet *o = &sk->out[k];
    o->removed += (PetscInt)glob[3 * k];
    o->m_removed += glob[3 * k + 1];
    o->id_removed += glob[3 * k + 2];
    dem->flow.removed += (PetscInt)glob[3 * k];
    dem->flow.m_removed += glob[3 * k + 1];
    dem->flow.id_removed += glob[3 * k + 2];
  }
  PetscCall(PetscFree2(loc, glob));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemCheckBalance(Dem dem)
{
  DemStats       st;
  const PetscInt n = dem->initial.n + dem->flow.inserted - dem->flow.removed;
  const double   c = dem->initial.checksum + dem->flow.id_inserted - dem->flow.id_removed;

  PetscFunctionBeginUser;
  PetscCall(DemGetStats(dem, &st));
  PetscCheck(st.n == n && st.checksum == c, dem->comm, PETSC_ERR_PLIB, "step %" PetscInt_FMT ": %" PetscInt_FMT " particles with id checksum %.17g, expected %" PetscInt_FMT " and %.17g (%" PetscInt_FMT " initial + %" PetscInt_FMT " inserted - %" PetscInt_FMT " removed): a particle was lost, duplicated or not counted", dem->clock.step, st.n, st.checksum, n, c, dem->initial.n, dem->flow.inserted, dem->flow.removed);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemGetOutletCount(Dem dem, PetscInt *n)
{
  PetscFunctionBeginUser;
  *n = dem->sinks.nout;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemGetOutletFlow(Dem dem, PetscInt k, const char **name, PetscInt *removed, PetscReal *mass)
{
  PetscFunctionBeginUser;
  PetscCheck(k >= 0 && k < dem->sinks.nout, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "outlet %" PetscInt_FMT " not in [0, %" PetscInt_FMT ")", k, dem->sinks.nout);
  if (name) *name = dem->sinks.out[k].name;
  if (removed) *removed = dem->sinks.out[k].removed;
  if (mass) *mass = dem->sinks.out[k].m_removed;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemFlowView(Dem dem, PetscViewer viewer)
{
  const DemFlow *f = &dem->flow;
  DemStats       st;

  PetscFunctionBeginUser;
  if (!dem->sinks.nout && !f->inserted && !f->removed) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(DemGetStats(dem, &st));
  PetscCall(PetscViewerASCIIPrintf(viewer, "flow: %" PetscInt_FMT " initial + %" PetscInt_FMT " inserted (%.6g kg) - %" PetscInt_FMT " removed (%.6g kg) = %" PetscInt_FMT " present; balance %" PetscInt_FMT "\n", dem->initial.n, f->inserted, (double)f->m_inserted, f->removed, (double)f->m_removed, st.n, dem->initial.n + f->inserted - f->removed - st.n));
  for (PetscInt k = 0; k < dem->sinks.nout; k++) {
    const DemOutlet *o = &dem->sinks.out[k];
    PetscCall(PetscViewerASCIIPrintf(viewer, "outlet %s: %" PetscInt_FMT " removed (%.6g kg)\n", o->name, o->removed, (double)o->m_removed));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. dem->flow and the outlets' totals, the same on every rank: one shared dataset,
 * read on any rank count. A checkpoint without it (written before outlets existed) leaves them
 * at zero. */
PetscErrorCode DemSinksCheckpoint(Dem dem, IoCkpt ck, PetscBool write)
{
  DemSinks      *sk = &dem->sinks;
  const PetscInt nv = 6 + 3 * sk->nout;
  double        *v;
  PetscBool      has = PETSC_TRUE;

  PetscFunctionBeginUser;
  if (!write) PetscCall(IoCkptHas(ck, "dem/flow", &has));
  if (!has) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscMalloc1(nv, &v));
  if (write) {
    const double f[6] = {(double)dem->flow.inserted, (double)dem->flow.removed, dem->flow.m_inserted, dem->flow.m_removed, dem->flow.id_inserted, dem->flow.id_removed};
    for (int k = 0; k < 6; k++) v[k] = f[k];
    for (PetscInt k = 0; k < sk->nout; k++) {
      v[6 + 3 * k]     = (double)sk->out[k].removed;
      v[6 + 3 * k + 1] = sk->out[k].m_removed;
      v[6 + 3 * k + 2] = sk->out[k].id_removed;
    }
    PetscCall(IoCkptWriteShared(ck, "dem/flow", IO_CKPT_REAL, nv, v));
  } else {
    long long   total;
    const char *path;
    PetscCall(IoCkptGetPath(ck, &path));
    PetscCall(IoCkptGetSize(ck, "dem/flow", &total));
    PetscCheck(total == nv, dem->comm, PETSC_ERR_FILE_UNEXPECTED, "-restart %s: the checkpoint has %lld outlet counters, the case's options make %" PetscInt_FMT " outlets (%" PetscInt_FMT " counters)", path, total, sk->nout, nv);
    PetscCall(IoCkptReadShared(ck, "dem/flow", IO_CKPT_REAL, nv, v));
    dem->flow.inserted    = (PetscInt)v[0];
    dem->flow.removed     = (PetscInt)v[1];
    dem->flow.m_inserted  = v[2];
    dem->flow.m_removed   = v[3];
    dem->flow.id_inserted = v[4];
    dem->flow.id_removed  = v[5];
    for (PetscInt k = 0; k < sk->nout; k++) {
      sk->out[k].removed    = (PetscInt)v[6 + 3 * k];
      sk->out[k].m_removed  = v[6 + 3 * k + 1];
      sk->out[k].id_removed = v[6 + 3 * k + 2];
    }
  }
  PetscCall(PetscFree(v));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemSinksDestroy(Dem dem)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree(dem->sinks.gone));
  PetscCall(PetscFree(dem->sinks.gone_out));
  PetscFunctionReturn(PETSC_SUCCESS);
}
