/* One coupling step (the algorithm and the exact momentum exchange are described in couple.c):
 * drag at the particles, DEM substeps, porosity and face drag fields, fluid step, then the
 * momentum owed to the fluid for the next step. */
#include "coupling/coupling_impl.h"

static PetscErrorCode CplPressureExchange(Cpl, Vec);

/* Drag coefficient, fluid velocity and buoyancy at the particles; zeroes the impulses. */
PetscErrorCode CplSetParticleDrag(Cpl cpl)
{
  DemArrays   pa;
  DemExternal ex;
  PetscReal  *eps, *fade, *gp = NULL, *ep = NULL;
  PetscInt    capped[2] = {0, 0};

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(cpl->ev.drag, 0, 0, 0, 0));
  PetscCall(DemGetArrays(cpl->dem, &pa));
  PetscCall(DemGetExternal(cpl->dem, &ex));
  PetscCall(PetscMalloc2(pa.nlocal + 1, &eps, pa.nlocal + 1, &fade));
  PetscCall(CplSeenPorosity(cpl, pa.nlocal, ex.u, eps, fade));
  if (cpl->drag.form == CPL_FORM_A) { /* the pressure gradient at the particles (p^n) and the porosity of its force's reaction */
    PetscCall(FluidGetPressureGradient(cpl->fl, cpl->ex.gp));
    PetscCall(DMGlobalToLocal(cpl->fda, cpl->ex.gp, INSERT_VALUES, cpl->ex.gploc));
    PetscCall(PetscMalloc2(3 * pa.nlocal + 1, &gp, 3 * pa.nlocal + 1, &ep));
    PetscCall(CplInterpolateFaces(cpl, cpl->ex.gploc, gp));
    if (cpl->drag.mode == CPL_MODE_TWOWAY) {
      PetscCall(CplPressureExchange(cpl, cpl->ex.floc[0]));
      PetscCall(CplInterpolateFaces(cpl, cpl->ex.floc[0], ep));
      for (PetscInt p = 0; p < pa.nlocal; p++) ep[p] = (ep[3 * p] + ep[3 * p + 1] + ep[3 * p + 2]) / 3;
    } else
      for (PetscInt p = 0; p < pa.nlocal; p++) ep[p] = 1; /* one-way: the fluid alone */
  }
  for (PetscInt p = 0; p < pa.nlocal; p++) {
    const PetscReal d = CplDiameterOf(cpl, &pa, p), vol = CplVolumeOf(cpl, &pa, p);
    PetscReal       w2 = 0;
    for (int k = 0; k < 3; k++) w2 += PetscSqr(ex.u[3 * p + k] - pa.v[3 * p + k]);
    const PetscReal re = cpl->prop.rho * d * eps[p] * PetscSqrtReal(w2) / cpl->prop.mu;
    if (cpl->self.u && fade[p] > 0) {
      PetscBool cap;
      ex.k[p] = CplUndisturbedK(cpl, p, d, eps[p], ex.u + 3 * p, pa.v + 3 * p, fade[p], &cap);
      capped[0] += cap;
    } else ex.k[p] = 3 * PETSC_PI * cpl->prop.mu * d * CplDragFactor(cpl->drag.law, eps[p], re);
    PetscCheck(PetscIsNormalReal(ex.k[p]), PETSC_COMM_SELF, PETSC_ERR_FP, "particle %" PetscInt_FMT ": drag coefficient %g at porosity %g, Re_p %g is not finite", pa.id[p], (double)ex.k[p], (double)eps[p], (double)re);
    for (int k = 0; k < 3; k++) {
      ex.fext[3 * p + k] = -cpl->prop.rho * vol * cpl->prop.g[k];
      ex.j[3 * p + k]    = 0;
    }
    if (gp) { /* form A: e times the law's drag, and -V grad p held over the step */
      ex.k[p] *= ep[p];
      for (int k = 0; k < 3; k++) ex.fext[3 * p + k] -= vol * gp[3 * p + k];
    }
  }
  PetscCall(PetscFree2(eps, fade));
  PetscCall(PetscFree2(gp, ep));
  if (cpl->self.u) { /* a counted warning, printed once: the corrected drag is too low there */
    PetscCall(MPIU_Allreduce(capped, capped + 1, 1, MPIU_INT, MPI_SUM, cpl->comm));
    const PetscReal hmin = PetscMin(PetscMin(cpl->dom->h[0], cpl->dom->h[1]), cpl->dom->h[2]);
    if (capped[1] > 0 && cpl->self.capped_total == 0)
      PetscCall(PetscPrintf(cpl->comm, "warning: -cpl_self_velocity capped for %" PetscInt_FMT " particle(s): the grid's response to a particle's own drag reaches its slip (G K >= 0.9), the cube kernel is hydrodynamically smaller than the particle on cells of %g m, its drag stays too low; raise -cpl_kernel_scale (now %g): a kernel side of two cells, %.3g here, held a single sphere within 1.2%% of its law at Re 10 and 100 on cells of 1 to 8 diameters\n", capped[1], (double)hmin, (double)cpl->kern.scale, (double)(0.999 * 2 * hmin / (PetscCbrtReal(PETSC_PI / 6) * cpl->kern.diam[0]))));
    cpl->self.capped_total += capped[1];
  }
  PetscCall(PetscLogEventEnd(cpl->ev.drag, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Form A, at the step's start (positions x^n, the face gradient g of p^n in ex.gp): the particles'
 * volumes spread onto the faces as beta is, phi = sum V_p W / V_f. A particle's force -V_p sum_f
 * W_pf g_f is given back face by face: the fluid's source R = phi g (ex.phi, added in
 * CplSetFluidDrag), so the fluid loses what the particles gain, exactly and locally (steady and
 * uniform: (1 - phi) g balances the drag, the fluid's -eps grad p). eloc (ghosted) gets the
 * porosity the particle's drag is scaled by, e = 1 - phi at a face, 1 - 2 phi on a wall or inlet
 * face point (its half cell), at least -cpl_porosity_floor. */
static PetscErrorCode CplPressureExchange(Cpl cpl, Vec eloc)
{
  DemArrays          pa;
  PetscReal         *vol;
  Vec                ev;
  PetscScalar       *e, *r;
  const PetscScalar *g;
  PetscInt           xs[3], xm[3], idx[3], c = 0;
  const Domain      *dom = cpl->dom;

  PetscFunctionBeginUser;
  PetscCall(DemGetArrays(cpl->dem, &pa));
  PetscCall(PetscMalloc1(pa.nlocal + 1, &vol));
  for (PetscInt p = 0; p < pa.nlocal; p++) vol[p] = CplVolumeOf(cpl, &pa, p);
  {
    const CplSpread sp = {vol, PETSC_TRUE, cpl->ex.phi};
    PetscCall(CplSpreadFaces(cpl, 1, &sp));
  }
  PetscCall(PetscFree(vol));
  PetscCall(DMGetGlobalVector(cpl->fda, &ev));
  PetscCall(DMDAGetCorners(cpl->fda, &xs[0], &xs[1], &xs[2], &xm[0], &xm[1], &xm[2]));
  PetscCall(VecGetArray(cpl->ex.phi, &r));
  PetscCall(VecGetArrayRead(cpl->ex.gp, &g));
  PetscCall(VecGetArray(ev, &e));
  for (idx[2] = xs[2]; idx[2] < xs[2] + xm[2]; idx[2]++)
    for (idx[1] = xs[1]; idx[1] < xs[1] + xm[1]; idx[1]++)
      for (idx[0] = xs[0]; idx[0] < xs[0] + xm[0]; idx[0]++, c += 3)
        for (int d = 0; d < 3; d++) {
          const PetscBool bnd = (PetscBool)(!dom->periodic[d] && (idx[d] == 0 || idx[d] == dom->cells[d]));
          e[c + d]            = PetscMax(1 - (bnd ? 2 : 1) * PetscRealPart(r[c + d]), cpl->drag.eps_floor);
          r[c + d] *= g[c + d];
        }
  PetscCall(VecRestoreArray(ev, &e));
  PetscCall(VecRestoreArrayRead(cpl->ex.gp, &g));
  PetscCall(VecRestoreArray(cpl->ex.phi, &r));
  PetscCall(DMGlobalToLocal(cpl->fda, ev, INSERT_VALUES, eloc));
  PetscCall(DMRestoreGlobalVector(cpl->fda, &ev));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Form A, for the step's mean fluid force: the sum of the particles' pressure-gradient forces,
 * fext + rho_f V g (fext less the buoyancy; 0 for a particle that joined during the step, whose
 * K is still 0: DemAddParticle clears its arrays). Local. */
static void CplPressureForceSum(Cpl cpl, const DemArrays *pa, const DemExternal *ex, PetscReal tot[3])
{
  tot[0] = tot[1] = tot[2] = 0;
  for (PetscInt p = 0; p < pa->nlocal; p++) {
    const PetscReal vol = CplVolumeOf(cpl, pa, p);
    if (ex->k[p] > 0)
      for (int k = 0; k < 3; k++) tot[k] += ex->fext[3 * p + k] + cpl->prop.rho * vol * cpl->prop.g[k];
  }
}

/* beta and u_s on the faces from K and the particle velocities at the new positions, and the
 * impulses of the DEM substeps just taken (for the momentum owed after the fluid step), in one
 * pass; the source is the momentum owed from the previous step. */
PetscErrorCode CplSetFluidDrag(Cpl cpl)
{
  DemArrays          pa;
  DemExternal        ex;
  Vec                beta, us, src;
  PetscReal         *kv, *ka, *kb, *fd;
  PetscScalar       *u;
  const PetscBool    smooth = (PetscBool)(cpl->pw.width > 0);
  const PetscScalar *b, *m;
  PetscInt           n;

  PetscFunctionBeginUser;
  PetscCall(DemGetArrays(cpl->dem, &pa));
  PetscCall(DemGetExternal(cpl->dem, &ex));
  PetscCall(FluidGetDragCoefficient(cpl->fl, &beta));
  PetscCall(FluidGetSolidVelocity(cpl->fl, &us));
  PetscCall(FluidGetMomentumSource(cpl->fl, &src));
  PetscCall(PetscMalloc4(3 * pa.nlocal + 1, &kv, pa.nlocal + 1, &ka, pa.nlocal + 1, &kb, pa.nlocal + 1, &fd));
  for (PetscInt p = 0; p < 3 * pa.nlocal; p++) kv[p] = ex.k[p / 3] * pa.v[p];
  if (smooth) { /* smooth.c: the particles' force on the fluid, beta_f = sum (K f W + eps_f K (1 - f) / eps_p W) / V_cell */
    PetscCall(CplSmoothSeen(cpl, pa.nlocal, kb, fd));
    for (PetscInt p = 0; p < pa.nlocal; p++) {
      ka[p] = ex.k[p] * fd[p];
      kb[p] = ex.k[p] * (1 - fd[p]) / kb[p];
    }
  }
  {
    const CplSpread sp[3] = {{smooth ? ka : ex.k, PETSC_TRUE, beta}, {kv, PETSC_FALSE, cpl->ex.kv}, {ex.j, PETSC_FALSE, cpl->ex.jf}};
    PetscCall(CplSpreadFaces(cpl, cpl->clock.correct ? 3 : 2, sp));
  }
  if (smooth) {
    Vec bb;
    PetscCall(DMGetGlobalVector(cpl->fda, &bb));
    {
      const CplSpread one = {kb, PETSC_TRUE, bb};
      PetscCall(CplSpreadFaces(cpl, 1, &one));
    }
    PetscCall(CplFacePorosityScale(cpl, bb));
    PetscCall(VecAXPY(beta, 1.0, bb));
    PetscCall(DMRestoreGlobalVector(cpl->fda, &bb));
  }
  PetscCall(PetscFree4(kv, ka, kb, fd));
  PetscCall(VecGetLocalSize(us, &n));
  PetscCall(VecGetArrayRead(beta, &b));
  PetscCall(VecGetArrayRead(cpl->ex.kv, &m));
  PetscCall(VecGetArray(us, &u));
  for (PetscInt i = 0; i < n; i++) u[i] = b[i] > 0 ? m[i] / b[i] : 0;
  PetscCall(VecRestoreArray(us, &u));
  PetscCall(VecRestoreArrayRead(cpl->ex.kv, &m));
  PetscCall(VecRestoreArrayRead(beta, &b));
  PetscCall(VecCopy(cpl->ex.owed, src));
  PetscCall(VecScale(src, 1.0 / (cpl->kern.cell_vol * cpl->clock.dt)));
  if (cpl->ves.on) { /* a face's momentum control volume is a_f V_cell (owed carries the a_f) */
    const PetscScalar *ar;
    PetscScalar       *sa;
    PetscCall(VecGetLocalSize(src, &n));
    PetscCall(VecGetArrayRead(cpl->ves.area, &ar));
    PetscCall(VecGetArray(src, &sa));
    for (PetscInt i = 0; i < n; i++) sa[i] = ar[i] > 0 ? sa[i] / ar[i] : 0;
    PetscCall(VecRestoreArray(src, &sa));
    PetscCall(VecRestoreArrayRead(cpl->ves.area, &ar));
  }
  if (cpl->ex.phi) PetscCall(VecAXPY(src, 1.0, cpl->ex.phi)); /* form A: the reaction of the particles' pressure-gradient forces (CplPressureExchange) */
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* owed = V_f (beta (u - u_s) dt - sum_p J_p W / V_cell) at interior faces, 0 elsewhere (the
 * spread impulses jf come from CplSetFluidDrag); V_f the face's momentum control volume, V_cell
 * in a box, a_f V_cell in a vessel that cuts the grid. */
static PetscErrorCode CplComputeOwed(Cpl cpl, PetscReal *norm)
{
  Vec                beta, us, u;
  const PetscScalar *b, *s, *v, *j, *ar = NULL;
  PetscScalar       *o;
  PetscInt           xs[3], xm[3], idx[3], c = 0;

  PetscFunctionBeginUser;
  PetscCall(VecZeroEntries(cpl->ex.owed));
  *norm = 0;
  if (!cpl->clock.correct) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(FluidGetDragCoefficient(cpl->fl, &beta));
  PetscCall(FluidGetSolidVelocity(cpl->fl, &us));
  PetscCall(FluidGetVelocity(cpl->fl, &u));
  PetscCall(DMDAGetCorners(cpl->fda, &xs[0], &xs[1], &xs[2], &xm[0], &xm[1], &xm[2]));
  PetscCall(VecGetArrayRead(beta, &b));
  PetscCall(VecGetArrayRead(us, &s));
  PetscCall(VecGetArrayRead(u, &v));
  PetscCall(VecGetArrayRead(cpl->ex.jf, &j));
  PetscCall(VecGetArray(cpl->ex.owed, &o));
  if (cpl->ves.on) PetscCall(VecGetArrayRead(cpl->ves.area, &ar));
  for (idx[2] = xs[2]; idx[2] < xs[2] + xm[2]; idx[2]++)
    for (idx[1] = xs[1]; idx[1] < xs[1] + xm[1]; idx[1]++)
      for (idx[0] = xs[0]; idx[0] < xs[0] + xm[0]; idx[0]++, c += 3)
        for (int d = 0; d < 3; d++)
          if (CplInteriorFace(cpl->dom, d, idx)) o[c + d] = (ar ? cpl->kern.cell_vol * ar[c + d] : cpl->kern.cell_vol) * (b[c + d] * (v[c + d] - s[c + d]) * cpl->clock.dt - j[c + d]);
  if (ar) PetscCall(VecRestoreArrayRead(cpl->ves.area, &ar));
  PetscCall(VecRestoreArray(cpl->ex.owed, &o));
  PetscCall(VecRestoreArrayRead(cpl->ex.jf, &j));
  PetscCall(VecRestoreArrayRead(u, &v));
  PetscCall(VecRestoreArrayRead(us, &s));
  PetscCall(VecRestoreArrayRead(beta, &b));
  PetscCall(VecNorm(cpl->ex.owed, NORM_2, norm));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Mean drag force on all particles over the step: the impulses received over dt. */
static PetscErrorCode CplDragTotal(Cpl cpl, PetscReal drag[3])
{
  DemArrays   pa;
  DemExternal ex;
  PetscReal   loc[3] = {0, 0, 0};

  PetscFunctionBeginUser;
  PetscCall(DemGetArrays(cpl->dem, &pa));
  PetscCall(DemGetExternal(cpl->dem, &ex));
  if (cpl->clock.frozen) /* no DEM steps: the drag the fixed particles feel at the step's start */
    for (PetscInt p = 0; p < pa.nlocal; p++)
      for (int k = 0; k < 3; k++) loc[k] += ex.k[p] * (ex.u[3 * p + k] - pa.v[3 * p + k]);
  else
    for (PetscInt p = 0; p < pa.nlocal; p++)
      for (int k = 0; k < 3; k++) loc[k] += ex.j[3 * p + k] / cpl->clock.dt;
  if (cpl->drag.form == CPL_FORM_A) { /* and the pressure-gradient force */
    PetscReal f[3];
    CplPressureForceSum(cpl, &pa, &ex, f);
    for (int k = 0; k < 3; k++) loc[k] += f[k];
  }
  PetscCall(MPIU_Allreduce(loc, drag, 3, MPIU_REAL, MPIU_SUM, cpl->comm));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Adaptive steps (-fluid_adaptive_dt). A frozen bed asks for -fluid_dt and takes what the fluid
 * takes. A moving bed: the step is the largest whole number of DEM
 * steps, at most -cpl_substeps, within 0.9 of the fluid's stability limit at the step's start
 * (the margin the fluid's own adaptive step takes). The DEM step stays -dem_dt, so the
 * particles' clock stays on its grid. The step depends on the fields only, never on the run's
 * end or cadences (a run may end up to one step past -cpl_t_end, as with fixed steps): so a run
 * stopped at a checkpoint takes the uninterrupted run's steps, and a restart needs nothing
 * beyond the clocks and fields already in the checkpoint. */
static PetscErrorCode CplChooseStep(Cpl cpl)
{
  PetscReal dtmax, fit;
  PetscInt  n = cpl->clock.substeps;

  PetscFunctionBeginUser;
  if (cpl->clock.frozen) { /* no DEM steps: ask for -fluid_dt; the fluid cuts it */
    cpl->clock.dt = cpl->clock.dtf;
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(FluidGetStableTimeStep(cpl->fl, &dtmax));
  fit = 0.9 * dtmax / cpl->clock.dtd;
  if (fit < (PetscReal)n) n = (PetscInt)PetscFloorReal(fit);
  PetscCheck(n >= 1, cpl->comm, PETSC_ERR_ARG_OUTOFRANGE, "at t = %g s the fluid's stability limit %g s (-fluid_cfl_max, -fluid_viscous_number_max) is below one DEM step -dem_dt %g s: lower -dem_dt, or use -fluid_viscous implicit if the viscous limit binds", (double)cpl->clock.t, (double)dtmax, (double)cpl->clock.dtd);
  cpl->clock.nsub = n;
  cpl->clock.dt   = n * cpl->clock.dtd;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The fluid's step: the drag fields and the owed momentum in two-way coupling; in one-way
 * coupling the fluid is single phase (porosity 1, no drag fields: they stay 0). */
static PetscErrorCode CplFluidPart(Cpl cpl, PetscBool inserted, CplStats *st)
{
  PetscLogDouble f0, f1;

  PetscFunctionBeginUser;
  if (cpl->drag.mode == CPL_MODE_TWOWAY) {
    PetscCall(CplProjectPorosity(cpl, st));
    if (inserted) PetscCall(CplAdmitNewParticles(cpl)); /* the same on every rank */
    PetscCall(PetscLogEventBegin(cpl->ev.exchange, 0, 0, 0, 0));
    PetscCall(CplSetFluidDrag(cpl));
    PetscCall(PetscLogEventEnd(cpl->ev.exchange, 0, 0, 0, 0));
  } else st->eps_min = 1;
  PetscCall(PetscTime(&f0));
  PetscCall(FluidStep(cpl->fl, cpl->clock.dt, &st->fluid));
  PetscCall(PetscTime(&f1));
  cpl->diag.t_fluid += f1 - f0;
  if (cpl->clock.frozen) cpl->clock.dt = st->fluid.dt; /* no particle moved: the step the fluid took is the step */
  PetscCheck(st->fluid.dt == cpl->clock.dt, cpl->comm, PETSC_ERR_ARG_INCOMP, "the fluid cut the coupling step %g s to %g s after the DEM substeps had run (the new porosity raised the viscous number beyond the 10%% margin of -fluid_adaptive_dt): lower -cpl_substeps or use -fluid_viscous implicit", (double)cpl->clock.dt, (double)st->fluid.dt);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CplStep(Cpl cpl, CplStats *st)
{
  DemFlowStats fl0, fl1;

  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(st, sizeof *st));
  if (cpl->clock.adaptive) PetscCall(CplChooseStep(cpl));
  PetscCall(CplSetParticleDrag(cpl));
  PetscCall(DemGetFlow(cpl->dem, &fl0));
  if (!cpl->clock.frozen) {
    PetscCall(PetscLogEventBegin(cpl->ev.dem, 0, 0, 0, 0));
    for (PetscInt s = 0; s < cpl->clock.nsub; s++) PetscCall(DemStep(cpl->dem));
    PetscCall(PetscLogEventEnd(cpl->ev.dem, 0, 0, 0, 0));
  }
  PetscCall(DemGetFlow(cpl->dem, &fl1));
  PetscCall(CplFluidPart(cpl, (PetscBool)(fl1.inserted != fl0.inserted), st));
  PetscCall(PetscLogEventBegin(cpl->ev.exchange, 0, 0, 0, 0));
  if (cpl->drag.mode == CPL_MODE_TWOWAY) PetscCall(CplComputeOwed(cpl, &st->owed_norm));
  PetscCall(CplDragTotal(cpl, st->drag));
  PetscCall(PetscLogEventEnd(cpl->ev.exchange, 0, 0, 0, 0));
  cpl->clock.t += cpl->clock.dt;
  cpl->clock.step++;
  PetscFunctionReturn(PETSC_SUCCESS);
}
