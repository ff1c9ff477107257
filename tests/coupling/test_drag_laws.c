/* The drag laws against their published formulas, evaluated outside Sable. The reference
 * values below were computed once with Python's math module from the formulas as published,
 * written independently of src/coupling/drag.c (no shared code, no log trick):
 *   Beetstra et al. (2007) = Grains3D Part II eq. (15), term by term with ** for the powers;
 *   Di Felice (1994): drag 1/2 Cd rho_f (pi d^2/4) eps^2 |w| w eps^-chi (w the interstitial slip,
 *     Re = rho_f d eps |w| / mu), total fluid force = drag / eps;
 *   Gidaspow (1994): the exchange coefficient beta of Ergun (eps < 0.8) or Wen and Yu, per
 *     particle K = beta V_p / ((1 - eps) eps).
 * Each is expressed as F = force / (3 pi mu d w), the form CplDragFactor returns, at d = rho_f =
 * mu = 1. Checks: all 48 values (4 porosities x 4 Re_p x 3 laws) to 1e-12 relative, and
 * Beetstra's single-sphere Stokes limit F(eps = 1, Re = 0) = 1 exactly. Schiller & Naumann
 * (1933) as in Clift, Grace & Weber (1978), Cd = 24/Re (1 + 0.15 Re^0.687) below Re = 1000, 0.44
 * from there, F = Cd Re / 24, at 7 Re_p on both sides of the switch (no porosity dependence:
 * the values hold at eps 0.5 and 1) to 1e-12. */
#include "check.h"
#include "coupling/coupling.h"

/* eps, Re_p, Beetstra, Di Felice, Gidaspow */
static const double Ref[16][5] = {
  {0.4, 0.01, 37.845903499096494, 29.201792513398374, 31.256076388888893},
  {0.4, 1, 37.865401459263332, 30.046335746081635, 31.857638888888889},
  {0.4, 100, 89.789415372358462, 90.062751651045559, 92.013888888888872},
  {0.4, 1000, 468.45585169885879, 622.83259370791689, 638.8888888888888},
  {0.4764, 0.01, 23.543751008760513, 15.298326657941343, 19.229661674863618},
  {0.4764, 1, 23.566062060782393, 16.328158587119816, 19.65375089424689},
  {0.4764, 100, 57.248150609949654, 52.145450704727836, 62.062672832573867},
  {0.4764, 1000, 298.78237698581682, 338.46754057576783, 447.59832681736458},
  {0.7, 0.01, 7.015036995748412, 3.685651765729792, 5.1040249433106579},
  {0.7, 1, 7.0560944401253032, 4.2642005528611922, 5.3004535147392291},
  {0.7, 100, 19.688225480212527, 15.657291706977057, 24.943310657596371},
  {0.7, 1000, 106.50846993563866, 88.39291129786514, 203.514739229025},
  {0.95, 0.01, 1.7595664142858227, 1.1912098714971899, 1.213538582759514},
  {0.95, 1, 1.8350591068145103, 1.4692991307619501, 1.3867771624502208},
  {0.95, 100, 6.8819036088125998, 6.0266937656547785, 5.4854628429972161},
  {0.95, 1000, 38.70226854669847, 30.457204375232191, 22.108041720220918},
};

/* Re_p, Schiller-Naumann F */
static const double RefSN[7][2] = {
  {0.01, 1.0063400292139841},
  {1, 1.15},
  {10, 1.7296108085371922},
  {100, 4.548879546228638},
  {999, 18.250144979412532},
  {1000, 18.333333333333332},
  {3000, 55.0},
};

int main(int argc, char **argv)
{
  const CplDragLaw law[3]  = {CPL_DRAG_BEETSTRA, CPL_DRAG_DIFELICE, CPL_DRAG_GIDASPOW};
  const char      *name[3] = {"Beetstra eq. (15)", "Di Felice", "Gidaspow (Ergun / Wen-Yu)"};

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  for (int l = 0; l < 3; l++) {
    double worst = 0, at[2] = {0, 0};
    for (int k = 0; k < 16; k++) {
      const double err = fabs(CplDragFactor(law[l], Ref[k][0], Ref[k][1]) / Ref[k][2 + l] - 1);
      if (!(err <= worst)) worst = err, at[0] = Ref[k][0], at[1] = Ref[k][1]; /* NaN is kept */
    }
    CheckDetail("at eps %g, Re_p %g", at[0], at[1]);
    PetscCall(CheckBelow(CheckName("drag law %s: 16 points eps 0.4-0.95, Re_p 0.01-1000, worst rel. error", name[l]), worst, 1e-12));
  }
  {
    double worst = 0, at = 0;
    for (int k = 0; k < 7; k++)
      for (int e = 0; e < 2; e++) {
        const double err = fabs(CplDragFactor(CPL_DRAG_SCHILLER, e ? 1.0 : 0.5, RefSN[k][0]) / RefSN[k][1] - 1);
        if (!(err <= worst)) worst = err, at = RefSN[k][0];
      }
    CheckDetail("at Re_p %g", at);
    PetscCall(CheckBelow("drag law Schiller-Naumann: 7 points Re_p 0.01-3000 at eps 0.5 and 1, worst rel. error", worst, 1e-12));
  }
  {
    const double F = CplDragFactor(CPL_DRAG_BEETSTRA, 1, 0);
    PetscCall(CheckEqualReal("drag law Beetstra: single sphere at Re_p 0 gives Stokes drag, F", F, 1));
  }
  PetscCall(PetscFinalize());
  return check_failures ? 1 : 0;
}
