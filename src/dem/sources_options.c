/* The options of the particle sources (-dem_insert_<k>_*, k = 0..9) and their set-up checks:
 * the region (box, cylinder, patch) and its bounds, the rate or total, times, velocity,
 * orientation, shape, seed, period, attempts and the size distribution (psd.h); after the time
 * step is known, the default period (200 steps), the patch's slab depth, and the refusals that
 * need them (a region outside the domain or thinner than the largest diameter, a batch larger
 * than the region holds at random close packing, a patch stream that does not leave it).
 * What the sources do with these: sources.c. */
#include "dem/dem_core.h"
#include "dem/dem_sources.h"

#define DEM_SRC_DENSE        0.64 /* random close packing: no batch can hold more */
#define DEM_SRC_PERIOD_STEPS 200  /* default period, in time steps */

static const char *const DemSourceRegionOption[DEM_MAX_SOURCES] = {"-dem_insert_0_region", "-dem_insert_1_region", "-dem_insert_2_region", "-dem_insert_3_region", "-dem_insert_4_region", "-dem_insert_5_region", "-dem_insert_6_region", "-dem_insert_7_region", "-dem_insert_8_region", "-dem_insert_9_region"};
static const char *const DemSourceOrientOption[DEM_MAX_SOURCES] = {"-dem_insert_0_random_orientation", "-dem_insert_1_random_orientation", "-dem_insert_2_random_orientation", "-dem_insert_3_random_orientation", "-dem_insert_4_random_orientation", "-dem_insert_5_random_orientation", "-dem_insert_6_random_orientation", "-dem_insert_7_random_orientation", "-dem_insert_8_random_orientation", "-dem_insert_9_random_orientation"};
static const char *const DemSourceRegionHelp[]                  = {"Source region: box xlo,ylo,zlo,xhi,yhi,zhi", "Source region: cylinder centre cx,cy,cz, axis ax,ay,az, radius R, length L", "Source region: rectangle with corners p0, p1, p2 (p1-p0 perpendicular to p2-p0); the stream leaves towards (p1-p0)x(p2-p0)"};

/* The geometry option of the region (geom/region.h), read into s->reg. With help (-help) the
 * options of the other regions are listed too, and a missing geometry is not an error. */
static PetscErrorCode DemSourceGeometryOptions(PetscOptionItems *PetscOptionsObject, Dem dem, int k, DemSource *s, GeomRegionKind kind, PetscBool help)
{
  char           opt[3][64];
  GeomRegionSpec spec;
  PetscBool      set;

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(opt[0], sizeof opt[0], "-dem_insert_%d_box", k));
  PetscCall(PetscSNPrintf(opt[1], sizeof opt[1], "-dem_insert_%d_cylinder", k));
  PetscCall(PetscSNPrintf(opt[2], sizeof opt[2], "-dem_insert_%d_patch", k));
  for (int r = 0; r < 3; r++) {
    spec.opt[r]  = help || r == (int)kind ? opt[r] : NULL;
    spec.text[r] = DemSourceRegionHelp[r];
  }
  PetscCall(GeomRegionOptions(&spec, &s->reg, &set));
  PetscCheck(set || help, dem->comm, PETSC_ERR_ARG_WRONG, "%s %s needs %s", DemSourceRegionOption[k], GeomRegionKinds[kind], opt[kind]);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The rates, totals, times and kinematics of source k (help: a source without a rate or a total
 * is not an error). */
