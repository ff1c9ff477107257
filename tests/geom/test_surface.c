/* Every registered surface kind (src/geom/surface.h) against itself: the sphere contact, the gap,
 * the bounding box, the face closing and the velocity of one description must agree, so a kind
 * whose gap would prune a touching sphere, or whose box leaves out a part of it, fails here.
 *
 * For each kind, its example (a unit-size instance in a box, surface_<kind>_example) moving with
 * v = (0.1, -0.2, 0.3) m/s and turning at 2 rad/s about a tilted axis, and 20000 spheres of
 * radius 0.02..0.3 at random centres x in the box grown by 0.5; for the touching ones (overlap
 * ov > 0, normal nrm from the centre to the surface, nearest surface point q = x + (r - ov) nrm):
 *   1. |nrm| = 1 and q lies on the surface: |gap(q)| <= 1e-12;
 *   2. the gap is a lower bound of the distance: gap(x) <= r - ov + 1e-12;
 *      where it is the distance (within 1e-12), a move of x by 1e-3 along nrm changes it by
 *      -1e-3 (within 1e-12): the normal is the gap's gradient;
 *   3. the list pruning keeps the sphere: surface_near(x, r + skin, skin) for skin 0 and 0.1 r;
 *   4. q lies in the bounding box (within 1e-12);
 * and for all kinds:
 *   5. the velocity is a rigid motion: (v(a) - v(b)).(a - b) = 0 (within 1e-12) for 1000 pairs;
 *   6. the example closes the faces of its box its kind says (surface_<kind>_example), and 400
 *      random points of every face it closes lie behind or on the surface (gap <= 1e-12): nothing
 *      crosses the face in front of it;
 *   7. the example was touched at all (at least 100 contacts), so 1-4 tested something.
 * Lengths in units of the example's box (1). */
#include "check.h"
#include "geom/surface.h"

static unsigned long long rng = 88172645463325252ULL;

static double uniform(void) /* xorshift64: the same numbers on every machine */
{
  rng ^= rng << 13;
  rng ^= rng >> 7;
  rng ^= rng << 17;
  return (double)(rng >> 11) * (1.0 / 9007199254740992.0);
}

/* Worst figures of checks 1-4 over the touching spheres of kind s. */
typedef struct {
  PetscInt n, pruned, outside_box;
  double   unit, onsurf, lower, gradient;
} Stats;

static void Touch(const Surface *s, const double lo[3], const double hi[3], Stats *st)
{
  double blo[3], bhi[3];
  surface_bbox(s, blo, bhi);
  for (int t = 0; t < 20000; t++) {
    double x[3], nrm[3], q[3];
    for (int k = 0; k < 3; k++) x[k] = lo[k] - 0.5 + (hi[k] - lo[k] + 1) * uniform();
    const double r  = 0.02 + 0.28 * uniform();
    const double ov = surface_sphere(s, x, r, nrm);
    if (ov <= 0) continue;
    st->n++;
    for (int k = 0; k < 3; k++) q[k] = x[k] + (r - ov) * nrm[k];
    st->unit       = PetscMax(st->unit, PetscAbsReal(sqrt(convex_dot(nrm, nrm)) - 1));
    st->onsurf     = PetscMax(st->onsurf, PetscAbsReal(surface_gap(s, q)));
    const double g = surface_gap(s, x);
    st->lower      = PetscMax(st->lower, g - (r - ov));
    if (PetscAbsReal(g - (r - ov)) <= 1e-12) {
      double y[3];
      for (int k = 0; k < 3; k++) y[k] = x[k] + 1e-3 * nrm[k];
      st->gradient = PetscMax(st->gradient, PetscAbsReal(surface_gap(s, y) - (g - 1e-3)));
    }
    if (!surface_near(s, x, r, 0) || !surface_near(s, x, 1.1 * r, 0.1 * r)) st->pruned++;
    for (int k = 0; k < 3; k++)
      if (q[k] < blo[k] - 1e-12 || q[k] > bhi[k] + 1e-12) {
        st->outside_box++;
        break;
      }
  }
}

