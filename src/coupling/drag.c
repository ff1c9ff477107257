/* Drag laws as the total fluid-particle force on a particle (buoyancy apart), the form of
 * Grains3D Part II eq. (14) where the fluid momentum equation carries -grad p (eq. 10):
 *   F = K (u - U),  K = 3 pi mu d F(eps, Re),  Re = rho_f d eps |u - U| / mu,
 * u the interstitial fluid velocity at the particle.
 *   Beetstra et al. (2007), eq. (15), phi = 1 - eps:
 *     F = 10 phi/eps^2 + eps^2 (1 + 1.5 sqrt(phi))
 *         + 0.413 Re / (24 eps^2) (1/eps + 3 eps phi + 8.4 Re^-0.343) / (1 + 10^(3 phi) Re^-(0.5 + 2 phi))
 *   Di Felice (1994): force 1/2 Cd rho (pi d^2/4) eps^2 |w| w eps^-chi on the particle, divided by
 *     eps for the total force in this form: F = Cd Re eps^-chi / 24, Cd = (0.63 + 4.8 Re^-1/2)^2,
 *     chi = 3.7 - 0.65 exp(-(1.5 - log10 Re)^2 / 2);
 *   Gidaspow (1994): the exchange coefficient beta (Ergun for eps < 0.8, Wen and Yu above) per
 *     particle, K = beta V_p / ((1 - eps) eps):
 *     eps < 0.8:  F = (150 phi + 1.75 Re) / (18 eps^2)
 *     eps >= 0.8: F = Cd Re eps^-3.65 / 24, Cd = 24/Re (1 + 0.15 Re^0.687) (Re < 1000), 0.44 above.
 *   Schiller & Naumann (1933), as given by Clift, Grace & Weber (1978), Table 5.2: the single
 *     sphere law without a voidage function, for dilute flows and one-way coupling:
 *     F = Cd Re / 24 = 1 + 0.15 Re^0.687 (Re < 1000), 0.44 Re / 24 above (Newton's range);
 *     Gidaspow at eps = 1 is the same law.
 * All four tend to Stokes drag (F = 1; Di Felice 0.96) for a single sphere at low Re. */
#include "coupling/coupling_impl.h"

PetscReal CplDragFactor(CplDragLaw law, PetscReal eps, PetscReal re)
{
  const PetscReal phi = 1 - eps;

  switch (law) {
  case CPL_DRAG_BEETSTRA: {
    PetscReal F = 10 * phi / (eps * eps) + eps * eps * (1 + 1.5 * PetscSqrtReal(phi));
    if (re > 1e-300) { /* Re^-0.343 and 10^(3 phi) Re^-(0.5 + 2 phi) from one logarithm */
      const PetscReal lre = PetscLogReal(re);
      const PetscReal num = 1 / eps + 3 * eps * phi + 8.4 * PetscExpReal(-0.343 * lre);
      const PetscReal den = 1 + PetscExpReal(3 * phi * 2.302585092994046 - (0.5 + 2 * phi) * lre);
      F += 0.413 * re / (24 * eps * eps) * num / den;
    }
    return F;
  }
  case CPL_DRAG_DIFELICE: {
    const PetscReal r   = PetscMax(re, 1e-12);
    const PetscReal cd  = PetscSqr(0.63 + 4.8 / PetscSqrtReal(r));
    const PetscReal chi = 3.7 - 0.65 * PetscExpReal(-0.5 * PetscSqr(1.5 - PetscLog10Real(r)));
    return cd * r * PetscPowReal(eps, -chi) / 24;
  }
  case CPL_DRAG_SCHILLER:
    return re < 1000 ? 1 + 0.15 * PetscPowReal(re, 0.687) : 0.44 * re / 24;
  case CPL_DRAG_GIDASPOW:
  default:
    if (eps < 0.8) return (150 * phi + 1.75 * re) / (18 * eps * eps);
    {
      const PetscReal cdre = re < 1000 ? 24 * (1 + 0.15 * PetscPowReal(re, 0.687)) : 0.44 * re;
      return cdre * PetscPowReal(eps, -3.65) / 24;
    }
  }
}

PetscReal CplPackedBedGradient(CplDragLaw law, PetscReal eps, PetscReal usup, PetscReal d, PetscReal rho, PetscReal mu)
{
  const PetscReal re = rho * d * PetscAbsReal(usup) / mu; /* rho d eps |u| / mu with u = U/eps */
  const PetscReal K  = 3 * PETSC_PI * mu * d * CplDragFactor(law, eps, re);
  const PetscReal n  = (1 - eps) / (PETSC_PI * d * d * d / 6);
  return n * K * PetscAbsReal(usup) / eps;
}