static PetscErrorCode DemSourceRateOptions(PetscOptionItems *PetscOptionsObject, Dem dem, int k, DemSource *s, PetscBool help)
{
  char      o[6][64];
  PetscBool set[6];

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(o[0], sizeof o[0], "-dem_insert_%d_rate", k));
  PetscCall(PetscSNPrintf(o[1], sizeof o[1], "-dem_insert_%d_mass_rate", k));
  PetscCall(PetscSNPrintf(o[2], sizeof o[2], "-dem_insert_%d_count", k));
  PetscCall(PetscSNPrintf(o[3], sizeof o[3], "-dem_insert_%d_mass", k));
  PetscCall(PetscSNPrintf(o[4], sizeof o[4], "-dem_insert_%d_start", k));
  PetscCall(PetscSNPrintf(o[5], sizeof o[5], "-dem_insert_%d_stop", k));
  PetscCall(SableOptionsReal(o[0], "Insertion rate in particles per second (0: none)", "1/s", "[0,inf)", 0, &s->rate, &set[0]));
  PetscCall(SableOptionsReal(o[1], "Insertion rate in mass per second (0: none)", "kg/s", "[0,inf)", 0, &s->mass_rate, &set[1]));
  PetscCall(SableOptionsInt(o[2], "Total number of particles to insert (default: no total)", NULL, "[0,inf)", -1, &s->count, &set[2]));
  PetscCall(SableOptionsReal(o[3], "Total mass to insert; the last particle may pass it by less than its own mass (default: no total)", "kg", "[0,inf)", -1, &s->mass, &set[3]));
  PetscCall(SableOptionsReal(o[4], "Time of the first batch", "s", "[0,inf)", 0, &s->start, &set[4]));
  PetscCall(SableOptionsReal(o[5], "Time after which no batch is placed (default: never)", "s", "(0,inf)", -1, &s->stop, &set[5]));
  PetscCheck(!(s->rate > 0 && s->mass_rate > 0), dem->comm, PETSC_ERR_ARG_INCOMP, "%s and %s both set the rate of source %d: give one of them", o[0], o[1], k);
  PetscCheck(!(set[2] && set[3]), dem->comm, PETSC_ERR_ARG_INCOMP, "%s and %s both set the total of source %d: give one of them", o[2], o[3], k);
  PetscCheck(help || s->rate > 0 || s->mass_rate > 0 || set[2] || set[3], dem->comm, PETSC_ERR_ARG_WRONG, "%s: give a rate (%s or %s) or a total (%s or %s)", DemSourceRegionOption[k], o[0], o[1], o[2], o[3]);
  PetscCheck(!set[5] || s->stop > s->start, dem->comm, PETSC_ERR_ARG_OUTOFRANGE, "%s %g must be after %s %g (s)", o[5], (double)s->stop, o[4], (double)s->start);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Velocity, orientation, shape, seed, period, attempts and sizes of source k (list: only read,
 * for -help, the scene unchanged). */
