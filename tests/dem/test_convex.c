/* Convex particles in the DEM: rest, conservation, rotation.
 * 1. A cube (a = 1 cm) dropped flat, on an edge and on a corner onto a plane, with friction and
 *    damping, comes to rest on a face: its centre at a/2 above the plane within twice the static
 *    overlap m g / kn (plus 1e-6 a), and one body axis vertical to 1e-3 rad.
 * 2. Free flight of an asymmetric rigid body (box 1 x 0.6 x 0.3 cm read from a vertex file),
 *    spun close to its intermediate axis so it tumbles (Dzhanibekov flips): over 1e5 steps the
 *    world angular momentum J W stays constant to 1e-10 relative (the splitting in rotation.c
 *    rotates q and L by the same orthogonal maps), and the energy to 1e-4.
 * 3. Tumbling bodies colliding with each other in free space (boxes and icosahedra, e = 1, no
 *    friction, linear law, dt = Tc/100): total linear and angular momentum (orbital + spin)
 *    conserved to 1e-10 (forces and torques are equal and opposite about the common contact
 *    point), energy drift (mean of the last tenth against the first) below 1e-4 over 1e5 steps
 *    for gentle impacts; faster impacts (0.12 m/s, 10 rad/s): below 1e-4 with the exact depth and
 *    the support point (an energy gradient); the defaults drift by about 5e-3 there, reported on
 *    a NOTE line (a known limitation of the patch point, not a check).
 *    Boxes only, whose pairs use the exact separating-axis narrow phase: momenta checked as above,
 *    the energy drift only reported (1.1e-3 with it and with libccd's MPR alike, above the 1e-4
 *    of 1e-4: the drift comes from the contact point model, see src/geom/README.md).
 * 4. A finite rectangle wall (-dem_rect_0, 3a x 3a): a cube (and a sphere) dropped on it rests
 *    at a/2 (r) above it; one dropped beside it falls past it. */
#include "dem_common.h"
#include "geom/quat.h"

static const double A = 0.01, RHO = 2500;

static PetscErrorCode DropCube(const char *label, const double q[4], double *z, double *tilt, double *bound)
{
  char         opts[1024];
  Domain       dom;
  Dem          dem;
  const double kn = 2e4, m = RHO * A * A * A;

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(opts, sizeof opts, "-domain_lo -0.05,-0.05,0 -domain_hi 0.05,0.05,0.05 -dem_shape cube -dem_shape_size %g -dem_density %g -dem_contact_law linear -dem_kn %g -dem_restitution 0.3 -dem_friction 0.5 -dem_dt 1e-5 -dem_plane_0 0,0,0,0,0,1", A, RHO, kn));
  PetscCall(TestDemCreate(opts, &dom, &dem));
  DemParticle p = {.id = 0, .shape = 0, .x = {0, 0, 1.5 * A}, .v = {0.02, 0, 0}, .w = {0, 0, 0}};
  for (int k = 0; k < 4; k++) p.q[k] = q[k];
  PetscCall(DemAddParticle(dem, &p));
  PetscCall(DemSetUp(dem));
  for (int s = 0; s < 150000; s++) PetscCall(DemStep(dem));
  p = TestGet(dem, 0);
  double R[9], best = 0;
  convex_quat_to_matrix(p.q, R);
  for (int k = 0; k < 3; k++) best = PetscMax(best, PetscAbsReal(R[6 + k])); /* z component of body axis k */
  *z     = p.x[2];
  *tilt  = PetscAcosReal(PetscMin(1.0, best));
  *bound = 2 * m * 9.81 / kn + 1e-6 * A;
  PetscCall(PetscInfo(NULL, "%s: z %g v %g\n", label, p.x[2], p.v[2]));
  PetscCall(TestDemDestroy(&dom, &dem));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* world angular momentum of one particle: R J R^T w, J principal (moments ascending) */
static void SpinMomentum(const DemParticle *p, const double J[3], double L[3])
{
  double R[9], wb[3];
  convex_quat_to_matrix(p->q, R);
  convex_mat_tvec(R, p->w, wb);
  for (int k = 0; k < 3; k++) wb[k] *= J[k];
  convex_mat_vec(R, wb, L);
}

