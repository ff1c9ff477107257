/* Inlet and outlet patches (-fluid_patch_<k>_*): a planar shape, a disc (centre, normal, radius),
 * a rectangle (three corners p0, p1, p2, as geom/region.h's patch) or a convex polygon, that is
 * an inlet (a superficial velocity U, m/s, or a mass flow, kg/s, each constant or a table in
 * time) or an outlet (a pressure, Pa).
 *   On a box face: the patch overrides the face's condition on the face points it covers (the
 *   face keeps its own condition elsewhere): an inlet point carries the flux
 *     Q_f = Q w_f / W,   W = sum_f w_f,
 *   Q the patch's volume flow (U W for a velocity, mdot/rho for a mass flow), w_f the area of the
 *   patch on face f (the polygon clipped to the face, exact; a disc is the regular 64-gon of the
 *   disc's area), so the sum over the faces is Q to round-off by construction. An outlet point
 *   (at least half of its face covered) is a Dirichlet pressure face, as a box outlet.
 *   Inside the domain (tilted, or off the faces): an inlet only, a volume source in continuity
 *     div(eps_f u) + deps/dt = S_c,   S_c = Q w_c / (W V_c),
 *   w_c the area of the patch inside cell c, V_c its volume (poisson.c's right-hand side); the
 *   source brings no momentum (the limit of a point source).
 * Maps of the face points (FluidBC.pkind, pvn, pp; fid, fw here) cover the whole face on every
 * rank: boundary ghosts of any decomposition read them, and the set-up is the same everywhere.
 * Units SI. Limits: outlets lie on a box face. */
#include "fluid/fluid_impl.h"
#include <ctype.h>

#define FLUID_PATCH_NV   64                   /* vertices of a disc's polygon, most of a polygon */
#define FLUID_PATCH_CLIP (FLUID_PATCH_NV + 8) /* room for a polygon clipped by 6 planes */

typedef struct {
  PetscInt   k;
  PetscBool  outlet, mass; /* an outlet; an inlet given as a mass flow (else a velocity) */
  PetscInt   nv;
  PetscReal  v[3 * FLUID_PATCH_NV]; /* the polygon */
  PetscInt   nq;                    /* a cylinder strip: its nq planar quads (4 vertices each), else 0 */
  PetscReal *quad;
  int        d, s;  /* the box face (axis, side); d = -1: a source inside */
  FluidBC    tab;   /* the inlet's value: vel0[0] constant, tab rows t, value, 0, 0 */
  PetscReal  value; /* the inlet's value now (m/s or kg/s) */
  PetscReal  p;     /* outlet pressure (Pa) */
  PetscReal  W;     /* sum of the weights (open area covered, m^2) */
  PetscInt   nc;    /* source: cells crossed, natural index, weight (m^2) */
  PetscInt  *cell;
  PetscReal *w;
} FluidPatch;

struct _FluidPatches {
  PetscInt    n;
  FluidPatch *p;
  PetscInt   *fid[3][2]; /* patch of each face point (-1: none) */
  PetscReal  *fw[3][2];  /* its weight: the patch's area on it times fa (m^2) */
  PetscReal  *fa[3][2];  /* the face's open-area fraction (1 without a vessel) */
  Vec         src;       /* S_c (1/s, cell Vec), NULL without sources */
  PetscReal   open[6];   /* open area of each box face (m^2; a_f summed) */
  PetscBool   sources, setup;
};

/* The options of patch k that take words (tools/gen-options.sh registers the patterns). */
static const char *const FluidPatchWordOptions[] = {"-fluid_patch_%d_type", "-fluid_patch_%d_face"};

static const char *const FluidPatchTypes[] = {"inlet", "outlet", "FluidPatchType", "FLUID_PATCH_", NULL};
static const char *const FluidPatchFaces[] = {"xlo", "xhi", "ylo", "yhi", "zlo", "zhi", "inside", "FluidPatchFace", "FLUID_PATCH_FACE_", NULL};

PetscErrorCode FluidPatchIndices(PetscInt *n, PetscInt **idx)
{
  char    *all, *tok, *save = NULL;
  PetscInt cap = 8;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(cap, idx));
  *n = 0;
  PetscCall(PetscOptionsGetAll(NULL, &all));
  for (tok = strtok_r(all, " ", &save); tok; tok = strtok_r(NULL, " ", &save)) {
    char *end;
    long  k;
    if (strncmp(tok, "-fluid_patch_", 13) || !isdigit((unsigned char)tok[13])) continue;
    k = strtol(tok + 13, &end, 10);
    if (*end != '_' || k > 999999) continue; /* the unused-option check names it */
    if (*n == cap) PetscCall(PetscRealloc(sizeof(PetscInt) * (cap *= 2), idx));
    (*idx)[(*n)++] = (PetscInt)k;
  }
  PetscCall(PetscFree(all));
  PetscCall(PetscSortRemoveDupsInt(n, *idx));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static inline void fluid_sub(const PetscReal a[3], const PetscReal b[3], PetscReal c[3])
{
  for (int e = 0; e < 3; e++) c[e] = a[e] - b[e];
}
static inline void fluid_cross(const PetscReal a[3], const PetscReal b[3], PetscReal c[3])
{
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}

/* Twice the vector area of a polygon (sum of v_i x v_i+1); its norm / 2 is the area. */
static void fluid_polygon_normal(PetscInt n, const PetscReal *v, PetscReal A[3])
{
  A[0] = A[1] = A[2] = 0;
  for (PetscInt i = 0; i < n; i++) {
    PetscReal c[3];
    fluid_cross(v + 3 * i, v + 3 * ((i + 1) % n), c);
    for (int e = 0; e < 3; e++) A[e] += c[e];
  }
}
static PetscReal fluid_polygon_area(PetscInt n, const PetscReal *v)
{
  PetscReal A[3];
  if (n < 3) return 0;
  fluid_polygon_normal(n, v, A);
  return 0.5 * PetscSqrtReal(A[0] * A[0] + A[1] * A[1] + A[2] * A[2]);
}

/* Sutherland-Hodgman: keeps the part of polygon (n, v) with sg (x_d - c) <= 0 into w. */
static PetscInt fluid_clip(PetscInt n, const PetscReal *v, int d, PetscReal c, PetscReal sg, PetscReal *w)
{
  PetscInt m = 0;
  for (PetscInt i = 0; i < n; i++) {
    const PetscReal *a = v + 3 * i, *b = v + 3 * ((i + 1) % n);
    const PetscReal  fa = sg * (a[d] - c), fb = sg * (b[d] - c);
    if (fa <= 0) {
      for (int e = 0; e < 3; e++) w[3 * m + e] = a[e];
      m++;
    }
    if ((fa < 0 && fb > 0) || (fa > 0 && fb < 0)) {
      const PetscReal t = fa / (fa - fb);
      for (int e = 0; e < 3; e++) w[3 * m + e] = a[e] + t * (b[e] - a[e]);
      w[3 * m + d] = c;
      m++;
    }
  }
  return m;
}

