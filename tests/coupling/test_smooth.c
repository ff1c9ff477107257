/* The drag's porosity on a length in diameters (-cpl_porosity_width, src/coupling/smooth.c).
 * Dimensionless (d = 1). A 12 x 24 x 12 d box, walled on x and z, periodic on y, holds 150 spheres: a
 * 5 x 5 x 5 lattice of spacing 1.1 d touching the x, y and z low sides, 25 more spread through the
 * box, and cells of 2, 3 and 4 d (1 d for the checks of a lone sphere). References:
 *  1. the solid volume: the smoothed field summed over the auxiliary grid equals the particles'
 *     volume to 1e-12 (the mirrored walls and the wrap keep it);
 *  2. the analytic smoothing: phi at each particle against sum_j V_j prod_e K_e, K_e the 1-D
 *     Gaussian of standard deviation sigma = W d / sqrt(8 ln 2) with its mirror images in the walls
 *     (one per wall) and its periodic images; the discrete smoothing matches its variance exactly,
 *     not its shape (cubic B-splines on nodes at most sigma / 1.5 apart and a sampled Gaussian):
 *     bound 0.5% of the bed's largest phi, at W = 2.2 and 3.5;
 *  3. grid independence: phi at each particle on cells of 3 and 4 d within 0.2% of the largest
 *     phi from that on 2 d cells (node spacings 0.5, 0.6, 0.57 d at W = 2.2; 0.67, 0.75, 0.8 d at
 *     W = 3.5);
 *  4. a lone sphere's own share: phi - own = 0 to 1e-14 at a cell centre, on a cell face and
 *     against the walls, and in a 4 d periodic period (the kernel overlaps its own images) and,
 *     with -cpl_self_porosity, the drag's porosity 1 to 1e-14 (the law sees no dip of its own), on
 *     1 d cells at W = 2;
 *  5. the fluid feels what the particles feel: the sum of the particles' drag K (u_seen - v) equals
 *     the sum over the faces of V_cell (beta u - sum K v W / V_cell) at the same state to 1e-12
 *     (moving spheres, self corrections on, so lone and bed particles blend the two velocities).
 * On 1 and 2 ranks (the periodic y axis split at y = 12). */
/* ranks: 1 2 */
#include "cpl_common.h"

#define BASE "-domain_lo 0,0,0 -domain_hi 12,24,12 -domain_periodic_y -dem_radius 0.5 -dem_density 2 -dem_kn 1e4 -dem_dt 1e-3 -dem_gravity 0,0,0 -fluid_density 1 -fluid_viscosity 0.1 "

/* On more than one rank the periodic y axis is split (at y = 12 on 2 ranks). */
static const char *Split(void)
{
  PetscMPIInt size;
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  return size > 1 ? " -da_processors_x 1 -da_processors_z 1" : "";
}

/* The 4 d period is too short to split: on more ranks z is. */
static const char *SplitZ(void)
{
  PetscMPIInt size;
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  return size > 1 ? " -da_processors_x 1 -da_processors_y 1" : "";
}

