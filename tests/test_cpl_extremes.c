/* Extremes of the coupled model: each case runs 1,000 fluid steps and must stay finite and
 * bounded (fluid speed below 50 inlet velocities, particle kinetic energy finite, porosity in
 * (0, 1]); the cases that cross a hard limit stop with a message (test_cpl_badinput.sh).
 *   density ratio 1.2 and 3000: the small fluidized bed of test_cpl_fluidization at U = 0.2;
 *   porosity 0.36: a frozen body-centred cubic bed (cube side 1.18 d, one cell per cube);
 *   Re_p 0.01 and 1000: the frozen lattice bed of test_cpl_packed with mu = 100 and 0.001. */
#include "cpl_common.h"

static const char *Bed = "-domain_lo 0,0,0 -domain_hi 8,4,48 -domain_periodic_x -domain_periodic_y -da_grid_x 4 -da_grid_y 2 -da_grid_z 24 "
                          "-dem_plane_0 0,0,2,0,0,1 -dem_plane_1 0,0,48,0,0,-1 "
                         "-dem_radius 0.5 -dem_gravity 0,0,-1 -dem_contact_law linear -dem_kn 1000 -dem_restitution 0.9 "
                         "-dem_friction 0.1 -dem_dt 0.005 -dem_lattice 8,4,12 -dem_lattice_spacing 1 "
                         "-dem_lattice_speed 0.01 -dem_lattice_origin 0,0,2 -fluid_density 1 -fluid_viscosity 0.01 -fluid_advection tvd "
                         "-fluid_bc_zlo inlet -fluid_bc_zhi outlet "
                         "-fluid_bc_zlo_velocity 0,0,0.2 -cpl_substeps 5";
static const char *Packed = "-domain_lo 0,0,0 -domain_hi 4,4,24 -domain_periodic_x -domain_periodic_y -da_grid_x 4 -da_grid_y 4 -da_grid_z 24 "
                            "-dem_radius 0.5 -dem_density 2 -dem_kn 1e4 -dem_dt 1e-3 -dem_frozen -dem_gravity 0,0,-1 "
                            "-fluid_density 1 -fluid_dt 0.05 -fluid_viscous implicit -fluid_advection tvd "
                            "-fluid_bc_zlo inlet -fluid_bc_zlo_velocity 0,0,1 -fluid_bc_zhi outlet";

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
        DemParticle p;
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

static PetscErrorCode Extreme(const char *name, const char *base, const char *extra, PetscReal uin, PetscErrorCode (*add)(Dem))
{
  TestCpl   t;
  CplStats  st;
  char      opts[2048];
  PetscReal umax = 0, emin = 1;
  PetscBool finite = PETSC_TRUE;
  DemStats  ds;
  Vec       u;

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(opts, sizeof opts, "%s %s", base, extra));
  PetscCall(TestCplCreateWith(opts, add, &t));
  PetscCall(FluidGetVelocity(t.fl, &u));
  for (PetscInt s = 0; s < 1000; s++) {
    PetscReal un;
    PetscCall(CplStep(t.cpl, &st));
    PetscCall(VecNorm(u, NORM_INFINITY, &un));
    finite = (PetscBool)(finite && PetscIsNormalReal(un));
    umax   = PetscMax(umax, un);
    emin   = PetscMin(emin, st.eps_min);
  }
  PetscCall(DemGetStats(t.dem, &ds));
  finite = (PetscBool)(finite && (PetscIsNormalReal(ds.ke) || ds.ke == 0));
  check((PetscBool)(finite && umax < 50 * uin && emin > 0), "%s: 1000 fluid steps, finite %s, max |u| / U_in %.3g (< 50), min porosity %.3f, particle KE %.3g", name, finite ? "yes" : "NO", (double)(umax / uin), (double)emin, (double)ds.ke);
  PetscCall(TestCplDestroy(&t));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(Extreme("density ratio 1.2", Bed, "-dem_density 1.2", 0.2, NULL));
  PetscCall(Extreme("density ratio 3000", Bed, "-dem_density 3000 -dem_kn 2e7 -dem_dt 0.001 -cpl_substeps 10", 0.2, NULL));
  PetscCall(Extreme("porosity 0.36 (frozen BCC bed, Re_p 10)", Packed, "-domain_hi 4.72,4.72,28.32 -dem_lattice 4,4,10 -dem_lattice_spacing 1.18 -dem_lattice_origin -0.59,-0.59,5.31 -fluid_viscosity 0.1", 1, AddBodyCentres));
  PetscCall(Extreme("Re_p 0.01 (frozen lattice)", Packed, "-dem_lattice 4,4,12 -dem_lattice_spacing 1 -dem_lattice_origin 0,0,6 -fluid_viscosity 100", 1, NULL));
  PetscCall(Extreme("Re_p 1000 (frozen lattice)", Packed, "-dem_lattice 4,4,12 -dem_lattice_spacing 1 -dem_lattice_origin 0,0,6 -fluid_viscosity 0.001", 1, NULL));
  PetscCall(PetscFinalize());
  return check_failures ? 1 : 0;
}
