/* Convex planar polygon walls: quadrilaterals (-dem_quad_<k>) and the four trapezoidal plates of
 * a square truncated-pyramid hopper (-dem_hopper).
 *
 * A polygon v0..v(n-1) is stored as its plane (point v0, unit normal n by Newell's formula, so
 * that the vertices run counter-clockwise seen from the granular side) and, per edge e from v_e
 * to v_(e+1), the unit in-plane normal m_e = n x (v_(e+1) - v_e) / |..| pointing inside. A point
 * y projects inside the polygon when (y - v_e).m_e >= 0 for every e (convexity makes this exact).
 * Checked at set-up: the vertices lie within 1e-6 L of their plane (L the largest edge), every
 * turn (v_(e+1) - v_e) x (v_(e+2) - v_(e+1)) has the sign of n (convex and in order), area > 0.
 *
 * Contacts (geom/surface_polygon.h): a sphere whose centre is in front of the
 * plane touches the face where its centre projects inside the polygon, with overlap r - (x - v0).n
 * (the rule of -dem_rect_<k>). Where the centre projects outside across an edge, the edge is
 * either a joint with a neighbour wall (no contact: the neighbour's face takes over, as for
 * rectangles) or a free rim: then the sphere touches the nearest point of that edge segment,
 * with normal from the centre to that point (a sphere on the orifice edge of a hopper is held
 * by the edge, never falls through it). -dem_quad_<k> edges are all joints (the rectangle rule);
 * the hopper's four bottom edges, the orifice, are rims. Convex particles use the face rule only.
 * Units SI. */
#include "dem/dem_walls.h"