static PetscErrorCode AddScatter(Dem dem)
{
  PetscMPIInt rank;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
  for (int i = 0; i < 25 && !rank; i++) { /* a fixed scatter clear of the lattice (the set-up sends each to its rank) */
    DemParticle q = {0};
    q.id          = 125 + i;
    q.x[0]        = 7.0 + 4.0 * ((i * 7) % 25) / 25.0;
    q.x[1]        = 0.3 + 23.4 * ((i * 11) % 25) / 25.0;
    q.x[2]        = 0.6 + 10.8 * i / 25.0;
    PetscCall(DemAddParticle(dem, &q));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* 1-D kernel of the analytic smoothing on axis e: the Gaussian and its images. */
static PetscReal K1(const Domain *dom, int e, PetscReal s, PetscReal x, PetscReal y)
{
  PetscReal       k = 0;
  const PetscReal c = 1 / (PetscSqrtReal(2 * PETSC_PI) * s);
  if (dom->periodic[e])
    for (int j = -3; j <= 3; j++) k += c * PetscExpReal(-0.5 * PetscSqr(x - y + j * dom->len[e]) / (s * s));
  else {
    const PetscReal img[3] = {y, 2 * dom->lo[e] - y, 2 * dom->hi[e] - y};
    for (int j = 0; j < 3; j++) k += c * PetscExpReal(-0.5 * PetscSqr(x - img[j]) / (s * s));
  }
  return k;
}

/* phi at every particle (by id, gathered on all ranks; nid ids) on cells of h, width w. */
static PetscErrorCode PhiById(PetscReal h, PetscReal w, PetscInt nid, PetscReal *phi, PetscReal *ana, PetscReal *sum_err)
{
  TestCpl     t;
  CplTestView tv;
  DemArrays   pa;
  char        opts[1024];
  PetscReal  *ph, vsum[2] = {0, 0};
  PetscInt    count;
  const int   n = (int)(12 / h + 0.5);

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(opts, sizeof opts, BASE "-da_grid_x %d -da_grid_y %d -da_grid_z %d -dem_lattice 5,5,5 -dem_lattice_spacing 1.1 -dem_lattice_origin 0.5,0.5,0.5 -cpl_porosity_width %g%s", n, 2 * n, n, (double)w, Split()));
  PetscCall(TestCplCreateWith(opts, AddScatter, &t));
  PetscCall(CplSmoothProject(t.cpl));
  PetscCall(CplGetTestView(t.cpl, &tv));
  PetscCall(DemGetArrays(t.dem, &pa));
  PetscCall(PetscMalloc1(pa.nlocal + 1, &ph));
  PetscCall(CplSmoothAt(t.cpl, pa.nlocal, ph, NULL));
  for (PetscInt i = 0; i < nid; i++) phi[i] = ana[i] = 0;
  for (PetscInt p = 0; p < pa.nlocal; p++) {
    PetscCheck(pa.id[p] >= 0 && pa.id[p] < nid, PETSC_COMM_SELF, PETSC_ERR_PLIB, "particle id %d beyond %d", (int)pa.id[p], (int)nid);
    phi[pa.id[p]] = ph[p];
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, phi, (PetscMPIInt)nid, MPIU_REAL, MPIU_SUM, PETSC_COMM_WORLD));
  { /* every rank computes the analytic sum over all particles */
    PetscReal *xs;
    PetscCall(PetscCalloc1(3 * nid, &xs));
    for (PetscInt p = 0; p < pa.nlocal; p++)
      for (int e = 0; e < 3; e++) xs[3 * pa.id[p] + e] = pa.x[3 * p + e];
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, xs, (PetscMPIInt)(3 * nid), MPIU_REAL, MPIU_SUM, PETSC_COMM_WORLD));
    for (PetscInt i = 0; i < nid; i++)
      for (PetscInt j = 0; j < nid; j++) {
        PetscReal k = PETSC_PI / 6;
        for (int e = 0; e < 3; e++) k *= K1(&t.dom, e, tv.smooth_sigma, xs[3 * i + e], xs[3 * j + e]);
        ana[i] += k;
      }
    PetscCall(PetscFree(xs));
  }
  { /* the solid volume on the auxiliary grid against the particles' */
    const PetscReal va = tv.smooth_h[0] * tv.smooth_h[1] * tv.smooth_h[2];
    PetscReal       s;
    PetscCall(VecSum(tv.smooth_solid, &s));
    vsum[0] = s * va;
    PetscCall(DemGetLocalCount(t.dem, &count));
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &count, 1, MPIU_INT, MPI_SUM, PETSC_COMM_WORLD));
    PetscCheck(count == nid, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "%d particles, %d expected", (int)count, (int)nid);
    vsum[1]  = nid * PETSC_PI / 6;
    *sum_err = PetscAbsReal(vsum[0] / vsum[1] - 1);
  }
  PetscCall(PetscFree(ph));
  PetscCall(TestCplDestroy(&t));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* A lone sphere at x on 1 d cells: phi - own and the drag's porosity under -cpl_self_porosity. */
