/* Extremes of the coupled model: each case runs 1,000 fluid steps and must stay finite and
 * bounded (fluid and particle velocity components below twice a speed scale, see Extreme;
 * particle kinetic energy finite, porosity in (0, 1]); the frozen beds must also reach their
 * designed porosity (none clipped to the floor); the cases that cross a hard limit stop with a
 * message (tests/coupling/test_badinput.sh).
 *   density ratio 1.2 and 3000: the small fluidized bed of test_fluidization.c at U = 0.2;
 *   porosity 0.36: a frozen body-centred cubic bed (cube side 1.18 d, one cell per cube);
 *   Re_p 0.01 and 1000: the frozen lattice bed of test_packed.c with mu = 100 and 0.001.
 * The scenes: fluidized_bed_periodic.opts and packed_bed.opts. */
#include "cpl_common.h"

/* The body centres of a BCC bed whose corners are the -dem_lattice sites: the lattice (4 x 4 x
 * 10, spacing a = 1.18, origin -a/2, -a/2, 4.5 a) puts its sites at (i a, j a, 5 a + k a); each body
 * centre sits half a spacing further along every axis, inside the periodic box (nearest-neighbour
 * distance sqrt(3) a / 2 = 1.022 d: no overlap), so a cube of the grid holds two spheres'
 * volume and the bed's porosity is 1 - 2 (pi/6) / a^3 = 0.363. */
