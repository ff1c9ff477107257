/* The region type (geom/region.h): for each kind (a tilted cylinder, a box, a tilted patch with
 * a slab), inside, crossed, sample and the bounding box agree with each other and with the
 * volume, and the option reader takes one syntax and refuses the retired patch spelling.
 *
 * Checks per kind, on 20000 points drawn from a fixed hash: every sample (inset 0) is inside and
 * within the bounding box, and a sample with inset d keeps a sphere of radius d inside (its six
 * axis points inside); the fraction of uniform points of the bounding box that are inside
 * matches volume / box volume within 4 standard deviations (a wrong inside or volume fails it);
 * crossed(a, b) is inside(a) != inside(b) for a box and a cylinder, and for a patch it holds
 * exactly for the segments through a sampled point of the rectangle along its normal and fails
 * for those that stop short of it or pass beside it. The reader: a patch of three corners gives
 * e1 = p1 - p0, e2 = p2 - p0 and the unit normal; p,e1,e2 values fail with the line naming the
 * new form; a box with lo >= hi and a cylinder of zero axis fail. */
#include "check.h"
#include "geom/region.h"
#include "sable.h"

/* A fixed uniform in [0,1) of (i, s): splitmix64. */
static double U(PetscInt i, int s)
{
  unsigned long long z = (unsigned long long)i * 0x9E3779B97F4A7C15ULL + (unsigned long long)s * 0xD1B54A32D192ED03ULL + 0x632BE59BD9B4E019ULL;
  z                    = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z                    = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  z ^= z >> 31;
  return (double)(z >> 11) / 9007199254740992.0;
}

static char last_msg[1024];

static PetscErrorCode RecordError(MPI_Comm comm, int line, const char *fun, const char *file, PetscErrorCode n, PetscErrorType p, const char *mess, void *ctx)
{
  (void)comm, (void)line, (void)fun, (void)file, (void)ctx;
  if (p == PETSC_ERROR_INITIAL) snprintf(last_msg, sizeof last_msg, "%s", mess ? mess : "");
  return n;
}