/* Area of the polygon inside the box [lo, hi] along the axes with mask[d]. */
static PetscReal fluid_clipped_polygon(PetscInt n, const PetscReal *v, const PetscReal lo[3], const PetscReal hi[3], const PetscBool mask[3])
{
  PetscReal a[3 * FLUID_PATCH_CLIP], b[3 * FLUID_PATCH_CLIP];

  for (PetscInt i = 0; i < 3 * n; i++) a[i] = v[i];
  for (int d = 0; d < 3 && n >= 3; d++) {
    if (!mask[d]) continue;
    n = fluid_clip(n, a, d, lo[d], -1, b);
    n = fluid_clip(n, b, d, hi[d], 1, a);
  }
  return fluid_polygon_area(n, a);
}
static PetscReal fluid_clipped_area(const FluidPatch *pt, const PetscReal lo[3], const PetscReal hi[3], const PetscBool mask[3])
{
  PetscReal A = 0;
  if (!pt->nq) return fluid_clipped_polygon(pt->nv, pt->v, lo, hi, mask);
  for (PetscInt q = 0; q < pt->nq; q++) A += fluid_clipped_polygon(4, pt->quad + 12 * q, lo, hi, mask);
  return A;
}

/* The bounding box of the patch's polygon or quads. */
static void fluid_patch_bounds(const FluidPatch *pt, PetscReal blo[3], PetscReal bhi[3])
{
  const PetscInt   n = pt->nq ? 4 * pt->nq : pt->nv;
  const PetscReal *v = pt->nq ? pt->quad : pt->v;
  for (int e = 0; e < 3; e++) blo[e] = PETSC_MAX_REAL, bhi[e] = -PETSC_MAX_REAL;
  for (PetscInt i = 0; i < n; i++)
    for (int e = 0; e < 3; e++) blo[e] = PetscMin(blo[e], v[3 * i + e]), bhi[e] = PetscMax(bhi[e], v[3 * i + e]);
}

/* A strip of a cylinder's surface, cx,cy,cz,ax,ay,az,R,L[,th0,th1]: centre, axis, radius,
 * length, angles (degrees, default 0,360) about the axis from e1, the x direction (y when the
 * axis is along x) across the axis, towards e2 = a x e1; as nq planar quads whose chords keep
 * the strip's area (radius R' = R (dth/2) / sin(dth/2) for quads of angle dth). */
