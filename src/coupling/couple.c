/* The coupling object and its step. One coupling step of length dt = substeps x dt_dem:
 *  1. at the particles (positions x^n): fluid velocity u_p and porosity eps_p from the kernel,
 *     drag coefficient K_p of the law (drag.c), buoyancy -rho_f V_p g as an external force;
 *  2. the DEM takes its substeps; each half kick treats K (u_p - U) implicitly and records the
 *     impulse J_p the particle actually received (dem/external.c);
 *  3. porosity eps^{n+1} from x^{n+1}; on the faces beta = sum K W / V_cell and
 *     beta u_s = sum K U W / V_cell (U at t^{n+1}); the fluid takes its step with the sink
 *     beta (u - u_s) implicit, plus the explicit source described next;
 *  4. exact exchange: the fluid lost T_f = beta_f (u_f^{n+1} - u_s,f) V_cell dt at each face,
 *     the particles gained G_f = sum_p J_p W_pf. The difference T_f - G_f is owed to the fluid:
 *     it is given back as the source (T_f - G_f)/(V_cell dt) of the next fluid step. So at every
 *     step end, particle momentum + fluid momentum + momentum owed is constant to roundoff
 *     (coupling/test_conserve), and the owed part is the change of drag over one step, which
 *     vanishes in steady flow. Faces on non-periodic domain faces (walls, inlets) take no part:
 *     there the boundary absorbs the drag, and nothing is owed.
 * A frozen bed (-dem_frozen) takes no DEM steps; its particles are fixed obstacles: the fluid
 * loses momentum to them and nothing is owed. */
#include "coupling/coupling_impl.h"

static const char *const CplDragNames[] = {"beetstra", "difelice", "gidaspow", "schiller", "CplDragLaw", "CPL_DRAG_", NULL};
static const char *const CplModeNames[] = {"twoway", "oneway", "CplMode", "CPL_MODE_", NULL};
static const char *const CplFormNames[] = {"B", "A", "CplForm", "CPL_FORM_", NULL};
static const char *const CplInitNames[] = {"rest", "uniform", "steady", "CplInitFluid", "CPL_INIT_", NULL};