static PetscErrorCode CheckKind(const char *name, const GeomRegion *r)
{
  const PetscInt N = 20000;
  PetscReal      lo[3], hi[3], vol, bvol, x[3], inset = 0.02;
  PetscInt       out = 0, outbox = 0, fat = 0, in = 0, bad = 0;

  PetscFunctionBeginUser;
  geom_region_bounds(r, lo, hi, &vol);
  bvol = (hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2]);
  for (PetscInt i = 0; i < N; i++) {
    const PetscReal u[3] = {U(i, 1), U(i, 2), U(i, 3)};
    geom_region_sample(r, u, 0, x);
    if (!geom_region_inside(r, x)) out++;
    for (int d = 0; d < 3; d++)
      if (x[d] < lo[d] - 1e-12 || x[d] > hi[d] + 1e-12) {
        outbox++;
        break;
      }
    geom_region_sample(r, u, inset, x);
    for (int d = 0; d < 3 && r->kind != GEOM_REGION_PATCH; d++)
      for (int s = -1; s <= 1; s += 2) {
        PetscReal y[3] = {x[0], x[1], x[2]};
        y[d] += s * inset * (1 - 1e-9);
        if (!geom_region_inside(r, y)) fat++;
      }
  }
  PetscCall(CheckEqual(CheckName("region %s: samples inside", name), out, 0));
  PetscCall(CheckEqual(CheckName("region %s: samples within the bounding box", name), outbox, 0));
  PetscCall(CheckEqual(CheckName("region %s: an inset sample keeps the sphere inside", name), fat, 0));
  for (PetscInt i = 0; i < N; i++) {
    for (int d = 0; d < 3; d++) x[d] = lo[d] + U(i, 4 + d) * (hi[d] - lo[d]);
    if (geom_region_inside(r, x)) in++;
  }
  if (r->kind != GEOM_REGION_PATCH || r->depth > 0) {
    const PetscReal f = vol / bvol, sd = PetscSqrtReal(f * (1 - f) / N);
    PetscCall(CheckCloseAbs(CheckName("region %s: inside fraction of its bounding box = volume / box volume", name), (PetscReal)in / N, f, 4 * sd + 1.0 / N));
  }
  for (PetscInt i = 0; i < N; i++) {
    PetscReal a[3], b[3];
    if (r->kind != GEOM_REGION_PATCH) {
      for (int d = 0; d < 3; d++) {
        a[d] = lo[d] + U(i, 10 + d) * (hi[d] - lo[d]);
        b[d] = lo[d] + U(i, 20 + d) * (hi[d] - lo[d]);
      }
      if (geom_region_crossed(r, a, b) != (geom_region_inside(r, a) != geom_region_inside(r, b))) bad++;
      continue;
    }
    /* through a point c of the rectangle (depth 0) along the tilted normal: crossed; stopping
       short of it, or beside the rectangle: not */
    const PetscReal u[3] = {0.05 + 0.9 * U(i, 30), 0.05 + 0.9 * U(i, 31), 0}, h = 0.01 + U(i, 32);
    GeomRegion      flat = *r;
    PetscReal       c[3];
    flat.depth = 0;
    geom_region_sample(&flat, u, 0, c);
    for (int d = 0; d < 3; d++) {
      a[d] = c[d] - h * r->n[d] + 0.001 * r->g[3 + d];
      b[d] = c[d] + 0.5 * h * r->n[d];
    }
    if (!geom_region_crossed(r, a, b) || !geom_region_crossed(r, b, a)) bad++;
    for (int d = 0; d < 3; d++) b[d] = c[d] - 0.1 * h * r->n[d];
    if (geom_region_crossed(r, a, b)) bad++;
    for (int d = 0; d < 3; d++) {
      a[d] += 1.5 * r->g[3 + d];
      b[d] = a[d] + 2 * h * r->n[d];
    }
    if (geom_region_crossed(r, a, b)) bad++;
  }
  PetscCall(CheckEqual(CheckName("region %s: crossed agrees with inside / the rectangle", name), bad, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Reads value as option opt of the kind; *ierr the reader's error code. */
static PetscErrorCode Read(const char *opt, const char *value, GeomRegionKind kind, GeomRegion *r, PetscErrorCode *ierr)
{
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsSetValue(NULL, opt, value));
  PetscOptionsBegin(PETSC_COMM_WORLD, NULL, "region test", NULL);
  PetscCall(PetscPushErrorHandler(RecordError, NULL));
  *ierr = GeomRegionOption(opt, kind, NULL, r, NULL);
  PetscCall(PetscPopErrorHandler());
  PetscOptionsEnd();
  PetscCall(PetscOptionsClearValue(NULL, opt));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  GeomRegion     r;
  PetscErrorCode ierr;
  const double   c = PetscCosReal(0.3), s = PetscSinReal(0.3);

  PetscCall(PetscInitialize(&argc, &argv, NULL, "region test"));
  {
    GeomRegion box = {GEOM_REGION_BOX, {0.1, -0.2, 0.3, 0.5, 0.4, 0.45}, {0, 0, 0}, 0};
    PetscCall(CheckKind("box", &box));
  }
  {
    const double L   = 1 / PetscSqrtReal(3.0);
    GeomRegion   cyl = {GEOM_REGION_CYLINDER, {0.2, 0.1, -0.3, L, L, L, 0.15, 0.5}, {0, 0, 0}, 0};
    PetscCall(CheckKind("cylinder", &cyl));
  }
  { /* a 0.4 x 0.25 rectangle tilted by 0.3 rad about x, with a slab 0.1 deep */
    GeomRegion patch = {GEOM_REGION_PATCH, {0.1, 0.2, 0.3, 0.4, 0, 0, 0, 0.25 * c, 0.25 * s}, {0, -s, c}, 0.1};
    PetscCall(CheckKind("patch", &patch));
  }
  PetscCall(Read("-t_patch", "0,0,1,2,0,1,0,0.5,1", GEOM_REGION_PATCH, &r, &ierr));
  PetscCall(CheckTrue("reader: patch of three corners", (PetscBool)(!ierr && r.kind == GEOM_REGION_PATCH && r.g[3] == 2 && r.g[5] == 0 && r.g[7] == 0.5 && r.n[2] == 1 && r.depth == 0), "e1 = p1 - p0, e2 = p2 - p0, n = +z"));
  PetscCall(Read("-t_outlet_patch", "0,0,1,2,0,0,0,0.5,0", GEOM_REGION_PATCH, &r, &ierr));
  PetscCall(CheckTrue("reader: an outlet's retired p,e1,e2 spelling refused, naming the corners", (PetscBool)(ierr == PETSC_ERR_ARG_WRONG && strstr(last_msg, "-t_outlet_patch takes three corners p0,p1,p2 now") && strstr(last_msg, "0,0,1,2,0,1,0,0.5,1")), last_msg));
  /* the same values for a patch that never took edges (a source's, a rectangle wall): degenerate */
  PetscCall(Read("-t_patch", "0,0,1,2,0,0,0,0.5,0", GEOM_REGION_PATCH, &r, &ierr));
  PetscCall(CheckTrue("reader: another skewed patch refused as such, no advice on a spelling it never had", (PetscBool)(ierr == PETSC_ERR_ARG_OUTOFRANGE && strstr(last_msg, "-t_patch: the edges") && !strstr(last_msg, "p,e1,e2")), last_msg));
  PetscCall(Read("-t_box", "0,0,0,1,0,1", GEOM_REGION_BOX, &r, &ierr));
  PetscCall(CheckTrue("reader: a flat box refused", (PetscBool)(ierr == PETSC_ERR_ARG_OUTOFRANGE && strstr(last_msg, "need lo < hi")), last_msg));
  PetscCall(Read("-t_cyl", "0,0,0,0,0,0,1,1", GEOM_REGION_CYLINDER, &r, &ierr));
  PetscCall(CheckTrue("reader: a cylinder of zero axis refused", (PetscBool)(ierr == PETSC_ERR_ARG_OUTOFRANGE && strstr(last_msg, "axis must be non-zero")), last_msg));
  PetscCall(Read("-t_cyl", "1,2,3,0,0,2,0.5,1", GEOM_REGION_CYLINDER, &r, &ierr));
  PetscCall(CheckTrue("reader: a cylinder's axis normalised", (PetscBool)(!ierr && r.g[5] == 1 && r.g[6] == 0.5), "axis 0,0,2 -> 0,0,1"));
  PetscCall(PetscFinalize());
  return check_failures ? 1 : 0;
}
