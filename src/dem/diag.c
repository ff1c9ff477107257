/* DEM diagnostics and reporting: global statistics by reductions (count, id checksum, energies,
 * contacts, largest overlap), bed figures (packing fraction, coordination number), the start-up
 * summary with the contact pre-flight figures, output of particle state, and the run loop with
 * its progress line. Elastic energy: linear 1/2 kn delta^2 + 1/2 kt |xi|^2; hertz
 * 8/15 E* sqrt(R*) delta^(5/2) (the tangential spring energy is left out for hertz). */
#include "dem/dem_core.h"
#include "dem/dem_walls.h"
#include "dem/dem_fields.h"

static double dem_spring_energy(const Dem dem, const DemPairParams *p, double delta, const double *xi)
{
  double e = dem->contact.law == DEM_LAW_HERTZ ? 8.0 / 15.0 * p->es * sqrt(p->reff) * pow(delta, 2.5) : 0.5 * p->kn * delta * delta;
  if (xi && dem->contact.law == DEM_LAW_LINEAR) e += 0.5 * p->kt * dem_dot(xi, xi);
  return e;
}

PetscErrorCode DemGetStats(Dem dem, DemStats *st)
{
  double   r[6] = {0, 0, 0, 0, 0, 0}, rmax = 0, g[6];
  PetscInt c[3] = {dem->p.n, 0, 0}, cg[3];

  PetscFunctionBeginUser;
  if (dem->shapes.convex) PetscCall(DemConvexStatsLocal(dem, r, c, &rmax)); /* convex_diag.c */
  for (PetscInt i = 0; i < dem->p.n && !dem->shapes.convex; i++) {
    const DemShape *s  = &dem->shapes.shp[dem->p.shape[i]];
    const double    mi = DemMass(&dem->p, &dem->shapes, i), ri = DemRadius(&dem->p, &dem->shapes, i);
    r[0] += 0.5 * mi * dem_dot(dem->p.v + 3 * i, dem->p.v + 3 * i);
    r[1] += 0.5 * (dem->p.invi ? 1.0 / dem->p.invi[i] : s->inertia) * dem_dot(dem->p.w + 3 * i, dem->p.w + 3 * i);
    r[2] -= mi * dem_dot(dem->g, dem->p.x + 3 * i);
    r[4] += (double)dem->p.id[i];
    for (PetscInt a = dem->nl.start[i]; a < dem->nl.start[i + 1]; a++) {
      const PetscInt j = dem->nl.nbr[a];
      /* a pair seen from both sides (full list, or a ghost partner) counts half on each */
      const PetscBool both = (PetscBool)(dem->nl.full_list || j >= dem->p.n);
      const double    rj = DemRadius(&dem->p, &dem->shapes, j), rs = ri + rj;
      const double    d[3]  = {dem->p.x[3 * j] - dem->p.x[3 * i], dem->p.x[3 * j + 1] - dem->p.x[3 * i + 1], dem->p.x[3 * j + 2] - dem->p.x[3 * i + 2]};
      const double    delta = rs - sqrt(dem_dot(d, d));
      if (delta <= 0) continue;
      if (!both || dem->p.id[i] < dem->p.id[j]) c[1]++;
      const DemPairParams *pp = &dem->contact.pp[dem->p.shape[i] * dem->shapes.nshape + dem->p.shape[j]];
      DemPairParams        sized;
      if (dem->p.rad) dem_pair_sized(dem->contact.law, pp, mi, ri, dem->p.m[j], rj, &sized);
      r[3] += (both ? 0.5 : 1.0) * dem_spring_energy(dem, dem->p.rad ? &sized : pp, delta, dem->nl.hist ? dem->nl.hist + 3 * a : NULL);
      rmax = PetscMax(rmax, delta / PetscMin(ri, rj));
    }
  }
  for (PetscInt w = 0; w < dem->walls.nwall && !dem->shapes.convex; w++) {
    const DemWall *wl = &dem->walls.wall[w];
    for (PetscInt a = 0; a < wl->cnt; a++) {
      const PetscInt i = wl->idx[a];
      double         nrm[3];
      const double   rr = DemRadius(&dem->p, &dem->shapes, i), delta = dem_wall_sphere(wl, dem->p.x + 3 * i, rr, nrm);
      DemPairParams  sized;
      if (delta <= 0) continue;
      c[2]++;
      if (dem->p.rad) dem_pair_sized(dem->contact.law, &dem->contact.pw[dem->p.shape[i]], dem->p.m[i], rr, 0, 0, &sized);
      r[3] += dem_spring_energy(dem, dem->p.rad ? &sized : &dem->contact.pw[dem->p.shape[i]], delta, dem->contact.law != DEM_LAW_LINEAR_NOHIST ? wl->hist + 3 * a : NULL);
      rmax = PetscMax(rmax, delta / rr);
    }
  }
  if (dem->meshes.n) PetscCall(DemMeshesStatsLocal(dem, r, c, &rmax)); /* walls_mesh.c */
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

PetscErrorCode DemGetFlow(Dem dem, DemFlowStats *f)
{
  PetscFunctionBeginUser;
  f->inserted   = dem->flow.inserted;
  f->removed    = dem->flow.removed;
  f->m_inserted = dem->flow.m_inserted;
  f->m_removed  = dem->flow.m_removed;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemGetBedFigures(Dem dem, PetscReal *phi, PetscReal *coord)
{
  const Domain *dom  = dem->dom;
  double        dmax = 0, vol = 0, vg, hsum = 0;
  PetscInt      gx, gy;
  double       *top, *gtop;
  DemStats      st;

  PetscFunctionBeginUser;
  for (PetscInt s = 0; s < dem->shapes.nshape; s++) dmax = PetscMax(dmax, 2 * dem->shapes.shp[s].r);
  if (dem->shapes.poly) dmax = PetscMax(dmax, 2 * dem->shapes.r_source_max);
  gx = PetscMax(1, (PetscInt)(dom->len[0] / dmax));
  gy = PetscMax(1, (PetscInt)(dom->len[1] / dmax));
  PetscCall(PetscMalloc2(gx * gy, &top, gx * gy, &gtop));
  for (PetscInt c = 0; c < gx * gy; c++) top[c] = -PETSC_MAX_REAL;
  for (PetscInt i = 0; i < dem->p.n; i++) {
    const double   r = DemRadius(&dem->p, &dem->shapes, i), *x = dem->p.x + 3 * i;
    const PetscInt cx = PetscMin(gx - 1, PetscMax(0, (PetscInt)((x[0] - dom->lo[0]) / dom->len[0] * gx)));
    const PetscInt cy = PetscMin(gy - 1, PetscMax(0, (PetscInt)((x[1] - dom->lo[1]) / dom->len[1] * gy)));
    top[cx + gx * cy] = PetscMax(top[cx + gx * cy], x[2] + r - dom->lo[2]);
    vol += dem->p.rad ? 4.0 / 3.0 * PETSC_PI * r * r * r : dem->shapes.shp[dem->p.shape[i]].vol;
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
  if (dem->contact.law == DEM_LAW_HERTZ) return 1.0934 * pow(p->meff * dem->contact.vimpact * dem->contact.vimpact / (4.0 / 3.0 * p->es * sqrt(p->reff)), 0.4);
  return dem->contact.vimpact * sqrt(p->meff / p->kn);
}

/* Spheres of their own sizes: the contact figures of the smallest and largest radius a source
 * adds (material 0), with each other and with a wall. */
static PetscErrorCode DemViewSizes(Dem dem, PetscViewer v)
{
  double r[2] = {dem->shapes.r_source_min > 0 ? dem->shapes.r_source_min : dem->shapes.shp[0].r, PetscMax(dem->shapes.r_source_max, dem->shapes.shp[0].r)};

  PetscFunctionBeginUser;
  PetscCall(PetscViewerASCIIPrintf(v, "  spheres of their own sizes, radii %g to %g m (per-pair m*, R*):\n", r[0], r[1]));
  for (int a = 0; a < 2; a++)
    for (int b = -1; b < 2; b++) {
      PetscReal     tc, e;
      DemPairParams q;
      const double  ri = r[a], rj = b < 0 ? 0 : r[b], mi = dem_sphere_mass(dem->shapes.shp[0].rho, ri), mj = b < 0 ? 0 : dem_sphere_mass(dem->shapes.shp[0].rho, rj);
      PetscCall(DemGetContactFiguresSized(dem, 0, b < 0 ? -1 : 0, ri, rj, dem->contact.vimpact, &tc, &e));
      dem_pair_sized(dem->contact.law, b < 0 ? &dem->contact.pw[0] : &dem->contact.pp[0], mi, ri, mj, rj, &q);
      char with[64] = "wall";
      if (b >= 0) PetscCall(PetscSNPrintf(with, sizeof with, "particle r=%g m", rj));
      PetscCall(PetscViewerASCIIPrintf(v, "  contact r=%g m with %s: Tc = %.3g s, dt/Tc = %.3g (limit %g), e = %g, overlap at %g m/s <= %.3g r\n", ri, with, (double)tc, (double)(dem->clock.dt / tc), (double)dem->clock.dt_frac, (double)e, (double)dem->contact.vimpact, DemImpactOverlap(dem, &q) / PetscMin(ri, b < 0 ? ri : rj)));
    }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemView(Dem dem, PetscViewer v)
{
  const char *law[] = {"linear spring-dashpot, Coulomb without history", "linear spring-dashpot with tangential history", "Hertz-Mindlin with tangential history"};
  DemStats    st;

  PetscFunctionBeginUser;
  PetscCall(DemGetStats(dem, &st));
  if (dem->clock.dt_tc > 0 && dem->clock.dt_set) PetscCall(PetscViewerASCIIPrintf(v, "time step: -dem_dt_tc %g gives dt = %g s, replacing -dem_dt %g s\n", (double)dem->clock.dt_tc, (double)dem->clock.dt, (double)dem->clock.dt_given));
  PetscCall(PetscViewerASCIIPrintf(v, "DEM: %" PetscInt_FMT " %s, %" PetscInt_FMT " shape(s), %s; rotation %s; %" PetscInt_FMT " wall(s)\n", st.n, dem->shapes.convex ? "convex particles" : "spheres", dem->shapes.nshape, law[dem->contact.law], dem->contact.rotation ? "on" : "off (no friction)", dem->walls.nwall));
  if (dem->contact.roll != DEM_ROLL_NONE) {
    const char *roll[] = {"", "constant torque, mu_r", "viscous, mu_r (s/m)", "k_ms (m s)"};
    PetscCall(PetscViewerASCIIPrintf(v, "  rolling resistance: %s %g with particles, %g with walls\n", roll[dem->contact.roll], (double)dem->contact.mat.mur, (double)dem->contact.wmat.mur));
  }
  if (dem->meshes.n) PetscCall(PetscViewerASCIIPrintf(v, "  %" PetscInt_FMT " mesh wall(s) (-dem_mesh_<k>_file)\n", dem->meshes.n));
  for (PetscInt s = 0; s < dem->shapes.nshape; s++)
    for (PetscInt t = -1; t < dem->shapes.nshape; t++) {
      PetscReal tc, e;
      PetscCall(DemGetContactFigures(dem, s, t, dem->contact.vimpact, &tc, &e));
      const DemPairParams *p  = t < 0 ? &dem->contact.pw[s] : &dem->contact.pp[s * dem->shapes.nshape + t];
      const double         ov = DemImpactOverlap(dem, p);
      PetscCall(PetscViewerASCIIPrintf(v, "  contact r=%g m with %s: Tc = %.3g s, dt/Tc = %.3g (limit %g), e = %g, overlap at %g m/s <= %.3g r\n", (double)dem->shapes.shp[s].r, t < 0 ? "wall" : "particle", (double)tc, (double)(dem->clock.dt / tc), (double)dem->clock.dt_frac, (double)e, (double)dem->contact.vimpact, ov / dem->shapes.shp[s].r));
    }
  if (dem->shapes.poly) PetscCall(DemViewSizes(dem, v));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemWriteOutput(Dem dem, Io io)
{
  double   *r, *x = dem->p.x;
  PetscBool per = (PetscBool)(dem->dom->periodic[0] || dem->dom->periodic[1] || dem->dom->periodic[2]), want;

  PetscFunctionBeginUser;
  PetscCall(IoFrameWants(io, "particles", NULL, &want)); /* not at this frame's time (-io_particle_interval) */
  if (!want) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscLogEventBegin(DEM_Output, 0, 0, 0, 0));
  PetscCall(PetscMalloc1(dem->p.n + 1, &r));
  for (PetscInt i = 0; i < dem->p.n; i++) r[i] = DemRadius(&dem->p, &dem->shapes, i); /* each sphere's own in a scene of own sizes */
  if (per) {                                                                          /* positions wrapped into the box along periodic axes, the run's own left as they are */
    PetscCall(PetscMalloc1(3 * dem->p.n + 3, &x));
    PetscCall(PetscArraycpy(x, dem->p.x, 3 * dem->p.n));
    for (PetscInt i = 0; i < dem->p.n; i++) DemWrapPeriodic(dem->dom, x + 3 * i);
  }
  for (int k = 0; k < dem_nfields; k++) { /* the frame rows of the field table (dem_fields.h), in its order */
    const DemField *f = &dem_fields[k];
    if (!f->frame || (f->frame_from != DEM_FRAME_RADIUS && !DemFieldOn(dem, f))) continue;
    if (f->type == DEM_FIELD_INT) PetscCall(IoWriteParticlesInt(io, f->frame, dem->p.n, (const PetscInt *)*DemFieldPtr(dem, f)));
    else PetscCall(IoWriteParticles(io, f->frame, dem->p.n, f->width, f->frame_from == DEM_FRAME_WRAPPED ? x : f->frame_from == DEM_FRAME_RADIUS ? r
                                                                                                                                                 : (const double *)*DemFieldPtr(dem, f)));
  }
  PetscCall(IoFrameWants(io, "surface", "surface", &want));
  if (dem->shapes.convex && want) PetscCall(DemConvexWriteSurface(dem, x, io)); /* convex_diag.c */
  PetscCall(PetscFree(r));
  if (per) PetscCall(PetscFree(x));
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
  for (PetscInt i = 0; i < dem->p.n; i++)
    for (PetscInt a = dem->nl.start[i]; a < dem->nl.start[i + 1]; a++) {
      const PetscInt j    = dem->nl.nbr[a];
      const double   rs   = DemRadius(&dem->p, &dem->shapes, i) + DemRadius(&dem->p, &dem->shapes, j);
      const double   d[3] = {dem->p.x[3 * j] - dem->p.x[3 * i], dem->p.x[3 * j + 1] - dem->p.x[3 * i + 1], dem->p.x[3 * j + 2] - dem->p.x[3 * i + 2]};
      if (dem_dot(d, d) < rs * rs && (!(dem->nl.full_list || j >= dem->p.n) || dem->p.id[i] < dem->p.id[j])) {
        count[0]++;
        key[0] += dem_pair_key(dem->p.id[i], dem->p.id[j]);
      }
    }
  for (PetscInt i = 0; i < dem->p.n; i++)
    for (PetscInt j = i + 1; j < dem->p.n; j++) {
      const double rs   = DemRadius(&dem->p, &dem->shapes, i) + DemRadius(&dem->p, &dem->shapes, j);
      const double d[3] = {dem->p.x[3 * j] - dem->p.x[3 * i], dem->p.x[3 * j + 1] - dem->p.x[3 * i + 1], dem->p.x[3 * j + 2] - dem->p.x[3 * i + 2]};
      if (dem_dot(d, d) < rs * rs) {
        count[1]++;
        key[1] += dem_pair_key(dem->p.id[i], dem->p.id[j]);
      }
    }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemCheckHealth(Dem dem, const DemStats *st)
{
  PetscReal tc = 0, e;

  PetscFunctionBeginUser;
  PetscCheck((PetscIsNormalReal(st->ke) || st->ke == 0) && (PetscIsNormalReal(st->ke_rot) || st->ke_rot == 0), dem->comm, PETSC_ERR_FP, "step %" PetscInt_FMT ": %s kinetic energy is not finite; lower -dem_dt", dem->clock.step, PetscIsNormalReal(st->ke) || st->ke == 0 ? "rotational" : "translational");
  if (st->max_overlap <= dem->overlap_max) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(DemGetContactFigures(dem, 0, 0, dem->contact.vimpact, &tc, &e));
  SETERRQ(dem->comm, PETSC_ERR_FP, "step %" PetscInt_FMT ": the largest overlap is %.3g radii, above -dem_overlap_max %g: the contacts are not resolved and the run is diverging (dt/Tc = %.3g); lower -dem_dt or raise -dem_kn", dem->clock.step, (double)st->max_overlap, (double)dem->overlap_max, (double)(dem->clock.dt / tc));
}
