/* DEM diagnostics and reporting: global statistics by reductions (count, id checksum, energies,
 * contacts, largest overlap), bed figures (packing fraction, coordination number), the start-up
 * summary with the contact pre-flight figures, output of particle state, and the run loop with
 * its progress line. Elastic energy: linear 1/2 kn delta^2 + 1/2 kt |xi|^2; hertz
 * 8/15 E* sqrt(R*) delta^(5/2) (the tangential spring energy is left out for hertz). */
#include "dem/dem_impl.h"

static double dem_spring_energy(const Dem dem, const DemPairParams *p, double delta, const double *xi)
{
  double e = dem->law == DEM_LAW_HERTZ ? 8.0 / 15.0 * p->es * sqrt(p->reff) * pow(delta, 2.5) : 0.5 * p->kn * delta * delta;
  if (xi && dem->law == DEM_LAW_LINEAR) e += 0.5 * p->kt * dem_dot(xi, xi);
  return e;
}

PetscErrorCode DemGetStats(Dem dem, DemStats *st)
{
  double   r[6] = {0, 0, 0, 0, 0, 0}, rmax = 0, g[6];
  PetscInt c[3] = {dem->n, 0, 0}, cg[3];

  PetscFunctionBeginUser;
  if (dem->convex) PetscCall(DemConvexStatsLocal(dem, r, c, &rmax)); /* convex_diag.c */
  for (PetscInt i = 0; i < dem->n && !dem->convex; i++) {
    const DemShape *s = &dem->shp[dem->shape[i]];
    r[0] += 0.5 * s->m * dem_dot(dem->v + 3 * i, dem->v + 3 * i);
    r[1] += 0.5 * s->inertia * dem_dot(dem->w + 3 * i, dem->w + 3 * i);
    r[2] -= s->m * dem_dot(dem->g, dem->x + 3 * i);
    r[4] += (double)dem->id[i];
    for (PetscInt a = dem->nl.start[i]; a < dem->nl.start[i + 1]; a++) {
      const PetscInt j  = dem->nl.nbr[a];
      /* a pair seen from both sides (full list, or a ghost partner) counts half on each */
      const PetscBool both = (PetscBool)(dem->full_list || j >= dem->n);
      const double   rs = s->r + dem->shp[dem->shape[j]].r;
      const double   d[3] = {dem->x[3 * j] - dem->x[3 * i], dem->x[3 * j + 1] - dem->x[3 * i + 1], dem->x[3 * j + 2] - dem->x[3 * i + 2]};
      const double   delta = rs - sqrt(dem_dot(d, d));
      if (delta <= 0) continue;
      if (!both || dem->id[i] < dem->id[j]) c[1]++;
      r[3] += (both ? 0.5 : 1.0) * dem_spring_energy(dem, &dem->pp[dem->shape[i] * dem->nshape + dem->shape[j]], delta, dem->nl.hist ? dem->nl.hist + 3 * a : NULL);
      rmax = PetscMax(rmax, delta / PetscMin(s->r, dem->shp[dem->shape[j]].r));
    }
  }
  for (PetscInt w = 0; w < dem->nwall && !dem->convex; w++) {
    const DemWall *wl = &dem->wall[w];
    for (PetscInt a = 0; a < wl->cnt; a++) {
      const PetscInt i = wl->idx[a];
      double         nrm[3];
      const double   rr = dem->shp[dem->shape[i]].r, delta = dem_wall_sphere(wl, dem->x + 3 * i, rr, nrm);
      if (delta <= 0) continue;
      c[2]++;
      r[3] += dem_spring_energy(dem, &dem->pw[dem->shape[i]], delta, dem->law != DEM_LAW_LINEAR_NOHIST ? wl->hist + 3 * a : NULL);
      rmax = PetscMax(rmax, delta / rr);
    }
  }
  r[5] = rmax;
  PetscCallMPI(MPI_Allreduce(r, g, 5, MPI_DOUBLE, MPI_SUM, dem->comm));
  PetscCallMPI(MPI_Allreduce(&r[5], &g[5], 1, MPI_DOUBLE, MPI_MAX, dem->comm));
  PetscCallMPI(MPI_Allreduce(c, cg, 3, MPIU_INT, MPI_SUM, dem->comm));
  st->n             = cg[0];
  st->contacts      = cg[1];
  st->wall_contacts = cg[2];
  st->ke            = g[0];
  st->ke_rot        = g[1];
  st->pe_grav       = g[2];
  st->pe_spring     = g[3];
  st->checksum      = g[4];
  st->max_overlap   = g[5];
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemGetBedFigures(Dem dem, PetscReal *phi, PetscReal *coord)
{
  const Domain *dom = dem->dom;
  double        dmax = 0, vol = 0, vg, hsum = 0;
  PetscInt      gx, gy;
  double       *top, *gtop;
  DemStats      st;

  PetscFunctionBeginUser;
  for (PetscInt s = 0; s < dem->nshape; s++) dmax = PetscMax(dmax, 2 * dem->shp[s].r);
  gx = PetscMax(1, (PetscInt)(dom->len[0] / dmax));
  gy = PetscMax(1, (PetscInt)(dom->len[1] / dmax));
  PetscCall(PetscMalloc2(gx * gy, &top, gx * gy, &gtop));
  for (PetscInt c = 0; c < gx * gy; c++) top[c] = -PETSC_MAX_REAL;
  for (PetscInt i = 0; i < dem->n; i++) {
    const double   r  = dem->shp[dem->shape[i]].r, *x = dem->x + 3 * i;
    const PetscInt cx = PetscMin(gx - 1, PetscMax(0, (PetscInt)((x[0] - dom->lo[0]) / dom->len[0] * gx)));
    const PetscInt cy = PetscMin(gy - 1, PetscMax(0, (PetscInt)((x[1] - dom->lo[1]) / dom->len[1] * gy)));
    top[cx + gx * cy] = PetscMax(top[cx + gx * cy], x[2] + r - dom->lo[2]);
    vol += dem->shp[dem->shape[i]].vol;
  }
  PetscCallMPI(MPI_Allreduce(top, gtop, (PetscMPIInt)(gx * gy), MPI_DOUBLE, MPI_MAX, dem->comm));
  PetscCallMPI(MPI_Allreduce(&vol, &vg, 1, MPI_DOUBLE, MPI_SUM, dem->comm));
  PetscInt nc = 0;
  for (PetscInt c = 0; c < gx * gy; c++)
    if (gtop[c] > -PETSC_MAX_REAL) {
      hsum += gtop[c];
      nc++;
    }
  PetscCall(PetscFree2(top, gtop));
  PetscCall(DemGetStats(dem, &st));
  *phi   = nc ? vg / (dom->len[0] * dom->len[1] * hsum / nc) : 0;
  *coord = st.n ? 2.0 * st.contacts / st.n : 0;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Undamped overlap bound of a contact at the impact speed V (-dem_impact_velocity): linear
 * V sqrt(meff/kn), hertz 1.0934 X (m). */
double DemImpactOverlap(Dem dem, const DemPairParams *p)
{
  if (dem->law == DEM_LAW_HERTZ) return 1.0934 * pow(p->meff * dem->vimpact * dem->vimpact / (4.0 / 3.0 * p->es * sqrt(p->reff)), 0.4);
  return dem->vimpact * sqrt(p->meff / p->kn);
}

PetscErrorCode DemView(Dem dem, PetscViewer v)
{
  const char *law[] = {"linear spring-dashpot, Coulomb without history", "linear spring-dashpot with tangential history", "Hertz-Mindlin with tangential history"};
  DemStats    st;

  PetscFunctionBeginUser;
  PetscCall(DemGetStats(dem, &st));
  if (dem->dt_tc > 0 && dem->dt_set) PetscCall(PetscViewerASCIIPrintf(v, "time step: -dem_dt_tc %g gives dt = %g s, replacing -dem_dt %g s\n", (double)dem->dt_tc, (double)dem->dt, (double)dem->dt_given));
  PetscCall(PetscViewerASCIIPrintf(v, "DEM: %" PetscInt_FMT " %s, %" PetscInt_FMT " shape(s), %s; rotation %s; %" PetscInt_FMT " wall(s)\n", st.n, dem->convex ? "convex particles" : "spheres", dem->nshape, law[dem->law], dem->rotation ? "on" : "off (no friction)", dem->nwall));
  for (PetscInt s = 0; s < dem->nshape; s++)
    for (PetscInt t = -1; t < dem->nshape; t++) {
      PetscReal tc, e;
      PetscCall(DemGetContactFigures(dem, s, t, dem->vimpact, &tc, &e));
      const DemPairParams *p = t < 0 ? &dem->pw[s] : &dem->pp[s * dem->nshape + t];
      const double         ov = DemImpactOverlap(dem, p);
      PetscCall(PetscViewerASCIIPrintf(v, "  contact r=%g m with %s: Tc = %.3g s, dt/Tc = %.3g (limit %g), e = %g, overlap at %g m/s <= %.3g r\n", (double)dem->shp[s].r, t < 0 ? "wall" : "particle", (double)tc, (double)(dem->dt / tc), (double)dem->dt_frac, (double)e, (double)dem->vimpact, ov / dem->shp[s].r));
    }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemWriteOutput(Dem dem, Io io)
{
  double *r;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(DEM_Output, 0, 0, 0, 0));
  PetscCall(PetscMalloc1(dem->n + 1, &r));
  for (PetscInt i = 0; i < dem->n; i++) r[i] = dem->shp[dem->shape[i]].r;
  PetscCall(IoWriteParticles(io, "position", dem->n, 3, dem->x));
  PetscCall(IoWriteParticles(io, "velocity", dem->n, 3, dem->v));
  PetscCall(IoWriteParticles(io, "angular_velocity", dem->n, 3, dem->w));
  PetscCall(IoWriteParticles(io, "quaternion", dem->n, 4, dem->q));
  PetscCall(IoWriteParticles(io, "radius", dem->n, 1, r));
  PetscCall(IoWriteParticlesInt(io, "id", dem->n, dem->id));
  PetscCall(IoWriteParticlesInt(io, "shape", dem->n, dem->shape));
  if (dem->convex) PetscCall(DemConvexWriteSurface(dem, io)); /* convex_diag.c */
  PetscCall(PetscFree(r));
  PetscCall(PetscLogEventEnd(DEM_Output, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* order-independent fingerprint of a pair of ids */
static double dem_pair_key(PetscInt a, PetscInt b)
{
  uint64_t z = (uint64_t)PetscMin(a, b) * 0x9E3779B97F4A7C15ULL ^ (uint64_t)PetscMax(a, b) * 0xC2B2AE3D27D4EB4FULL;
  z          = (z ^ (z >> 31)) * 0x94D049BB133111EBULL;
  return (double)(z >> 40); /* 24 bits: sums stay exact in double */
}

PetscErrorCode DemCountContactsBoth(Dem dem, PetscInt count[2], PetscReal key[2])
{
  PetscFunctionBeginUser;
  count[0] = count[1] = 0;
  key[0] = key[1] = 0;
  for (PetscInt i = 0; i < dem->n; i++)
    for (PetscInt a = dem->nl.start[i]; a < dem->nl.start[i + 1]; a++) {
      const PetscInt j    = dem->nl.nbr[a];
      const double   rs   = dem->shp[dem->shape[i]].r + dem->shp[dem->shape[j]].r;
      const double   d[3] = {dem->x[3 * j] - dem->x[3 * i], dem->x[3 * j + 1] - dem->x[3 * i + 1], dem->x[3 * j + 2] - dem->x[3 * i + 2]};
      if (dem_dot(d, d) < rs * rs && (!(dem->full_list || j >= dem->n) || dem->id[i] < dem->id[j])) {
        count[0]++;
        key[0] += dem_pair_key(dem->id[i], dem->id[j]);
      }
    }
  for (PetscInt i = 0; i < dem->n; i++)
    for (PetscInt j = i + 1; j < dem->n; j++) {
      const double rs   = dem->shp[dem->shape[i]].r + dem->shp[dem->shape[j]].r;
      const double d[3] = {dem->x[3 * j] - dem->x[3 * i], dem->x[3 * j + 1] - dem->x[3 * i + 1], dem->x[3 * j + 2] - dem->x[3 * i + 2]};
      if (dem_dot(d, d) < rs * rs) {
        count[1]++;
        key[1] += dem_pair_key(dem->id[i], dem->id[j]);
      }
    }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemCheckHealth(Dem dem, const DemStats *st)
{
  PetscReal tc = 0, e;

  PetscFunctionBeginUser;
  PetscCheck(PetscIsNormalReal(st->ke) || st->ke == 0, dem->comm, PETSC_ERR_FP, "step %" PetscInt_FMT ": kinetic energy is not finite; lower -dem_dt", dem->step);
  if (st->max_overlap <= dem->overlap_max) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(DemGetContactFigures(dem, 0, 0, dem->vimpact, &tc, &e));
  SETERRQ(dem->comm, PETSC_ERR_FP, "step %" PetscInt_FMT ": the largest overlap is %.3g radii, above -dem_overlap_max %g: the contacts are not resolved and the run is diverging (dt/Tc = %.3g); lower -dem_dt or raise -dem_kn", dem->step, (double)st->max_overlap, (double)dem->overlap_max, (double)(dem->dt / tc));
}
