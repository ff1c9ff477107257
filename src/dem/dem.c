/* The Dem object: options, set-up and the time step (see dem.h).
 * One step (velocity Verlet): half kick + drift (+ rebuild check) -> walls move -> a source's
 * batch placed when due (sources.c), then lists rebuilt (rebuild.c) if it was, or if a particle
 * or a wall moved more than skin/2 -> forces (gravity, pairs, walls) -> half kick.
 * The time step is checked against the contact time at set-up: dt <= dt_max_fraction * Tc for
 * every pair type (Tc of the hertz law at -dem_impact_velocity); -dem_dt_tc sets dt to a fraction
 * of the shortest Tc instead. A run that diverges anyway (dt too large for the stiffness: the
 * particles pass through each other while every number stays finite) stops at the next progress
 * line or output frame when the largest overlap exceeds -dem_overlap_max radii (diag.c). */
#include "dem/dem_core.h"
#include "dem/dem_walls.h"
#include "dem/dem_sources.h"
#include "dem/dem_fields.h"

static const char *const DemLawNames[] = {"linear_nohist", "linear", "hertz", "DemLaw", "DEM_LAW_", NULL};

PetscErrorCode DemCreate(Domain *dom, Dem *dem)
{
  Dem d;

  PetscFunctionBeginUser;
  PetscCall(DemEventsRegister());
  PetscCall(PetscNew(&d));
  d->comm                   = dom->comm;
  d->dom                    = dom;
  d->shapes.nshape          = 1;
  d->shapes.shp[0].r        = 0.0069;
  d->shapes.shp[0].rho      = 2500;
  d->shapes.shape_frac[0]   = 1;
  d->contact.law            = DEM_LAW_LINEAR;
  d->contact.mat.e          = 0.75;
  d->contact.mat.mu         = 0.3;
  d->contact.mat.nu         = 0.3;
  d->contact.tdamp_ratio    = 1;
  d->contact.vimpact        = 1;
  d->narrow.convex_sat      = PETSC_TRUE;
  d->narrow.convex_sat_axes = 16; /* box-box: 3 + 3 face normals, 3 x 3 edge-edge axes */
  d->narrow.convex_point    = CONVEX_POINT_PATCH;
  d->nl.skin                = -1;
  d->nl.sort_interval       = 1;
  d->clock.dt               = 1e-5;
  d->clock.dt_frac          = 0.1;
  d->insert.lat_count       = -1; /* all lattice sites */
  d->insert.seed            = 1;
  d->overlap_max            = 0.5;
  d->g[2]                   = -9.81;
  *dem                      = d;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The material options of the particles and of the walls, written out so that grep (and the
 * option list the Makefile builds from the sources) finds them. */
static const char *const DemMaterialNames[2][6] = {
  {"-dem_kn", "-dem_kt", "-dem_restitution", "-dem_friction", "-dem_youngs_modulus", "-dem_poisson_ratio"},
  {"-dem_wall_kn", "-dem_wall_kt", "-dem_wall_restitution", "-dem_wall_friction", "-dem_wall_youngs_modulus", "-dem_wall_poisson_ratio"}};

static PetscErrorCode DemMaterialOptions(PetscOptionItems *PetscOptionsObject, const char *const o[6], DemMaterial *m, const DemMaterial *dflt)
{
  PetscFunctionBeginUser;
  if (dflt) *m = *dflt;
  PetscCall(SableOptionsReal(o[0], "Normal stiffness of the linear laws", "N/m", "(0,inf)", m->kn, &m->kn, &m->kn_set));
  PetscCall(SableOptionsReal(o[1], "Tangential stiffness; default 2/7 kn", "N/m", "[0,inf)", m->kt, &m->kt, &m->kt_set));
  PetscCall(SableOptionsReal(o[2], "Coefficient of restitution", NULL, "(0,1]", m->e, &m->e, NULL));
  PetscCall(SableOptionsReal(o[3], "Coulomb friction coefficient", NULL, "[0,inf)", m->mu, &m->mu, NULL));
  PetscCall(SableOptionsReal(o[4], "Young's modulus, for hertz or to derive kn", "Pa", "(0,inf)", m->E, &m->E, &m->E_set));
  PetscCall(SableOptionsReal(o[5], "Poisson ratio", NULL, "(-1,0.5)", m->nu, &m->nu, NULL));
  if (dflt) { /* a wall inherits what it was not given */
    m->kn_set = (PetscBool)(m->kn_set || dflt->kn_set);
    m->kt_set = (PetscBool)(m->kt_set || dflt->kt_set);
    m->E_set  = (PetscBool)(m->E_set || dflt->E_set);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Rolling resistance (contact_laws.h): the model and the coefficients of the particles and the
 * walls (the walls take the particles' unless given). A coefficient without a model, or a model
 * without a coefficient, is refused: one of them would be ignored. */
static const char *const DemRollNames[] = {"none", "constant", "viscous", "kms", "DemRoll", "DEM_ROLL_", NULL};

static PetscErrorCode DemRollingOptions(PetscOptionItems *PetscOptionsObject, Dem dem)
{
  PetscInt  roll = dem->contact.roll;
  PetscBool pset, wset;

  PetscFunctionBeginUser;
  PetscCall(SableOptionsEnum("-dem_rolling_model", "Rolling resistance of every contact: none, constant (torque mu_r R* |Fn|) or viscous (mu_r R* |Fn| |V_omega|), as Lethe's; kms (k_ms |Fn| (w_t + 1e-3 w_n)), as Grains3D's", DemRollNames, 4, roll, &roll, NULL));
  dem->contact.roll = (DemRoll)roll;
  PetscCall(SableOptionsReal("-dem_rolling_friction", "Rolling friction coefficient mu_r (constant: -, viscous: s/m, kms: k_ms in m s)", NULL, "[0,inf)", dem->contact.mat.mur, &dem->contact.mat.mur, &pset));
  dem->contact.wmat.mur = dem->contact.mat.mur;
  PetscCall(SableOptionsReal("-dem_wall_rolling_friction", "Rolling friction coefficient against the walls; default -dem_rolling_friction", NULL, "[0,inf)", dem->contact.wmat.mur, &dem->contact.wmat.mur, &wset));
  PetscCheck(dem->contact.roll != DEM_ROLL_NONE || !(pset || wset), dem->comm, PETSC_ERR_ARG_INCOMP, "%s is ignored by -dem_rolling_model none: give -dem_rolling_model constant, viscous or kms", pset ? "-dem_rolling_friction" : "-dem_wall_rolling_friction");
  PetscCheck(dem->contact.roll == DEM_ROLL_NONE || pset || wset, dem->comm, PETSC_ERR_ARG_WRONG, "-dem_rolling_model %s needs -dem_rolling_friction (and optionally -dem_wall_rolling_friction)", DemRollNames[dem->contact.roll]);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Material options that the contact law or another option would leave unread are refused,
 * naming both: hertz takes its stiffness from E and nu, not kn and kt; linear_nohist has no
 * tangential spring (kt); under the linear laws -dem_kn sets every contact's stiffness (walls
 * inherit it), so E and nu, which only derive a stiffness, would be ignored. */
static PetscErrorCode DemCheckMaterialConflicts(Dem dem)
{
  const char *const *o = DemMaterialNames[0], *const *w = DemMaterialNames[1];
  PetscBool          has[2][6];

  PetscFunctionBeginUser;
  for (int m = 0; m < 2; m++)
    for (int k = 0; k < 6; k++) PetscCall(PetscOptionsHasName(NULL, NULL, DemMaterialNames[m][k], &has[m][k]));
  for (int m = 0; m < 2; m++) {
    const char *const *n = DemMaterialNames[m];
    for (int k = 0; k < 2; k++) PetscCheck(dem->contact.law != DEM_LAW_HERTZ || !has[m][k], dem->comm, PETSC_ERR_ARG_INCOMP, "%s is ignored by -dem_contact_law hertz, which takes the stiffness from %s and %s: give one of them", n[k], n[4], n[5]);
    PetscCheck(dem->contact.law != DEM_LAW_LINEAR_NOHIST || !has[m][1], dem->comm, PETSC_ERR_ARG_INCOMP, "%s is ignored by -dem_contact_law linear_nohist, which has no tangential spring: give one of them", n[1]);
  }
  if (dem->contact.law == DEM_LAW_HERTZ) PetscFunctionReturn(PETSC_SUCCESS);
  for (int k = 4; k < 6; k++) {
    PetscCheck(!has[0][0] || !has[0][k], dem->comm, PETSC_ERR_ARG_INCOMP, "%s and %s both set the contact stiffness of -dem_contact_law %s; %s wins and %s would be ignored: give one of them", o[0], o[k], DemLawNames[dem->contact.law], o[0], o[k]);
    PetscCheck(!(has[0][0] || has[1][0]) || !has[1][k], dem->comm, PETSC_ERR_ARG_INCOMP, "%s and %s both set the wall stiffness of -dem_contact_law %s%s; %s wins and %s would be ignored: give one of them", has[1][0] ? w[0] : o[0], w[k], DemLawNames[dem->contact.law], has[1][0] ? "" : " (walls take -dem_kn unless -dem_wall_kn is given)", has[1][0] ? w[0] : o[0], w[k]);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemSetFromOptions(Dem dem)
{
  PetscReal r[DEM_MAX_SHAPES] = {0}, fr[DEM_MAX_SHAPES] = {0}, sum = 0;
  PetscInt  nr = DEM_MAX_SHAPES, nf = DEM_MAX_SHAPES, law = dem->contact.law, point = dem->narrow.convex_point;
  PetscBool rset, fset, gset, sset;

  PetscFunctionBeginUser;
  r[0]  = dem->shapes.shp[0].r; /* the defaults -help shows: one shape of the default radius */
  fr[0] = 1;
  PetscOptionsBegin(dem->comm, NULL, "DEM: particles, contacts, time stepping", NULL);
  PetscCall(SableOptionsRealArray("-dem_radius", "Sphere radii r1,r2,..., one shape each", "m", r, 1, &nr, &rset));
  PetscCall(SableOptionsRealArray("-dem_radius_fraction", "Number fraction of each radius (default equal)", NULL, fr, 1, &nf, &fset));
  PetscCall(SableOptionsReal("-dem_density", "Particle density", "kg/m^3", "(0,inf)", dem->shapes.shp[0].rho, &dem->shapes.shp[0].rho, NULL));
  PetscCall(SableOptionsEnum("-dem_contact_law", "Contact law", DemLawNames, 3, law, &law, NULL));
  dem->contact.law = (DemLaw)law;
  PetscCall(DemMaterialOptions(PetscOptionsObject, DemMaterialNames[0], &dem->contact.mat, NULL));
  PetscCall(DemMaterialOptions(PetscOptionsObject, DemMaterialNames[1], &dem->contact.wmat, &dem->contact.mat));
  PetscCall(DemRollingOptions(PetscOptionsObject, dem));
  PetscCall(SableOptionsReal("-dem_tangential_damping", "Tangential over normal damping ratio", NULL, "[0,inf)", dem->contact.tdamp_ratio, &dem->contact.tdamp_ratio, NULL));
  PetscCall(SableOptionsReal("-dem_impact_velocity", "Impact speed for the hertz contact time, kn from E and overlap estimates", "m/s", "(0,inf)", dem->contact.vimpact, &dem->contact.vimpact, NULL));
  PetscCall(SableOptionsReal("-dem_dt", "Time step", "s", "(0,inf)", dem->clock.dt, &dem->clock.dt, &dem->clock.dt_set));
  PetscCall(SableOptionsReal("-dem_dt_tc", "Time step as this fraction of the shortest contact time (every pair type, at -dem_impact_velocity); replaces -dem_dt when > 0 (the presets in cases/presets use it); 0: use -dem_dt", NULL, "[0,1]", dem->clock.dt_tc, &dem->clock.dt_tc, NULL));
  PetscCall(SableOptionsReal("-dem_dt_max_fraction", "Largest allowed dt / contact time", NULL, "(0,1]", dem->clock.dt_frac, &dem->clock.dt_frac, NULL));
  PetscCall(SableOptionsReal("-dem_overlap_max", "Largest overlap / radius allowed at a progress line or output frame; above it the run is diverging and stops", NULL, "(0,inf)", dem->overlap_max, &dem->overlap_max, NULL));
  PetscCall(SableOptionsRealN("-dem_gravity", "Gravity gx,gy,gz", "m/s^2", dem->g, 3, 3, &gset));
  PetscCall(SableOptionsReal("-dem_skin", "Verlet skin; default 0.1 x the largest diameter", "m", "(0,inf)", dem->nl.skin, &dem->nl.skin, &sset));
  PetscCall(SableOptionsBool("-dem_convex_sat", "Polyhedron pairs with at most -dem_convex_sat_axes candidate axes by the exact separating-axis test instead of libccd's MPR", dem->narrow.convex_sat, &dem->narrow.convex_sat, NULL));
  PetscCall(SableOptionsInt("-dem_convex_sat_axes", "Most candidate axes (distinct face normals of both + edge-direction pairs) of a pair that takes the separating-axis test: 16 = box-box; 58 box-icosahedron, 245 icosahedron pairs (exact, ~9x MPR's cost in a dense bed)", NULL, "[0,inf)", dem->narrow.convex_sat_axes, &dem->narrow.convex_sat_axes, NULL));
  PetscCall(SableOptionsEnum("-dem_convex_contact_point", "Pair contact point: patch (centroid of the contact patch, smooth) or support (the deepest vertex / edge crossing: the energy's own gradient, conserves energy with the exact depth)", ConvexPointModels, 2, point, &point, NULL));
  dem->narrow.convex_point = (ConvexPointModel)point;
  PetscCall(SableOptionsBool("-dem_deterministic", "Full neighbour rows summed in id order: results bitwise independent of the rank count (about 2x the contact cost)", dem->nl.full_list, &dem->nl.full_list, NULL));
  PetscCall(SableOptionsInt("-dem_check_every", "Debug: check the global particle count and id checksum every this many steps (0 = never)", NULL, "[0,inf)", dem->check_every, &dem->check_every, NULL));
  PetscCall(SableOptionsInt("-dem_sort_interval", "Re-sort particles by cell every this many list builds (0 = never)", NULL, "[0,inf)", dem->nl.sort_interval, &dem->nl.sort_interval, NULL));
  PetscOptionsEnd();
  dem->clock.dt_given = dem->clock.dt;
  PetscCall(DemCheckMaterialConflicts(dem));
  if (rset) {
    PetscCheck(nr >= 1, dem->comm, PETSC_ERR_ARG_SIZ, "-dem_radius needs at least one value");
    for (PetscInt s = 0; s < nr; s++) {
      PetscCheck(r[s] > 0, dem->comm, PETSC_ERR_ARG_OUTOFRANGE, "-dem_radius %g must be > 0 (m)", (double)r[s]);
      dem->shapes.shp[s]   = dem->shapes.shp[0];
      dem->shapes.shp[s].r = r[s];
    }
    dem->shapes.nshape = nr;
  }
  PetscCall(DemShapesSetFromOptions(dem)); /* -dem_shape: non-spherical shapes (shapes.c) */
  PetscCheck(!fset || nf == dem->shapes.nshape, dem->comm, PETSC_ERR_ARG_SIZ, "-dem_radius_fraction has %" PetscInt_FMT " values for %" PetscInt_FMT " radii", nf, dem->shapes.nshape);
  for (PetscInt s = 0; s < dem->shapes.nshape; s++) {
    dem->shapes.shape_frac[s] = fset ? fr[s] : 1.0;
    PetscCheck(dem->shapes.shape_frac[s] >= 0, dem->comm, PETSC_ERR_ARG_OUTOFRANGE, "-dem_radius_fraction %g must be >= 0", (double)dem->shapes.shape_frac[s]);
    sum += dem->shapes.shape_frac[s];
  }
  PetscCheck(sum > 0, dem->comm, PETSC_ERR_ARG_OUTOFRANGE, "-dem_radius_fraction must not be all zero");
  for (PetscInt s = 0; s < dem->shapes.nshape; s++) dem->shapes.shape_frac[s] /= sum;
  PetscCall(DemWallsSetFromOptions(dem));
  PetscCall(DemInsertSetFromOptions(dem));
  PetscCall(DemSinksSetFromOptions(dem));
  PetscCall(DemSourcesSetFromOptions(dem)); /* -dem_insert_<k>_* (sources.c) */
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* dt against the contact time of every pair type; with -dem_dt_tc, dt is first set to that
 * fraction of the shortest one. */
static PetscErrorCode DemCheckTimeStep(Dem dem)
{
  PetscFunctionBeginUser;
  if (dem->clock.dt_tc > 0) {
    PetscReal tmin = PETSC_MAX_REAL;
    for (PetscInt s = 0; s < dem->shapes.nshape; s++)
      for (PetscInt t = -1; t < dem->shapes.nshape; t++) {
        PetscReal tc, e;
        PetscCall(DemGetContactFigures(dem, s, t, dem->contact.vimpact, &tc, &e));
        tmin = PetscMin(tmin, tc);
      }
    dem->clock.dt = dem->clock.dt_tc * tmin;
  }
  for (PetscInt s = 0; s < dem->shapes.nshape; s++)
    for (PetscInt t = -1; t < dem->shapes.nshape; t++) {
      PetscReal tc, e;
      PetscCall(DemGetContactFigures(dem, s, t, dem->contact.vimpact, &tc, &e));
      PetscCheck(dem->clock.dt <= dem->clock.dt_frac * tc, dem->comm, PETSC_ERR_ARG_OUTOFRANGE,
                 "%s %g s exceeds -dem_dt_max_fraction %g x the contact time %g s (%s, radius %g m): use -dem_dt <= %g", dem->clock.dt_tc > 0 ? "-dem_dt_tc gives dt" : "-dem_dt", (double)dem->clock.dt, (double)dem->clock.dt_frac, (double)tc, t < 0 ? "particle-wall" : "particle-particle", (double)dem->shapes.shp[s].r, (double)(dem->clock.dt_frac * tc));
    }
  if (dem->shapes.poly) PetscCall(DemCheckTimeStepSizes(dem)); /* contact_laws.c: the sizes a source adds */
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The mesh contacts (walls_mesh.c), their wall time and the candidate triangles they tested:
 * the cost per candidate that the balancer's measured weights take (redistribute.c). */
static PetscErrorCode DemContactsMeshesTimed(Dem dem)
{
  PetscLogDouble m0, m1;

  PetscFunctionBeginUser;
  PetscCall(PetscTime(&m0));
  if (dem->shapes.convex) PetscCall(DemContactsMeshesConvex(dem)); /* convex_contacts.c */
  else PetscCall(DemContactsMeshes(dem));
  PetscCall(PetscTime(&m1));
  dem->t_mesh += m1 - m0;
  for (PetscInt k = 0; k < dem->meshes.n; k++)
    if (dem->meshes.m[k].cstart) dem->mesh_cand += (PetscReal)dem->meshes.m[k].cstart[dem->p.n];
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode DemComputeForces(Dem dem)
{
  PetscFunctionBeginUser;
  double *restrict f = dem->p.f;
  const double g[3]  = {dem->g[0], dem->g[1], dem->g[2]};
  if (dem->p.m) /* spheres of their own sizes */
    for (PetscInt i = 0; i < dem->p.n; i++)
      for (int k = 0; k < 3; k++) f[3 * i + k] = dem->p.m[i] * g[k];
  else
    for (PetscInt i = 0; i < dem->p.n; i++) {
      const double m = dem->shapes.shp[dem->shapes.nshape == 1 ? 0 : dem->p.shape[i]].m;
      for (int k = 0; k < 3; k++) f[3 * i + k] = m * g[k];
    }
  if (dem->contact.rotation) PetscCall(PetscArrayzero(dem->p.tq, 3 * dem->p.n));
  if (dem->shapes.convex) { /* convex shapes: libccd narrow phase (convex_contacts.c) */
    PetscCall(DemContactsPairsConvex(dem));
    PetscCall(DemContactsWallsConvex(dem));
    if (dem->meshes.n) PetscCall(DemContactsMeshesTimed(dem));
  } else {
    PetscCall(DemContactsPairs(&dem->p, &dem->shapes, &dem->contact, &dem->nl, dem->clock.dt));
    PetscCall(DemContactsWalls(&dem->p, &dem->shapes, &dem->contact, &dem->walls, dem->clock.dt));
    if (dem->meshes.n) PetscCall(DemContactsMeshesTimed(dem));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemSetUp(Dem dem)
{
  double rmax = 0;

  PetscFunctionBeginUser;
  dem->state++;
  if (!dem->restart) PetscCall(DemInsert(dem)); /* a restart reads its particles below */
  else PetscCall(DemInsertRestartSizes(dem));   /* insert.c: own sizes of an init file, as when inserted */
  for (PetscInt s = 0; s < dem->shapes.nshape; s++) {
    DemShape *sh = &dem->shapes.shp[s];
    sh->m        = dem_sphere_mass(sh->rho, sh->r);
    sh->inertia  = 0.4 * sh->m * sh->r * sh->r;
    sh->invm     = 1.0 / sh->m;
    sh->invi     = 1.0 / sh->inertia;
    rmax         = PetscMax(rmax, sh->r);
  }
  PetscCheck(!dem->shapes.poly || !dem->shapes.convex, dem->comm, PETSC_ERR_ARG_INCOMP, "-dem_shape: convex shapes keep one size per shape; a source or -dem_init_file_radii own of spheres of their own sizes cannot be combined with them");
  if (dem->shapes.poly) rmax = PetscMax(rmax, dem->shapes.r_source_max); /* reach, skin and cells cover the largest size a source adds */
  PetscCall(DemShapesSetUp(dem));                                        /* convex shapes: mass, inertia tensor (shapes.c) */
  PetscCall(DemMaterialsSetUp(dem));
  PetscCall(DemCheckTimeStep(dem));
  PetscCall(DemSourcesSetUp(dem)); /* needs dt and the shapes' masses */
  if (dem->nl.skin < 0) dem->nl.skin = 0.2 * rmax;
  PetscCheck(dem->nl.skin > 0, dem->comm, PETSC_ERR_ARG_OUTOFRANGE, "-dem_skin %g must be > 0 (m)", (double)dem->nl.skin);
  dem->nl.reach = 2 * rmax + dem->nl.skin;
  PetscCheck(dem->contact.roll == DEM_ROLL_NONE || !dem->shapes.convex, dem->comm, PETSC_ERR_ARG_INCOMP, "-dem_rolling_model %s applies to spheres; convex shapes (-dem_shape) take none", DemRollNames[dem->contact.roll]);
  dem->contact.rotation = (PetscBool)(dem->contact.mat.mu > 0 || dem->contact.wmat.mu > 0 || dem->shapes.convex || dem->contact.roll != DEM_ROLL_NONE);
  for (PetscInt w = 0; w < dem->walls.nwall; w++) dem->contact.rotation = (PetscBool)(dem->contact.rotation || dem->walls.wall[w].mu > 0);
  if (dem->meshes.n) PetscCall(DemMeshesSetUp(dem)); /* walls_mesh_options.c: materials, pose */
  PetscCall(DemExchangeSetUp(dem));
  PetscCall(DemRebuild(dem));
  PetscCall(DemCheckPlacement(dem)); /* needs the ghosts: pairs across ranks */
  PetscCall(DemGetStats(dem, &dem->initial));
  PetscCall(DemComputeForces(dem));
  /* after the forces: computing them again would advance the springs a second time */
  if (dem->restart) PetscCall(DemCheckpointRead(dem, dem->restart));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemSetRestart(Dem dem, IoCkpt ck)
{
  PetscFunctionBeginUser;
  dem->restart = ck;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemStep(Dem dem)
{
  double d2, wmax = 0;

  PetscFunctionBeginUser;
  dem->state++;
  PetscCall(DemIntegrateFirstHalf(&dem->p, &dem->shapes, &dem->ext, dem->contact.rotation, dem->clock.dt, &d2));
  PetscCheck(PetscIsNormalReal(d2) || d2 == 0, PETSC_COMM_SELF, PETSC_ERR_FP, "step %" PetscInt_FMT ": a particle position became non-finite; lower -dem_dt (now %g s)", dem->clock.step, (double)dem->clock.dt);
  for (PetscInt w = 0; w < dem->walls.nwall; w++) {
    DemWall *wl = &dem->walls.wall[w];
    if (!wl->removed && dem->clock.t + dem->clock.dt >= wl->t_remove) { /* -dem_plane_<k>_remove_time */
      wl->removed = PETSC_TRUE;
      wl->cnt     = 0;
    }
    if (wl->removed) continue;
    for (int k = 0; k < 3; k++) wl->s.p[k] += wl->s.v[k] * dem->clock.dt;
    wl->moved += sqrt(dem_dot(wl->s.v, wl->s.v)) * dem->clock.dt;
    wmax = PetscMax(wmax, wl->moved);
  }
  if (dem->meshes.n) { /* a moving mesh's travel bound counts as a wall's (walls_mesh.c) */
    double mmax;
    PetscCall(DemMeshesMove(dem, dem->clock.t + dem->clock.dt, &mmax));
    wmax = PetscMax(wmax, mmax);
  }
  if (dem->sinks.nout) PetscCall(DemSinksMark(dem)); /* a particle taken by an outlet asks for a rebuild */
  /* every rank rebuilds when one needs to: the ghosts must be re-created everywhere */
  /* the same reduction tells every rank whether any caught a signal (the run loop stops at the
     next step, on every rank alike) */
  /* a source's batch is placed at a rebuild (sources.c): the same decision on every rank */
  const PetscBool due     = dem->src.n ? DemSourcesDue(dem) : PETSC_FALSE;
  int             need[2] = {due || dem->need_build || 4 * d2 > dem->nl.skin * dem->nl.skin || 2 * wmax > dem->nl.skin, SableSignalCaught()}, any[2] = {need[0], need[1]};
  if (dem->ex.active) PetscCallMPI(MPI_Allreduce(need, any, 2, MPI_INT, MPI_MAX, dem->comm));
  dem->stop_sig = any[1];
  SableProgress();
  if (due) PetscCall(DemSourcesPlace(dem));
  if (any[0]) PetscCall(DemRebuild(dem));
  else PetscCall(DemGhostsUpdate(dem));
  PetscLogDouble c0, c1;
  PetscCall(PetscTime(&c0));
  PetscCall(DemComputeForces(dem));
  PetscCall(DemIntegrateSecondHalf(&dem->p, &dem->shapes, &dem->ext, dem->contact.rotation, dem->clock.dt));
  PetscCall(PetscTime(&c1));
  dem->t_compute += c1 - c0; /* local work only, no waiting: the measured load-balancing weight */
  dem->clock.t += dem->clock.dt;
  dem->clock.step++;
  if (dem->check_every > 0 && dem->clock.step % dem->check_every == 0) PetscCall(DemCheckBalance(dem));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemGetStopSignal(Dem dem, int *sig)
{
  PetscFunctionBeginUser;
  *sig = dem->stop_sig;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemGetTime(Dem dem, PetscReal *t, PetscInt *step)
{
  PetscFunctionBeginUser;
  if (t) *t = dem->clock.t;
  if (step) *step = dem->clock.step;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemGetTimeStep(Dem dem, PetscReal *dt)
{
  PetscFunctionBeginUser;
  *dt = dem->clock.dt;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemGetTimeStepOption(Dem dem, const char **opt)
{
  PetscFunctionBeginUser;
  *opt = dem->clock.dt_tc > 0 ? "-dem_dt_tc" : "-dem_dt";
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemDestroy(Dem *dem)
{
  PetscFunctionBeginUser;
  if (!*dem) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(DemSetExternal(*dem, PETSC_FALSE));
  PetscCall(DemNeighDestroy(*dem));
  PetscCall(DemExchangeDestroy(*dem));
  PetscCall(DemShapesDestroy(*dem));
  PetscCall(DemSinksDestroy(*dem));
  PetscCall(DemSourcesDestroy(*dem));
  PetscCall(DemMeshesDestroy(*dem));
  for (PetscInt w = 0; w < (*dem)->walls.nwall; w++) {
    PetscCall(PetscFree((*dem)->walls.wall[w].idx));
    PetscCall(PetscFree((*dem)->walls.wall[w].hist));
  }
  PetscCall(DemParticlesDestroy(*dem)); /* particles.c: every array of the field table */
  PetscCall(PetscFree(*dem));
  PetscFunctionReturn(PETSC_SUCCESS);
}