static PetscErrorCode Lone(const char *box, const char *split, const PetscReal x[3], PetscReal *diff, PetscReal *own, PetscReal *eps)
{
  TestCpl   t;
  DemArrays pa;
  char      opts[1024];
  PetscReal ph[2] = {0, 0}, ow[2] = {0, 0}, ep[2] = {0, 0};

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(opts, sizeof opts, BASE "%s -dem_lattice 1,1,1 -dem_lattice_spacing 1 -dem_lattice_origin %.17g,%.17g,%.17g -cpl_porosity_width 2 -cpl_self_porosity%s", box, (double)x[0], (double)x[1], (double)x[2], split));
  PetscCall(TestCplCreate(opts, &t));
  PetscCall(CplSmoothProject(t.cpl));
  PetscCall(DemGetArrays(t.dem, &pa));
  if (pa.nlocal) {
    PetscCall(CplSmoothAt(t.cpl, 1, ph, ow));
    PetscCall(CplSmoothSeen(t.cpl, 1, ep, NULL));
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, ph, 1, MPIU_REAL, MPIU_SUM, PETSC_COMM_WORLD));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, ow, 1, MPIU_REAL, MPIU_SUM, PETSC_COMM_WORLD));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, ep, 1, MPIU_REAL, MPIU_SUM, PETSC_COMM_WORLD));
  *diff = PetscAbsReal(ph[0] - ow[0]);
  *own  = ow[0];
  *eps  = ep[0];
  PetscCall(TestCplDestroy(&t));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The fluid feels what the particles feel: after 10 steps of a moving bed (self corrections on,
 * no fade off: lone and bed particles both), the drag set-up's two halves at the same fluid state
 * and positions give sum_p K_p (u_p - v_p) = sum_faces V_cell (beta u - sum K v W / V_cell). */
