/* Regions (public header): the one type of the places a user names by coordinates, for the
 * particle sources, the outlets and the monitor's boxes.
 *
 * A GeomRegion is a box (lo, hi), a finite cylinder (centre c, unit axis a, radius R, length L)
 * or a patch: the rectangle p0 + s e1 + t e2, s, t in [0,1], e1 = p1 - p0 perpendicular to
 * e2 = p2 - p0, with the unit normal n = e1 x e2 / (|e1| |e2|), and a depth: the slab
 * p + h n, 0 <= h <= depth, in front of it is its volume (0: the flat patch). Kernels, all pure
 * and header-only (the outlets call them per particle and step):
 *   inside(x): closed (a point on the boundary is inside); a patch: in its slab;
 *   crossed(a, b): the segment a -> b crosses the region's surface; a patch: its centre passes
 *     through the rectangle, either way (strictly from one side, n.(x - p0) > 0, to the other,
 *     the crossing point taken on the straight segment); a box or a cylinder: exactly one end
 *     inside;
 *   sample(u, inset, x): the point of the three uniforms u in [0,1) from the caller's own
 *     generator, at least inset from the boundary (a sphere of that radius wholly inside);
 *     uniform in a box, a cylinder (radius by sqrt(u0), angle by u1, along the axis by u2) and a
 *     patch's slab (e1, e2, n by u0, u1, u2);
 *   bounds(lo, hi): the bounding box; volume (a flat patch has none).
 * The option reader (region.c) is the one syntax of every user: -<name> xlo,ylo,zlo,xhi,yhi,zhi
 * for a box, cx,cy,cz,ax,ay,az,R,L for a cylinder, p0x,p0y,p0z,p1x,p1y,p1z,p2x,p2y,p2z (three
 * corners, as the rectangle walls -dem_rect_<k>) for a patch. Units: the caller's (SI). */
#pragma once
#include <petscsys.h>
#include "geom/quat.h"

typedef enum {
  GEOM_REGION_BOX,
  GEOM_REGION_CYLINDER,
  GEOM_REGION_PATCH
} GeomRegionKind;
extern const char *const GeomRegionKinds[]; /* "box", "cylinder", "patch" */

typedef struct {
  GeomRegionKind kind;
  PetscReal      g[9];  /* box lo, hi; cylinder c, unit a, R, L; patch p0, e1, e2 */
  PetscReal      n[3];  /* patch: unit normal e1 x e2 / (|e1| |e2|) */
  PetscReal      depth; /* patch: depth of the slab in front of it (0: flat) */
} GeomRegion;

static inline PetscBool geom_region_inside(const GeomRegion *r, const PetscReal x[3])
{
  const PetscReal *g = r->g;
  PetscReal        y[3];
  for (int d = 0; d < 3; d++) y[d] = x[d] - g[d];
  if (r->kind == GEOM_REGION_BOX) return (PetscBool)(x[0] >= g[0] && x[1] >= g[1] && x[2] >= g[2] && x[0] <= g[3] && x[1] <= g[4] && x[2] <= g[5]);
  if (r->kind == GEOM_REGION_CYLINDER) {
    const PetscReal h = convex_dot(y, g + 3), q = convex_dot(y, y) - h * h;
    return (PetscBool)(PetscAbsReal(h) <= 0.5 * g[7] && q <= g[6] * g[6]);
  }
  const PetscReal a = convex_dot(y, g + 3) / convex_dot(g + 3, g + 3), b = convex_dot(y, g + 6) / convex_dot(g + 6, g + 6), h = convex_dot(y, r->n);
  return (PetscBool)(a >= 0 && a <= 1 && b >= 0 && b <= 1 && h >= 0 && h <= r->depth);
}

static inline PetscBool geom_region_crossed(const GeomRegion *r, const PetscReal a[3], const PetscReal b[3])
{
  if (r->kind != GEOM_REGION_PATCH) return (PetscBool)(geom_region_inside(r, a) != geom_region_inside(r, b));
  const PetscReal *p = r->g, *e1 = r->g + 3, *e2 = r->g + 6;
  const PetscReal  u[3] = {a[0] - p[0], a[1] - p[1], a[2] - p[2]}, w[3] = {b[0] - p[0], b[1] - p[1], b[2] - p[2]};
  const PetscReal  s0 = convex_dot(u, r->n), s1 = convex_dot(w, r->n);
  if ((s0 > 0) == (s1 > 0)) return PETSC_FALSE;
  const PetscReal f = s0 / (s0 - s1), c[3] = {u[0] + f * (w[0] - u[0]), u[1] + f * (w[1] - u[1]), u[2] + f * (w[2] - u[2])};
  const PetscReal s = convex_dot(c, e1) / convex_dot(e1, e1), t = convex_dot(c, e2) / convex_dot(e2, e2);
  return (PetscBool)(s >= 0 && s <= 1 && t >= 0 && t <= 1);
}

