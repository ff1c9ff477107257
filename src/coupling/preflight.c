/* Pre-flight checks of a coupled run, printed at start-up (CplView) and enforced at set-up:
 *  - dt_dem / contact duration (the DEM itself stops above -dem_dt_max_fraction);
 *  - coupling step / particle relaxation time tau = m / K, K from the drag law at the smallest
 *    cell porosity of the initial state (a restart's: the bed it restores) and Re_p -> 0 (the
 *    viscous end). With the drag
 *    implicit the step stays stable beyond tau, but the particle then relaxes to the fluid
 *    within one step and the exchange lags a step: hard limit -cpl_relaxation_ratio_max (1);
 *  - cell size / diameter (below 1 the porosity of a cell fluctuates with every particle that
 *    enters it: a warning) and kernel side / cell size (hard limit 2: the cube must reach at most
 *    one cell beyond its own, the ghost width of the grids);
 *  - every fluid face that is a wall, a slip wall or an inlet has a DEM wall at it or inside the
 *    domain before it (DemWallsCloseFace): else a particle that reaches it leaves the domain and
 *    the run stops (exchange.c). A warning per face, none for a frozen bed. Periodicity cannot
 *    differ: both read -domain_periodic_*, and a periodic fluid condition on a non-periodic
 *    axis (bc.c), a non-periodic one on a periodic axis (bc.c) or a -dem_box across a periodic
 *    axis (walls.c) is an error where it is read. */
#include "coupling/coupling_impl.h"

static PetscErrorCode CplCheckFaces(Cpl cpl, PetscViewer viewer)
{
  const char *side[2] = {"lo", "hi"}, *ax = "xyz";

  PetscFunctionBeginUser;
  if (cpl->clock.frozen) PetscFunctionReturn(PETSC_SUCCESS);
  for (int d = 0; d < 3; d++)
    for (int s = 0; s < 2; s++) {
      FluidBCType t;
      PetscBool   closed;
      PetscCall(FluidGetBC(cpl->fl, d, s, &t));
      if (t != FLUID_BC_WALL && t != FLUID_BC_SLIP && t != FLUID_BC_INLET) continue;
      PetscCall(DemWallsCloseFace(cpl->dem, d, s, &closed));
      if (!closed) PetscCall(PetscViewerASCIIPrintf(viewer, "warning: -fluid_bc_%c%s %s at %c = %.6g has no DEM wall there (-dem_box or -dem_plane_k): particles that reach it leave the domain and stop the run\n", ax[d], side[s], FluidBCNames[t], ax[d], (double)(s ? cpl->dom->hi[d] : cpl->dom->lo[d])));
    }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CplPreflight(Cpl cpl, PetscViewer viewer, PetscBool enforce)
{
  PetscReal hmin = PetscMin(cpl->dom->h[0], PetscMin(cpl->dom->h[1], cpl->dom->h[2]));
  PetscReal dmax = 0, smax = 0, tau = PETSC_MAX_REAL, dtc = 0, dtd, tc, e, rs[2];
  PetscBool poly;

  PetscFunctionBeginUser;
  PetscCall(DemGetTimeStep(cpl->dem, &dtd));
  for (PetscInt s = 0; s < cpl->kern.nshape; s++) {
    const PetscReal K = 3 * PETSC_PI * cpl->prop.mu * cpl->kern.diam[s] * CplDragFactor(cpl->drag.law, cpl->diag.eps_min0, 0);
    dmax              = PetscMax(dmax, cpl->kern.diam[s]);
    smax              = PetscMax(smax, cpl->kern.side[s]);
    tau               = PetscMin(tau, cpl->kern.mass[s] / K);
    PetscCall(DemGetContactFigures(cpl->dem, s, s, 1.0, &tc, &e));
    dtc = PetscMax(dtc, dtd / tc);
  }
  PetscCall(DemGetOwnSizes(cpl->dem, &poly, &rs[0], &rs[1]));
  for (int a = 0; a < 2 && poly; a++) { /* spheres of their own sizes: the smallest and the largest */
    const PetscReal v = 4.0 / 3.0 * PETSC_PI * rs[a] * rs[a] * rs[a], K = 3 * PETSC_PI * cpl->prop.mu * 2 * rs[a] * CplDragFactor(cpl->drag.law, cpl->diag.eps_min0, 0);
    dmax = PetscMax(dmax, 2 * rs[a]);
    smax = PetscMax(smax, cpl->kern.scale * PetscCbrtReal(v));
    tau  = PetscMin(tau, cpl->kern.mass[0] / cpl->kern.vol[0] * v / K);
    PetscCall(DemGetContactFiguresSized(cpl->dem, 0, 0, rs[a], rs[a], 1.0, &tc, &e));
    dtc = PetscMax(dtc, dtd / tc);
  }
  if (viewer) {
    PetscCall(PetscViewerASCIIPrintf(viewer, "pre-flight: dt_dem / contact time %.3g%s\n", (double)dtc, cpl->clock.frozen ? " (frozen: no DEM steps)" : ""));
    PetscCall(PetscViewerASCIIPrintf(viewer, "pre-flight: coupling step / particle relaxation time %.3g (tau = %.4g s at porosity %.3f, the smallest cell's of the %s; limit -cpl_relaxation_ratio_max %g)\n", (double)(cpl->clock.dt / tau), (double)tau, (double)cpl->diag.eps_min0, cpl->start.restarting ? "checkpoint's bed" : "start", (double)cpl->start.relax_max));
    PetscCall(PetscViewerASCIIPrintf(viewer, "pre-flight: cell / diameter %.3g, kernel side / cell %.3g (limit 2)\n", (double)(hmin / dmax), (double)(smax / hmin)));
    if (hmin < dmax) PetscCall(PetscViewerASCIIPrintf(viewer, "pre-flight: warning: cells smaller than a particle diameter; the porosity will fluctuate cell by cell\n"));
    PetscCall(CplCheckFaces(cpl, viewer));
  }
  if (!enforce) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCheck(smax <= 2 * hmin * (1 + 1e-12), cpl->comm, PETSC_ERR_ARG_OUTOFRANGE, "cube kernel side %g is %g cells of size %g, above the limit of 2: coarsen the grid (-da_grid_x/y/z) or lower -cpl_kernel_scale %g", (double)smax, (double)(smax / hmin), (double)hmin, (double)cpl->kern.scale);
  PetscCheck(cpl->clock.frozen || cpl->clock.dt <= cpl->start.relax_max * tau, cpl->comm, PETSC_ERR_ARG_OUTOFRANGE, "coupling step %g s is %g particle relaxation times (tau = m/K = %g s), above -cpl_relaxation_ratio_max %g: lower -dem_dt or -cpl_substeps, or raise the limit knowingly", (double)cpl->clock.dt, (double)(cpl->clock.dt / tau), (double)tau, (double)cpl->start.relax_max);
  PetscFunctionReturn(PETSC_SUCCESS);
}
