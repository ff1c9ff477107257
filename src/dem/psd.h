/* Particle size distributions of a particle source (psd.c). A distribution is of the DIAMETER
 * (m), as practitioners quote a powder: a table of diameters with number or mass fractions, a
 * normal or lognormal law given by the number-weighted mean and standard deviation of the
 * diameter, or uniform, each optionally cut to [min, max]. A sample is drawn by inverting the
 * number-weighted cumulative distribution at a uniform number u in [0,1) (so the caller's
 * stateless hash gives the same diameter for the same particle on any rank count); with
 * classes > 0 the samples are snapped to that many diameters. Options (prefix e.g.
 * -dem_insert_0): <prefix>_psd kind, _psd_diameters, _psd_fractions, _psd_mean, _psd_std,
 * _psd_min, _psd_max, _psd_classes. */
#pragma once
#include <petscsys.h>

typedef enum {
  DEM_PSD_SINGLE, /* one diameter: mean */
  DEM_PSD_NUMBER, /* table: diameters and number fractions */
  DEM_PSD_MASS,   /* table: diameters and mass fractions */
  DEM_PSD_NORMAL,
  DEM_PSD_LOGNORMAL,
  DEM_PSD_UNIFORM /* uniform in [min, max] */
} DemPsdKind;

#define DEM_PSD_MAX_TABLE 64

typedef struct {
  DemPsdKind kind;
  PetscInt   ntab;
  PetscReal  d[DEM_PSD_MAX_TABLE], frac[DEM_PSD_MAX_TABLE]; /* table; frac as given */
  PetscReal  cum[DEM_PSD_MAX_TABLE];                        /* number-weighted cumulative fractions */
  PetscReal  mean, std, dmin, dmax;                         /* diameters (m); dmin/dmax the cut-offs */
  PetscInt   classes;                                       /* > 0: samples snapped to this many diameters */
  PetscReal  mu, sigma, plo, phi;                           /* derived: log-parameters, CDF at the cut-offs */
  PetscReal  qlo, qhi;                                      /* 1 - CDF at the cut-offs (a window above the median samples by these) */
} DemPsd;

/* Reads <prefix>_psd* inside an open PetscOptionsBegin block; checks the values (one line naming
 * the option, value and range); dflt_d is the diameter of a single-size source. Under -help it
 * only reads (the law is left single, of diameter dflt_d: an incomplete one is no error). */
PetscErrorCode DemPsdSetFromOptions(PetscOptionItems *PetscOptionsObject, MPI_Comm comm, const char *prefix, PetscReal dflt_d, DemPsd *psd);
/* The diameter (m) at the uniform number u in [0,1). */
double DemPsdSample(const DemPsd *psd, double u);
/* The smallest and largest diameter a sample can take (m). */
void DemPsdRange(const DemPsd *psd, double *dmin, double *dmax);
/* The number-weighted mean of d^3 (m^3): mass per particle = rho pi/6 <d^3>, for kg/s rates. */
double DemPsdMeanCube(const DemPsd *psd);
/* The quantile of the standard normal law at p in (0,1) (-inf at 0, inf at 1), to ~1e-15. */
double DemPsdNormalQuantile(double p);
/* Not collective. One line saying the distribution (kind, sizes, cut-offs), for a summary. */
PetscErrorCode DemPsdDescribe(const DemPsd *psd, char *buf, size_t size);