static inline void geom_region_sample(const GeomRegion *r, const PetscReal u[3], PetscReal inset, PetscReal x[3])
{
  const PetscReal *g = r->g;
  if (r->kind == GEOM_REGION_BOX) {
    for (int k = 0; k < 3; k++) x[k] = g[k] + inset + u[k] * (g[3 + k] - g[k] - 2 * inset);
  } else if (r->kind == GEOM_REGION_CYLINDER) {
    const PetscReal *a = g + 3, e[3] = {PetscAbsReal(a[0]) < 0.6 ? 1 : 0, PetscAbsReal(a[0]) < 0.6 ? 0 : 1, 0};
    PetscReal        b1[3], b2[3];
    convex_cross(a, e, b1);
    const PetscReal l = PetscSqrtReal(convex_dot(b1, b1)), rho = (g[6] - inset) * PetscSqrtReal(u[0]), phi = 2 * PETSC_PI * u[1], h = -0.5 * g[7] + inset + u[2] * (g[7] - 2 * inset);
    for (int k = 0; k < 3; k++) b1[k] /= l;
    convex_cross(a, b1, b2);
    for (int k = 0; k < 3; k++) x[k] = g[k] + h * a[k] + rho * (PetscCosReal(phi) * b1[k] + PetscSinReal(phi) * b2[k]);
  } else {
    const PetscReal l1 = PetscSqrtReal(convex_dot(g + 3, g + 3)), l2 = PetscSqrtReal(convex_dot(g + 6, g + 6));
    const PetscReal s1 = (inset + u[0] * (l1 - 2 * inset)) / l1, s2 = (inset + u[1] * (l2 - 2 * inset)) / l2, h = inset + u[2] * PetscMax(0.0, r->depth - 2 * inset);
    for (int k = 0; k < 3; k++) x[k] = g[k] + s1 * g[3 + k] + s2 * g[6 + k] + h * r->n[k];
  }
}

/* The bounding box (a cylinder's exactly: its two end discs; a patch's: the 8 corners of its
 * slab) and the volume (m^3). */
static inline void geom_region_bounds(const GeomRegion *r, PetscReal lo[3], PetscReal hi[3], PetscReal *vol)
{
  const PetscReal *g = r->g;
  if (r->kind == GEOM_REGION_BOX) {
    for (int d = 0; d < 3; d++) {
      lo[d] = g[d];
      hi[d] = g[3 + d];
    }
    *vol = (hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2]);
  } else if (r->kind == GEOM_REGION_CYLINDER) {
    for (int d = 0; d < 3; d++) {
      const PetscReal e = PetscAbsReal(g[3 + d]) * 0.5 * g[7] + g[6] * PetscSqrtReal(PetscMax(0.0, 1 - g[3 + d] * g[3 + d]));
      lo[d]             = g[d] - e;
      hi[d]             = g[d] + e;
    }
    *vol = PETSC_PI * g[6] * g[6] * g[7];
  } else {
    for (int d = 0; d < 3; d++) lo[d] = hi[d] = g[d];
    for (int c = 1; c < 8; c++)
      for (int d = 0; d < 3; d++) {
        const PetscReal x = g[d] + (c & 1 ? g[3 + d] : 0) + (c & 2 ? g[6 + d] : 0) + (c & 4 ? r->depth * r->n[d] : 0);
        lo[d]             = PetscMin(lo[d], x);
        hi[d]             = PetscMax(hi[d], x);
      }
    *vol = PetscSqrtReal(convex_dot(g + 3, g + 3) * convex_dot(g + 6, g + 6)) * r->depth;
  }
}

/* The option reader (region.c), inside the caller's PetscOptionsBegin block; collective on
 * that block's communicator (its errors). GeomRegionOption reads the option opt (its full name,
 * "-mon_box_3") as a region of the given kind: -help shows text (NULL: the kind's syntax) and
 * "m"; a box needs lo < hi on every axis, a cylinder a non-zero axis (normalised) and R, L > 0,
 * a patch edges p1 - p0 and p2 - p0 non-zero and perpendicular (cosine within 1e-9; values that
 * read as the retired spelling p,e1,e2 get the corners to give). *set: given (r untouched if
 * not). GeomRegionOptions reads the options opt[kind] of the kinds the caller allows (NULL: not
 * allowed), in kind order, and refuses more than one given. */
typedef struct {
  const char *opt[3];  /* the option of each kind ("-dem_outlet_2_box"), NULL: not allowed */
  const char *text[3]; /* its -help line (NULL: the kind's syntax) */
} GeomRegionSpec;
#define GeomRegionOption(opt, kind, text, r, set) GeomRegionOption_Private(PetscOptionsObject, opt, kind, text, r, set)
#define GeomRegionOptions(spec, r, set)           GeomRegionOptions_Private(PetscOptionsObject, spec, r, set)
PetscErrorCode GeomRegionOption_Private(PetscOptionItems *, const char[], GeomRegionKind, const char[], GeomRegion *, PetscBool *);
PetscErrorCode GeomRegionOptions_Private(PetscOptionItems *, const GeomRegionSpec *, GeomRegion *, PetscBool *);