static PetscErrorCode AddBodyCentres(Dem dem)
{
  const PetscReal a = 1.18;

  PetscFunctionBeginUser;
  for (PetscInt k = 0; k < 10; k++)
    for (PetscInt j = 0; j < 4; j++)
      for (PetscInt i = 0; i < 4; i++) {
        DemParticle p = {0};
        PetscCall(PetscMemzero(&p, sizeof p));
        p.id   = 100000 + i + 4 * (j + 4 * k);
        p.q[0] = 1;
        p.x[0] = (i + 0.5) * a;
        p.x[1] = (j + 0.5) * a;
        p.x[2] = 5 * a + (k + 0.5) * a;
        PetscCall(DemAddParticle(dem, &p));
      }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Runs 1,000 fluid steps of base + extra; eps_want > 0: the bed's designed porosity, which the
 * smallest cell porosity must equal (to 0.005, no cell clipped to the floor). Speed scale S =
 * max(U_in / eps_min, sqrt(2 g H)): continuity makes U_in / eps the interstitial speed at the
 * densest cell, and a bed of height H (0 when frozen) released from rest cannot give a particle
 * more than its free-fall speed over H; the drag cannot push a particle past the fluid. Fluid
 * and particle velocity components must stay below 2 S. */
typedef struct {
  const char *name, *scene, *extra; /* scene: an options file of this folder */
  PetscReal   uin, H, eps_want;
  PetscErrorCode (*add)(Dem);
} ExtremeCase;

static PetscErrorCode Extreme(const ExtremeCase *c)
{
  const char     *name = c->name;
  const PetscReal uin = c->uin, H = c->H, eps_want = c->eps_want;
  TestCpl         t;
  CplStats        st;
  PetscReal       umax = 0, vmax = 0, emin = 1, bound;
  PetscInt        clipped = 0;
  PetscBool       finite  = PETSC_TRUE;
  DemStats        ds;
  Vec             u;

  PetscFunctionBeginUser;
  PetscCall(TestCplCreateScene(c->scene, c->extra, c->add, &t));
  PetscCall(FluidGetVelocity(t.fl, &u));
  for (PetscInt s = 0; s < 1000; s++) {
    PetscReal un, vl = 0, vg;
    DemArrays pa;
    PetscCall(CplStep(t.cpl, &st));
    PetscCall(VecNorm(u, NORM_INFINITY, &un));
    PetscCall(DemGetArrays(t.dem, &pa));
    for (PetscInt p = 0; p < 3 * pa.nlocal; p++) vl = PetscMax(vl, PetscAbsReal(pa.v[p]));
    if (PetscIsNanReal(vl)) vl = PETSC_INFINITY;
    PetscCall(MPIU_Allreduce(&vl, &vg, 1, MPIU_REAL, MPIU_MAX, PETSC_COMM_WORLD));
    finite = (PetscBool)(finite && PetscIsNormalReal(un) && !PetscIsInfOrNanReal(vg));
    umax   = PetscMax(umax, un);
    vmax   = PetscMax(vmax, vg);
    emin   = PetscMin(emin, st.eps_min);
    clipped += st.clipped;
  }
  PetscCall(DemGetStats(t.dem, &ds));
  finite = (PetscBool)(finite && (PetscIsNormalReal(ds.ke) || ds.ke == 0));
  bound  = 2 * PetscMax(uin / emin, PetscSqrtReal(2 * 1.0 * H)); /* g = 1 in both set-ups */
  CheckDetail("particle KE %.3g", (double)ds.ke);
  PetscCall(CheckTrue(CheckName("%s: 1000 fluid steps, finite", name), finite, NULL));
  PetscCall(CheckBelow(CheckName("%s: max fluid |u_i| (bound 2 S)", name), umax, bound));
  PetscCall(CheckBelow(CheckName("%s: max particle |v_i| (bound 2 S)", name), vmax, bound));
  PetscCall(CheckAbove(CheckName("%s: min porosity, positive", name), emin, 0));
  PetscCall(CheckAtMost(CheckName("%s: min porosity, at most 1", name), emin, 1));
  if (eps_want > 0) {
    PetscCall(CheckCloseAbs(CheckName("%s: the bed reaches its designed porosity (min porosity)", name), emin, eps_want, 0.005));
    PetscCall(CheckEqual(CheckName("%s: cells clipped to the porosity floor", name), clipped, 0));
  }
  PetscCall(TestCplDestroy(&t));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  const PetscReal a = 1.18, eps_bcc = 1 - 2 * (PETSC_PI / 6) / (a * a * a), eps_sc = 1 - PETSC_PI / 6;

  PetscCall(Extreme(&(ExtremeCase){"density ratio 1.2", "fluidized_bed_periodic.opts", "-fluid_bc_zlo_velocity 0,0,0.2 -dem_density 1.2", 0.2, 12, 0, NULL}));
  PetscCall(Extreme(&(ExtremeCase){"density ratio 3000", "fluidized_bed_periodic.opts", "-fluid_bc_zlo_velocity 0,0,0.2 -dem_density 3000 -dem_kn 2e7 -dem_dt 0.001 -cpl_substeps 10", 0.2, 12, 0, NULL}));
  PetscCall(Extreme(&(ExtremeCase){"porosity 0.36 (frozen BCC bed, Re_p 10)", "packed_bed.opts", "-domain_hi 4.72,4.72,28.32 -dem_lattice 4,4,10 -dem_lattice_spacing 1.18 -dem_lattice_origin -0.59,-0.59,5.31 -fluid_viscosity 0.1", 1, 0, eps_bcc, AddBodyCentres}));
  /* Re_p = rho_f d U / mu with the superficial U = 1 (the interstitial form rho d eps |u| / mu
   * is the same number in a uniform bed) */
  PetscCall(Extreme(&(ExtremeCase){"Re_p 0.01 (frozen lattice, mu 100)", "packed_bed.opts", "-dem_lattice 4,4,12 -dem_lattice_spacing 1 -dem_lattice_origin 0,0,6 -fluid_viscosity 100", 1, 0, eps_sc, NULL}));
  PetscCall(Extreme(&(ExtremeCase){"Re_p 1000 (frozen lattice, mu 0.001)", "packed_bed.opts", "-dem_lattice 4,4,12 -dem_lattice_spacing 1 -dem_lattice_origin 0,0,6 -fluid_viscosity 0.001", 1, 0, eps_sc, NULL}));
  PetscCall(PetscFinalize());
  return check_failures ? 1 : 0;
}