static PetscErrorCode WriteBoxFile(const char *path, double lx, double ly, double lz)
{
  FILE *fp = fopen(path, "w");

  PetscFunctionBeginUser;
  PetscCheck(fp, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "cannot write %s", path);
  for (int c = 0; c < 8; c++) fprintf(fp, "%.17g %.17g %.17g\n", (c & 1 ? 0.5 : -0.5) * lx, (c & 2 ? 0.5 : -0.5) * ly, (c & 4 ? 0.5 : -0.5) * lz);
  fclose(fp);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* principal moments (ascending) of the 1 x 0.6 x 0.3 A box and of the icosahedron of edge A/2 */
static void Moments(PetscInt shape, double J[3], double *m)
{
  if (shape == 0) {
    const double lx = A, ly = 0.6 * A, lz = 0.3 * A;
    *m   = RHO * lx * ly * lz;
    J[0] = *m * (ly * ly + lz * lz) / 12;
    J[1] = *m * (lx * lx + lz * lz) / 12;
    J[2] = *m * (lx * lx + ly * ly) / 12;
  } else {
    const double a = 0.5 * A, phi = 0.5 * (1 + sqrt(5.0));
    *m   = RHO * 5.0 / 12.0 * (3 + sqrt(5.0)) * a * a * a;
    J[0] = J[1] = J[2] = *m * phi * phi * a * a / 10;
  }
}

/* total linear momentum P and angular momentum about the origin L */
static void Momenta(Dem dem, double P[3], double L[3])
{
  PetscInt n;
  DemGetLocalCount(dem, &n);
  for (int k = 0; k < 3; k++) P[k] = L[k] = 0;
  for (PetscInt i = 0; i < n; i++) {
    DemParticle p = {0};
    double      J[3], m, Ls[3], mv[3], o[3];
    DemGetParticle(dem, i, &p);
    Moments(p.shape, J, &m);
    SpinMomentum(&p, J, Ls);
    for (int k = 0; k < 3; k++) mv[k] = m * p.v[k];
    convex_cross(p.x, mv, o);
    for (int k = 0; k < 3; k++) {
      P[k] += mv[k];
      L[k] += Ls[k] + o[k];
    }
  }
}

static double Dist(const double a[3], const double b[3], double scale)
{
  double d[3];
  convex_sub(a, b, d);
  return convex_norm(d) / scale;
}

static PetscErrorCode FreeFlight(void)
{
  char     opts[1024];
  Domain   dom;
  Dem      dem;
  DemStats st;
  double   P0[3], L0[3], P[3], L[3], e0, emax = 0, lmax = 0;

  PetscFunctionBeginUser;
  PetscCall(WriteBoxFile("test_convex_box.txt", A, 0.6 * A, 0.3 * A));
  PetscCall(PetscSNPrintf(opts, sizeof opts, "-domain_lo -0.05,-0.05,-0.05 -domain_hi 0.05,0.05,0.05 -dem_shape polyhedron -dem_shape_file test_convex_box.txt -dem_density %g -dem_kn 1e4 -dem_restitution 1 -dem_friction 0 -dem_gravity 0,0,0 -dem_dt 1e-5", RHO));
  PetscCall(TestDemCreate(opts, &dom, &dem));
  DemParticle  p  = {.id = 0, .shape = 0, .x = {0, 0, 0}, .v = {0.01, 0, 0}, .w = {0.3, 20, 0.2}, .q = {0.9, 0.1, 0.3, -0.2}};
  const double qn = sqrt(0.81 + 0.01 + 0.09 + 0.04);
  for (int k = 0; k < 4; k++) p.q[k] /= qn;
  PetscCall(DemAddParticle(dem, &p));
  PetscCall(DemSetUp(dem));
  PetscCall(DemGetStats(dem, &st));
  e0 = st.ke + st.ke_rot;
  Momenta(dem, P0, L0);
  for (int s = 1; s <= 100000; s++) {
    PetscCall(DemStep(dem));
    if (s % 100) continue;
    PetscCall(DemGetStats(dem, &st));
    Momenta(dem, P, L);
    emax = PetscMax(emax, PetscAbsReal(st.ke + st.ke_rot - e0) / e0);
    lmax = PetscMax(lmax, Dist(L, L0, convex_norm(L0)));
  }
  DemParticle pe = TestGet(dem, 0);
  double      R[9];
  convex_quat_to_matrix(pe.q, R);
  PetscCall(CheckBelow("free flight of a tumbling box, 1e5 steps: angular momentum error (relative)", lmax, 1e-10));
  PetscCall(CheckBelow("free flight of a tumbling box, 1e5 steps: energy error (relative)", emax, 1e-4));
  PetscCall(TestDemDestroy(&dom, &dem));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* A box: half extents along its body axes x, y, z, and its pose. */
typedef struct {
  double h[3], x[3], R[9];
} TestBox;

/* Least overlap of two boxes, by brute force: both bodies' 8 vertices projected on the 15
 * candidate axes (face normals, edge cross products), the 1-D interval overlap
 * min(maxA - minB, maxB - minA) on each; < 0 when apart. With n: also its axis, oriented from a
 * to b, and in *second the least overlap over the axes not parallel to it. */
static double BoxDepthAxis(const TestBox *a, const TestBox *b, double n[3], double *second);
static double BoxDepth(const TestBox *a, const TestBox *b)
{
  return BoxDepthAxis(a, b, NULL, NULL);
}

static double BoxDepthAxis(const TestBox *a, const TestBox *b, double n[3], double *second)
{
  const double *Ra = a->R, *Rb = b->R;
  double        ax[15][3], va[8][3], vb[8][3], best = PETSC_MAX_REAL;
  int           na = 0;
  for (int c = 0; c < 8; c++) {
    const double u[3] = {(c & 1 ? 1 : -1) * a->h[0], (c & 2 ? 1 : -1) * a->h[1], (c & 4 ? 1 : -1) * a->h[2]};
    const double v[3] = {(c & 1 ? 1 : -1) * b->h[0], (c & 2 ? 1 : -1) * b->h[1], (c & 4 ? 1 : -1) * b->h[2]};
    convex_mat_vec(Ra, u, va[c]);
    convex_mat_vec(Rb, v, vb[c]);
    for (int k = 0; k < 3; k++) va[c][k] += a->x[k], vb[c][k] += b->x[k];
  }
  for (int k = 0; k < 3; k++) /* face normals: the body axes, columns of R */
    for (int m = 0; m < 3; m++) ax[2 * k][m] = Ra[3 * m + k], ax[2 * k + 1][m] = Rb[3 * m + k];
  na = 6;
  for (int k = 0; k < 3; k++)
    for (int l = 0; l < 3; l++) {
      const double ea[3] = {Ra[k], Ra[3 + k], Ra[6 + k]}, eb[3] = {Rb[l], Rb[3 + l], Rb[6 + l]};
      double       c[3];
      convex_cross(ea, eb, c);
      const double n2 = convex_dot(c, c);
      if (n2 < 1e-12) continue;
      for (int m = 0; m < 3; m++) ax[na][m] = c[m] / sqrt(n2);
      na++;
    }
  double ov[15], sg[15];
  int    ib = 0;
  for (int a = 0; a < na; a++) {
    double lo[2] = {PETSC_MAX_REAL, PETSC_MAX_REAL}, hi[2] = {-PETSC_MAX_REAL, -PETSC_MAX_REAL};
    for (int c = 0; c < 8; c++) {
      const double pa = convex_dot(va[c], ax[a]), pb = convex_dot(vb[c], ax[a]);
      lo[0] = PetscMin(lo[0], pa), hi[0] = PetscMax(hi[0], pa), lo[1] = PetscMin(lo[1], pb), hi[1] = PetscMax(hi[1], pb);
    }
    ov[a] = PetscMin(hi[0] - lo[1], hi[1] - lo[0]);
    sg[a] = hi[0] - lo[1] <= hi[1] - lo[0] ? 1 : -1; /* b above a along the axis: n = +axis */
    if (ov[a] < best) best = ov[a], ib = a;
  }
  if (n) {
    for (int m = 0; m < 3; m++) n[m] = sg[ib] * ax[ib][m];
    *second = PETSC_MAX_REAL;
    for (int a = 0; a < na; a++)
      if (PetscAbsReal(convex_dot(ax[a], ax[ib])) < 1 - 1e-12) *second = PetscMin(*second, ov[a]);
  }
  return best;
}

static void RandomQuat(double q[4])
{
  const double u1 = (double)rand() / RAND_MAX, u2 = 2 * PETSC_PI * rand() / RAND_MAX, u3 = 2 * PETSC_PI * rand() / RAND_MAX;
  q[0] = sqrt(1 - u1) * sin(u2), q[1] = sqrt(1 - u1) * cos(u2), q[2] = sqrt(u1) * sin(u3), q[3] = sqrt(u1) * cos(u3);
}

/* The DEM's box-box narrow phase (closed-form separating axes, sat_box.c) against BoxDepth: a
 * 1 x 0.6 x 0.3 and a 0.8 x 0.5 x 0.4 box (different, so a mix-up of the two boxes' extents
 * shows). Three kinds of poses:
 *  - random orientations, the second box moved along a random direction to just inside or (one
 *    in four) just outside touching (bisection on BoxDepth);
 *  - nearly aligned: the second box turned from the first by 1e-7 to 1e-4 rad about a random
 *    axis (nearly parallel edges), placed the same way;
 *  - face on face with the second box turned about their common y axis by 1.3e-6 to 3.2e-6 rad:
 *    the depth is the y overlap delta exactly, and every edge pair in the x-z planes crosses
 *    along y too, so the nearly parallel edge axes tie with the face axis (their length must
 *    not lose its digits).
 * The DEM's depth is read back from the elastic energy 1/2 kn delta^2 of its statistics. Near
 * parallel edges make an edge axis ill-conditioned (rounding / sin phi, in the brute force too),
 * so those poses are held to 1e-14 of the edge over sin phi, random ones to 1e-12. The normal
 * the forces use (pair loop, its caches, the contact law) comes from the second body's change of
 * velocity over a DEM step of the two bodies (dt 1e-9 s: they barely turn; no damping, friction,
 * gravity), compared with BoxDepth's axis where no other axis comes within 1e-9 of the edge of
 * the least overlap. Both boxes' body frames are their input frames. */
/* One pose of BoxPairs: the two particles and boxes, the reference depth and axis (a to b),
 * the least overlap over the other axes, the turn between the boxes (1 for random poses). */
typedef struct {
  DemParticle p0, p1;
  TestBox     ba, bb;
  double      ref, nref[3], second, ang;
  PetscBool   near; /* nearly parallel edges: held to the conditioned bound */
} BoxSample;

static void RandomUnit(double u[3])
{
  double l;
  do {
    for (int k = 0; k < 3; k++) u[k] = 2.0 * rand() / RAND_MAX - 1;
  } while (convex_dot(u, u) > 1 || convex_dot(u, u) < 1e-2);
  l = sqrt(convex_dot(u, u));
  for (int k = 0; k < 3; k++) u[k] /= l;
}

static void BoxSampleDraw(int t, BoxSample *b)
{
  const PetscBool tie = (PetscBool)(t % 8 == 5), aligned = (PetscBool)(t % 4 == 1 && !tie);
  double          u[3], lo = 0, hi = 2 * A, dq[4];

  b->second = PETSC_MAX_REAL, b->ang = 1, b->near = (PetscBool)(tie || aligned);
  RandomQuat(b->p0.q);
  RandomQuat(b->p1.q);
  if (aligned) { /* q1 = q0 turned by 1e-7 to 1e-4 rad */
    RandomUnit(u);
    b->ang = pow(10.0, -7 + 3.0 * rand() / RAND_MAX);
    convex_quat_from_axis_angle(u, b->ang, dq);
    convex_quat_mul(b->p0.q, dq, b->p1.q);
  }
  if (tie) { /* face on face along y, turned about y: the depth is delta */
    const double ey[3] = {0, 1, 0}, delta = 0.005 * A * (1 + (double)rand() / RAND_MAX), dy[3] = {0, b->ba.h[1] + b->bb.h[1] - delta, 0};
    b->ang = pow(10.0, -5.9 + 0.4 * rand() / RAND_MAX);
    convex_quat_from_axis_angle(ey, b->ang, dq);
    convex_quat_mul(b->p0.q, dq, b->p1.q);
    convex_quat_to_matrix(b->p0.q, b->ba.R);
    convex_mat_vec(b->ba.R, dy, b->p1.x);
    convex_mat_vec(b->ba.R, ey, b->nref);
    b->ref = delta;
    return;
  }
  convex_quat_to_matrix(b->p0.q, b->ba.R);
  convex_quat_to_matrix(b->p1.q, b->bb.R);
  RandomUnit(u);
  for (int it = 0; it < 80; it++) { /* touching distance along u */
    const double mid = 0.5 * (lo + hi);
    for (int k = 0; k < 3; k++) b->bb.x[k] = mid * u[k];
    if (BoxDepth(&b->ba, &b->bb) > 0) lo = mid;
    else hi = mid;
  }
  const double s = lo + (t % 4 == 3 ? 1 : -1) * 0.01 * A * (0.05 + (double)rand() / RAND_MAX); /* one in four apart */
  for (int k = 0; k < 3; k++) b->p1.x[k] = b->bb.x[k] = s * u[k];
  b->ref = BoxDepthAxis(&b->ba, &b->bb, b->nref, &b->second);
}

/* The change of velocity of particle id 1 over a DEM step, after a first step that flushes the
 * force of the previous pose (its first half kick). */
static PetscErrorCode BoxForceDirection(Dem dem, double dv[3])
{
  PetscFunctionBeginUser;
  dv[0] = dv[1] = dv[2] = 0;
  for (int s = 0; s < 2; s++) {
    PetscCall(DemStep(dem));
    for (PetscInt i = 0; i < 2; i++) {
      DemParticle q = {0};
      PetscCall(DemGetParticle(dem, i, &q));
      if (q.id == 1)
        for (int k = 0; k < 3; k++) dv[k] += (s ? 1 : -1) * q.v[k];
    }
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode BoxPairs(void)
{
  char         opts[512];
  Domain       dom;
  Dem          dem;
  const double kn  = 1e4;
  BoxSample    b   = {.p0 = {.id = 0, .shape = 0, .q = {1, 0, 0, 0}}, .p1 = {.id = 1, .shape = 1, .x = {0.5 * A, 0, 0}, .q = {1, 0, 0, 0}}, .ba = {.h = {0.5 * A, 0.3 * A, 0.15 * A}}, .bb = {.h = {0.4 * A, 0.25 * A, 0.2 * A}}};
  double       err = 0, errs = 0, nerr = 0;
  int          wrong = 0, touching = 0, nchecked = 0;

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(opts, sizeof opts, "-domain_lo -0.05,-0.05,-0.05 -domain_hi 0.05,0.05,0.05 -dem_shape polyhedron,polyhedron -dem_shape_file test_convex_box.txt,test_convex_box2.txt -dem_shape_size 1,1 -dem_radius_fraction 1,1 -dem_density %g -dem_contact_law linear -dem_kn %g -dem_restitution 1 -dem_friction 0 -dem_gravity 0,0,0 -dem_dt 1e-9", RHO, kn));
  PetscCall(WriteBoxFile("test_convex_box2.txt", 0.8 * A, 0.5 * A, 0.4 * A));
  PetscCall(TestDemCreate(opts, &dom, &dem));
  PetscCall(DemAddParticle(dem, &b.p0));
  PetscCall(DemAddParticle(dem, &b.p1));
  PetscCall(DemSetUp(dem));
  srand(7);
  for (int t = 0; t < 400; t++) {
    DemStats st;
    BoxSampleDraw(t, &b);
    { /* the slots by id: a step may re-sort them (DemSetParticle keeps a slot's id and shape) */
      DemParticle q0;
      PetscCall(DemGetParticle(dem, 0, &q0));
      PetscCall(DemSetParticle(dem, q0.id == 0 ? 0 : 1, &b.p0));
      PetscCall(DemSetParticle(dem, q0.id == 0 ? 1 : 0, &b.p1));
    }
    PetscCall(DemGetStats(dem, &st));
    if ((st.contacts > 0) != (b.ref > 0)) wrong++;
    if (b.ref <= 0 || st.contacts == 0) continue;
    const double e = PetscAbsReal(sqrt(2 * st.pe_spring / kn) - b.ref) / A;
    touching++;
    if (b.near) errs = PetscMax(errs, e * sin(b.ang));
    else err = PetscMax(err, e);
    if (b.second - b.ref > 1e-9 * A) { /* a clear least-overlap axis: the force's direction */
      double dv[3], e2 = 0, vn;
      PetscCall(BoxForceDirection(dem, dv));
      vn = sqrt(convex_dot(dv, dv));
      for (int k = 0; k < 3; k++) e2 += PetscSqr(dv[k] / vn - b.nref[k]);
      nerr = PetscMax(nerr, sqrt(e2));
      nchecked++;
    }
  }
  PetscCall(CheckEqual("box-box narrow phase of the DEM (closed-form separating axes), 400 poses near touching: poses where contact or not differs from the brute-force test", wrong, 0));
  PetscCall(CheckAbove("box-box narrow phase of the DEM, 400 poses near touching: poses touching", touching, 250));
  PetscCall(CheckBelow("box-box narrow phase of the DEM, random poses: depth against the brute-force separating-axis test, largest error / edge", err, 1e-12));
  PetscCall(CheckBelow("box-box narrow phase of the DEM, nearly parallel edges (turned by 1e-7 to 1e-4 rad; face on face with tying edge axes): depth error x sin(angle), largest / edge", errs, 1e-14));
  PetscCall(CheckAbove("box-box narrow phase of the DEM: poses with a clear least-overlap axis", nchecked, 200));
  PetscCall(CheckBelow("box-box narrow phase of the DEM: the force's direction over one step against the brute-force least-overlap axis (from the first box to the second), largest |dv/|dv| - n|", nerr, 1e-9));
  PetscCall(TestDemDestroy(&dom, &dem));
  remove("test_convex_box2.txt");
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* 27 colliding bodies for 1e5 steps of Tc/(100 dtf); model: extra DEM options (contact point,
 * narrow phase). Checks the contacts and both momenta; returns the energy drift. */
static PetscErrorCode Collisions(PetscBool boxes, double vs, double ws, const char *model, int dtf, double *drift_out)
{
  char         opts[1024];
  Domain       dom;
  Dem          dem;
  DemStats     st;
  const int    N    = 100000 * dtf; /* the same simulated time at every dt */
  const char  *what = boxes ? "boxes" : "bodies";
  const double kn   = 1e4;
  double       P0[3], L0[3], P[3], L[3], e0 = 0, first = 0, last = 0, pmax = 0, lmax = 0, m, J[3], omax = 0;
  int          nf = 0, nl = 0;
  PetscInt     contacts = 0;

  char shapes[256];

  PetscFunctionBeginUser;
  Moments(1, J, &m);
  const double tc = PETSC_PI * sqrt(0.5 * m / kn);
  if (boxes) PetscCall(PetscSNPrintf(shapes, sizeof shapes, "-dem_shape polyhedron -dem_shape_file test_convex_box.txt -dem_shape_size 1"));
  else PetscCall(PetscSNPrintf(shapes, sizeof shapes, "-dem_shape polyhedron,icosahedron -dem_shape_file test_convex_box.txt -dem_shape_size 1,%g -dem_radius_fraction 1,1", 0.5 * A));
  PetscCall(PetscSNPrintf(opts, sizeof opts, "-domain_lo -0.5,-0.5,-0.5 -domain_hi 0.5,0.5,0.5 %s -dem_density %g -dem_contact_law linear -dem_kn %g -dem_restitution 1 -dem_friction 0 -dem_gravity 0,0,0 -dem_dt %g -dem_lattice 3,3,3 -dem_lattice_spacing %g -dem_lattice_origin %g,%g,%g -dem_lattice_random_orientation -dem_lattice_speed 0.05 %s", shapes, RHO, kn, tc / (100.0 * dtf), 1.25 * A, -1.5 * 1.25 * A, -1.5 * 1.25 * A, -1.5 * 1.25 * A, model));
  PetscCall(TestDemCreate(opts, &dom, &dem));
  PetscCall(DemSetUp(dem));
  { /* give every body a spin, and aim them at the centre */
    PetscInt n;
    PetscCall(DemGetLocalCount(dem, &n));
    for (PetscInt i = 0; i < n; i++) {
      DemParticle p = {0};
      PetscCall(DemGetParticle(dem, i, &p));
      for (int k = 0; k < 3; k++) {
        p.w[k] = ws * sin(1.7 * p.id + 2.1 * k);
        p.v[k] += -vs * p.x[k] / A;
      }
      PetscCall(DemSetParticle(dem, i, &p));
    }
  }
  for (int s = 0; s <= N; s++) {
    if (s % 10 == 0) {
      PetscCall(DemGetStats(dem, &st));
      const double e = st.ke + st.ke_rot + st.pe_spring;
      contacts += st.contacts;
      Momenta(dem, P, L);
      if (s == 0) {
        e0 = e;
        for (int k = 0; k < 3; k++) P0[k] = P[k], L0[k] = L[k];
      }
      pmax = PetscMax(pmax, Dist(P, P0, m * 0.4));
      lmax = PetscMax(lmax, Dist(L, L0, convex_norm(L0)));
      omax = PetscMax(omax, st.max_overlap);
      if (s < N / 10) first += e, nf++;
      if (s > N - N / 10) last += e, nl++;
    }
    if (s < N) PetscCall(DemStep(dem));
  }
  const double drift = PetscAbsReal(last / nl - first / nf) / e0;
  CheckDetail("largest overlap %.3f d_eq/2", omax);
  PetscCall(CheckAbove(CheckName("colliding tumbling %s (approach %g m/s, spin %g rad/s, dt = Tc/%d, %s): contact samples", boxes ? "boxes" : "boxes and icosahedra", 0.4 * vs * 3, ws, 100 * dtf, model[0] ? model : "defaults"), contacts, 100));
  /* round-off accumulates step by step: 1e-10 per 1e5 steps */
  PetscCall(CheckBelow(CheckName("colliding tumbling %s, %d steps: linear momentum error (of m v)", what, N), pmax, 1e-10 * dtf));
  PetscCall(CheckBelow(CheckName("colliding tumbling %s, %d steps: angular momentum about the origin (orbital + spin) error (relative)", what, N), lmax, 1e-10 * dtf));
  *drift_out = drift;
  PetscCall(TestDemDestroy(&dom, &dem));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode RectDrop(const char *shape, double rest)
{
  char   opts[1024];
  Domain dom;
  Dem    dem;

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(opts, sizeof opts, "-domain_lo -0.05,-0.05,-0.5 -domain_hi 0.05,0.05,0.05 %s -dem_density %g -dem_contact_law linear -dem_kn 2e4 -dem_restitution 0.3 -dem_friction 0.5 -dem_dt 1e-5 -dem_rect_0 %g,%g,0,%g,%g,0,%g,%g,0", shape, RHO, -1.5 * A, -1.5 * A, 1.5 * A, -1.5 * A, -1.5 * A, 1.5 * A));
  PetscCall(TestDemCreate(opts, &dom, &dem));
  DemParticle on = {.id = 0, .shape = 0, .x = {0, 0, 1.5 * A}, .q = {1, 0, 0, 0}}, off = {.id = 1, .shape = 0, .x = {4 * A, 0, 1.5 * A}, .q = {1, 0, 0, 0}};
  PetscCall(DemAddParticle(dem, &on));
  PetscCall(DemAddParticle(dem, &off));
  PetscCall(DemSetUp(dem));
  for (int s = 0; s < 30000; s++) PetscCall(DemStep(dem));
  on                 = TestGet(dem, 0);
  off                = TestGet(dem, 1);
  const double bound = 2 * RHO * A * A * A * 9.81 / 2e4;
  PetscCall(CheckCloseAbs(CheckName("%s on a finite rectangle rests at z [m]", shape), on.x[2], rest, bound));
  PetscCall(CheckBelow(CheckName("%s beside a finite rectangle falls past it: z after 0.3 s [m]", shape), off.x[2], -0.3));
  PetscCall(TestDemDestroy(&dom, &dem));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  const double c = cos(PETSC_PI / 8), s = sin(PETSC_PI / 8);
  /* flat (slightly tilted), on an edge (45 deg about x), on a corner (body diagonal vertical) */
  const double th = 0.5 * acos(1 / sqrt(3.0)), ax[3] = {1 / sqrt(2.0), -1 / sqrt(2.0), 0};
  const double qs[3][4] = {{cos(0.01), sin(0.01), 0, 0}, {c, s, 0.01, 0}, {cos(th), sin(th) * ax[0], sin(th) * ax[1], 0}};
  const char  *names[3] = {"flat", "edge", "corner"};

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  { /* shape table: -dem_shape_deq scales each shape to the volume of the sphere of diameter d */
    Domain       dom;
    Dem          dem;
    const double d = 0.007, vref = PETSC_PI * d * d * d / 6;
    double       err = 0;
    PetscCall(TestDemCreate("-domain_lo 0,0,0 -domain_hi 0.1,0.1,0.1 -dem_shape cube,tetrahedron,octahedron,icosahedron,cylinder -dem_shape_deq 0.007,0.007,0.007,0.007,0.007 -dem_kn 1e4", &dom, &dem));
    PetscCall(DemSetUp(dem));
    for (PetscInt k = 0; k < 5; k++) {
      PetscReal v, de;
      PetscCall(DemGetShapeGeometry(dem, k, &v, &de));
      err = PetscMax(err, PetscMax(PetscAbsReal(v - vref) / vref, PetscAbsReal(de - d) / d));
    }
    PetscCall(CheckBelow("-dem_shape_deq: volume and d_eq of 5 built-ins scaled to d = 7 mm, largest error (relative)", err, 1e-12));
    PetscCall(TestDemDestroy(&dom, &dem));
  }
  for (int k = 0; k < 3; k++) {
    double z = 0, tilt = 0, bound = 0, q[4], n = 0;
    for (int j = 0; j < 4; j++) n += qs[k][j] * qs[k][j];
    for (int j = 0; j < 4; j++) q[j] = qs[k][j] / sqrt(n);
    PetscCall(DropCube(names[k], q, &z, &tilt, &bound));
    CheckDetail("bound 2 m g/kn");
    PetscCall(CheckCloseAbs(CheckName("cube dropped on its %s rests at z = a/2 [m]", names[k]), z, 0.5 * A, bound));
    PetscCall(CheckBelow(CheckName("cube dropped on its %s rests on a face: tilt [rad]", names[k]), tilt, 1e-3));
  }
  {
    char cube[128], sphere[128];
    PetscCall(PetscSNPrintf(cube, sizeof cube, "-dem_shape cube -dem_shape_size %g", A));
    PetscCall(PetscSNPrintf(sphere, sizeof sphere, "-dem_radius %g", 0.5 * A));
    PetscCall(RectDrop(cube, 0.5 * A));
    PetscCall(RectDrop(sphere, 0.5 * A));
  }
  PetscCall(FreeFlight());
  PetscCall(BoxPairs());
  { /* energy of frictionless elastic collisions (e = 1), mean over the last tenth of the run
       against the first; 1e5 steps at Tc/100, the same simulated time at smaller dt. The two
       contact point models: src/geom/README.md */
    const char *exact = "-dem_convex_contact_point support -dem_convex_sat_axes 300";
    double      d0, d1, d2, d3, d4;
    PetscCall(Collisions(PETSC_FALSE, 0.03, 3, "", 1, &d0));
    PetscCall(CheckBelow("gentle collisions, defaults (patch point, MPR for icosahedra), dt = Tc/100, 1e5 steps: energy drift (relative)", d0, 1e-4));
    /* faster impacts: the exact minimum penetration (separating axes for every pair) with the
       support point is the gradient of the elastic energy; what is left is the time-step error
       of crossing the energy's kinks (the deepest vertex changing), which falls with dt */
    PetscCall(Collisions(PETSC_FALSE, 0.1, 10, exact, 1, &d1));
    PetscCall(Collisions(PETSC_FALSE, 0.1, 10, exact, 4, &d2));
    PetscCall(CheckBelow("fast collisions of boxes and icosahedra, exact depth + support point, dt = Tc/100, 1e5 steps: energy drift (relative)", d1, 1e-4));
    CheckDetail("bound 1/4 of the drift %.2e at Tc/100", d1);
    PetscCall(CheckBelow("fast collisions, exact depth + support point: the drift falls with dt, drift at Tc/400", d2, 0.25 * d1));
    /* the defaults (patch point; MPR's depth for icosahedra) are not an energy gradient: their
       drift does not fall with dt; reported, not checked */
    PetscCall(Collisions(PETSC_FALSE, 0.1, 10, "", 1, &d3));
    PetscCall(Collisions(PETSC_FALSE, 0.1, 10, "", 4, &d4));
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "NOTE fast collisions with the defaults (patch point, MPR for icosahedra): energy drift %.2e at Tc/100, %.2e at Tc/400 (not checked: this model is not an energy gradient and misses the 1e-4 bound, src/geom/README.md)\n", d3, d4));
    PetscCall(Collisions(PETSC_TRUE, 0.1, 10, "-dem_convex_contact_point support", 1, &d1));
    PetscCall(Collisions(PETSC_TRUE, 0.1, 10, "-dem_convex_contact_point support", 4, &d2));
    CheckDetail("%.2e at Tc/100", d1);
    PetscCall(CheckBelow("fast collisions of boxes (separating axes by default) + support point, dt = Tc/400: energy drift (relative)", d2, 1e-4));
  }
  remove("test_convex_box.txt");
  PetscCall(PetscFinalize());
  return check_failures ? 1 : 0;
}
