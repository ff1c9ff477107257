/* The state of insertion, sources and outlets that struct _p_Dem embeds (insert.c, sources.c,
 * sinks.c): struct definitions only, included by dem_core.h where the layout needs them; the
 * functions are in dem_sources.h. */
#pragma once
#include "dem/dem.h"
#include "dem/psd.h"
#include "geom/region.h"

/* Insertion (insert.c). */
typedef struct {
  PetscInt  lat[3], lat_count; /* lattice sites, and how many of them are filled (-1: all) */
  PetscReal lat_a, lat_origin[3], lat_jitter, lat_speed;
  PetscBool lat_origin_set, random_orient;
  PetscInt  seed;
  char      init_file[PETSC_MAX_PATH_LEN];
  /* where the inserted particles came from, by id (placement.c): the file's are below file_end
     (0: no file), the lattice's follow, [file_end, file_end + lat_count) */
  PetscInt  file_end;
  PetscReal init_overlap_max; /* -dem_init_file_overlap_max (radii); 0: from the contact design */
  /* -dem_init_file_radii auto|shapes|own: whether the file's spheres keep their own radii (a
     scene of own sizes) or become shapes by radius; the file's radius range (m) */
  PetscInt  file_radii;
  PetscBool file_own;
  PetscReal file_rmin, file_rmax;
} DemInsertion;

/* The particles that entered and left the run (sources.c, sinks.c): global totals, the same on
 * every rank; the mass balance is initial + inserted - removed = present, in count and in the
 * id checksum (DemStep's -dem_check_every). */
typedef struct {
  PetscInt  inserted, removed;       /* particles */
  PetscReal m_inserted, m_removed;   /* their mass (kg) */
  PetscReal id_inserted, id_removed; /* sums of their ids */
} DemFlow;

/* Outlets (sinks.c): a box, a plane patch or a domain side that removes particles in the
 * window t_start <= t <= t_stop, with its global totals; the particles marked at this step
 * (local indices, increasing, and the outlet of each) wait for the rebuild that removes them. */
#define DEM_MAX_OUTLETS 10 /* -dem_outlet_<k>, k = 0..9; a coupled run may add the 6 sides */
typedef enum {
  DEM_OUTLET_REGION,
  DEM_OUTLET_SIDE
} DemOutletKind;
typedef struct {
  DemOutletKind kind;
  char          name[48];        /* the option that made it, for messages and the summary */
  GeomRegion    reg;             /* region: a box (centre inside) or a patch (centre crossed it) */
  int           axis, side;      /* side: axis 0..2, 0 lo / 1 hi */
  double        t_start, t_stop; /* s */
  PetscInt      removed;         /* global totals */
  double        m_removed, id_removed;
} DemOutlet;
typedef struct {
  DemOutlet out[DEM_MAX_OUTLETS + 6];
  PetscInt  nout;
  PetscInt *gone, *gone_out, ngone, capgone;
} DemSinks;
/* Particle sources (sources.c): -dem_insert_<k>_*. Geometry and rates as set; the state (counts,
 * mass, candidate counter, batch number, shortfall) is the same on every rank and checkpointed. */
#define DEM_MAX_SOURCES 10
typedef struct {
  PetscInt   k;                   /* its option index: -dem_insert_<k>_* */
  GeomRegion reg;                 /* box, cylinder or patch (its depth: the stream's slab, m) */
  PetscReal  lo[3], hi[3];        /* the region's bounding box (m) */
  PetscReal  rate, mass_rate;     /* 1/s, kg/s; 0: none */
  PetscInt   count;               /* total; < 0: none */
  PetscReal  mass;                /* total (kg); < 0: none */
  PetscReal  start, stop, period; /* s */
  PetscReal  v[3], vspread;       /* m/s */
  PetscBool  random_orient;
  PetscInt   shape, seed, attempts;
  DemPsd     psd;
  PetscReal  m_mean; /* mean particle mass (kg) */
  PetscReal  vol;    /* the region's volume (m^3) */
  /* state */
  PetscInt  inserted, cand, batch, shortfall;
  PetscInt  said, sh_max; /* the log's note (1) and warning (2) printed; the largest shortfall */
  PetscReal m_inserted;
  PetscReal t_caught; /* when the shortfall last returned to 0 (s; < 0: never or not now) */
  PetscReal fill;     /* the region's solids volume fraction after the last batch that left a shortfall */
} DemSource;
typedef struct {
  DemSource    s[DEM_MAX_SOURCES];
  PetscInt     n;
  DemParticle *pend; /* accepted at this step, added by the owner at the rebuild */
  PetscInt     npend, cappend;
} DemSources;