/* Adds the convex polygon v[3*nv] (the first edges given rim[] = PETSC_TRUE are free rims). */
static PetscErrorCode DemWallAddPolygon(Dem dem, const char *opt, PetscInt nv, const double *v, const PetscBool *rim)
{
  double   n[3] = {0, 0, 0}, L = 0, nn;
  DemWall *w;

  PetscFunctionBeginUser;
  PetscCheck(nv >= 3 && nv <= SURFACE_POLY_MAX, dem->comm, PETSC_ERR_ARG_OUTOFRANGE, "%s: %" PetscInt_FMT " vertices, must be in [3,%d]", opt, nv, SURFACE_POLY_MAX);
  for (PetscInt e = 0; e < nv; e++) { /* Newell's normal: twice the vector area */
    const double *a = v + 3 * e, *b = v + 3 * ((e + 1) % nv);
    const double  d[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    double        c[3];
    dem_cross(a, b, c);
    for (int k = 0; k < 3; k++) n[k] += c[k];
    L = PetscMax(L, sqrt(dem_dot(d, d)));
  }
  nn = sqrt(dem_dot(n, n));
  PetscCheck(L > 0 && nn > 1e-12 * L * L, dem->comm, PETSC_ERR_ARG_OUTOFRANGE, "%s: the polygon has zero area (repeated or collinear vertices, or crossing edges)", opt);
  for (int k = 0; k < 3; k++) n[k] /= nn;
  double mean = 0; /* offset of the mean plane (normal n) from v0 */
  for (PetscInt e = 0; e < nv; e++) {
    const double d[3] = {v[3 * e] - v[0], v[3 * e + 1] - v[1], v[3 * e + 2] - v[2]};
    mean += dem_dot(d, n) / nv;
  }
  for (PetscInt e = 0; e < nv; e++) {
    const double d[3] = {v[3 * e] - v[0], v[3 * e + 1] - v[1], v[3 * e + 2] - v[2]};
    const double off  = PetscAbsReal(dem_dot(d, n) - mean);
    PetscCheck(off <= 1e-6 * L, dem->comm, PETSC_ERR_ARG_OUTOFRANGE, "%s: the vertices are not planar: vertex %" PetscInt_FMT " is %g m off their mean plane (tolerance 1e-6 x the longest edge = %g m)", opt, e, off, 1e-6 * L);
  }
  for (PetscInt e = 0; e < nv; e++) {
    const double *a = v + 3 * e, *b = v + 3 * ((e + 1) % nv), *c = v + 3 * ((e + 2) % nv);
    const double  ab[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, bc[3] = {c[0] - b[0], c[1] - b[1], c[2] - b[2]};
    double        t[3];
    dem_cross(ab, bc, t);
    PetscCheck(dem_dot(t, n) > 1e-9 * L * L, dem->comm, PETSC_ERR_ARG_OUTOFRANGE, "%s: the polygon is not convex, or its vertices are not in order around it (turn at vertex %" PetscInt_FMT " is %s)", opt, (e + 1) % nv, dem_dot(t, n) < 0 ? "the wrong way" : "straight");
  }
  PetscCall(DemWallAdd(dem, opt, v, n, (double[3]){0, 0, 0}));
  w         = &dem->walls.wall[dem->walls.nwall - 1];
  w->s.kind = SURFACE_POLYGON;
  w->s.nv   = nv;
  for (PetscInt e = 0; e < nv; e++) {
    const double *a = v + 3 * e, *b = v + 3 * ((e + 1) % nv);
    const double  d[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    double        m[3];
    dem_cross(n, d, m);
    const double lm = sqrt(dem_dot(m, m));
    for (int k = 0; k < 3; k++) {
      w->s.vert[e][k] = a[k];
      w->s.en[e][k]   = m[k] / lm;
    }
    w->s.rim[e] = rim ? rim[e] : PETSC_FALSE;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The four trapezoids of a square truncated pyramid, axis vertical, facing inward and up:
 * h = cx,cy,ztop,halftop,zbot,halfbot. Each plate: bottom edge (the rim) first. */
static PetscErrorCode DemWallAddHopper(Dem dem, const PetscReal h[6])
{
  const double cx = h[0], cy = h[1], zt = h[2], at = h[3], zb = h[4], ab = h[5];

  PetscFunctionBeginUser;
  PetscCheck(zt > zb, dem->comm, PETSC_ERR_ARG_OUTOFRANGE, "-dem_hopper: top z %g must exceed bottom z %g (m)", (double)zt, (double)zb);
  PetscCheck(ab > 0 && at > ab, dem->comm, PETSC_ERR_ARG_OUTOFRANGE, "-dem_hopper: half-widths top %g and bottom %g must satisfy top > bottom > 0 (m)", (double)at, (double)ab);
  /* plate facing +x (the x-low side), then rotated by 90 degrees about the vertical three times */
  const double    tpl[4][3] = {{-ab, -ab, zb}, {-ab, ab, zb}, {-at, at, zt}, {-at, -at, zt}};
  const PetscBool rim[4]    = {PETSC_TRUE, PETSC_FALSE, PETSC_FALSE, PETSC_FALSE};
  for (int q = 0; q < 4; q++) {
    double v[12];
    for (int c = 0; c < 4; c++) {
      double x = tpl[c][0], y = tpl[c][1];
      for (int r = 0; r < q; r++) { /* (x, y) -> (-y, x) */
        const double t = x;
        x              = -y;
        y              = t;
      }
      v[3 * c]     = cx + x;
      v[3 * c + 1] = cy + y;
      v[3 * c + 2] = tpl[c][2];
    }
    PetscCall(DemWallAddPolygon(dem, "-dem_hopper", 4, v, rim));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Reads -dem_quad_<k> (k = 0..9), -dem_quad_<k>_friction, -dem_hopper, -dem_hopper_friction
 * inside the walls' options block (walls.c). */
PetscErrorCode DemWallPolygonOptions(PetscOptionItems *PetscOptionsObject, Dem dem)
{
  PetscReal v[12], h[6];
  PetscBool set, help;
  char      opt[64], optf[80];

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsHasHelp(NULL, &help)); /* -help: the friction of every wall listed */
  for (int k = 0; k < 10; k++) {
    PetscCall(PetscSNPrintf(opt, sizeof opt, "-dem_quad_%d", k));
    PetscCall(SableOptionsRealN(opt, "Convex planar quadrilateral wall: x0,y0,z0,...,x3,y3,z3 in order around it, counter-clockwise seen from the granular side", "m", v, 0, 12, &set));
    if (set) {
      double dv[12];
      for (int c = 0; c < 12; c++) dv[c] = v[c];
      PetscCall(DemWallAddPolygon(dem, opt, 4, dv, NULL));
    }
    PetscCall(PetscSNPrintf(optf, sizeof optf, "-dem_quad_%d_friction", k));
    if (set || help) PetscCall(DemWallFrictionOption(PetscOptionsObject, dem, optf, 1, set ? dem->walls.nwall - 1 : -1));
  }
  PetscCall(SableOptionsRealN("-dem_hopper", "Square truncated-pyramid hopper, four plates facing inward: centre x,y, top z, top half-width, bottom z, bottom half-width; wall angle from the horizontal atan((ztop-zbot)/(htop-hbot))", "m", h, 0, 6, &set));
  if (set) {
    PetscCall(DemWallAddHopper(dem, h));
    PetscCall(DemWallFrictionOption(PetscOptionsObject, dem, "-dem_hopper_friction", 1, dem->walls.nwall - 4));
    for (int q = 1; q < 4; q++) dem->walls.wall[dem->walls.nwall - 4 + q].mu = dem->walls.wall[dem->walls.nwall - 4].mu;
  } else if (help) PetscCall(DemWallFrictionOption(PetscOptionsObject, dem, "-dem_hopper_friction", 1, -1));
  PetscFunctionReturn(PETSC_SUCCESS);
}