PetscErrorCode CplCreate(Domain *dom, Dem dem, Fluid fl, Cpl *cpl)
{
  static PetscBool     done = PETSC_FALSE;
  static PetscClassId  cid;
  static PetscLogEvent ev[6];
  Cpl                  c;

  PetscFunctionBeginUser;
  if (!done) {
    PetscCall(PetscClassIdRegister("Coupling", &cid));
    PetscCall(PetscLogEventRegister("CplProject", cid, &ev[0]));
    PetscCall(PetscLogEventRegister("CplDrag", cid, &ev[1]));
    PetscCall(PetscLogEventRegister("CplExchange", cid, &ev[2]));
    PetscCall(PetscLogEventRegister("CplDemSubsteps", cid, &ev[3]));
    PetscCall(PetscLogEventRegister("CplFilter", cid, &ev[4]));
    PetscCall(PetscLogEventRegister("CplSmooth", cid, &ev[5]));
    done = PETSC_TRUE;
  }
  PetscCall(PetscNew(&c));
  c->comm            = PetscObjectComm((PetscObject)dom->da);
  c->dom             = dom;
  c->dem             = dem;
  c->fl              = fl;
  c->drag.law        = CPL_DRAG_BEETSTRA;
  c->clock.substeps  = 2;
  c->kern.scale      = 1;
  c->self.fade       = 0.1;
  c->drag.eps_floor  = 0.2;
  c->start.relax_max = 1;
  c->drag.umf_eps    = CPL_UMF_POROSITY;
  c->start.rtol      = 1e-4;
  c->start.max_steps = 1000;
  c->ev.project      = ev[0];
  c->ev.drag         = ev[1];
  c->ev.exchange     = ev[2];
  c->ev.dem          = ev[3];
  c->ev.filter       = ev[4];
  c->ev.smooth       = ev[5];
  *cpl               = c;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* -cpl_outlet_remove: every fluid outlet face becomes a DEM outlet (dem/sinks.c) that removes
 * the particles leaving the domain across it; without it such a particle stops the run. */
static PetscErrorCode CplOutletFaces(Cpl cpl, PetscBool remove)
{
  const char *side[2] = {"lo", "hi"};
  char        name[48];
  PetscInt    n = 0;

  PetscFunctionBeginUser;
  if (!remove) PetscFunctionReturn(PETSC_SUCCESS);
  for (int d = 0; d < 3; d++)
    for (int s = 0; s < 2; s++) {
      FluidBCType t;
      PetscCall(FluidGetBC(cpl->fl, d, s, &t));
      if (t != FLUID_BC_OUTLET) continue;
      PetscCall(PetscSNPrintf(name, sizeof name, "-cpl_outlet_remove %c%s", "xyz"[d], side[s]));
      PetscCall(DemAddOutletSide(cpl->dem, d, s, name));
      n++;
    }
  PetscCheck(n > 0, cpl->comm, PETSC_ERR_ARG_INCOMP, "-cpl_outlet_remove: the fluid has no outlet face (-fluid_bc_<side> outlet): nothing to remove particles at");
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The fluid's properties come from the Fluid (FluidSetFromOptions has read them). */
PetscErrorCode CplSetFromOptions(Cpl cpl)
{
  PetscReal fg[3];
  PetscBool remove = PETSC_FALSE;
  PetscInt  law = cpl->drag.law, mode = cpl->drag.mode, init = cpl->start.init, form = cpl->drag.form;

  PetscFunctionBeginUser;
  PetscOptionsBegin(cpl->comm, NULL, "CFD-DEM coupling", NULL);
  PetscCall(SableOptionsEnum("-cpl_drag", "Drag law: beetstra (eq. 15), difelice, gidaspow (Ergun / Wen-Yu), schiller (Schiller-Naumann, single sphere)", CplDragNames, 4, law, &law, NULL));
  cpl->drag.law = (CplDragLaw)law;
  PetscCall(SableOptionsEnum("-cpl_form", "Form of the averaged momentum equations: B, the fluid feels -grad p and the drag law carries the whole fluid-particle force but buoyancy; A, the fluid feels -eps grad p and the particles -V grad p besides eps times the law's drag (Zhou et al. 2010; the same force in a steady uniform bed)", CplFormNames, 2, form, &form, NULL));
  cpl->drag.form = (CplForm)form;
  PetscCall(SableOptionsEnum("-cpl_mode", "twoway: fluid and particles act on each other; oneway: the fluid acts on the particles only (the fluid is single phase: porosity 1 everywhere, no drag reaction)", CplModeNames, 2, mode, &mode, NULL));
  cpl->drag.mode = (CplMode)mode;
  PetscCall(SableOptionsEnum("-cpl_init_fluid", "Fluid velocity before the first step: rest, uniform (the inlet's superficial velocity over the porosity), steady (a steady solve through the initial bed held fixed)", CplInitNames, 3, init, &init, NULL));
  cpl->start.init = (CplInitFluid)init;
  PetscCall(SableOptionsReal("-cpl_init_fluid_rtol", "-cpl_init_fluid steady: stop when a pseudo step changes the velocity by less than this times its maximum", NULL, "(0,1)", cpl->start.rtol, &cpl->start.rtol, NULL));
  PetscCall(SableOptionsInt("-cpl_init_fluid_max_steps", "-cpl_init_fluid steady: most pseudo steps (of the coupling step) before the run stops unconverged", NULL, "[1,inf)", cpl->start.max_steps, &cpl->start.max_steps, NULL));
  PetscCall(SableOptionsInt("-cpl_substeps", "DEM steps per fluid step; the fluid step is this times -dem_dt", NULL, "[1,inf)", cpl->clock.substeps, &cpl->clock.substeps, &cpl->clock.substeps_set));
  PetscCall(SableOptionsReal("-cpl_kernel_scale", "Cube kernel side over the volume-equivalent cube side (pi/6)^(1/3) d", NULL, "(0,inf)", cpl->kern.scale, &cpl->kern.scale, NULL));
  PetscCall(SableOptionsReal("-cpl_filter_width", "Diffusion filter of the solid fraction and the drag fields: Gaussian full width at half maximum, in mean particle diameters (0: off)", NULL, "[0,inf)", cpl->filt.width, &cpl->filt.width, NULL));
  PetscCall(SableOptionsReal("-cpl_porosity_width", "The drag law's porosity at each particle: the particles' volumes smoothed by a Gaussian of this full width at half maximum, in mean particle diameters, on a grid finer than the fluid's, with the superficial velocity over it (0: the kernel's cell porosity and the cell's velocity)", NULL, "[0,inf)", cpl->pw.width, &cpl->pw.width, NULL));
  PetscCall(SableOptionsReal("-cpl_porosity_floor", "Porosity below this is raised to it (counted in the log)", NULL, "(0,1)", cpl->drag.eps_floor, &cpl->drag.eps_floor, NULL));
  PetscCall(SableOptionsReal("-cpl_relaxation_ratio_max", "Largest allowed coupling step / particle relaxation time m/K (at the smallest initial porosity, Stokes limit)", NULL, "(0,inf)", cpl->start.relax_max, &cpl->start.relax_max, NULL));
  PetscCall(SableOptionsReal("-cpl_umf_porosity", "Porosity at which the bed: line takes U_mf (default: the bed's own when it is packed, at most 0.445, else 0.40: a packed bed at minimum fluidization)", NULL, "(0,1)", cpl->drag.umf_eps, &cpl->drag.umf_eps, &cpl->drag.umf_eps_set));
  PetscCall(SableOptionsBool("-cpl_self_porosity", "The drag law sees the porosity of the other particles: the particle's own kernel dip is removed", cpl->self.eps, &cpl->self.eps, NULL));
  PetscCall(SableOptionsBool("-cpl_self_velocity", "The drag law sees the undisturbed fluid: its own disturbance (the exact discrete response of the grid to its stencil, coupling/self.c) is removed, K' = K / (1 - G K)", cpl->self.u, &cpl->self.u, NULL));
  PetscCall(SableOptionsReal("-cpl_self_fade", "-cpl_self_porosity/-cpl_self_velocity: both fade linearly to nothing as the other particles' solid fraction reaches this (0: no fade)", NULL, "[0,1)", cpl->self.fade, &cpl->self.fade, NULL));
  PetscCall(SableOptionsBool("-cpl_outlet_remove", "A particle reaching a fluid outlet face (-fluid_bc_<side> outlet) leaves the run, counted as a DEM outlet, instead of stopping it", remove, &remove, NULL));
  PetscOptionsEnd();
  PetscCheck(!(cpl->self.eps && cpl->filt.width > 0), cpl->comm, PETSC_ERR_ARG_INCOMP, "-cpl_self_porosity removes the particle's unfiltered kernel dip, which -cpl_filter_width %g changes: use one of the two (the filtered dip is not implemented)", (double)cpl->filt.width);
  PetscCheck(!(cpl->pw.width > 0 && cpl->filt.width > 0), cpl->comm, PETSC_ERR_ARG_INCOMP, "-cpl_porosity_width %g with -cpl_filter_width %g: both smooth over a width in diameters (the drag's porosity, the spread fields); use one of the two", (double)cpl->pw.width, (double)cpl->filt.width);
  PetscCheck(!(cpl->pw.width > 0 && cpl->drag.mode == CPL_MODE_ONEWAY), cpl->comm, PETSC_ERR_ARG_INCOMP, "-cpl_porosity_width %g with -cpl_mode oneway: a one-way run's drag sees porosity 1; drop one of them", (double)cpl->pw.width);
  PetscCheck(!(cpl->drag.form == CPL_FORM_A && cpl->filt.width > 0), cpl->comm, PETSC_ERR_SUP, "-cpl_filter_width %g with -cpl_form A: the filter would move the pressure-gradient force's reaction off the faces the particles read; use -cpl_form B or leave out the filter", (double)cpl->filt.width);
  PetscCheck(!(cpl->drag.form == CPL_FORM_A && cpl->self.u), cpl->comm, PETSC_ERR_SUP, "-cpl_self_velocity with -cpl_form A: the undisturbed drag is derived for form B's coefficient only; use -cpl_form B or leave out -cpl_self_velocity");
  PetscCall(CplOutletFaces(cpl, remove));
  PetscCall(FluidGetDensity(cpl->fl, &cpl->prop.rho));
  PetscCall(FluidGetViscosity(cpl->fl, &cpl->prop.mu));
  PetscCall(FluidGetGravity(cpl->fl, fg));
  PetscCheck(fg[0] == 0 && fg[1] == 0 && fg[2] == 0, cpl->comm, PETSC_ERR_ARG_INCOMP, "-fluid_gravity %g,%g,%g must be 0,0,0 in a coupled run: the fluid pressure is hydrodynamic and the buoyancy acts on the particles (eq. 11); set gravity with -dem_gravity", (double)fg[0], (double)fg[1], (double)fg[2]);
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode CplSetUpShapes(Cpl cpl)
{
  PetscFunctionBeginUser;
  PetscCall(DemGetShapeCount(cpl->dem, &cpl->kern.nshape));
  PetscCall(PetscMalloc4(cpl->kern.nshape, &cpl->kern.side, cpl->kern.nshape, &cpl->kern.vol, cpl->kern.nshape, &cpl->kern.diam, cpl->kern.nshape, &cpl->kern.mass));
  for (PetscInt s = 0; s < cpl->kern.nshape; s++) {
    PetscCall(CplKernelSide(cpl, s, &cpl->kern.side[s], &cpl->kern.vol[s], &cpl->kern.diam[s]));
    PetscCall(DemGetShape(cpl->dem, s, NULL, &cpl->kern.mass[s]));
    for (int e = 0; e < 3; e++)
      PetscCheck(cpl->dom->periodic[e] || cpl->kern.side[s] <= cpl->dom->len[e], cpl->comm, PETSC_ERR_ARG_OUTOFRANGE, "cube kernel side %g exceeds the domain length %g on axis %d; lower -cpl_kernel_scale %g", (double)cpl->kern.side[s], (double)cpl->dom->len[e], e, (double)cpl->kern.scale);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CplSetUp(Cpl cpl)
{
  PetscReal dtd, dtf;
  PetscBool fset;

  PetscFunctionBeginUser;
  PetscCall(FluidGetDMs(cpl->fl, &cpl->cda, &cpl->fda));
  PetscCall(DMCreateLocalVector(cpl->cda, &cpl->ex.cloc));
  for (int s = 0; s < 3; s++) PetscCall(DMCreateLocalVector(cpl->fda, &cpl->ex.floc[s]));
  PetscCall(DMCreateGlobalVector(cpl->fda, &cpl->ex.kv));
  PetscCall(VecDuplicate(cpl->ex.kv, &cpl->ex.jf));
  PetscCall(VecDuplicate(cpl->ex.kv, &cpl->ex.owed));
  PetscCall(VecZeroEntries(cpl->ex.owed));
  if (cpl->drag.form == CPL_FORM_A) { /* the pressure gradient at the particles; the fluid's -eps grad p */
    PetscCall(VecDuplicate(cpl->ex.kv, &cpl->ex.gp));
    PetscCall(DMCreateLocalVector(cpl->fda, &cpl->ex.gploc));
    if (cpl->drag.mode == CPL_MODE_TWOWAY) PetscCall(VecDuplicate(cpl->ex.kv, &cpl->ex.phi));
  }
  cpl->kern.cell_vol = cpl->dom->h[0] * cpl->dom->h[1] * cpl->dom->h[2];
  PetscCall(DemGetGravity(cpl->dem, cpl->prop.g));
  PetscCall(DemGetFrozen(cpl->dem, &cpl->clock.frozen));
  cpl->clock.correct = (PetscBool)!cpl->clock.frozen;
  PetscCall(DemSetExternal(cpl->dem, PETSC_TRUE));
  PetscCall(CplSetUpShapes(cpl));
  PetscCall(CplFilterSetUp(cpl, 0));
  PetscCall(CplSmoothSetUp(cpl, 0));
  PetscCall(CplVesselSetUp(cpl)); /* vessel.c: a vessel cutting the fluid grid, else nothing */
  PetscCall(DemGetTimeStep(cpl->dem, &dtd));
  PetscCall(FluidGetTimeStep(cpl->fl, &dtf, &fset));
  /* a frozen bed takes no DEM steps: the coupling step is the fluid's */
  PetscCheck(!cpl->clock.frozen || !cpl->clock.substeps_set, cpl->comm, PETSC_ERR_ARG_INCOMP, "-cpl_substeps %d is ignored with -dem_frozen (no DEM steps; the step is -fluid_dt): give one of them", (int)cpl->clock.substeps);
  PetscCheck(!cpl->clock.frozen || cpl->drag.mode == CPL_MODE_TWOWAY, cpl->comm, PETSC_ERR_ARG_INCOMP, "-cpl_mode oneway with -dem_frozen: a frozen bed only acts on the fluid, one-way coupling only on the particles; nothing would be coupled");
  PetscCall(FluidGetAdaptive(cpl->fl, &cpl->clock.adaptive));
  cpl->clock.dtd  = dtd;
  cpl->clock.dtf  = dtf;
  cpl->clock.nsub = cpl->clock.substeps;
  if (cpl->clock.frozen) cpl->clock.dt = dtf;
  else {
    cpl->clock.dt = cpl->clock.substeps * dtd;
    PetscCheck(!fset || PetscAbsReal(dtf - cpl->clock.dt) <= 1e-9 * cpl->clock.dt, cpl->comm, PETSC_ERR_ARG_INCOMP, "-fluid_dt %g differs from -cpl_substeps %d x -dem_dt %g = %g: give one of them consistently (the fluid step is substeps x dt_dem)", (double)dtf, (int)cpl->clock.substeps, (double)dtd, (double)cpl->clock.dt);
  }
  {
    char name[96];
    if (cpl->clock.frozen) PetscCall(PetscSNPrintf(name, sizeof name, "-fluid_dt"));
    else PetscCall(PetscSNPrintf(name, sizeof name, "-cpl_substeps %d x -dem_dt %g s", (int)cpl->clock.substeps, (double)dtd));
    PetscCall(FluidSetTimeStepName(cpl->fl, name));
  }
  {
    CplStats st;
    PetscCall(CplProjectPorosity(cpl, &st));
    cpl->diag.eps_min0 = st.eps_min;
  }
  if (cpl->drag.mode == CPL_MODE_ONEWAY) { /* the solid volume above stays the diagnostics' figure */
    Vec eps;
    PetscCall(FluidGetPorosity(cpl->fl, &eps));
    PetscCall(VecSet(eps, 1.0));
    cpl->diag.eps_min0 = 1;
  }
  PetscCall(FluidInitPorosity(cpl->fl));
  PetscCall(CplPreflight(cpl, NULL, PETSC_TRUE));
  if (!cpl->start.restarting) PetscCall(CplInitFluidState(cpl));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CplRedistribute(Cpl cpl)
{
  DM   ofda   = cpl->fda;
  Vec *face[] = {&cpl->ex.kv, &cpl->ex.jf, &cpl->ex.owed, &cpl->ex.gp, &cpl->ex.phi};

  PetscFunctionBeginUser;
  PetscCall(PetscObjectReference((PetscObject)ofda)); /* the fluid drops its old DMs */
  PetscCall(FluidRedistribute(cpl->fl));
  PetscCall(FluidGetDMs(cpl->fl, &cpl->cda, &cpl->fda));
  for (size_t i = 0; i < sizeof face / sizeof face[0]; i++)
    if (*face[i]) PetscCall(DomainMoveVec(ofda, cpl->fda, face[i]));
  if (cpl->ex.gploc) {
    PetscCall(VecDestroy(&cpl->ex.gploc));
    PetscCall(DMCreateLocalVector(cpl->fda, &cpl->ex.gploc));
  }
  PetscCall(DMDestroy(&ofda));
  PetscCall(VecDestroy(&cpl->ex.cloc));
  PetscCall(DMCreateLocalVector(cpl->cda, &cpl->ex.cloc));
  for (int s = 0; s < 3; s++) {
    PetscCall(VecDestroy(&cpl->ex.floc[s]));
    PetscCall(DMCreateLocalVector(cpl->fda, &cpl->ex.floc[s]));
  }
  PetscCall(DemRedistribute(cpl->dem));
  PetscCall(CplSmoothDestroyGrid(cpl));
  PetscCall(CplVesselSetUp(cpl)); /* the fluid's fractions on the new layout */
  CplInvalidateStencils(cpl);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CplView(Cpl cpl, PetscViewer viewer)
{
  PetscFunctionBeginUser;
  PetscCall(PetscViewerASCIIPrintf(viewer, "coupling: drag %s, %d DEM steps per fluid step of %g s, cube kernel %g x the volume-equivalent side, porosity floor %g%s\n", CplDragNames[cpl->drag.law], (int)cpl->clock.substeps, (double)(cpl->clock.adaptive ? (cpl->clock.frozen ? cpl->clock.dtf : cpl->clock.substeps * cpl->clock.dtd) : cpl->clock.dt), (double)cpl->kern.scale, (double)cpl->drag.eps_floor, cpl->clock.frozen ? ", frozen bed (no DEM steps)" : ""));
  if (cpl->filt.n > 0) PetscCall(PetscViewerASCIIPrintf(viewer, "coupling: diffusion filter -cpl_filter_width %g x mean diameter %g m: Gaussian sigma %g m, %d sweeps per field\n", (double)cpl->filt.width, (double)cpl->filt.d, (double)PetscSqrtReal(cpl->filt.var), (int)cpl->filt.n));
  if (cpl->pw.width > 0) PetscCall(PetscViewerASCIIPrintf(viewer, "coupling: the drag's porosity -cpl_porosity_width %g x mean diameter %g m: Gaussian sigma %g m on a grid %d x %d x %d times finer than the fluid's\n", (double)cpl->pw.width, (double)cpl->pw.d, (double)cpl->pw.sigma, (int)cpl->pw.n[0], (int)cpl->pw.n[1], (int)cpl->pw.n[2]));
  if (cpl->drag.form == CPL_FORM_A) PetscCall(PetscViewerASCIIPrintf(viewer, "coupling: momentum equations' form A (-cpl_form A): the fluid feels -eps grad p, the particles -V grad p and eps times the law's drag\n"));
  if (cpl->drag.mode == CPL_MODE_ONEWAY) PetscCall(PetscViewerASCIIPrintf(viewer, "coupling: one-way (-cpl_mode oneway): the fluid acts on the particles only; the fluid is single phase (porosity 1, no drag reaction)\n"));
  if (cpl->clock.adaptive && cpl->clock.frozen) PetscCall(PetscViewerASCIIPrintf(viewer, "coupling: adaptive fluid step (-fluid_adaptive_dt): at most -fluid_dt %g s, within 0.9 of the fluid's stability limit\n", (double)cpl->clock.dtf));
  else if (cpl->clock.adaptive) PetscCall(PetscViewerASCIIPrintf(viewer, "coupling: adaptive fluid step (-fluid_adaptive_dt): 1 to %d DEM steps of %g s per fluid step, within 0.9 of the fluid's stability limit\n", (int)cpl->clock.substeps, (double)cpl->clock.dtd));
  if (cpl->start.init != CPL_INIT_REST) PetscCall(PetscViewerASCIIPrintf(viewer, "coupling: initial fluid %s%s\n", CplInitNames[cpl->start.init], cpl->start.restarting ? " (not applied: the fluid comes from the checkpoint)" : ""));
  if (cpl->start.init == CPL_INIT_STEADY && !cpl->start.restarting) PetscCall(PetscViewerASCIIPrintf(viewer, "coupling: the steady start converged in %d pseudo steps of %g s (-cpl_init_fluid_rtol %g)\n", (int)cpl->start.its, (double)(cpl->clock.frozen ? cpl->clock.dt : cpl->clock.substeps * cpl->clock.dtd), (double)cpl->start.rtol));
  PetscCall(CplPreflight(cpl, viewer, PETSC_FALSE));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CplDestroy(Cpl *cpl)
{
  PetscFunctionBeginUser;
  if (!*cpl) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(VecDestroy(&(*cpl)->ex.cloc));
  for (int s = 0; s < 3; s++) PetscCall(VecDestroy(&(*cpl)->ex.floc[s]));
  PetscCall(VecDestroy(&(*cpl)->ex.kv));
  PetscCall(VecDestroy(&(*cpl)->ex.jf));
  PetscCall(VecDestroy(&(*cpl)->ex.owed));
  PetscCall(VecDestroy(&(*cpl)->ex.gp));
  PetscCall(VecDestroy(&(*cpl)->ex.gploc));
  PetscCall(VecDestroy(&(*cpl)->ex.phi));
  PetscCall(PetscFree4((*cpl)->kern.side, (*cpl)->kern.vol, (*cpl)->kern.diam, (*cpl)->kern.mass));
  PetscCall(PetscFree((*cpl)->kern.stc));
  PetscCall(CplSelfTableDestroy(*cpl));
  PetscCall(CplSmoothDestroy(*cpl));
  PetscCall(CplVesselDestroy(*cpl));
  PetscCall(PetscFree(*cpl));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CplGetTime(Cpl cpl, PetscReal *t, PetscInt *step)
{
  PetscFunctionBeginUser;
  if (t) *t = cpl->clock.t;
  if (step) *step = cpl->clock.step;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CplGetFluidTime(Cpl cpl, PetscLogDouble *t)
{
  PetscFunctionBeginUser;
  *t = cpl->diag.t_fluid;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CplGetSubsteps(Cpl cpl, PetscInt *substeps)
{
  PetscFunctionBeginUser;
  *substeps = cpl->clock.substeps;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CplGetClippedCount(Cpl cpl, PetscInt *count)
{
  PetscFunctionBeginUser;
  *count = cpl->diag.clipped_total;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CplGetSelfCappedCount(Cpl cpl, PetscInt *count)
{
  PetscFunctionBeginUser;
  *count = cpl->self.capped_total;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CplGetStepQuantum(Cpl cpl, PetscReal *dq)
{
  PetscFunctionBeginUser;
  *dq = cpl->clock.adaptive ? (cpl->clock.frozen ? 1e-9 * cpl->clock.dtf : cpl->clock.dtd) : cpl->clock.dt;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CplSetRestarting(Cpl cpl, PetscBool on)
{
  PetscFunctionBeginUser;
  cpl->start.restarting = on;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CplGetMode(Cpl cpl, CplMode *mode)
{
  PetscFunctionBeginUser;
  *mode = cpl->drag.mode;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CplGetTimeStep(Cpl cpl, PetscReal *dt)
{
  PetscFunctionBeginUser;
  *dt = cpl->clock.dt;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CplGetTestView(Cpl cpl, CplTestView *v)
{
  PetscFunctionBeginUser;
  v->cell_vol      = cpl->kern.cell_vol;
  v->filter_var    = cpl->filt.var;
  v->filter_sweeps = cpl->filt.n;
  v->smooth_sigma  = cpl->pw.sigma;
  v->smooth_solid  = cpl->pw.glob;
  v->kv            = cpl->ex.kv;
  for (int d = 0; d < 3; d++) {
    v->filter_lam[d] = cpl->filt.lam[d];
    v->smooth_h[d]   = cpl->pw.h[d];
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}
