/* Pre-flight checks of a coupled run, printed at start-up (CplView) and enforced at set-up:
 *  - dt_dem / contact duration (the DEM itself stops above -dem_dt_max_fraction);
 *  - coupling step / particle relaxation time tau = m / K, K from the drag law at the smallest
 *    cell porosity of the initial state and Re_p -> 0 (the viscous end). With the drag
 *    implicit the step stays stable beyond tau, but the particle then relaxes to the fluid
 *    within one step and the exchange lags a step: hard limit -cpl_relaxation_ratio_max (1);
 *  - cell size / diameter (below 1 the porosity of a cell fluctuates with every particle that
 *    enters it: a warning) and kernel side / cell size (hard limit 2: the cube must reach at most
 *    one cell beyond its own, the ghost width of the grids). */
#include "coupling/coupling_impl.h"

PetscErrorCode CplPreflight(Cpl cpl, PetscViewer viewer, PetscBool enforce)
{
  PetscReal hmin = PetscMin(cpl->dom->h[0], PetscMin(cpl->dom->h[1], cpl->dom->h[2]));
  PetscReal dmax = 0, smax = 0, tau = PETSC_MAX_REAL, dtc = 0, dtd, tc, e;

  PetscFunctionBeginUser;
  PetscCall(DemGetTimeStep(cpl->dem, &dtd));
  for (PetscInt s = 0; s < cpl->nshape; s++) {
    const PetscReal K = 3 * PETSC_PI * cpl->mu * cpl->diam[s] * CplDragFactor(cpl->law, cpl->eps_min0, 0);
    dmax = PetscMax(dmax, cpl->diam[s]);
    smax = PetscMax(smax, cpl->side[s]);
    tau  = PetscMin(tau, cpl->mass[s] / K);
    PetscCall(DemGetContactFigures(cpl->dem, s, s, 1.0, &tc, &e));
    dtc = PetscMax(dtc, dtd / tc);
  }
  if (viewer) {
    PetscCall(PetscViewerASCIIPrintf(viewer, "pre-flight: dt_dem / contact time %.3g%s\n", (double)dtc, cpl->frozen ? " (frozen: no DEM steps)" : ""));
    PetscCall(PetscViewerASCIIPrintf(viewer, "pre-flight: coupling step / particle relaxation time %.3g (tau = %.4g s at porosity %.3f; limit -cpl_relaxation_ratio_max %g)\n", (double)(cpl->dt / tau), (double)tau, (double)cpl->eps_min0, (double)cpl->relax_max));
    PetscCall(PetscViewerASCIIPrintf(viewer, "pre-flight: cell / diameter %.3g, kernel side / cell %.3g (limit 2)\n", (double)(hmin / dmax), (double)(smax / hmin)));
    if (hmin < dmax) PetscCall(PetscViewerASCIIPrintf(viewer, "pre-flight: warning: cells smaller than a particle diameter; the porosity will fluctuate cell by cell\n"));
  }
  if (!enforce) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCheck(smax <= 2 * hmin * (1 + 1e-12), cpl->comm, PETSC_ERR_ARG_OUTOFRANGE, "cube kernel side %g is %g cells of size %g, above the limit of 2: coarsen the grid (-da_grid_x/y/z) or lower -cpl_kernel_scale %g", (double)smax, (double)(smax / hmin), (double)hmin, (double)cpl->kscale);
  PetscCheck(cpl->frozen || cpl->dt <= cpl->relax_max * tau, cpl->comm, PETSC_ERR_ARG_OUTOFRANGE, "coupling step %g s is %g particle relaxation times (tau = m/K = %g s), above -cpl_relaxation_ratio_max %g: lower -dem_dt or -cpl_substeps, or raise the limit knowingly", (double)cpl->dt, (double)(cpl->dt / tau), (double)tau, (double)cpl->relax_max);
  PetscFunctionReturn(PETSC_SUCCESS);
}