static PetscErrorCode FluidPatchCylinder(Fluid fl, const char *opt, const PetscReal *g, PetscInt n, FluidPatch *pt)
{
  const PetscReal an = PetscSqrtReal(g[3] * g[3] + g[4] * g[4] + g[5] * g[5]);
  const PetscReal t0 = n == 10 ? g[8] * PETSC_PI / 180 : 0, t1 = n == 10 ? g[9] * PETSC_PI / 180 : 2 * PETSC_PI;
  PetscReal       ax[3], e1[3], e2[3], ref[3] = {1, 0, 0};

  PetscFunctionBeginUser;
  PetscCheck(n == 8 || n == 10, fl->comm, PETSC_ERR_ARG_SIZ, "%s takes cx,cy,cz,ax,ay,az,R,L[,theta0,theta1]; got %d values", opt, (int)n);
  PetscCheck(an > 0 && g[6] > 0 && g[7] > 0 && t1 > t0 && t1 - t0 <= 2 * PETSC_PI + 1e-12, fl->comm, PETSC_ERR_ARG_OUTOFRANGE, "%s: the axis must be non-zero, R and L > 0 (m), theta0 < theta1 <= theta0 + 360 (degrees)", opt);
  for (int e = 0; e < 3; e++) ax[e] = g[3 + e] / an;
  if (PetscAbsReal(ax[0]) > 0.9) ref[0] = 0, ref[1] = 1;
  const PetscReal r = ref[0] * ax[0] + ref[1] * ax[1] + ref[2] * ax[2];
  for (int e = 0; e < 3; e++) e1[e] = ref[e] - r * ax[e];
  const PetscReal l1 = PetscSqrtReal(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
  for (int e = 0; e < 3; e++) e1[e] /= l1;
  fluid_cross(ax, e1, e2);
  pt->nq              = PetscMax(4, (PetscInt)PetscCeilReal(FLUID_PATCH_NV * (t1 - t0) / (2 * PETSC_PI)));
  const PetscReal dth = (t1 - t0) / pt->nq;
  const PetscReal Rp  = g[6] * 0.5 * dth / PetscSinReal(0.5 * dth);
  PetscCall(PetscMalloc1(12 * pt->nq, &pt->quad));
  for (PetscInt q = 0; q < pt->nq; q++)
    for (int k = 0; k < 4; k++) {
      const PetscReal th = t0 + (q + (k == 1 || k == 2 ? 1 : 0)) * dth, h = (k >= 2 ? 0.5 : -0.5) * g[7];
      for (int e = 0; e < 3; e++) pt->quad[12 * q + 3 * k + e] = g[e] + h * ax[e] + Rp * (PetscCosReal(th) * e1[e] + PetscSinReal(th) * e2[e]);
    }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The shape options of patch pt (exactly one of disc, rect, polygon) into its polygon. */
static PetscErrorCode FluidPatchReadShape(PetscOptionItems *PetscOptionsObject, Fluid fl, FluidPatch *pt)
{
  char      od[64], orr[64], op[64], oc[64];
  PetscReal g[3 * FLUID_PATCH_NV + 3];
  PetscInt  n = 3 * FLUID_PATCH_NV + 3, given = 0;
  PetscBool set;
  PetscReal A[3], tol;

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(od, sizeof od, "-fluid_patch_%d_disc", (int)pt->k));
  PetscCall(PetscSNPrintf(orr, sizeof orr, "-fluid_patch_%d_rect", (int)pt->k));
  PetscCall(PetscSNPrintf(op, sizeof op, "-fluid_patch_%d_polygon", (int)pt->k));
  PetscCall(SableOptionsRealN(od, "A disc patch: centre, normal, radius cx,cy,cz,nx,ny,nz,R", "m", g, 0, 7, &set));
  if (set) {
    const PetscReal nn = PetscSqrtReal(g[3] * g[3] + g[4] * g[4] + g[5] * g[5]);
    PetscCheck(nn > 0 && g[6] > 0, fl->comm, PETSC_ERR_ARG_OUTOFRANGE, "%s %g,%g,%g,%g,%g,%g,%g: the normal must be non-zero and the radius > 0 (m)", od, (double)g[0], (double)g[1], (double)g[2], (double)g[3], (double)g[4], (double)g[5], (double)g[6]);
    PetscReal e1[3], e2[3], n1[3] = {g[3] / nn, g[4] / nn, g[5] / nn}, t[3] = {1, 0, 0};
    if (PetscAbsReal(n1[0]) > 0.6) t[0] = 0, t[1] = 1;
    fluid_cross(n1, t, e1);
    const PetscReal l1 = PetscSqrtReal(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
    for (int e = 0; e < 3; e++) e1[e] /= l1;
    fluid_cross(n1, e1, e2);
    /* the regular polygon of the disc's area: R' = R sqrt(2 pi / (N sin(2 pi / N))) */
    const PetscReal Rp = g[6] * PetscSqrtReal(2 * PETSC_PI / (FLUID_PATCH_NV * PetscSinReal(2 * PETSC_PI / FLUID_PATCH_NV)));
    pt->nv             = FLUID_PATCH_NV;
    for (PetscInt i = 0; i < FLUID_PATCH_NV; i++) {
      const PetscReal a = 2 * PETSC_PI * i / FLUID_PATCH_NV;
      for (int e = 0; e < 3; e++) pt->v[3 * i + e] = g[e] + Rp * (PetscCosReal(a) * e1[e] + PetscSinReal(a) * e2[e]);
    }
    given++;
  }
  PetscCall(SableOptionsRealN(orr, "A rectangle patch: corners p0, p1, p2 (p1 - p0 perpendicular to p2 - p0)", "m", g, 0, 9, &set));
  if (set) {
    PetscReal e1[3], e2[3];
    fluid_sub(g + 3, g, e1);
    fluid_sub(g + 6, g, e2);
    const PetscReal l1 = PetscSqrtReal(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]), l2 = PetscSqrtReal(e2[0] * e2[0] + e2[1] * e2[1] + e2[2] * e2[2]);
    PetscCheck(l1 > 0 && l2 > 0 && PetscAbsReal(e1[0] * e2[0] + e1[1] * e2[1] + e1[2] * e2[2]) <= 1e-9 * l1 * l2, fl->comm, PETSC_ERR_ARG_OUTOFRANGE, "%s: p1 - p0 and p2 - p0 must be non-zero and perpendicular (m)", orr);
    pt->nv = 4;
    for (int e = 0; e < 3; e++) {
      pt->v[e]     = g[e];
      pt->v[3 + e] = g[3 + e];
      pt->v[6 + e] = g[3 + e] + e2[e];
      pt->v[9 + e] = g[6 + e];
    }
    given++;
  }
  PetscCall(SableOptionsRealArray(op, "A convex polygon patch: its vertices in order x1,y1,z1,x2,... (3 to 64, in one plane)", "m", g, 0, &n, &set));
  if (set) {
    PetscCheck(n % 3 == 0 && n >= 9 && n <= 3 * FLUID_PATCH_NV, fl->comm, PETSC_ERR_ARG_SIZ, "%s: give 3 to %d vertices of 3 coordinates; got %d values", op, FLUID_PATCH_NV, (int)n);
    pt->nv = n / 3;
    PetscCall(PetscArraycpy(pt->v, g, n));
    given++;
  }
  PetscCall(PetscSNPrintf(oc, sizeof oc, "-fluid_patch_%d_cylinder", (int)pt->k));
  n = 10;
  PetscCall(SableOptionsRealArray(oc, "A strip of a cylinder's surface (a source inside): centre, axis, radius, length, angles about the axis from x (y for an axis along x) cx,cy,cz,ax,ay,az,R,L[,theta0,theta1]", "m, degrees", g, 0, &n, &set));
  if (set) {
    PetscCall(FluidPatchCylinder(fl, oc, g, n, pt));
    given++;
  }
  PetscCheck(given == 1, fl->comm, PETSC_ERR_ARG_WRONG, "-fluid_patch_%d_*: give exactly one shape of %s, %s, %s, %s (got %d)", (int)pt->k, od, orr, op, oc, (int)given);
  if (pt->nq) PetscFunctionReturn(PETSC_SUCCESS);
  /* planar and convex: every corner turns the same way as the polygon's normal, every vertex in its plane */
  fluid_polygon_normal(pt->nv, pt->v, A);
  const PetscReal An = PetscSqrtReal(A[0] * A[0] + A[1] * A[1] + A[2] * A[2]);
  PetscCheck(An > 0, fl->comm, PETSC_ERR_ARG_OUTOFRANGE, "-fluid_patch_%d: the shape has no area", (int)pt->k);
  tol = 1e-9 * PetscSqrtReal(An);
  for (PetscInt i = 0; i < pt->nv; i++) {
    PetscReal a[3], b[3], c[3], r[3];
    fluid_sub(pt->v + 3 * ((i + 1) % pt->nv), pt->v + 3 * i, a);
    fluid_sub(pt->v + 3 * ((i + 2) % pt->nv), pt->v + 3 * ((i + 1) % pt->nv), b);
    fluid_cross(a, b, c);
    fluid_sub(pt->v + 3 * i, pt->v, r);
    PetscCheck(c[0] * A[0] + c[1] * A[1] + c[2] * A[2] > 0 && PetscAbsReal(r[0] * A[0] + r[1] * A[1] + r[2] * A[2]) / An <= tol, fl->comm, PETSC_ERR_ARG_OUTOFRANGE, "%s: the vertices must make a convex polygon in one plane, in order (vertex %d breaks it)", op, (int)((i + 1) % pt->nv) + 1);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The box face the polygon lies on ((d, s) with every vertex within 1e-6 h of the face's
 * plane), or d = -1. */
static void FluidPatchFindFace(Fluid fl, const FluidPatch *pt, int *d, int *s)
{
  *d = -1;
  *s = 0;
  for (int e = 0; e < 3 && *d < 0 && !pt->nq; e++)
    for (int t = 0; t < 2 && *d < 0; t++) {
      const PetscReal x  = t ? fl->dom->hi[e] : fl->dom->lo[e];
      PetscBool       on = PETSC_TRUE;
      for (PetscInt i = 0; i < pt->nv; i++) on = (PetscBool)(on && PetscAbsReal(pt->v[3 * i + e] - x) <= 1e-6 * fl->dom->h[e]);
      if (on) *d = e, *s = t;
    }
}

/* The value options of patch pt (its type known). */
static PetscErrorCode FluidPatchReadValue(PetscOptionItems *PetscOptionsObject, Fluid fl, FluidPatch *pt)
{
  char      ov[64], om[64], ovt[64], omt[64], opr[64];
  PetscReal U = 0, m = 0, buf[2 * FLUID_INLET_TABLE_MAX + 2];
  PetscBool sv, sm, svt, smt, sp;
  PetscInt  nv = 2 * FLUID_INLET_TABLE_MAX + 2, nm = nv, n;

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(ov, sizeof ov, "-fluid_patch_%d_velocity", (int)pt->k));
  PetscCall(PetscSNPrintf(om, sizeof om, "-fluid_patch_%d_mass_flow", (int)pt->k));
  PetscCall(PetscSNPrintf(ovt, sizeof ovt, "-fluid_patch_%d_velocity_table", (int)pt->k));
  PetscCall(PetscSNPrintf(omt, sizeof omt, "-fluid_patch_%d_mass_flow_table", (int)pt->k));
  PetscCall(PetscSNPrintf(opr, sizeof opr, "-fluid_patch_%d_pressure", (int)pt->k));
  PetscCall(SableOptionsReal(ov, "Inlet patch: superficial velocity into the domain (the volume flow over the open area; along the normal for a source)", "m/s", NULL, 0, &U, &sv));
  PetscCall(SableOptionsReal(om, "Inlet patch: mass flow into the domain", "kg/s", NULL, 0, &m, &sm));
  PetscCall(SableOptionsRealArray(ovt, "Inlet patch: velocity from each time on: t1,U1,t2,U2,... (as -fluid_bc_<face>_velocity_table)", "s, m/s", buf, 0, &nv, &svt));
  if (!svt) PetscCall(SableOptionsRealArray(omt, "Inlet patch: mass flow from each time on: t1,m1,t2,m2,...", "s, kg/s", buf, 0, &nm, &smt));
  else {
    PetscReal tmp[2];
    PetscInt  nt = 2;
    PetscCall(SableOptionsRealArray(omt, "Inlet patch: mass flow from each time on: t1,m1,t2,m2,...", "s, kg/s", tmp, 0, &nt, &smt));
  }
  PetscCall(SableOptionsReal(opr, "Outlet patch: pressure (default -fluid_outlet_pressure)", "Pa", NULL, fl->bc.p_out, &pt->p, &sp));
  if (pt->outlet) {
    PetscCheck(!sv && !sm && !svt && !smt, fl->comm, PETSC_ERR_ARG_WRONG, "%s: patch %d is an outlet; it takes a pressure (%s), not a velocity or a mass flow", sv ? ov : sm  ? om
                                                                                                                                                                        : svt ? ovt
                                                                                                                                                                              : omt,
               (int)pt->k, opr);
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCheck(!sp, fl->comm, PETSC_ERR_ARG_WRONG, "%s: patch %d is an inlet; it takes a velocity or a mass flow, not a pressure", opr, (int)pt->k);
  PetscCheck(!((sv || svt) && (sm || smt)), fl->comm, PETSC_ERR_ARG_WRONG, "-fluid_patch_%d: give a velocity (%s) or a mass flow (%s), not both", (int)pt->k, ov, om);
  PetscCheck(sv || sm || svt || smt, fl->comm, PETSC_ERR_ARG_WRONG, "-fluid_patch_%d: an inlet needs %s or %s (or a table)", (int)pt->k, ov, om);
  pt->mass        = (PetscBool)(sm || smt);
  pt->tab.vel0[0] = pt->mass ? m : U;
  pt->tab.vel[0]  = pt->tab.vel0[0];
  pt->tab.row     = -1;
  n               = pt->mass ? nm : nv;
  const char *opt = pt->mass ? omt : ovt;
  if (svt || smt) {
    PetscCheck(n > 0 && n % 2 == 0 && n <= 2 * FLUID_INLET_TABLE_MAX, fl->comm, PETSC_ERR_ARG_SIZ, "%s takes rows of 2 values t,value, 1 to %d rows; got %d values", opt, FLUID_INLET_TABLE_MAX, (int)n);
    pt->tab.ntab = n / 2;
    for (PetscInt r = 0; r < pt->tab.ntab; r++) {
      pt->tab.tab[4 * r]     = buf[2 * r];
      pt->tab.tab[4 * r + 1] = buf[2 * r + 1];
      PetscCheck(buf[2 * r] >= 0 && (r == 0 || buf[2 * r] > buf[2 * r - 2]), fl->comm, PETSC_ERR_ARG_OUTOFRANGE, "%s: times must be >= 0 and increase strictly (row %d: %g s)", opt, (int)r + 1, (double)buf[2 * r]);
    }
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* -help without patches: the family's lines, for k = 0 (nothing is read). */
static PetscErrorCode FluidPatchHelp(Fluid fl)
{
  PetscReal g[3 * FLUID_PATCH_NV] = {0}, x = 0;
  PetscInt  n = 3 * FLUID_PATCH_NV, e = 0;

  PetscFunctionBeginUser;
  PetscOptionsBegin(fl->comm, NULL, "Fluid inlet and outlet patches (any k >= 0)", NULL);
  PetscCall(SableOptionsEnum("-fluid_patch_0_type", "Patch k: inlet or outlet", FluidPatchTypes, 2, e, &e, NULL));
  PetscCall(SableOptionsRealN("-fluid_patch_0_disc", "A disc patch: centre, normal, radius cx,cy,cz,nx,ny,nz,R", "m", g, 0, 7, NULL));
  PetscCall(SableOptionsRealN("-fluid_patch_0_rect", "A rectangle patch: corners p0, p1, p2 (p1 - p0 perpendicular to p2 - p0)", "m", g, 0, 9, NULL));
  PetscCall(SableOptionsRealArray("-fluid_patch_0_polygon", "A convex polygon patch: its vertices in order x1,y1,z1,x2,... (3 to 64, in one plane)", "m", g, 0, &n, NULL));
  PetscCall(SableOptionsRealArray("-fluid_patch_0_cylinder", "A strip of a cylinder's surface (a source inside): centre, axis, radius, length, angles about the axis from x (y for an axis along x) cx,cy,cz,ax,ay,az,R,L[,theta0,theta1]", "m, degrees", g, 0, &n, NULL));
  PetscCall(SableOptionsEnum("-fluid_patch_0_face", "The box face the patch lies on, or inside (a volume source); default: found from the shape", FluidPatchFaces, 7, 6, &e, NULL));
  PetscCall(SableOptionsReal("-fluid_patch_0_velocity", "Inlet patch: superficial velocity into the domain (the volume flow over the open area; along the normal for a source)", "m/s", NULL, x, &x, NULL));
  PetscCall(SableOptionsReal("-fluid_patch_0_mass_flow", "Inlet patch: mass flow into the domain", "kg/s", NULL, x, &x, NULL));
  PetscCall(SableOptionsRealArray("-fluid_patch_0_velocity_table", "Inlet patch: velocity from each time on: t1,U1,t2,U2,...", "s, m/s", g, 0, &n, NULL));
  PetscCall(SableOptionsRealArray("-fluid_patch_0_mass_flow_table", "Inlet patch: mass flow from each time on: t1,m1,t2,m2,...", "s, kg/s", g, 0, &n, NULL));
  PetscCall(SableOptionsReal("-fluid_patch_0_pressure", "Outlet patch: pressure (default -fluid_outlet_pressure)", "Pa", NULL, fl->bc.p_out, &x, NULL));
  PetscOptionsEnd();
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FluidSetFromOptionsPatch(Fluid fl)
{
  PetscInt *idx, n;
  PetscBool help;

  PetscFunctionBeginUser;
  PetscCall(FluidDestroyPatches(fl));
  PetscCall(FluidPatchIndices(&n, &idx));
  if (!n) {
    PetscCall(PetscFree(idx));
    PetscCall(PetscOptionsHasHelp(NULL, &help));
    if (help) PetscCall(FluidPatchHelp(fl));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(PetscNew(&fl->patch));
  PetscCall(PetscCalloc1(n, &fl->patch->p));
  fl->patch->n = n;
  PetscOptionsBegin(fl->comm, NULL, "Fluid inlet and outlet patches", NULL);
  for (PetscInt i = 0; i < n; i++) {
    FluidPatch *pt = &fl->patch->p[i];
    char        ot[64], of[64];
    PetscInt    type = 0, face = 6;
    PetscBool   set, fset;
    int         d, s;

    pt->k = idx[i];
    PetscCall(PetscSNPrintf(ot, sizeof ot, FluidPatchWordOptions[0], (int)pt->k));
    PetscCall(PetscSNPrintf(of, sizeof of, FluidPatchWordOptions[1], (int)pt->k));
    PetscCall(SableOptionsEnum(ot, "Patch k: inlet or outlet", FluidPatchTypes, 2, type, &type, &set));
    PetscCheck(set, fl->comm, PETSC_ERR_ARG_WRONG, "-fluid_patch_%d_* options are given without %s inlet|outlet", (int)pt->k, ot);
    pt->outlet = (PetscBool)(type == 1);
    PetscCall(FluidPatchReadShape(PetscOptionsObject, fl, pt));
    PetscCall(SableOptionsEnum(of, "The box face the patch lies on, or inside (a volume source); default: found from the shape", FluidPatchFaces, 7, face, &face, &fset));
    FluidPatchFindFace(fl, pt, &d, &s);
    if (fset && face < 6) {
      PetscCheck(d == face / 2 && s == face % 2, fl->comm, PETSC_ERR_ARG_OUTOFRANGE, "%s %s: the shape of patch %d does not lie on that face (%c = %g m)", of, FluidPatchFaces[face], (int)pt->k, "xyz"[face / 2], (double)(face % 2 ? fl->dom->hi[face / 2] : fl->dom->lo[face / 2]));
    } else if (fset) d = -1;
    pt->d = d;
    pt->s = s;
    PetscCheck(d >= 0 || !pt->outlet, fl->comm, PETSC_ERR_SUP, "-fluid_patch_%d: an outlet must lie on a box face (a stated limit); this one lies on none", (int)pt->k);
    PetscCheck(d < 0 || !FluidPeriodic(fl, d), fl->comm, PETSC_ERR_ARG_OUTOFRANGE, "-fluid_patch_%d lies on the %s face, but the %c axis is periodic", (int)pt->k, FluidPatchFaces[2 * d + s], "xyz"[d]);
    PetscCall(FluidPatchReadValue(PetscOptionsObject, fl, pt));
    if (pt->outlet) fl->pois.singular = PETSC_FALSE;
    else if (d >= 0) fl->bc.has_inlet = PETSC_TRUE;
    else fl->patch->sources = PETSC_TRUE;
  }
  PetscOptionsEnd();
  PetscCall(PetscFree(idx));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The open-area fraction of every face point of box face (d, s) on every rank (1 without a
 * vessel): each owner writes its points, summed over ranks (one non-zero per point, exact). */
static PetscErrorCode FluidPatchFaceOpen(Fluid fl, int d, int s, PetscReal *fa)
{
  const FluidGrid *g = &fl->g;
  const int        a = (d + 1) % 3, b = (d + 2) % 3;
  const PetscInt   n = g->N[a] * g->N[b];
  PetscReal       *loc;
  PetscInt         q[3];

  PetscFunctionBeginUser;
  for (PetscInt k = 0; k < n; k++) fa[k] = 1;
  if (!fl->ves.cut) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscCalloc1(n, &loc));
  if (s ? g->xs[d] + g->xm[d] == g->N[d] : g->xs[d] == 0) {
    const PetscScalar ****ar;
    PetscCall(DMDAVecGetArrayDOFRead(g->fda, fl->ves.area, &ar));
    q[d] = s ? g->N[d] : 0;
    for (q[b] = g->xs[b]; q[b] < g->xs[b] + g->xm[b]; q[b]++)
      for (q[a] = g->xs[a]; q[a] < g->xs[a] + g->xm[a]; q[a]++) loc[q[a] + g->N[a] * q[b]] = PetscRealPart(ar[q[2]][q[1]][q[0]][d]);
    PetscCall(DMDAVecRestoreArrayDOFRead(g->fda, fl->ves.area, &ar));
  }
  PetscCallMPI(MPIU_Allreduce(loc, fa, (PetscMPIInt)n, MPIU_REAL, MPIU_SUM, fl->comm));
  PetscCall(PetscFree(loc));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The open-volume fraction of the n cells (natural indices) on every rank, as above. */
static PetscErrorCode FluidPatchCellOpen(Fluid fl, PetscInt n, const PetscInt *cell, PetscReal *v)
{
  const FluidGrid   *g = &fl->g;
  const PetscScalar *vol;
  PetscReal         *loc;

  PetscFunctionBeginUser;
  PetscCall(PetscCalloc1(n, &loc));
  PetscCall(VecGetArrayRead(fl->ves.vol, &vol));
  for (PetscInt j = 0; j < n; j++) {
    PetscInt c[3] = {cell[j] % g->N[0], (cell[j] / g->N[0]) % g->N[1], cell[j] / (g->N[0] * g->N[1])}, own = 1;
    for (int e = 0; e < 3; e++) own = own && c[e] >= g->xs[e] && c[e] < g->xs[e] + g->xm[e];
    if (own) loc[j] = PetscRealPart(vol[((c[2] - g->xs[2]) * g->xm[1] + (c[1] - g->xs[1])) * g->xm[0] + (c[0] - g->xs[0])]);
  }
  PetscCall(VecRestoreArrayRead(fl->ves.vol, &vol));
  PetscCallMPI(MPIU_Allreduce(loc, v, (PetscMPIInt)n, MPIU_REAL, MPIU_SUM, fl->comm));
  PetscCall(PetscFree(loc));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The face maps of patch i on its box face (d, s). */
static PetscErrorCode FluidPatchCoverFace(Fluid fl, PetscInt i)
{
  FluidPatches   *P  = fl->patch;
  FluidPatch     *pt = &P->p[i];
  const int       d = pt->d, s = pt->s, a = (d + 1) % 3, b = (d + 2) % 3;
  FluidBC        *bc = &fl->bc.face[d][s];
  const PetscInt  Na = fl->g.N[a], Nb = fl->g.N[b];
  const PetscReal ha = fl->g.h[a], hb = fl->g.h[b];
  PetscReal       lo[3], hi[3], blo[3] = {PETSC_MAX_REAL, PETSC_MAX_REAL, PETSC_MAX_REAL}, bhi[3] = {-PETSC_MAX_REAL, -PETSC_MAX_REAL, -PETSC_MAX_REAL};
  PetscBool       mask[3] = {PETSC_FALSE, PETSC_FALSE, PETSC_FALSE};

  PetscFunctionBeginUser;
  if (!bc->pkind) {
    PetscCall(PetscCalloc3(Na * Nb, &bc->pkind, Na * Nb, &bc->pvn, Na * Nb, &bc->pp));
    PetscCall(PetscMalloc3(Na * Nb, &P->fid[d][s], Na * Nb, &P->fw[d][s], Na * Nb, &P->fa[d][s]));
    for (PetscInt q = 0; q < Na * Nb; q++) P->fid[d][s][q] = -1, P->fw[d][s][q] = 0;
    PetscCall(FluidPatchFaceOpen(fl, d, s, P->fa[d][s]));
  }
  fluid_patch_bounds(pt, blo, bhi);
  mask[a] = mask[b]  = PETSC_TRUE;
  const PetscInt ia0 = PetscMax(0, (PetscInt)PetscFloorReal((blo[a] - fl->g.lo[a]) / ha)), ia1 = PetscMin(Na - 1, (PetscInt)PetscFloorReal((bhi[a] - fl->g.lo[a]) / ha));
  const PetscInt ib0 = PetscMax(0, (PetscInt)PetscFloorReal((blo[b] - fl->g.lo[b]) / hb)), ib1 = PetscMin(Nb - 1, (PetscInt)PetscFloorReal((bhi[b] - fl->g.lo[b]) / hb));
  pt->W = 0;
  for (PetscInt ib = ib0; ib <= ib1; ib++)
    for (PetscInt ia = ia0; ia <= ia1; ia++) {
      const PetscInt q = ia + Na * ib;
      lo[a] = fl->g.lo[a] + ia * ha, hi[a] = lo[a] + ha;
      lo[b] = fl->g.lo[b] + ib * hb, hi[b] = lo[b] + hb;
      lo[d] = hi[d]     = 0;
      const PetscReal A = fluid_clipped_area(pt, lo, hi, mask);
      if (A <= 1e-12 * ha * hb || (pt->outlet && A < 0.5 * ha * hb) || P->fa[d][s][q] == 0) continue; /* an outlet takes the faces it covers at least half; closed faces stay closed */
      PetscCheck(P->fid[d][s][q] < 0, fl->comm, PETSC_ERR_ARG_OUTOFRANGE, "-fluid_patch_%d overlaps -fluid_patch_%d on the %s face (face point %d,%d)", (int)pt->k, (int)P->p[P->fid[d][s][q]].k, FluidPatchFaces[2 * d + s], (int)ia, (int)ib);
      P->fid[d][s][q] = i;
      P->fw[d][s][q]  = (pt->outlet ? ha * hb : A) * P->fa[d][s][q];
      bc->pkind[q]    = (signed char)(pt->outlet ? FLUID_BC_OUTLET : FLUID_BC_INLET);
      bc->pp[q]       = pt->p;
      pt->W += P->fw[d][s][q];
    }
  PetscCheck(pt->W > 0, fl->comm, PETSC_ERR_ARG_OUTOFRANGE, "-fluid_patch_%d lies on the %s face but covers no open face of the grid%s", (int)pt->k, FluidPatchFaces[2 * d + s], pt->outlet ? " (an outlet takes the faces it covers at least half)" : "");
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The cells source patch i crosses and its area in each. */
static PetscErrorCode FluidPatchCoverCells(Fluid fl, PetscInt i)
{
  FluidPatch *pt     = &fl->patch->p[i];
  PetscReal   blo[3] = {PETSC_MAX_REAL, PETSC_MAX_REAL, PETSC_MAX_REAL}, bhi[3] = {-PETSC_MAX_REAL, -PETSC_MAX_REAL, -PETSC_MAX_REAL};
  PetscInt    c0[3], c1[3], cap = 16, c[3];
  PetscBool   mask[3] = {PETSC_TRUE, PETSC_TRUE, PETSC_TRUE};

  PetscFunctionBeginUser;
  fluid_patch_bounds(pt, blo, bhi);
  for (int e = 0; e < 3; e++) {
    c0[e] = PetscMax(0, (PetscInt)PetscFloorReal((blo[e] - fl->g.lo[e]) / fl->g.h[e]));
    c1[e] = PetscMin(fl->g.N[e] - 1, (PetscInt)PetscFloorReal((bhi[e] - fl->g.lo[e]) / fl->g.h[e]));
    /* flat on a plane of cell faces: the cells above it only (the two sides would both take it) */
    const PetscReal sl = (blo[e] - fl->g.lo[e]) / fl->g.h[e], sh = (bhi[e] - fl->g.lo[e]) / fl->g.h[e];
    if (sh - sl <= 1e-9 && PetscAbsReal(sl - PetscFloorReal(sl + 0.5)) <= 1e-9) c0[e] = c1[e] = PetscMin(fl->g.N[e] - 1, (PetscInt)PetscFloorReal(sl + 0.5));
  }
  PetscCall(PetscMalloc2(cap, &pt->cell, cap, &pt->w));
  pt->nc = 0;
  pt->W  = 0;
  for (c[2] = c0[2]; c[2] <= c1[2]; c[2]++)
    for (c[1] = c0[1]; c[1] <= c1[1]; c[1]++)
      for (c[0] = c0[0]; c[0] <= c1[0]; c[0]++) {
        PetscReal lo[3], hi[3];
        for (int e = 0; e < 3; e++) lo[e] = fl->g.lo[e] + c[e] * fl->g.h[e], hi[e] = lo[e] + fl->g.h[e];
        const PetscReal A = fluid_clipped_area(pt, lo, hi, mask);
        if (A <= 1e-12 * fl->g.h[0] * fl->g.h[1]) continue;
        if (pt->nc == cap) {
          PetscInt  *nc;
          PetscReal *nw;
          PetscCall(PetscMalloc2(2 * cap, &nc, 2 * cap, &nw));
          PetscCall(PetscArraycpy(nc, pt->cell, cap));
          PetscCall(PetscArraycpy(nw, pt->w, cap));
          PetscCall(PetscFree2(pt->cell, pt->w));
          pt->cell = nc, pt->w = nw, cap *= 2;
        }
        pt->cell[pt->nc] = c[0] + fl->g.N[0] * (c[1] + fl->g.N[1] * c[2]);
        pt->w[pt->nc++]  = A;
        pt->W += A;
      }
  if (fl->ves.cut) { /* with a vessel: the patch's area in the open part, approximated as area x vol_c */
    PetscReal *v;
    PetscCall(PetscMalloc1(pt->nc, &v));
    PetscCall(FluidPatchCellOpen(fl, pt->nc, pt->cell, v));
    pt->W = 0;
    for (PetscInt j = 0; j < pt->nc; j++) pt->W += (pt->w[j] *= v[j]);
    PetscCall(PetscFree(v));
  }
  PetscCheck(pt->W > 0, fl->comm, PETSC_ERR_ARG_OUTOFRANGE, "-fluid_patch_%d lies on no box face and crosses no open cell of the grid", (int)pt->k);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* With a vessel cutting the grid: a box face declared inlet or outlet must keep some open area,
 * and an open inlet (a face, a patch or a source) needs an open outlet. A vessel with neither
 * (closed, or periodic and driven by a pressure gradient) is allowed. */
static PetscErrorCode FluidCheckOpenBoundaries(Fluid fl)
{
  const FluidGrid *g       = &fl->g;
  PetscReal        loc[12] = {0}, open[12], in = 0, out = 0;
  PetscInt         q[3];

  PetscFunctionBeginUser;
  for (int d = 0; d < 3; d++)
    for (int s = 0; s < 2; s++) {
      const int a = (d + 1) % 3, b = (d + 2) % 3;
      if (FluidPeriodic(fl, d) || (s ? g->xs[d] + g->xm[d] != g->N[d] : g->xs[d] != 0)) continue;
      q[d] = s ? g->N[d] : 0;
      for (q[b] = g->xs[b]; q[b] < g->xs[b] + g->xm[b]; q[b]++)
        for (q[a] = g->xs[a]; q[a] < g->xs[a] + g->xm[a]; q[a]++) {
          const FluidBCType t  = fluid_bc_at(fl, d, s, q);
          const PetscReal   Af = fl->ves.aloc[FluidFaceOff(g, q[0], q[1], q[2]) + d] * g->h[a] * g->h[b];
          if (t == FLUID_BC_INLET) loc[2 * (2 * d + s)] += Af;
          if (t == FLUID_BC_OUTLET) loc[2 * (2 * d + s) + 1] += Af;
        }
    }
  PetscCallMPI(MPIU_Allreduce(loc, open, 12, MPIU_REAL, MPIU_SUM, fl->comm));
  for (int f = 0; f < 6; f++) {
    const FluidBCType t = fl->bc.face[f / 2][f % 2].type;
    in += open[2 * f];
    out += open[2 * f + 1];
    PetscCheck(!(t == FLUID_BC_INLET && open[2 * f] == 0) && !(t == FLUID_BC_OUTLET && open[2 * f + 1] == 0), fl->comm, PETSC_ERR_ARG_INCOMP, "-fluid_bc_%s %s: the vessel closes every face of it (open area 0 m^2); open the vessel there or give the %s as a -fluid_patch_<k> where the vessel is open", FluidPatchFaces[f], FluidBCNames[t], FluidBCNames[t]);
  }
  for (PetscInt i = 0; fl->patch && i < fl->patch->n; i++)
    if (fl->patch->p[i].d < 0) in += fl->patch->p[i].W;
  PetscCheck(in == 0 || out > 0, fl->comm, PETSC_ERR_ARG_INCOMP, "the fluid has open inlets (%g m^2) but the vessel leaves no open outlet (0 m^2): give an outlet (-fluid_bc_<face> outlet or -fluid_patch_<k>_type outlet) where the vessel is open", (double)in);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FluidSetUpPatches(Fluid fl)
{
  PetscFunctionBeginUser;
  if (fl->patch && !fl->patch->setup) {
    for (PetscInt i = 0; i < fl->patch->n; i++) {
      if (fl->patch->p[i].d >= 0) PetscCall(FluidPatchCoverFace(fl, i));
      else PetscCall(FluidPatchCoverCells(fl, i));
    }
    fl->patch->setup = PETSC_TRUE;
    for (int f = 0; f < 6; f++) {
      const int       d = f / 2, a = (d + 1) % 3, b = (d + 2) % 3;
      const PetscInt  nq = fl->g.N[a] * fl->g.N[b];
      const PetscReal Af = fl->g.h[a] * fl->g.h[b];
      PetscReal      *fa;
      fl->patch->open[f] = 0;
      if (FluidPeriodic(fl, d)) continue;
      PetscCall(PetscMalloc1(nq, &fa));
      PetscCall(FluidPatchFaceOpen(fl, d, f % 2, fa));
      for (PetscInt q = 0; q < nq; q++) fl->patch->open[f] += fa[q] * Af;
      PetscCall(PetscFree(fa));
    }
    for (PetscInt i = 0; i < fl->patch->n; i++) fl->patch->p[i].value = PETSC_MAX_REAL; /* every value is new */
    PetscCall(FluidUpdatePatches(fl, fl->clock.time, NULL));
  }
  if (fl->ves.cut) PetscCall(FluidCheckOpenBoundaries(fl));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. After a checkpoint restored the clock: every patch's value, face velocities and
 * source at the clock's time, as the interrupted run held them. */
PetscErrorCode FluidPatchesAtClock(Fluid fl)
{
  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < fl->patch->n; i++) fl->patch->p[i].value = PETSC_MAX_REAL; /* every value is new */
  PetscCall(FluidUpdatePatches(fl, fl->clock.time, NULL));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective after the set-up. The inlets' values at time t (their tables), their face
 * velocities and sources; *changed (may be NULL) is set when a value changed. */
PetscErrorCode FluidUpdatePatches(Fluid fl, PetscReal t, PetscBool *changed)
{
  FluidPatches *P  = fl->patch;
  PetscBool     ch = PETSC_FALSE;

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < P->n; i++) {
    FluidPatch *pt = &P->p[i];
    PetscReal   v[3];
    if (pt->outlet) continue;
    pt->tab.row = fluid_inlet_at(&pt->tab, fl->inlet.linear, t, v);
    if (v[0] != pt->value || !P->setup) ch = PETSC_TRUE;
    pt->value = v[0];
  }
  if (!P->setup || !ch) {
    if (changed && ch) *changed = PETSC_TRUE;
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  for (int d = 0; d < 3; d++)
    for (int s = 0; s < 2; s++) {
      const PetscInt  a = (d + 1) % 3, b = (d + 2) % 3, nq = fl->g.N[a] * fl->g.N[b];
      const PetscReal Af = fl->g.h[a] * fl->g.h[b];
      FluidBC        *bc = &fl->bc.face[d][s];
      if (!bc->pkind) continue;
      for (PetscInt q = 0; q < nq; q++) {
        const PetscInt i = P->fid[d][s][q];
        if (i < 0 || P->p[i].outlet) continue;
        const FluidPatch *pt = &P->p[i];
        const PetscReal   Q  = pt->mass ? pt->value / fl->prop.rho : pt->value * pt->W;             /* m^3/s */
        bc->pvn[q]           = (s ? -1 : 1) * Q * (P->fw[d][s][q] / pt->W) / (P->fa[d][s][q] * Af); /* the flux a_f U A = Q w_f / W */
      }
    }
  if (P->sources) {
    const FluidGrid *g = &fl->g;
    const PetscReal  V = g->h[0] * g->h[1] * g->h[2];
    PetscScalar     *S;
    if (!P->src) PetscCall(DMCreateGlobalVector(g->cda, &P->src));
    PetscCall(VecSet(P->src, 0));
    PetscCall(VecGetArray(P->src, &S));
    for (PetscInt i = 0; i < P->n; i++) {
      const FluidPatch *pt = &P->p[i];
      const PetscReal   Q  = pt->mass ? pt->value / fl->prop.rho : pt->value * pt->W;
      if (pt->d >= 0) continue;
      for (PetscInt j = 0; j < pt->nc; j++) {
        PetscInt c[3] = {pt->cell[j] % g->N[0], (pt->cell[j] / g->N[0]) % g->N[1], pt->cell[j] / (g->N[0] * g->N[1])}, own = 1;
        for (int e = 0; e < 3; e++) own = own && c[e] >= g->xs[e] && c[e] < g->xs[e] + g->xm[e];
        if (own) S[((c[2] - g->xs[2]) * g->xm[1] + (c[1] - g->xs[1])) * g->xm[0] + (c[0] - g->xs[0])] += Q * (pt->w[j] / pt->W) / V;
      }
    }
    PetscCall(VecRestoreArray(P->src, &S));
  }
  if (changed) *changed = PETSC_TRUE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FluidPatchSource(Fluid fl, Vec *src)
{
  PetscFunctionBeginUser;
  *src = NULL;
  if (!fl->patch || !fl->patch->sources) PetscFunctionReturn(PETSC_SUCCESS);
  if (!fl->patch->src) { /* after a redistribution: on the new layout */
    PetscCall(DMCreateGlobalVector(fl->g.cda, &fl->patch->src));
    for (PetscInt i = 0; i < fl->patch->n; i++) fl->patch->p[i].value = PETSC_MAX_REAL;
    PetscCall(FluidUpdatePatches(fl, fl->clock.time, NULL));
  }
  *src = fl->patch->src;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* After a redistribution: the source Vec is made again on the new layout at its next use. */
PetscErrorCode FluidPatchesRelayout(Fluid fl)
{
  PetscFunctionBeginUser;
  if (fl->patch) PetscCall(VecDestroy(&fl->patch->src));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FluidDestroyPatches(Fluid fl)
{
  FluidPatches *P = fl->patch;

  PetscFunctionBeginUser;
  if (!P) PetscFunctionReturn(PETSC_SUCCESS);
  for (int d = 0; d < 3; d++)
    for (int s = 0; s < 2; s++) {
      FluidBC *bc = &fl->bc.face[d][s];
      PetscCall(PetscFree3(bc->pkind, bc->pvn, bc->pp));
      PetscCall(PetscFree3(P->fid[d][s], P->fw[d][s], P->fa[d][s]));
    }
  for (PetscInt i = 0; i < P->n; i++) {
    PetscCall(PetscFree2(P->p[i].cell, P->p[i].w));
    PetscCall(PetscFree(P->p[i].quad));
  }
  PetscCall(VecDestroy(&P->src));
  PetscCall(PetscFree(P->p));
  PetscCall(PetscFree(fl->patch));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Not collective. With inlet patches on one box face after the set-up: their superficial
 * velocity over that face's open area, U_d = Q / A_open (sign: into the domain), and n = 1;
 * else n = 0 (init.c, a uniform initial fluid). */
PetscErrorCode FluidPatchInletVelocity(Fluid fl, PetscReal U[3], PetscInt *n)
{
  FluidPatches *P    = fl->patch;
  int           face = -1;
  PetscReal     Q    = 0;

  PetscFunctionBeginUser;
  *n = 0;
  if (!P || !P->setup) PetscFunctionReturn(PETSC_SUCCESS);
  for (PetscInt i = 0; i < P->n; i++) {
    const FluidPatch *pt = &P->p[i];
    if (pt->outlet || pt->d < 0) continue;
    PetscCheck(face < 0 || face == 2 * pt->d + pt->s, fl->comm, PETSC_ERR_ARG_INCOMP, "-fluid_patch_%d: inlet patches on two box faces (%s, %s); a uniform initial fluid needs the inlets on one face", (int)pt->k, FluidPatchFaces[face], FluidPatchFaces[2 * pt->d + pt->s]);
    face = 2 * pt->d + pt->s;
    Q += pt->mass ? pt->value / fl->prop.rho : pt->value * pt->W;
  }
  if (face < 0 || P->open[face] <= 0) PetscFunctionReturn(PETSC_SUCCESS);
  for (int k = 0; k < 3; k++) U[k] = 0;
  U[face / 2] = (face % 2 ? -1 : 1) * Q / P->open[face];
  *n          = 1;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FluidGetPatchCount(Fluid fl, PetscInt *n)
{
  PetscFunctionBeginUser;
  *n = fl->patch ? fl->patch->n : 0;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. Patch i's option index, mean pressure over it (Pa: the face pressure, 1.5 p1 -
 * 0.5 p2 along the normal plus the drag's shift (faceshift.c), the set pressure on outlet faces;
 * a source: the cells' pressure) and
 * its mass flow measured from the face fluxes rho eps_f u A (kg/s; into the domain at an inlet,
 * out of it at an outlet; a source: rho sum S_c V_c). */
PetscErrorCode FluidPatchMeasure(Fluid fl, PetscInt i, PetscInt *k, PetscReal *pmean, PetscReal *mdot)
{
  const FluidGrid   *g      = &fl->g;
  FluidPatches      *P      = fl->patch;
  const FluidPatch  *pt     = &P->p[i];
  PetscReal          loc[2] = {0, 0}, sum[2];
  const PetscScalar *p, *eps, *vol = NULL;
  PetscBool          any;

  PetscFunctionBeginUser;
  *k = pt->k;
  PetscCall(FluidFaceShiftUpdate(fl, &any));
  PetscCall(VecGetArrayRead(fl->fld.p, &p));
  PetscCall(VecGetArrayRead(fl->fld.eps_old, &eps));
  if (fl->ves.cut) PetscCall(VecGetArrayRead(fl->ves.vol, &vol));
  if (pt->d < 0) { /* a source: its pressure over the cells it crosses, its flow as imposed on them */
    const PetscReal Q = pt->mass ? pt->value / fl->prop.rho : pt->value * pt->W;
    for (PetscInt j = 0; j < pt->nc; j++) {
      PetscInt c[3] = {pt->cell[j] % g->N[0], (pt->cell[j] / g->N[0]) % g->N[1], pt->cell[j] / (g->N[0] * g->N[1])}, own = 1;
      for (int e = 0; e < 3; e++) own = own && c[e] >= g->xs[e] && c[e] < g->xs[e] + g->xm[e];
      if (!own) continue;
      loc[0] += pt->w[j] * PetscRealPart(p[((c[2] - g->xs[2]) * g->xm[1] + (c[1] - g->xs[1])) * g->xm[0] + (c[0] - g->xs[0])]);
      loc[1] += fl->prop.rho * Q * (pt->w[j] / pt->W);
    }
  } else if (pt->s ? g->xs[pt->d] + g->xm[pt->d] == g->N[pt->d] : g->xs[pt->d] == 0) {
    const int             d = pt->d, s = pt->s, a = (d + 1) % 3, b = (d + 2) % 3;
    const PetscReal       Af = g->h[a] * g->h[b];
    const PetscScalar ****u;
    PetscInt              q[3], c1[3], c2[3];
    PetscCall(DMDAVecGetArrayDOFRead(g->fda, fl->fld.u, &u));
    q[d] = s ? g->N[d] : 0;
    for (q[b] = g->xs[b]; q[b] < g->xs[b] + g->xm[b]; q[b]++)
      for (q[a] = g->xs[a]; q[a] < g->xs[a] + g->xm[a]; q[a]++) {
        const PetscInt m = q[a] + g->N[a] * q[b];
        if (P->fid[d][s][m] != i) continue;
        for (int e = 0; e < 3; e++) c1[e] = c2[e] = q[e] - g->xs[e];
        c1[d]              = s ? g->xm[d] - 1 : 0;
        c2[d]              = s ? g->xm[d] - 2 : 1;
        const PetscInt  o1 = (c1[2] * g->xm[1] + c1[1]) * g->xm[0] + c1[0], o2 = (c2[2] * g->xm[1] + c2[1]) * g->xm[0] + c2[0];
        const PetscBool line   = (PetscBool)(!vol || PetscRealPart(vol[o2]) > 0); /* the second centre closed by the vessel: the first alone */
        const PetscReal pf     = pt->outlet ? pt->p : (line ? 1.5 * PetscRealPart(p[o1]) - 0.5 * PetscRealPart(p[o2]) : PetscRealPart(p[o1])) + FluidFaceShiftPoint(fl, d, s, m);
        const PetscReal fl_out = (s ? 1 : -1) * P->fa[d][s][m] * PetscRealPart(eps[o1] * u[q[2]][q[1]][q[0]][d]) * Af; /* m^3/s out of the domain */
        loc[0] += P->fw[d][s][m] * pf;
        loc[1] += fl->prop.rho * (pt->outlet ? fl_out : -fl_out);
      }
    PetscCall(DMDAVecRestoreArrayDOFRead(g->fda, fl->fld.u, &u));
  }
  if (vol) PetscCall(VecRestoreArrayRead(fl->ves.vol, &vol));
  PetscCall(VecRestoreArrayRead(fl->fld.eps_old, &eps));
  PetscCall(VecRestoreArrayRead(fl->fld.p, &p));
  PetscCallMPI(MPIU_Allreduce(loc, sum, 2, MPIU_REAL, MPIU_SUM, fl->comm));
  *pmean = sum[0] / pt->W;
  *mdot  = sum[1];
  PetscFunctionReturn(PETSC_SUCCESS);
}
