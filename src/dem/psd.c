/* Particle size distributions (psd.h): the single-size law only. A source's diameter is
 * <prefix>_psd_mean (m), by default the diameter the caller gives (its shape's). The tables,
 * normal, lognormal and uniform laws of psd.h are not read here. */
#include "sable.h"
#include "dem/psd.h"

PetscErrorCode DemPsdSetFromOptions(PetscOptionItems *PetscOptionsObject, MPI_Comm comm, const char *prefix, PetscReal dflt_d, DemPsd *psd)
{
  char opt[96];

  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(psd, sizeof *psd));
  psd->kind = DEM_PSD_SINGLE;
  PetscCall(PetscSNPrintf(opt, sizeof opt, "%s_psd_mean", prefix));
  psd->mean = dflt_d;
  PetscCall(PetscOptionsReal(opt, "Diameter of the particles of a single-size source (m); default the shape's", NULL, psd->mean, &psd->mean, NULL));
  PetscCheck(psd->mean > 0 && PetscIsNormalReal(psd->mean), comm, PETSC_ERR_ARG_OUTOFRANGE, "%s %g must be > 0 (m)", opt, (double)psd->mean);
  psd->dmin = psd->dmax = psd->mean;
  PetscFunctionReturn(PETSC_SUCCESS);
}

double DemPsdSample(const DemPsd *psd, double u)
{
  (void)u;
  return psd->mean;
}

void DemPsdRange(const DemPsd *psd, double *dmin, double *dmax)
{
  *dmin = psd->dmin;
  *dmax = psd->dmax;
}

double DemPsdMeanCube(const DemPsd *psd)
{
  return psd->mean * psd->mean * psd->mean;
}
