/* The diffusion filter of the coupling fields (-cpl_filter_width, src/coupling/filter.c).
 * Dimensionless (d = 1). References are exact properties of the discrete diffusion:
 *  1. one sweep of a unit value in one cell is the discrete stencil: 1 - 2 sum_e lam_e at the
 *     cell, lam_e = sigma^2 / (2 h_e^2) at its two neighbours along e, 0 elsewhere (anisotropic
 *     cells 1 x 1.25 x 1.5, periodic box, W = 1.2 so that one sweep is the whole filter);
 *     the same for a face field, and at the first interior face above a wall the missing
 *     neighbour's share stays at the face (no flux into the boundary face, which stays 0);
 *  2. the full filter (W = 4: 9 sweeps) adds exactly sigma^2 = (W d)^2 / (8 ln 2) to the
 *     variance of a unit cell per axis, and the same to the variance of the solid fraction a
 *     particle spreads (its kernel's own variance measured with the filter off), and keeps the
 *     centroid;
 *  3. conservation (test_conserve's periodic box of 64 moving spheres, W = 4): solid volume on
 *     the grid = the particles' to 1e-12 at the start and after 40 steps, particle + fluid + owed
 *     momentum constant to 1e-10 of sum |m v|; in a walled box the solid volume to 1e-12 with
 *     spheres against the walls. On 1 and 2 ranks (cell 12 of 24: on the rank boundary when an
 *     axis is split in two). */
/* ranks: 1 2 */
#include "cpl_common.h"

#define BOX_P "-domain_lo 0,0,0 -domain_hi 24,30,36 -da_grid_x 24 -da_grid_y 24 -da_grid_z 24 -domain_periodic_x -domain_periodic_y -domain_periodic_z -dem_radius 0.5 -dem_density 2 -dem_kn 1e4 -dem_dt 1e-3 -dem_gravity 0,0,0 -dem_lattice 1,1,1 -dem_lattice_spacing 1 -dem_lattice_origin 11.3,14.1,17.8 -fluid_density 1 -fluid_viscosity 0.1 -cpl_substeps 5 -fluid_poisson_pc_hypre_boomeramg_relax_type_coarse symmetric-SOR/Jacobi "
#define BOX_W "-domain_lo 0,0,0 -domain_hi 24,30,36 -da_grid_x 24 -da_grid_y 24 -da_grid_z 24 -dem_radius 0.5 -dem_density 2 -dem_kn 1e4 -dem_dt 1e-3 -dem_gravity 0,0,0 -dem_lattice 4,4,4 -dem_lattice_spacing 1 -dem_lattice_origin 0,0,0 -fluid_density 1 -fluid_viscosity 0.1 -cpl_substeps 5 "

/* What the checks read of a set-up: the coupling's figures and the fluid's DMDAs. */
typedef struct {
  CplTestView tv;
  DM          cda, fda;
  PetscInt    cells[3];
} View;

