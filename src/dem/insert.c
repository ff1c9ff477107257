/* Insertion. A cubic lattice of nx x ny x nz sites of spacing a, site (i,j,k) at
 * origin + ((i+1/2) a, (j+1/2) a, (k+1/2) a), id = i + nx (j + ny k). Optional perturbations,
 * all functions of the site and the seed only (so independent of the rank count):
 *   position jitter, uniform in +-jitter (a - d_max)/2 per axis;
 *   velocity v_c = V (2 h_c - 1), h_c = frac(43758.5453 sin(12.9898 (id+1) + 78.233 c)),
 *   c = 1, 2, 3 — the symmetry-breaking velocity of the LIGGGHTS peer decks, so both codes start
 *   from the same state; shapes drawn by number fraction (-dem_radius_fraction); with
 *   -dem_lattice_random_orientation, a uniformly random orientation (for convex shapes).
 * Or: particles from an HDF5 file that Sable wrote (-dem_init_file), the last frame's state; its
 * spheres become shapes by radius, or keep their own radii (-dem_init_file_radii own, or auto:
 * when the scene has sizes of their own or the file more distinct radii than shapes can hold).
 * Both at once: the lattice's ids follow the file's. Whether they start clear of the walls and
 * of each other is checked once the ghosts exist (placement.c). */
#include "dem/dem_core.h"
#include "dem/dem_sources.h"

static double dem_hash_frac(double n, int c)
{
  const double s = 43758.5453 * sin(12.9898 * n + 78.233 * c);
  return s - floor(s);
}

/* A uniformly distributed unit quaternion (Shoemake, Graphics Gems III, 1992) from streams 4-6. */
static void dem_random_quat(PetscInt seed, PetscInt site, double q[4])
{
  const double u1 = dem_uniform(seed, site, 4), a = 2 * PETSC_PI * dem_uniform(seed, site, 5), b = 2 * PETSC_PI * dem_uniform(seed, site, 6);
  const double s1 = sqrt(1 - u1), s2 = sqrt(u1);
  q[0] = s2 * cos(b);
  q[1] = s1 * sin(a);
  q[2] = s1 * cos(a);
  q[3] = s2 * sin(b);
}

static const char *const DemFileRadiiNames[] = {"auto", "shapes", "own"};

/* Collective. From all rows d of the -dem_init_file's radii: their range, and whether the spheres
 * keep them (a scene of own sizes, declared so that reach and cells cover the file's largest).
 * Particles added before that had their shape's radius: they keep it, now as their own. */