/* Check 6: the faces of the box lo..hi the surface closes, and the worst gap of their points. */
static void Faces(const Surface *s, const double lo[3], const double hi[3], PetscInt *nclosed, double *worst)
{
  *nclosed = 0;
  *worst   = -PETSC_MAX_REAL;
  for (int d = 0; d < 3; d++)
    for (int side = 0; side < 2; side++) {
      const int a = (d + 1) % 3, b = (d + 2) % 3;
      double    c[4][3];
      for (int q = 0; q < 4; q++) {
        c[q][d] = side ? hi[d] : lo[d];
        c[q][a] = q & 1 ? hi[a] : lo[a];
        c[q][b] = q & 2 ? hi[b] : lo[b];
      }
      if (!surface_closes_face(s, d, side, (const double(*)[3])c, 1e-12)) continue;
      (*nclosed)++;
      for (int t = 0; t < 400; t++) {
        double y[3];
        y[d]   = c[0][d];
        y[a]   = lo[a] + (hi[a] - lo[a]) * uniform();
        y[b]   = lo[b] + (hi[b] - lo[b]) * uniform();
        *worst = PetscMax(*worst, surface_gap(s, y));
      }
    }
}

int main(int argc, char **argv)
{
  PetscFunctionBeginUser;
  PetscCall(PetscInitialize(&argc, &argv, NULL, "surface kinds test"));
  for (int kind = 0; kind < SURFACE_NKINDS; kind++) {
    const char *name = SurfaceKinds[kind]->name;
    Surface     s;
    double      lo[3], hi[3], rigid = 0, worst;
    Stats       st = {0};
    PetscInt    nclosed;

    const int nfaces = surface_example((SurfaceKind)kind, &s, lo, hi);
    PetscCall(CheckEqual(CheckName("%s: the example is of its kind", name), s.kind, kind));
    Touch(&s, lo, hi, &st);
    PetscCall(CheckAtMost(CheckName("%s: |normal| - 1 of %" PetscInt_FMT " touching spheres", name, st.n), st.unit, 1e-12));
    PetscCall(CheckAtMost(CheckName("%s: |gap| of the nearest surface point", name), st.onsurf, 1e-12));
    PetscCall(CheckAtMost(CheckName("%s: gap - distance of the centre (a lower bound)", name), st.lower, 1e-12));
    PetscCall(CheckAtMost(CheckName("%s: change of the gap along the normal, error", name), st.gradient, 1e-12));
    PetscCall(CheckEqual(CheckName("%s: touching spheres the list pruning drops", name), st.pruned, 0));
    PetscCall(CheckEqual(CheckName("%s: touching points outside the bounding box", name), st.outside_box, 0));
    PetscCall(CheckAtLeast(CheckName("%s: touching spheres sampled", name), (double)st.n, 100));

    const double u[3] = {0.36, 0.48, 0.8}; /* unit */
    for (int k = 0; k < 3; k++) s.v[k] = (k == 1 ? -0.2 : 0.1 * (k + 1)), s.ax_p[k] = 0.1 * k, s.ax_u[k] = u[k];
    s.omega = 2;
    for (int t = 0; t < 1000; t++) {
      double a[3], b[3], va[3], vb[3], dv[3], dx[3];
      for (int k = 0; k < 3; k++) a[k] = 4 * uniform() - 2, b[k] = 4 * uniform() - 2;
      surface_velocity(&s, a, va);
      surface_velocity(&s, b, vb);
      for (int k = 0; k < 3; k++) dv[k] = va[k] - vb[k], dx[k] = a[k] - b[k];
      rigid = PetscMax(rigid, PetscAbsReal(convex_dot(dv, dx)));
    }
    PetscCall(CheckAtMost(CheckName("%s: velocity field, |(v(a) - v(b)).(a - b)|", name), rigid, 1e-12));

    Faces(&s, lo, hi, &nclosed, &worst);
    PetscCall(CheckEqual(CheckName("%s: faces of its box it closes", name), nclosed, nfaces));
    if (nclosed) PetscCall(CheckAtMost(CheckName("%s: largest gap of the points of the closed faces", name), worst, 1e-12));
  }
  PetscCall(PetscFinalize());
  return check_failures ? 1 : 0;
}