static PetscErrorCode FaceBalance(void)
{
  TestCpl            t;
  CplTestView        tv;
  CplStats           st;
  DemArrays          pa;
  DemExternal        ex;
  Vec                beta, u;
  const PetscScalar *b, *kv, *uf;
  PetscInt           n;
  char               opts[1024];
  PetscReal          loc[6] = {0, 0, 0, 0, 0, 0}, sum[6], err = 0, scale = 0;

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(opts, sizeof opts, BASE "-da_grid_x 6 -da_grid_y 12 -da_grid_z 6 -dem_lattice 5,5,5 -dem_lattice_spacing 1.1 -dem_lattice_origin 0.5,0.5,0.5 -dem_lattice_speed 0.5 -cpl_porosity_width 2.2 -cpl_self_porosity -cpl_self_velocity -cpl_substeps 5%s", Split()));
  PetscCall(TestCplCreateWith(opts, AddScatter, &t));
  PetscCall(TestCplRun(&t, 10, &st));
  PetscCall(CplSetParticleDrag(t.cpl));
  PetscCall(CplSetFluidDrag(t.cpl));
  PetscCall(CplGetTestView(t.cpl, &tv));
  PetscCall(DemGetArrays(t.dem, &pa));
  PetscCall(DemGetExternal(t.dem, &ex));
  for (PetscInt p = 0; p < pa.nlocal; p++)
    for (int k = 0; k < 3; k++) {
      loc[k] += ex.k[p] * (ex.u[3 * p + k] - pa.v[3 * p + k]);
      scale += PetscAbsReal(ex.k[p] * (ex.u[3 * p + k] - pa.v[3 * p + k]));
    }
  PetscCall(FluidGetDragCoefficient(t.fl, &beta));
  PetscCall(FluidGetVelocity(t.fl, &u));
  PetscCall(VecGetLocalSize(beta, &n));
  PetscCall(VecGetArrayRead(beta, &b));
  PetscCall(VecGetArrayRead(tv.kv, &kv));
  PetscCall(VecGetArrayRead(u, &uf));
  for (PetscInt i = 0; i < n; i++) loc[3 + i % 3] += tv.cell_vol * (b[i] * uf[i] - kv[i]);
  PetscCall(VecRestoreArrayRead(u, &uf));
  PetscCall(VecRestoreArrayRead(tv.kv, &kv));
  PetscCall(VecRestoreArrayRead(beta, &b));
  PetscCall(MPIU_Allreduce(loc, sum, 6, MPIU_REAL, MPIU_SUM, PETSC_COMM_WORLD));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &scale, 1, MPIU_REAL, MPIU_SUM, PETSC_COMM_WORLD));
  for (int k = 0; k < 3; k++) err = PetscMax(err, PetscAbsReal(sum[k] - sum[3 + k]));
  PetscCall(CheckBelow("the fluid's face drag equals the particles' drag: max |sum K (u - v) - sum V (beta u - K v W)| / sum |K (u - v)|", err / scale, 1e-12));
  PetscCall(TestCplDestroy(&t));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  const PetscInt  nid   = 150;
  const PetscReal hs[3] = {2, 3, 4}, ws[2] = {2.2, 3.5};
  PetscReal      *phi[3], *ana, serr;

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  for (int g = 0; g < 3; g++) PetscCall(PetscMalloc1(nid, &phi[g]));
  PetscCall(PetscMalloc1(nid, &ana));
  for (int iw = 0; iw < 2; iw++) {
    PetscReal top = 0, dmax = 0;
    for (int g = 0; g < 3; g++) {
      PetscReal err = 0;
      PetscCall(PhiById(hs[g], ws[iw], nid, phi[g], ana, &serr));
      PetscCall(CheckBelow(CheckName("W = %g, cells of %g d: smoothed solid volume / the particles' - 1", (double)ws[iw], (double)hs[g]), serr, 1e-12));
      for (PetscInt i = 0; i < nid; i++) top = PetscMax(top, ana[i]);
      for (PetscInt i = 0; i < nid; i++) err = PetscMax(err, PetscAbsReal(phi[g][i] - ana[i]));
      PetscCall(CheckBelow(CheckName("W = %g, cells of %g d: max |phi - analytic Gaussian with wall images| / max phi", (double)ws[iw], (double)hs[g]), err / top, 0.005));
    }
    for (PetscInt i = 0; i < nid; i++)
      for (int g = 1; g < 3; g++) dmax = PetscMax(dmax, PetscAbsReal(phi[g][i] - phi[0][i]));
    PetscCall(CheckBelow(CheckName("W = %g: max |phi(3 d or 4 d cells) - phi(2 d cells)| / max phi", (double)ws[iw]), dmax / top, 0.002));
  }
  {
    const PetscReal xs[4][3] = {{6.5, 6.5, 6.5}, {6.0, 6.5, 6.0}, {0.5, 3.0, 0.5}, {6.5, 1.5, 6.5}};
    const char     *where[4] = {"a cell centre", "an x and a z face", "the x and z walls", "a cell centre, y period 4 d (the kernel overlaps its own images)"};
    const char     *box[4]   = {"-da_grid_x 12 -da_grid_y 24 -da_grid_z 12", "-da_grid_x 12 -da_grid_y 24 -da_grid_z 12", "-da_grid_x 12 -da_grid_y 24 -da_grid_z 12", "-domain_hi 12,4,12 -da_grid_x 12 -da_grid_y 4 -da_grid_z 12"};
    for (int q = 0; q < 4; q++) {
      PetscReal diff, own, eps;
      PetscCall(Lone(box[q], q < 3 ? Split() : SplitZ(), xs[q], &diff, &own, &eps));
      PetscCall(CheckBelow(CheckName("lone sphere at %s: |phi - own share|", where[q]), diff, 1e-14));
      CheckDetail("own share %.4f", (double)own);
      PetscCall(CheckBelow(CheckName("lone sphere at %s, -cpl_self_porosity: |1 - the drag's porosity|", where[q]), PetscAbsReal(1 - eps), 1e-14));
    }
  }
  PetscCall(FaceBalance());
  for (int g = 0; g < 3; g++) PetscCall(PetscFree(phi[g]));
  PetscCall(PetscFree(ana));
  PetscCall(PetscFinalize());
  return check_failures ? 1 : 0;
}