static PetscErrorCode GetView(const TestCpl *t, View *w)
{
  PetscFunctionBeginUser;
  PetscCall(CplGetTestView(t->cpl, &w->tv));
  PetscCall(FluidGetDMs(t->fl, &w->cda, &w->fda));
  for (int e = 0; e < 3; e++) w->cells[e] = t->dom.cells[e];
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Largest deviation of v (dof 1: cells; 3: faces, component d) from the one-sweep stencil of a
 * unit at c (the share lost towards a missing neighbour stays at c), and the sum of v. */
static PetscErrorCode StencilError(const View *w, DM da, Vec v, int d, const PetscInt c[3], const PetscInt missing[3][2], PetscReal *err, PetscReal *sum)
{
  PetscInt     xs[3], xm[3], dof;
  PetscScalar *a;
  PetscReal    loc[2] = {0, 0};

  PetscFunctionBeginUser;
  PetscCall(DMDAGetInfo(da, NULL, NULL, NULL, NULL, NULL, NULL, NULL, &dof, NULL, NULL, NULL, NULL, NULL));
  PetscCall(DMDAGetCorners(da, &xs[0], &xs[1], &xs[2], &xm[0], &xm[1], &xm[2]));
  PetscCall(VecGetArray(v, &a));
  for (PetscInt k = xs[2], o = 0; k < xs[2] + xm[2]; k++)
    for (PetscInt j = xs[1]; j < xs[1] + xm[1]; j++)
      for (PetscInt i = xs[0]; i < xs[0] + xm[0]; i++, o += dof) {
        const PetscInt idx[3] = {i, j, k};
        PetscReal      want = 0, ctr = 1;
        int            off = 0, at = -1;
        for (int e = 0; e < 3; e++) {
          off += idx[e] != c[e];
          if (idx[e] != c[e]) at = e;
        }
        for (int e = 0; e < 3; e++) ctr -= (2 - missing[e][0] - missing[e][1]) * w->tv.filter_lam[e];
        if (off == 0) want = ctr;
        else if (off == 1) {
          const PetscInt dd = idx[at] - c[at], n = w->cells[at];
          const PetscInt s = (dd == 1 || dd == 1 - n) ? 1 : (dd == -1 || dd == n - 1) ? 0
                                                                                      : -1;
          if (s >= 0 && !missing[at][s]) want = w->tv.filter_lam[at];
        }
        loc[0] = PetscMax(loc[0], PetscAbsReal(a[o + d] - want));
        for (int q = 0; q < dof; q++) loc[1] += a[o + q];
      }
  PetscCall(VecRestoreArray(v, &a));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &loc[0], 1, MPIU_REAL, MPIU_MAX, PETSC_COMM_WORLD));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &loc[1], 1, MPIU_REAL, MPIU_SUM, PETSC_COMM_WORLD));
  *err = loc[0];
  *sum = loc[1];
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Sets v to a unit at point c, component d (on the owning rank). */
static PetscErrorCode Unit(DM da, Vec v, int d, const PetscInt c[3])
{
  PetscInt     xs[3], xm[3], dof;
  PetscScalar *a;

  PetscFunctionBeginUser;
  PetscCall(DMDAGetInfo(da, NULL, NULL, NULL, NULL, NULL, NULL, NULL, &dof, NULL, NULL, NULL, NULL, NULL));
  PetscCall(DMDAGetCorners(da, &xs[0], &xs[1], &xs[2], &xm[0], &xm[1], &xm[2]));
  PetscCall(VecZeroEntries(v));
  PetscCall(VecGetArray(v, &a));
  if (c[0] >= xs[0] && c[0] < xs[0] + xm[0] && c[1] >= xs[1] && c[1] < xs[1] + xm[1] && c[2] >= xs[2] && c[2] < xs[2] + xm[2]) a[dof * (((c[2] - xs[2]) * xm[1] + (c[1] - xs[1])) * xm[0] + (c[0] - xs[0])) + d] = 1;
  PetscCall(VecRestoreArray(v, &a));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Mass, centroid offset from x0 and variance per axis of a cell field (periodic box: offsets
 * taken within half a box of x0). */
static PetscErrorCode Moments(const Domain *dom, DM da, Vec v, const PetscReal x0[3], PetscReal *mass, PetscReal mean[3], PetscReal var[3])
{
  PetscInt     xs[3], xm[3];
  PetscScalar *a;
  PetscReal    s[7] = {0};

  PetscFunctionBeginUser;
  PetscCall(DMDAGetCorners(da, &xs[0], &xs[1], &xs[2], &xm[0], &xm[1], &xm[2]));
  PetscCall(VecGetArray(v, &a));
  for (PetscInt k = xs[2], o = 0; k < xs[2] + xm[2]; k++)
    for (PetscInt j = xs[1]; j < xs[1] + xm[1]; j++)
      for (PetscInt i = xs[0]; i < xs[0] + xm[0]; i++, o++) {
        const PetscInt idx[3] = {i, j, k};
        s[0] += a[o];
        for (int e = 0; e < 3; e++) {
          PetscReal dx = dom->lo[e] + (idx[e] + 0.5) * dom->h[e] - x0[e];
          dx -= dom->len[e] * PetscFloorReal(dx / dom->len[e] + 0.5);
          s[1 + e] += a[o] * dx;
          s[4 + e] += a[o] * dx * dx;
        }
      }
  PetscCall(VecRestoreArray(v, &a));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, s, 7, MPIU_REAL, MPIU_SUM, PETSC_COMM_WORLD));
  *mass = s[0];
  for (int e = 0; e < 3; e++) {
    mean[e] = s[1 + e] / s[0];
    var[e]  = s[4 + e] / s[0] - mean[e] * mean[e];
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Check 1: one sweep of a unit cell and of a unit face value. */
static PetscErrorCode OneSweep(void)
{
  TestCpl        t;
  View           w;
  Vec            v;
  PetscReal      err, sum;
  const PetscInt c[3] = {12, 12, 12}, none[3][2] = {{0}};

  PetscFunctionBeginUser;
  PetscCall(TestCplCreate(BOX_P "-cpl_filter_width 1.2", &t));
  PetscCall(GetView(&t, &w));
  PetscCall(CheckTrue("W = 1.2 on cells 1 x 1.25 x 1.5 is one sweep", (PetscBool)(w.tv.filter_sweeps == 1), w.tv.filter_sweeps == 1 ? "1 sweep" : "not 1 sweep"));
  CheckDetail("bound 1e-15; lam = %.4f %.4f %.4f", (double)w.tv.filter_lam[0], (double)w.tv.filter_lam[1], (double)w.tv.filter_lam[2]);
  PetscCall(CheckClose("lam_x h_x^2 = sigma^2/2 = W^2/(16 ln 2)", w.tv.filter_lam[0], 1.44 / (16 * PetscLogReal(2.0)), 1e-14));
  PetscCall(DMGetGlobalVector(w.cda, &v));
  PetscCall(Unit(w.cda, v, 0, c));
  PetscCall(CplFilter(t.cpl, v, PETSC_FALSE));
  PetscCall(StencilError(&w, w.cda, v, 0, c, none, &err, &sum));
  PetscCall(CheckBelow("one sweep of a unit cell vs the discrete stencil (periodic, anisotropic): max error", err, 1e-15));
  PetscCall(CheckClose("one sweep of a unit cell: sum", sum, 1, 1e-15));
  PetscCall(DMRestoreGlobalVector(w.cda, &v));
  PetscCall(DMGetGlobalVector(w.fda, &v));
  PetscCall(Unit(w.fda, v, 1, c));
  PetscCall(CplFilter(t.cpl, v, PETSC_TRUE));
  PetscCall(StencilError(&w, w.fda, v, 1, c, none, &err, &sum));
  PetscCall(CheckBelow("one sweep of a unit y-face value vs the discrete stencil (periodic): max error", err, 1e-15));
  PetscCall(DMRestoreGlobalVector(w.fda, &v));
  PetscCall(TestCplDestroy(&t));

  PetscCall(TestCplCreate(BOX_W "-cpl_filter_width 1.2", &t));
  PetscCall(GetView(&t, &w));
  {
    const PetscInt f[3] = {5, 7, 1}, miss[3][2] = {{0, 0}, {0, 0}, {1, 0}}; /* z-face 1: face 0 is the wall's */
    PetscCall(DMGetGlobalVector(w.fda, &v));
    PetscCall(Unit(w.fda, v, 2, f));
    PetscCall(CplFilter(t.cpl, v, PETSC_TRUE));
    PetscCall(StencilError(&w, w.fda, v, 2, f, miss, &err, &sum));
    PetscCall(CheckBelow("one sweep of a unit z-face value above a wall (no flux to the wall's face): max error", err, 1e-15));
    PetscCall(CheckClose("one sweep of a unit z-face value above a wall: sum", sum, 1, 1e-15));
    PetscCall(DMRestoreGlobalVector(w.fda, &v));
  }
  PetscCall(TestCplDestroy(&t));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Check 2: the variance added by the whole filter, to a unit cell and to a particle's spread. */
static PetscErrorCode Variance(void)
{
  TestCpl         t;
  View            w;
  Vec             v, eps;
  PetscReal       m, mean[3], var[3], mean0[3], var0[3], sig2, err = 0, cerr = 0;
  const PetscInt  c[3]  = {12, 12, 12};
  const PetscReal xp[3] = {11.8, 14.6, 18.3}; /* the sphere's centre (the lattice's origin + r) */

  PetscFunctionBeginUser;
  PetscCall(TestCplCreate(BOX_P, &t)); /* filter off: the kernel's own spread */
  PetscCall(GetView(&t, &w));
  PetscCall(FluidGetPorosity(t.fl, &eps));
  PetscCall(DMGetGlobalVector(w.cda, &v));
  PetscCall(VecSet(v, 1.0));
  PetscCall(VecAXPY(v, -1.0, eps));
  PetscCall(Moments(&t.dom, w.cda, v, xp, &m, mean0, var0));
  PetscCall(DMRestoreGlobalVector(w.cda, &v));
  PetscCall(TestCplDestroy(&t));

  PetscCall(TestCplCreate(BOX_P "-cpl_filter_width 4", &t));
  PetscCall(GetView(&t, &w));
  sig2 = 16 / (8 * PetscLogReal(2.0));
  PetscCall(CheckClose("W = 4: the filter's variance (W d)^2 / (8 ln 2)", w.tv.filter_var, sig2, 1e-14));
  CheckDetail("bound 1/6; %d sweeps", (int)w.tv.filter_sweeps);
  PetscCall(CheckAtMost("W = 4: largest diffusion number of a sweep", PetscMax(w.tv.filter_lam[0], PetscMax(w.tv.filter_lam[1], w.tv.filter_lam[2])), 1.0 / 6));
  PetscCall(DMGetGlobalVector(w.cda, &v));
  {
    const PetscReal xc[3] = {12.5, 15.625, 18.75}; /* cell 12's centre */
    PetscCall(Unit(w.cda, v, 0, c));
    PetscCall(CplFilter(t.cpl, v, PETSC_FALSE));
    PetscCall(Moments(&t.dom, w.cda, v, xc, &m, mean, var));
    for (int e = 0; e < 3; e++) err = PetscMax(err, PetscAbsReal(var[e] - sig2) / sig2);
    PetscCall(CheckBelow("W = 4 (9 sweeps): variance of a unit cell vs sigma^2, max over axes, relative", err, 1e-12));
    PetscCall(CheckClose("W = 4: sum of a unit cell", m, 1, 1e-14));
  }
  PetscCall(FluidGetPorosity(t.fl, &eps));
  PetscCall(VecSet(v, 1.0));
  PetscCall(VecAXPY(v, -1.0, eps));
  PetscCall(Moments(&t.dom, w.cda, v, xp, &m, mean, var));
  err = 0;
  for (int e = 0; e < 3; e++) {
    err  = PetscMax(err, PetscAbsReal(var[e] - var0[e] - sig2) / sig2);
    cerr = PetscMax(cerr, PetscAbsReal(mean[e] - mean0[e]));
  }
  CheckDetail("bound 1e-10; kernel's own variance %.4f %.4f %.4f, filtered %.4f %.4f %.4f", (double)var0[0], (double)var0[1], (double)var0[2], (double)var[0], (double)var[1], (double)var[2]);
  PetscCall(CheckBelow("W = 4: a sphere's solid fraction, variance filtered - unfiltered vs sigma^2, max over axes, relative", err, 1e-10));
  PetscCall(CheckBelow("W = 4: a sphere's solid fraction, centroid shift (d)", cerr, 1e-10));
  PetscCall(DMRestoreGlobalVector(w.cda, &v));
  PetscCall(TestCplDestroy(&t));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Check 3: conservation with the filter on. */
static PetscErrorCode Conserve(void)
{
  TestCpl   t;
  CplStats  st;
  PetscReal g0, p0, g1, p1, P0[3], P1[3], s0, s1, err = 0, emin0, emin1;

  PetscFunctionBeginUser;
  PetscCall(TestCplCreateScene("test_conserve.opts", NULL, NULL, &t));
  PetscCall(CplStep(t.cpl, &st));
  emin0 = st.eps_min;
  PetscCall(TestCplDestroy(&t));
  PetscCall(TestCplCreateScene("test_conserve.opts", "-cpl_filter_width 4", NULL, &t));
  PetscCall(CplGetSolidVolume(t.cpl, &g0, &p0));
  PetscCall(TestCplMomentum(&t, P0, NULL, &s0));
  PetscCall(CplStep(t.cpl, &st));
  emin1 = st.eps_min;
  PetscCall(TestCplRun(&t, 39, &st));
  PetscCall(CplGetSolidVolume(t.cpl, &g1, &p1));
  PetscCall(TestCplMomentum(&t, P1, NULL, &s1));
  for (int k = 0; k < 3; k++) err = PetscMax(err, PetscAbsReal(P1[k] - P0[k]) / s0);
  CheckDetail("bound: the unfiltered %.4f", (double)emin0);
  PetscCall(CheckAbove("W = 4 smooths: smallest porosity after a step", emin1, emin0));
  PetscCall(CheckClose("W = 4: solid volume on the grid vs the particles', at the start", g0, p0, 1e-12));
  PetscCall(CheckClose("W = 4: solid volume on the grid vs the particles', after 40 steps", g1, p1, 1e-12));
  PetscCall(CheckBelow("W = 4: particle + fluid + owed momentum over 40 steps: max change / sum|m v|", err, 1e-10));
  PetscCall(CheckBelow("W = 4: the particles slowed: sum|m v| after 40 steps (bound: at the start)", s1, s0));
  PetscCall(TestCplDestroy(&t));

  PetscCall(TestCplCreate(BOX_W "-cpl_filter_width 4", &t)); /* 64 spheres in the corner at x, y, z = 0 */
  PetscCall(CplGetSolidVolume(t.cpl, &g0, &p0));
  PetscCall(CheckClose("W = 4, walls: solid volume on the grid vs the particles' (spheres against three walls)", g0, p0, 1e-12));
  PetscCall(CheckClose("W = 4, walls: the particles' volume vs 64 pi/6", p0, 64 * PETSC_PI / 6, 1e-12));
  PetscCall(TestCplDestroy(&t));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(OneSweep());
  PetscCall(Variance());
  PetscCall(Conserve());
  PetscCall(PetscFinalize());
  return check_failures ? 1 : 0;
}