static PetscErrorCode DemSourceParticleOptions(PetscOptionItems *PetscOptionsObject, Dem dem, int k, DemSource *s, PetscBool list)
{
  char      opt[64];
  PetscBool set;
  double    dmin, dmax;

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(opt, sizeof opt, "-dem_insert_%d_velocity", k));
  PetscCall(SableOptionsRealN(opt, "Initial velocity of the inserted particles vx,vy,vz", "m/s", s->v, 3, 3, NULL));
  PetscCall(PetscSNPrintf(opt, sizeof opt, "-dem_insert_%d_velocity_spread", k));
  PetscCall(SableOptionsReal(opt, "Each velocity component gets a uniform random term in +-this", "m/s", "[0,inf)", 0, &s->vspread, NULL));
  s->random_orient = dem->shapes.convex;
  PetscCall(SableOptionsBool(DemSourceOrientOption[k], "Uniformly random orientations (default: for convex shapes)", s->random_orient, &s->random_orient, NULL));
  PetscCall(PetscSNPrintf(opt, sizeof opt, "-dem_insert_%d_shape", k));
  PetscCall(SableOptionsInt(opt, "Shape (material) index of the inserted particles, as in -dem_radius / -dem_shape", NULL, "[0,inf)", 0, &s->shape, NULL));
  PetscCheck(s->shape < dem->shapes.nshape, dem->comm, PETSC_ERR_ARG_OUTOFRANGE, "%s %" PetscInt_FMT " must be in [0, %" PetscInt_FMT "] (the shapes of -dem_radius or -dem_shape)", opt, s->shape, dem->shapes.nshape - 1);
  PetscCall(PetscSNPrintf(opt, sizeof opt, "-dem_insert_%d_seed", k));
  PetscCall(SableOptionsInt(opt, "Seed of the source's candidates (positions, sizes, velocities, orientations)", NULL, "[0,inf)", k + 1, &s->seed, NULL));
  PetscCall(PetscSNPrintf(opt, sizeof opt, "-dem_insert_%d_period", k));
  PetscCall(SableOptionsReal(opt, "Time between batches; each batch costs a list rebuild (default 200 time steps)", "s", "(0,inf)", -1, &s->period, &set));
  PetscCall(PetscSNPrintf(opt, sizeof opt, "-dem_insert_%d_attempts", k));
  PetscCall(SableOptionsInt(opt, "Candidates drawn per particle of a batch before the rest is carried to the next batch", NULL, "[1,inf)", 50, &s->attempts, NULL));
  PetscCall(PetscSNPrintf(opt, sizeof opt, "-dem_insert_%d", k));
  PetscCall(DemPsdSetFromOptions(PetscOptionsObject, dem->comm, opt, 2 * dem->shapes.shp[s->shape].r, &s->psd));
  DemPsdRange(&s->psd, &dmin, &dmax);
  if (list) PetscFunctionReturn(PETSC_SUCCESS);
  if (PetscAbsReal(dmin - 2 * dem->shapes.shp[s->shape].r) > 1e-12 * dmin || PetscAbsReal(dmax - dmin) > 1e-12 * dmin) {
    PetscCheck(!dem->shapes.convex, dem->comm, PETSC_ERR_ARG_INCOMP, "%s_psd: a source of convex shapes inserts its shape's size (bounding diameter %g m), not a distribution", opt, (double)(2 * dem->shapes.shp[s->shape].r));
    PetscCall(DemSetOwnSizes(dem, 0.5 * dmin, 0.5 * dmax)); /* spheres of their own sizes: reach, cells and time step cover them */
  } else {
    dem->shapes.r_source_max = PetscMax(dem->shapes.r_source_max, 0.5 * dmax);
    dem->shapes.r_source_min = dem->shapes.r_source_min > 0 ? PetscMin(dem->shapes.r_source_min, 0.5 * dmin) : 0.5 * dmin;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The suffixes of a source's options: any of them without its _region is an error. */
static const char *const DemSourceSuffixes[] = {"box", "cylinder", "patch", "rate", "mass_rate", "count", "mass", "start", "stop", "velocity", "velocity_spread", "random_orientation", "shape", "seed", "period", "attempts", "psd", "psd_mean", "psd_std", "psd_min", "psd_max", "psd_diameters", "psd_fractions", "psd_classes"};

/* -help lists every source's options (a source not given is read into a scratch copy) and
 * raises no error of a source left incomplete. */
PetscErrorCode DemSourcesSetFromOptions(Dem dem)
{
  PetscBool help;

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsHasHelp(NULL, &help));
  PetscOptionsBegin(dem->comm, NULL, "DEM particle sources", NULL);
  for (int k = 0; k < DEM_MAX_SOURCES; k++) {
    DemSource *s      = &dem->src.s[dem->src.n];
    PetscInt   region = 0;
    PetscBool  set;
    PetscCall(SableOptionsEnum(DemSourceRegionOption[k], "Particle source: the region candidates are drawn in", GeomRegionKinds, 3, 0, &region, &set));
    if (!set && help) {
      DemSource scratch;
      PetscCall(PetscMemzero(&scratch, sizeof scratch));
      PetscCall(DemSourceGeometryOptions(PetscOptionsObject, dem, k, &scratch, GEOM_REGION_BOX, PETSC_TRUE));
      PetscCall(DemSourceRateOptions(PetscOptionsObject, dem, k, &scratch, PETSC_TRUE));
      PetscCall(DemSourceParticleOptions(PetscOptionsObject, dem, k, &scratch, PETSC_TRUE));
      continue;
    }
    if (!set) {
      for (size_t a = 0; a < sizeof DemSourceSuffixes / sizeof DemSourceSuffixes[0]; a++) {
        char      opt[64];
        PetscBool has;
        PetscCall(PetscSNPrintf(opt, sizeof opt, "-dem_insert_%d_%s", k, DemSourceSuffixes[a]));
        PetscCall(PetscOptionsHasName(NULL, NULL, opt, &has));
        PetscCheck(!has, dem->comm, PETSC_ERR_ARG_WRONG, "%s given without %s (box, cylinder or patch)", opt, DemSourceRegionOption[k]);
      }
      PetscBool ro = PETSC_FALSE; /* read (not given) so that -help lists the flag of every source */
      PetscCall(SableOptionsBool(DemSourceOrientOption[k], "Uniformly random orientations (default: for convex shapes)", ro, &ro, NULL));
      continue;
    }
    PetscCall(PetscMemzero(s, sizeof *s));
    PetscCall(DemSourceGeometryOptions(PetscOptionsObject, dem, k, s, (GeomRegionKind)region, help));
    PetscCall(DemSourceRateOptions(PetscOptionsObject, dem, k, s, help));
    PetscCall(DemSourceParticleOptions(PetscOptionsObject, dem, k, s, PETSC_FALSE));
    s->k = k;
    dem->src.n++;
  }
  PetscOptionsEnd();
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Mass (kg) of a particle of diameter d from source s: its shape's at the shape's size. */
double DemSourceMass(Dem dem, const DemSource *s, double d)
{
  const DemShape *sh = &dem->shapes.shp[s->shape];
  if (sh->cvx || PetscAbsReal(d - 2 * sh->r) <= 1e-12 * d) return sh->m;
  return dem_sphere_mass(sh->rho, 0.5 * d); /* the mass the particle will carry (DemParticleSetSize) */
}

/* The smallest extent of the region a particle must fit in (m). */
static double DemSourceThinnest(const DemSource *s)
{
  const double *g = s->reg.g;
  if (s->reg.kind == GEOM_REGION_BOX) return PetscMin(PetscMin(g[3] - g[0], g[4] - g[1]), g[5] - g[2]);
  if (s->reg.kind == GEOM_REGION_CYLINDER) return PetscMin(2 * g[6], g[7]);
  return PetscMin(sqrt(dem_dot(g + 3, g + 3)), sqrt(dem_dot(g + 6, g + 6)));
}

/* Collective. After the time step and the shapes' masses: the period, the patch's depth, the
 * region's bounds, the checks that need them, the mean mass. */
PetscErrorCode DemSourcesSetUp(Dem dem)
{
  const double dt = dem->clock.dt;

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < dem->src.n; i++) {
    DemSource   *s  = &dem->src.s[i];
    const char  *rn = GeomRegionKinds[s->reg.kind];
    const int    k  = (int)s->k;
    double       dmin, dmax, vol, vn = dem_dot(s->v, s->reg.n);
    char         go[64];
    const double rho = dem->shapes.shp[s->shape].rho;
    PetscCall(PetscSNPrintf(go, sizeof go, "-dem_insert_%d_%s", k, rn));
    DemPsdRange(&s->psd, &dmin, &dmax);
    if (s->period < 0) s->period = DEM_SRC_PERIOD_STEPS * dt;
    PetscCheck(s->period >= dt, dem->comm, PETSC_ERR_ARG_OUTOFRANGE, "-dem_insert_%d_period %g must be at least the time step %g s", k, (double)s->period, dt);
    PetscCheck(s->reg.kind != GEOM_REGION_PATCH || vn > 0, dem->comm, PETSC_ERR_ARG_OUTOFRANGE, "-dem_insert_%d_velocity must leave the patch: its component %g along the patch normal (%g,%g,%g) must be > 0 (m/s)", k, vn, (double)s->reg.n[0], (double)s->reg.n[1], (double)s->reg.n[2]);
    s->reg.depth = PetscMax(vn * s->period, dmax);
    geom_region_bounds(&s->reg, s->lo, s->hi, &vol);
    s->vol      = vol;
    s->t_caught = -1;
    PetscCheck(DemSourceThinnest(s) >= dmax, dem->comm, PETSC_ERR_ARG_OUTOFRANGE, "%s: the region is %g m thin, less than the largest diameter %g m", go, DemSourceThinnest(s), dmax);
    for (int d = 0; d < 3; d++) {
      const double tol = 1e-12 * dem->dom->len[d];
      PetscCheck(s->lo[d] >= dem->dom->lo[d] - tol && s->hi[d] <= dem->dom->hi[d] + tol, dem->comm, PETSC_ERR_ARG_OUTOFRANGE, "%s: the region spans [%g, %g] along %c, outside the domain [%g, %g] (-domain_lo/-domain_hi)", go, s->lo[d], s->hi[d], "xyz"[d], (double)dem -> dom -> lo[d], (double)dem -> dom -> hi[d]);
    }
    s->m_mean = dem->shapes.shp[s->shape].cvx ? dem->shapes.shp[s->shape].m : DemSourceMass(dem, s, cbrt(DemPsdMeanCube(&s->psd)));
    {
      const double per = s->rate > 0 ? s->rate * s->period : s->mass_rate * s->period / s->m_mean;
      const double vp = s->m_mean / rho, cap = DEM_SRC_DENSE * vol / vp;
      const char  *ropt  = s->rate > 0 ? "rate" : "mass_rate";
      const double value = s->rate > 0 ? s->rate : s->mass_rate;
      PetscCheck(per <= cap, dem->comm, PETSC_ERR_ARG_OUTOFRANGE, "-dem_insert_%d_%s %g x period %g s = %.4g particles per batch, more than the region holds at random close packing (%.4g = %g x %.4g m^3 / %.4g m^3 per particle): lower the rate or -dem_insert_%d_period, or enlarge %s", k, ropt, value, (double)s->period, per, cap, DEM_SRC_DENSE, vol, vp, k, go);
    }
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}
