/* Cylinder wall with particles inside, rotating about its own axis (a rotating drum).
 *
 * Axis through point a with unit direction u, radius R. A sphere of centre x, radius r has
 * radial offset rho = (x - a) - ((x - a).u) u and overlap delta = r + |rho| - R; the normal from
 * the centre to the wall is rho/|rho| (geom/surface_cylinder.h). The drum turns at omega
 * (rad/s, right-handed about u): its surface velocity at the contact point c = x + (r - delta/2)
 * rho/|rho| is omega u x (c - a), and it enters the relative velocity of the contact, hence the
 * tangential (friction) force, exactly as a translating plane's velocity does (walls.c). The
 * geometry does not change as it turns, so the wall never triggers a list rebuild.
 * The curvature is ignored in the contact law (the wall is a partner of infinite radius, R* = r,
 * as for planes: exact for the linear laws, for Hertz an error of order r/R in the stiffness).
 * End caps (-dem_cylinder_caps s0,s1): two planes perpendicular to the axis at a + s0 u and
 * a + s1 u facing inward, co-rotating with the drum (surface velocity omega u x (c - a), in their
 * plane); inside the cylinder a plane is the same as the disc. The cylinder is infinitely long
 * without caps (close it with caps, planes, or a periodic domain axis).
 * Options: -dem_cylinder ax,ay,az,ux,uy,uz,R (m, -, m); -dem_cylinder_omega (rad/s);
 * -dem_cylinder_caps s0,s1 (m); -dem_cylinder_friction (cylinder and caps); -dem_cylinder_fluid
 * yes|no (default yes) and -dem_cylinder_caps_fluid yes|no (default no): whether they bound the
 * gas of a coupled run as well (vessel.c). Spheres only. */
#include "dem/dem_walls.h"

/* Reads the cylinder options inside the walls' options block (walls.c). */
PetscErrorCode DemWallCylinderOptions(PetscOptionItems *PetscOptionsObject, Dem dem)
{
  PetscReal cyl[7], caps[2], omega = 0;
  PetscBool set, oset, cset, help, gas, gset, capgas, capset;
  DemWall  *w;

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsHasHelp(NULL, &help)); /* -help: the friction listed without a cylinder */
  PetscCall(SableOptionsRealN("-dem_cylinder", "Cylinder wall, particles inside: axis point ax,ay,az (m), axis direction ux,uy,uz (-), radius R (m)", NULL, cyl, 0, 7, &set));
  PetscCall(SableOptionsReal("-dem_cylinder_omega", "Angular velocity of the cylinder (and its caps) about its axis, right-handed", "rad/s", NULL, 0, &omega, &oset));
  PetscCall(SableOptionsRealN("-dem_cylinder_caps", "End caps: axial positions s0,s1 (from the axis point along the axis) of two planes perpendicular to the axis, co-rotating; default no caps", "m", caps, 0, 2, &cset));
  PetscCall(SableOptionsBool("-dem_cylinder_fluid", "Whether the cylinder also bounds the gas in a coupled run (the gas inside it; it may turn about its own axis)", PETSC_TRUE, &gas, &gset));
  PetscCall(SableOptionsBool("-dem_cylinder_caps_fluid", "Whether the end caps also bound the gas in a coupled run (default no: they let the gas through, as a distributor and an outlet)", PETSC_FALSE, &capgas, &capset));
  PetscCheck(set || (!oset && !cset && !gset && !capset) || help, dem->comm, PETSC_ERR_ARG_WRONG, "%s given without -dem_cylinder", oset ? "-dem_cylinder_omega" : cset ? "-dem_cylinder_caps"
                                                                                                                                                                 : gset ? "-dem_cylinder_fluid"
                                                                                                                                                                        : "-dem_cylinder_caps_fluid");
  PetscCheck(cset || !capset || help, dem->comm, PETSC_ERR_ARG_WRONG, "-dem_cylinder_caps_fluid given without -dem_cylinder_caps");
  if (!set && help) PetscCall(DemWallFrictionOption(PetscOptionsObject, dem, "-dem_cylinder_friction", 1, -1));
  if (!set) PetscFunctionReturn(PETSC_SUCCESS);
  const double u[3] = {cyl[3], cyl[4], cyl[5]}, lu = sqrt(dem_dot(u, u));
  PetscCheck(lu > 0, dem->comm, PETSC_ERR_ARG_OUTOFRANGE, "-dem_cylinder: the axis direction %g,%g,%g must be non-zero", (double)u[0], (double)u[1], (double)u[2]);
  PetscCheck(cyl[6] > 0, dem->comm, PETSC_ERR_ARG_OUTOFRANGE, "-dem_cylinder: radius %g must be > 0 (m)", (double)cyl[6]);
  PetscCheck(!cset || caps[1] > caps[0], dem->comm, PETSC_ERR_ARG_OUTOFRANGE, "-dem_cylinder_caps: s1 %g must exceed s0 %g (m)", (double)caps[1], (double)caps[0]);
  const double   a[3] = {cyl[0], cyl[1], cyl[2]}, un[3] = {u[0] / lu, u[1] / lu, u[2] / lu};
  const PetscInt first = dem->walls.nwall;
  PetscCall(DemWallAdd(dem, "-dem_cylinder", a, un, (double[3]){0, 0, 0}));
  w         = &dem->walls.wall[dem->walls.nwall - 1];
  w->s.kind = SURFACE_CYLINDER;
  w->s.R    = cyl[6];
  for (int c = 0; c < 2 && cset; c++) { /* caps facing inward: +u at s0, -u at s1 */
    const double p[3] = {a[0] + caps[c] * un[0], a[1] + caps[c] * un[1], a[2] + caps[c] * un[2]};
    const double n[3] = {c ? -un[0] : un[0], c ? -un[1] : un[1], c ? -un[2] : un[2]};
    PetscCall(DemWallAdd(dem, c ? "-dem_cylinder_caps s1" : "-dem_cylinder_caps s0", p, n, (double[3]){0, 0, 0}));
  }
  for (PetscInt k = first; k < dem->walls.nwall; k++) {
    w          = &dem->walls.wall[k];
    w->s.omega = omega;
    w->fluid   = k == first ? gas : capgas;
    for (int c = 0; c < 3; c++) {
      w->s.ax_p[c] = a[c];
      w->s.ax_u[c] = un[c];
    }
  }
  PetscCall(DemWallFrictionOption(PetscOptionsObject, dem, "-dem_cylinder_friction", 1, first));
  for (PetscInt k = first + 1; k < dem->walls.nwall; k++) dem->walls.wall[k].mu = dem->walls.wall[first].mu;
  PetscFunctionReturn(PETSC_SUCCESS);
}