static PetscErrorCode DemInitFileRadii(Dem dem, const PetscReal *dr, PetscInt rows)
{
  PetscReal *d;
  PetscInt   nnew = 0;
  PetscBool  was  = dem->shapes.poly;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(rows + 1, &d));
  PetscCall(PetscArraycpy(d, dr, rows));
  dem->insert.file_rmin = PETSC_MAX_REAL;
  dem->insert.file_rmax = 0;
  for (PetscInt i = 0; i < rows; i++) {
    PetscCheck(d[i] > 0 && PetscIsNormalReal(d[i]), dem->comm, PETSC_ERR_FILE_UNEXPECTED, "-dem_init_file %s: row %" PetscInt_FMT " of /particles/radius, %g, must be > 0 (m)", dem->insert.init_file, i, (double)d[i]);
    dem->insert.file_rmin = PetscMin(dem->insert.file_rmin, d[i]);
    dem->insert.file_rmax = PetscMax(dem->insert.file_rmax, d[i]);
  }
  if (dem->insert.file_radii == 0) { /* auto: count the radii no shape has */
    PetscCall(PetscSortReal(rows, d));
    for (PetscInt i = 0; i < rows && nnew <= DEM_MAX_SHAPES; i++) {
      PetscBool known = (PetscBool)(i > 0 && PetscAbsReal(d[i] - d[i - 1]) <= 1e-12 * d[i]);
      for (PetscInt s = 0; s < dem->shapes.nshape && !known; s++) known = (PetscBool)(PetscAbsReal(dem->shapes.shp[s].r - d[i]) <= 1e-12 * d[i]);
      nnew += !known;
    }
  }
  PetscCall(PetscFree(d));
  dem->insert.file_own = (PetscBool)(dem->insert.file_radii == 2 || (dem->insert.file_radii == 0 && (dem->shapes.poly || dem->shapes.nshape + nnew > DEM_MAX_SHAPES)));
  if (!dem->insert.file_own || !rows) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(DemSetOwnSizes(dem, dem->insert.file_rmin, dem->insert.file_rmax));
  if (!was && dem->p.n) {
    PetscCall(DemParticlesReserve(dem, dem->p.n)); /* the size arrays */
    for (PetscInt i = 0; i < dem->p.n; i++) DemParticleSetSize(dem, i, dem->shapes.shp[dem->p.shape[i]].r);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DemInsertSetFromOptions(Dem dem)
{
  PetscBool help;

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsHasHelp(NULL, &help)); /* -help opens no file: the init file may not exist yet */
  PetscOptionsBegin(dem->comm, NULL, "DEM insertion", NULL);
  PetscCall(SableOptionsIntN("-dem_lattice", "Cubic lattice site counts nx,ny,nz (0 = no lattice)", NULL, "[0,inf)", dem->insert.lat, 3, 3, NULL));
  PetscCall(SableOptionsInt("-dem_lattice_count", "Fill only the first this many lattice sites, x fastest then y then z; default all nx*ny*nz", NULL, "[0,inf)", dem->insert.lat_count, &dem->insert.lat_count, NULL));
  PetscCall(SableOptionsReal("-dem_lattice_spacing", "Lattice spacing; default 1.05 x the largest diameter", "m", "(0,inf)", dem->insert.lat_a, &dem->insert.lat_a, NULL));
  PetscCall(SableOptionsRealN("-dem_lattice_origin", "Lower corner of the lattice region; default the domain's lower corner", "m", dem->insert.lat_origin, 0, 3, &dem->insert.lat_origin_set));
  PetscCall(SableOptionsReal("-dem_lattice_jitter", "Random position perturbation, fraction of the gap (a - d)/2", NULL, "[0,1]", dem->insert.lat_jitter, &dem->insert.lat_jitter, NULL));
  PetscCall(SableOptionsReal("-dem_lattice_speed", "Amplitude of the deterministic random initial velocity", "m/s", "[0,inf)", dem->insert.lat_speed, &dem->insert.lat_speed, NULL));
  PetscCall(SableOptionsBool("-dem_lattice_random_orientation", "Uniformly random initial orientations (convex shapes)", dem->insert.random_orient, &dem->insert.random_orient, NULL));
  PetscCall(SableOptionsInt("-dem_seed", "Seed of the insertion perturbations", NULL, NULL, dem->insert.seed, &dem->insert.seed, NULL));
  PetscCall(SableOptionsString("-dem_init_file", "HDF5 file written by Sable to start from (its particles); default none (the particles come from -dem_lattice)", dem->insert.init_file, sizeof dem->insert.init_file, NULL));
  PetscCall(SableOptionsEnum("-dem_init_file_radii", "Spheres of -dem_init_file: own (each keeps its radius: a scene of own sizes, the shape index names the material), shapes (one shape per distinct radius, at most 32), or auto (own when the scene has own sizes or the file has more distinct radii than shapes can hold)", DemFileRadiiNames, 3, dem->insert.file_radii, &dem->insert.file_radii, NULL));
  PetscCall(SableOptionsReal("-dem_init_file_overlap_max", "Largest overlap / radius a -dem_init_file particle may start with, with another or with a wall; default twice the contact design's overlap at -dem_impact_velocity, at least 0.05", NULL, "(0,2)", dem->insert.init_overlap_max, &dem->insert.init_overlap_max, NULL));
  PetscOptionsEnd();
  {
    const double sites = (double)dem->insert.lat[0] * (double)dem->insert.lat[1] * (double)dem->insert.lat[2];
    PetscCheck(sites <= (double)PETSC_MAX_INT, dem->comm, PETSC_ERR_ARG_OUTOFRANGE, "-dem_lattice %" PetscInt_FMT ",%" PetscInt_FMT ",%" PetscInt_FMT ": %.0f sites, more than %" PetscInt_FMT " (the integer size PETSc was built with)", dem->insert.lat[0], dem->insert.lat[1], dem->insert.lat[2], sites, (PetscInt)PETSC_MAX_INT);
  }
  PetscCheck(dem->insert.lat_count <= dem->insert.lat[0] * dem->insert.lat[1] * dem->insert.lat[2], dem->comm, PETSC_ERR_ARG_OUTOFRANGE, "-dem_lattice_count %" PetscInt_FMT " must be in [0, nx*ny*nz = %" PetscInt_FMT "]", dem->insert.lat_count, dem->insert.lat[0] * dem->insert.lat[1] * dem->insert.lat[2]);
  if (dem->insert.lat_count < 0) dem->insert.lat_count = dem->insert.lat[0] * dem->insert.lat[1] * dem->insert.lat[2];
  if (dem->insert.init_file[0] && !help) PetscCall(IoCheckReadable(dem->comm, "-dem_init_file", dem->insert.init_file));
  if (dem->insert.init_file[0] && !help && dem->insert.file_radii == 2 && !dem->shapes.convex) { /* own: declared now, so a restart has it too */
    PetscReal *d;
    PetscInt   rows;
    PetscCall(IoReadDatasetAll(dem->comm, dem->insert.init_file, "/particles/radius", 1, &rows, &d));
    PetscCall(DemInitFileRadii(dem, d, rows));
    PetscCall(PetscFree(d));
  }
  PetscCheck(dem->insert.file_radii != 2 || !dem->shapes.convex, dem->comm, PETSC_ERR_ARG_INCOMP, "-dem_init_file_radii own: convex shapes (-dem_shape) keep one size per shape");
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The lattice spacing: -dem_lattice_spacing, or 1.05 x the largest diameter. */
double DemLatticeSpacing(Dem dem)
{
  double dmax = 0;
  for (PetscInt s = 0; s < dem->shapes.nshape; s++) dmax = PetscMax(dmax, 2 * dem->shapes.shp[s].r);
  return dem->insert.lat_a > 0 ? dem->insert.lat_a : 1.05 * dmax;
}

/* Site n gets id base + n: base is 0, or one past the largest id of the -dem_init_file
 * particles (ids stay unique). */
static PetscErrorCode DemInsertLattice(Dem dem, PetscInt base)
{
  double   dmax  = 0, a, gap;
  PetscInt nsite = dem->insert.lat_count;

  PetscFunctionBeginUser;
  for (PetscInt s = 0; s < dem->shapes.nshape; s++) dmax = PetscMax(dmax, 2 * dem->shapes.shp[s].r);
  a = DemLatticeSpacing(dem);
  PetscCheck(a >= dmax, dem->comm, PETSC_ERR_ARG_OUTOFRANGE, "-dem_lattice_spacing %g must be >= the largest diameter %g", a, dmax);
  gap = 0.5 * (a - dmax) * dem->insert.lat_jitter;
  if (!dem->insert.lat_origin_set)
    for (int k = 0; k < 3; k++) dem->insert.lat_origin[k] = dem->dom->lo[k];
  PetscCall(DemParticlesReserve(dem, dem->p.n + nsite)); /* exact, not by doubling (upper bound on one rank) */
  for (PetscInt n = 0; n < nsite; n++) {
    const PetscInt ijk[3] = {n % dem->insert.lat[0], (n / dem->insert.lat[0]) % dem->insert.lat[1], n / (dem->insert.lat[0] * dem->insert.lat[1])};
    DemParticle    p;
    double         u = dem_uniform(dem->insert.seed, n, 0), acc = 0;
    PetscCall(PetscMemzero(&p, sizeof p));
    p.id    = base + n;
    p.q[0]  = 1;
    p.shape = dem->shapes.nshape - 1;
    for (PetscInt s = 0; s < dem->shapes.nshape; s++) {
      acc += dem->shapes.shape_frac[s];
      if (u < acc) {
        p.shape = s;
        break;
      }
    }
    for (int k = 0; k < 3; k++) {
      p.x[k] = dem->insert.lat_origin[k] + (ijk[k] + 0.5) * a + gap * (2 * dem_uniform(dem->insert.seed, n, 1 + k) - 1);
      p.v[k] = dem->insert.lat_speed * (2 * dem_hash_frac((double)(n + 1), k + 1) - 1);
    }
    if (dem->insert.random_orient) dem_random_quat(dem->insert.seed, n, p.q);
    if (dem_in_box(dem->dom, p.x)) PetscCall(DemAddParticle(dem, &p));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The shape with radius r, created (with the -dem_density) if new. */
static PetscErrorCode DemShapeForRadius(Dem dem, double r, PetscInt *s)
{
  PetscFunctionBeginUser;
  for (*s = 0; *s < dem->shapes.nshape; (*s)++)
    if (PetscAbsReal(dem->shapes.shp[*s].r - r) <= 1e-12 * r) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCheck(dem->shapes.nshape < DEM_MAX_SHAPES, dem->comm, PETSC_ERR_ARG_OUTOFRANGE, "-dem_init_file %s: more than %d distinct radii", dem->insert.init_file, DEM_MAX_SHAPES);
  PetscCheck(r > 0, dem->comm, PETSC_ERR_ARG_OUTOFRANGE, "-dem_init_file %s: radius %g must be > 0", dem->insert.init_file, r);
  PetscCheck(!dem->shapes.convex, dem->comm, PETSC_ERR_ARG_WRONG, "-dem_init_file %s: bounding radius %g matches none of the -dem_shape shapes", dem->insert.init_file, r);
  dem->shapes.shp[dem->shapes.nshape]     = dem->shapes.shp[0];
  dem->shapes.shp[dem->shapes.nshape++].r = r;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Every rank reads all rows of /particles/id: each checks they are whole, >= 0 and distinct. */
static PetscErrorCode DemCheckFileIds(Dem dem, const PetscReal *d, PetscInt rows)
{
  PetscInt *ids;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(rows + 1, &ids));
  for (PetscInt i = 0; i < rows; i++) {
    PetscCheck(d[i] >= 0 && d[i] == PetscFloorReal(d[i]) && d[i] <= (PetscReal)PETSC_MAX_INT, dem->comm, PETSC_ERR_FILE_UNEXPECTED, "-dem_init_file %s: row %" PetscInt_FMT " of /particles/id, %g, is not an id (a whole number >= 0)", dem->insert.init_file, i, (double)d[i]);
    ids[i] = (PetscInt)d[i];
  }
  PetscCall(PetscSortInt(rows, ids));
  for (PetscInt i = 1; i < rows; i++) PetscCheck(ids[i] != ids[i - 1], dem->comm, PETSC_ERR_FILE_UNEXPECTED, "-dem_init_file %s: particle id %" PetscInt_FMT " appears more than once in /particles/id", dem->insert.init_file, ids[i]);
  PetscCall(PetscFree(ids));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode DemInsertFile(Dem dem, PetscInt *nfile)
{
  const char *names[6] = {"/particles/position", "/particles/velocity", "/particles/angular_velocity", "/particles/quaternion", "/particles/id", "/particles/radius"};
  const int   width[6] = {3, 3, 3, 4, 1, 1};
  PetscReal  *d;
  PetscInt    rows = 0, r, *mine, nmine = 0, n0 = dem->p.n;
  PetscBool   own = dem->insert.file_own;

  PetscFunctionBeginUser;
  /* one dataset at a time, keeping only this rank's rows: the peak is one column of the file */
  for (int k = 0; k < 6; k++) {
    PetscCall(IoReadDatasetAll(dem->comm, dem->insert.init_file, names[k], width[k], &r, &d));
    PetscCheck(k == 0 || r == rows, dem->comm, PETSC_ERR_FILE_UNEXPECTED, "-dem_init_file %s: %s has %" PetscInt_FMT " rows, expected %" PetscInt_FMT " (as /particles/position)", dem->insert.init_file, names[k], r, rows);
    if (k == 0) {
      rows = r;
      PetscCall(PetscMalloc1(rows + 1, &mine));
      for (PetscInt i = 0; i < rows; i++) {
        DemWrapPeriodic(dem->dom, d + 3 * i);
        if (dem_in_box(dem->dom, d + 3 * i)) mine[nmine++] = i;
      }
      PetscCall(DemParticlesReserve(dem, n0 + nmine));
      for (PetscInt a = 0; a < nmine; a++) {
        DemParticle p = {0};
        PetscCall(PetscMemzero(&p, sizeof p));
        for (int c = 0; c < 3; c++) p.x[c] = d[3 * mine[a] + c];
        p.q[0] = 1;
        PetscCall(DemAddParticle(dem, &p));
      }
    }
    if (k == 4) PetscCall(DemCheckFileIds(dem, d, rows));
    if (k == 5 && dem->insert.file_radii == 0) { /* auto: decided once the rows are known */
      PetscCall(DemInitFileRadii(dem, d, rows));
      own = dem->insert.file_own;
    }
    for (PetscInt a = 0; a < nmine && k > 0; a++) {
      const PetscInt i = n0 + a, row = mine[a];
      if (k == 1 || k == 2) { /* the integrators square them: |v|^2, |w|^2 must be finite */
        const PetscReal *u = d + 3 * row, u2 = u[0] * u[0] + u[1] * u[1] + u[2] * u[2];
        PetscCheck(PetscIsNormalReal(u2) || u2 == 0, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "-dem_init_file %s: row %" PetscInt_FMT " of %s, (%g, %g, %g), is not a finite %s", dem->insert.init_file, row, names[k], (double)u[0], (double)u[1], (double)u[2], k == 1 ? "velocity (m/s)" : "spin (rad/s)");
        for (int c = 0; c < 3; c++) (k == 1 ? dem->p.v : dem->p.w)[3 * i + c] = u[c];
      }
      if (k == 3) {
        const PetscReal *q = d + 4 * row, nq = PetscSqrtReal(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
        PetscCheck(PetscIsNormalReal(nq) && nq > 1e-12, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "-dem_init_file %s: row %" PetscInt_FMT " of /particles/quaternion, (%g, %g, %g, %g), is not a rotation (norm %g)", dem->insert.init_file, row, (double)q[0], (double)q[1], (double)q[2], (double)q[3], (double)nq);
        const PetscReal sc = PetscAbsReal(nq - 1) < 1e-12 ? 1 : 1 / nq; /* Sable's own (unit) ones kept bitwise, others normalised */
        for (int c = 0; c < 4; c++) dem->p.q[4 * i + c] = q[c] * sc;
      }
      if (k == 4) dem->p.id[i] = (PetscInt)d[row];
      if (k == 5 && own) DemParticleSetSize(dem, i, d[row]); /* material 0 unless the file names another */
      else if (k == 5) PetscCall(DemShapeForRadius(dem, d[row], &dem->p.shape[i]));
    }
    PetscCall(PetscFree(d));
  }
  { /* the shape index written with the frame, when it names a shape of this run with the same
       (bounding) radius; else the shape found by radius stays */
    PetscBool hasshape;
    PetscCall(IoHasDataset(dem->insert.init_file, "/particles/shape", &hasshape));
    if (hasshape) {
      PetscCall(IoReadDatasetAll(dem->comm, dem->insert.init_file, "/particles/shape", 1, &r, &d));
      PetscCheck(r == rows, dem->comm, PETSC_ERR_FILE_UNEXPECTED, "-dem_init_file %s: /particles/shape has %" PetscInt_FMT " rows, expected %" PetscInt_FMT, dem->insert.init_file, r, rows);
      for (PetscInt a = 0; a < nmine; a++) {
        const PetscInt i = n0 + a, s = (PetscInt)d[mine[a]];
        if (own && s >= 0 && s < dem->shapes.nshape) { /* the material it had */
          dem->p.shape[i] = s;
          DemParticleSetSize(dem, i, dem->p.rad[i]);
        } else if (!own && s >= 0 && s < dem->shapes.nshape && PetscAbsReal(dem->shapes.shp[s].r - dem->shapes.shp[dem->p.shape[i]].r) <= 1e-12 * dem->shapes.shp[s].r) dem->p.shape[i] = s;
      }
      PetscCall(PetscFree(d));
    }
  }
  for (PetscInt a = 0; a < nmine; a++) dem->p.next_id = PetscMax(dem->p.next_id, dem->p.id[n0 + a] + 1);
  PetscCall(PetscFree(mine));
  *nfile = rows;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. A restart inserts nothing, but its scene has own sizes as the run that wrote it:
 * -dem_init_file_radii auto decides from the file's radii as DemInsert would have. */
PetscErrorCode DemInsertRestartSizes(Dem dem)
{
  PetscReal *d;
  PetscInt   rows;

  PetscFunctionBeginUser;
  if (!dem->insert.init_file[0] || dem->insert.file_radii != 0 || dem->shapes.convex) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(IoReadDatasetAll(dem->comm, dem->insert.init_file, "/particles/radius", 1, &rows, &d));
  PetscCall(DemInitFileRadii(dem, d, rows));
  PetscCall(PetscFree(d));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. Inserts the lattice and/or the file's particles. */
PetscErrorCode DemInsert(Dem dem)
{
  PetscInt nfile = 0, n0 = dem->p.n, added, got;

  PetscFunctionBeginUser;
  /* a particle outside every rank's box would be lost silently: refuse */
  if (dem->insert.init_file[0]) {
    PetscCall(DemInsertFile(dem, &nfile));
    added = dem->p.n - n0;
    PetscCallMPI(MPI_Allreduce(&added, &got, 1, MPIU_INT, MPI_SUM, dem->comm));
    PetscCheck(got == nfile, dem->comm, PETSC_ERR_ARG_OUTOFRANGE, "-dem_init_file %s: %" PetscInt_FMT " of its %" PetscInt_FMT " particles lie outside the domain box (-domain_lo/-domain_hi): give the domain of the run that wrote it", dem->insert.init_file, nfile - got, nfile);
    /* one past the file's largest id: its particles have ids below it, the lattice's start there */
    if (nfile) PetscCallMPI(MPI_Allreduce(&dem->p.next_id, &dem->insert.file_end, 1, MPIU_INT, MPI_MAX, dem->comm));
  }
  if (dem->insert.lat_count > 0) {
    n0 = dem->p.n;
    PetscCall(DemInsertLattice(dem, dem->insert.file_end));
    added = dem->p.n - n0;
    PetscCallMPI(MPI_Allreduce(&added, &got, 1, MPIU_INT, MPI_SUM, dem->comm));
    PetscCheck(got == dem->insert.lat_count, dem->comm, PETSC_ERR_ARG_OUTOFRANGE, "%" PetscInt_FMT " of %" PetscInt_FMT " lattice particles lie outside the domain box (-domain_lo/-domain_hi); enlarge it or move the lattice (-dem_lattice_origin)", dem->insert.lat_count - got, dem->insert.lat_count);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}
