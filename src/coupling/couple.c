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
  c->comm        = PetscObjectComm((PetscObject)dom->da);
  c->dom         = dom;
  c->dem         = dem;
  c->fl          = fl;
  c->law         = CPL_DRAG_BEETSTRA;
  c->substeps    = 2;
  c->kscale      = 1;
  c->self_fade   = 0.1;
  c->eps_floor   = 0.2;
  c->relax_max   = 1;
  c->umf_eps     = CPL_UMF_POROSITY;
  c->init_rtol   = 1e-4;
  c->init_max    = 1000;
  c->ev_project  = ev[0];
  c->ev_drag     = ev[1];
  c->ev_exchange = ev[2];
  c->ev_dem      = ev[3];
  c->ev_filter   = ev[4];
  c->ev_smooth   = ev[5];
  *cpl           = c;
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

  PetscFunctionBeginUser;
  PetscOptionsBegin(cpl->comm, NULL, "CFD-DEM coupling", NULL);
  PetscCall(PetscOptionsEnum("-cpl_drag", "Drag law: beetstra (eq. 15), difelice, gidaspow (Ergun / Wen-Yu), schiller (Schiller-Naumann, single sphere)", NULL, CplDragNames, (PetscEnum)cpl->law, (PetscEnum *)&cpl->law, NULL));
  PetscCall(PetscOptionsEnum("-cpl_mode", "twoway: fluid and particles act on each other; oneway: the fluid acts on the particles only (the fluid is single phase: porosity 1 everywhere, no drag reaction)", NULL, CplModeNames, (PetscEnum)cpl->mode, (PetscEnum *)&cpl->mode, NULL));
  PetscCall(PetscOptionsEnum("-cpl_init_fluid", "Fluid velocity before the first step: rest, uniform (the inlet's superficial velocity over the porosity), steady (a steady solve through the initial bed held fixed)", NULL, CplInitNames, (PetscEnum)cpl->init, (PetscEnum *)&cpl->init, NULL));
  PetscCall(SableOptionsReal("-cpl_init_fluid_rtol", "-cpl_init_fluid steady: stop when a pseudo step changes the velocity by less than this times its maximum", NULL, "(0,1)", cpl->init_rtol, &cpl->init_rtol, NULL));
  PetscCall(SableOptionsInt("-cpl_init_fluid_max_steps", "-cpl_init_fluid steady: most pseudo steps (of the coupling step) before the run stops unconverged", NULL, "[1,inf)", cpl->init_max, &cpl->init_max, NULL));
  PetscCall(SableOptionsInt("-cpl_substeps", "DEM steps per fluid step; the fluid step is this times -dem_dt", NULL, "[1,inf)", cpl->substeps, &cpl->substeps, &cpl->substeps_set));
  PetscCall(SableOptionsReal("-cpl_kernel_scale", "Cube kernel side over the volume-equivalent cube side (pi/6)^(1/3) d", NULL, "(0,inf)", cpl->kscale, &cpl->kscale, NULL));
  PetscCall(SableOptionsReal("-cpl_filter_width", "Diffusion filter of the solid fraction and the drag fields: Gaussian full width at half maximum, in mean particle diameters (0: off)", NULL, "[0,inf)", cpl->filter_width, &cpl->filter_width, NULL));
  PetscCall(SableOptionsReal("-cpl_porosity_width", "The drag law's porosity at each particle: the particles' volumes smoothed by a Gaussian of this full width at half maximum, in mean particle diameters, on a grid finer than the fluid's, with the superficial velocity over it (0: the kernel's cell porosity and the cell's velocity)", NULL, "[0,inf)", cpl->pw_width, &cpl->pw_width, NULL));
  PetscCall(SableOptionsReal("-cpl_porosity_floor", "Porosity below this is raised to it (counted in the log)", NULL, "(0,1)", cpl->eps_floor, &cpl->eps_floor, NULL));
  PetscCall(SableOptionsReal("-cpl_relaxation_ratio_max", "Largest allowed coupling step / particle relaxation time m/K (at the smallest initial porosity, Stokes limit)", NULL, "(0,inf)", cpl->relax_max, &cpl->relax_max, NULL));
  PetscCall(SableOptionsReal("-cpl_umf_porosity", "Porosity at which the bed: line takes U_mf (default: the bed's own when it is packed, at most 0.445, else 0.40: a packed bed at minimum fluidization)", NULL, "(0,1)", cpl->umf_eps, &cpl->umf_eps, &cpl->umf_eps_set));
  PetscCall(PetscOptionsBool("-cpl_self_porosity", "The drag law sees the porosity of the other particles: the particle's own kernel dip is removed", NULL, cpl->self_eps, &cpl->self_eps, NULL));
  PetscCall(PetscOptionsBool("-cpl_self_velocity", "The drag law sees the undisturbed fluid: its own disturbance (the exact discrete response of the grid to its stencil, coupling/self.c) is removed, K' = K / (1 - G K)", NULL, cpl->self_u, &cpl->self_u, NULL));
  PetscCall(SableOptionsReal("-cpl_self_fade", "-cpl_self_porosity/-cpl_self_velocity: both fade linearly to nothing as the other particles' solid fraction reaches this (0: no fade)", NULL, "[0,1)", cpl->self_fade, &cpl->self_fade, NULL));
  PetscCall(PetscOptionsBool("-cpl_outlet_remove", "A particle reaching a fluid outlet face (-fluid_bc_<side> outlet) leaves the run, counted as a DEM outlet, instead of stopping it", NULL, remove, &remove, NULL));
  PetscOptionsEnd();
  PetscCheck(!(cpl->self_eps && cpl->filter_width > 0), cpl->comm, PETSC_ERR_ARG_INCOMP, "-cpl_self_porosity removes the particle's unfiltered kernel dip, which -cpl_filter_width %g changes: use one of the two (the filtered dip is not implemented)", (double)cpl->filter_width);
  PetscCheck(!(cpl->pw_width > 0 && cpl->filter_width > 0), cpl->comm, PETSC_ERR_ARG_INCOMP, "-cpl_porosity_width %g with -cpl_filter_width %g: both smooth over a width in diameters (the drag's porosity, the spread fields); use one of the two", (double)cpl->pw_width, (double)cpl->filter_width);
  PetscCheck(!(cpl->pw_width > 0 && cpl->mode == CPL_MODE_ONEWAY), cpl->comm, PETSC_ERR_ARG_INCOMP, "-cpl_porosity_width %g with -cpl_mode oneway: a one-way run's drag sees porosity 1; drop one of them", (double)cpl->pw_width);
  PetscCall(CplOutletFaces(cpl, remove));
  PetscCall(FluidGetDensity(cpl->fl, &cpl->rho));
  PetscCall(FluidGetViscosity(cpl->fl, &cpl->mu));
  PetscCall(FluidGetGravity(cpl->fl, fg));
  PetscCheck(fg[0] == 0 && fg[1] == 0 && fg[2] == 0, cpl->comm, PETSC_ERR_ARG_INCOMP, "-fluid_gravity %g,%g,%g must be 0,0,0 in a coupled run: the fluid pressure is hydrodynamic and the buoyancy acts on the particles (eq. 11); set gravity with -dem_gravity", (double)fg[0], (double)fg[1], (double)fg[2]);
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode CplSetUpShapes(Cpl cpl)
{
  PetscFunctionBeginUser;
  PetscCall(DemGetShapeCount(cpl->dem, &cpl->nshape));
  PetscCall(PetscMalloc4(cpl->nshape, &cpl->side, cpl->nshape, &cpl->vol, cpl->nshape, &cpl->diam, cpl->nshape, &cpl->mass));
  for (PetscInt s = 0; s < cpl->nshape; s++) {
    PetscCall(CplKernelSide(cpl, s, &cpl->side[s], &cpl->vol[s], &cpl->diam[s]));
    PetscCall(DemGetShape(cpl->dem, s, NULL, &cpl->mass[s]));
    for (int e = 0; e < 3; e++)
      PetscCheck(cpl->dom->periodic[e] || cpl->side[s] <= cpl->dom->len[e], cpl->comm, PETSC_ERR_ARG_OUTOFRANGE, "cube kernel side %g exceeds the domain length %g on axis %d; lower -cpl_kernel_scale %g", (double)cpl->side[s], (double)cpl->dom->len[e], e, (double)cpl->kscale);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CplSetUp(Cpl cpl)
{
  PetscReal dtd, dtf;
  PetscBool fset;

  PetscFunctionBeginUser;
  PetscCall(FluidGetDMs(cpl->fl, &cpl->cda, &cpl->fda));
  PetscCall(DMCreateLocalVector(cpl->cda, &cpl->cloc));
  for (int s = 0; s < 3; s++) PetscCall(DMCreateLocalVector(cpl->fda, &cpl->floc[s]));
  PetscCall(DMCreateGlobalVector(cpl->fda, &cpl->kv));
  PetscCall(VecDuplicate(cpl->kv, &cpl->jf));
  PetscCall(VecDuplicate(cpl->kv, &cpl->owed));
  PetscCall(VecZeroEntries(cpl->owed));
  cpl->cell_vol = cpl->dom->h[0] * cpl->dom->h[1] * cpl->dom->h[2];
  PetscCall(DemGetGravity(cpl->dem, cpl->g));
  PetscCall(DemGetFrozen(cpl->dem, &cpl->frozen));
  cpl->correct = (PetscBool)!cpl->frozen;
  PetscCall(DemSetExternal(cpl->dem, PETSC_TRUE));
  PetscCall(CplSetUpShapes(cpl));
  PetscCall(CplFilterSetUp(cpl, 0));
  PetscCall(CplSmoothSetUp(cpl, 0));
  PetscCall(DemGetTimeStep(cpl->dem, &dtd));
  PetscCall(FluidGetTimeStep(cpl->fl, &dtf, &fset));
  /* a frozen bed takes no DEM steps: the coupling step is the fluid's */
  PetscCheck(!cpl->frozen || !cpl->substeps_set, cpl->comm, PETSC_ERR_ARG_INCOMP, "-cpl_substeps %d is ignored with -dem_frozen (no DEM steps; the step is -fluid_dt): give one of them", (int)cpl->substeps);
  PetscCheck(!cpl->frozen || cpl->mode == CPL_MODE_TWOWAY, cpl->comm, PETSC_ERR_ARG_INCOMP, "-cpl_mode oneway with -dem_frozen: a frozen bed only acts on the fluid, one-way coupling only on the particles; nothing would be coupled");
  PetscCall(FluidGetAdaptive(cpl->fl, &cpl->adaptive));
  cpl->dtd  = dtd;
  cpl->dtf  = dtf;
  cpl->nsub = cpl->substeps;
  if (cpl->frozen) cpl->dt = dtf;
  else {
    cpl->dt = cpl->substeps * dtd;
    PetscCheck(!fset || PetscAbsReal(dtf - cpl->dt) <= 1e-9 * cpl->dt, cpl->comm, PETSC_ERR_ARG_INCOMP, "-fluid_dt %g differs from -cpl_substeps %d x -dem_dt %g = %g: give one of them consistently (the fluid step is substeps x dt_dem)", (double)dtf, (int)cpl->substeps, (double)dtd, (double)cpl->dt);
  }
  {
    char name[96];
    if (cpl->frozen) PetscCall(PetscSNPrintf(name, sizeof name, "-fluid_dt"));
    else PetscCall(PetscSNPrintf(name, sizeof name, "-cpl_substeps %d x -dem_dt %g s", (int)cpl->substeps, (double)dtd));
    PetscCall(FluidSetTimeStepName(cpl->fl, name));
  }
  {
    CplStats st;
    PetscCall(CplProjectPorosity(cpl, &st));
    cpl->eps_min0 = st.eps_min;
  }
  if (cpl->mode == CPL_MODE_ONEWAY) { /* the solid volume above stays the diagnostics' figure */
    Vec eps;
    PetscCall(FluidGetPorosity(cpl->fl, &eps));
    PetscCall(VecSet(eps, 1.0));
    cpl->eps_min0 = 1;
  }
  PetscCall(FluidInitPorosity(cpl->fl));
  PetscCall(CplPreflight(cpl, NULL, PETSC_TRUE));
  if (!cpl->restarting) PetscCall(CplInitFluidState(cpl));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CplRedistribute(Cpl cpl)
{
  DM   ofda   = cpl->fda;
  Vec *face[] = {&cpl->kv, &cpl->jf, &cpl->owed};

  PetscFunctionBeginUser;
  PetscCall(PetscObjectReference((PetscObject)ofda)); /* the fluid drops its old DMs */
  PetscCall(FluidRedistribute(cpl->fl));
  PetscCall(FluidGetDMs(cpl->fl, &cpl->cda, &cpl->fda));
  for (size_t i = 0; i < sizeof face / sizeof face[0]; i++) PetscCall(DomainMoveVec(ofda, cpl->fda, face[i]));
  PetscCall(DMDestroy(&ofda));
  PetscCall(VecDestroy(&cpl->cloc));
  PetscCall(DMCreateLocalVector(cpl->cda, &cpl->cloc));
  for (int s = 0; s < 3; s++) {
    PetscCall(VecDestroy(&cpl->floc[s]));
    PetscCall(DMCreateLocalVector(cpl->fda, &cpl->floc[s]));
  }
  PetscCall(DemRedistribute(cpl->dem));
  PetscCall(CplSmoothDestroyGrid(cpl));
  CplInvalidateStencils(cpl);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CplView(Cpl cpl, PetscViewer viewer)
{
  PetscFunctionBeginUser;
  PetscCall(PetscViewerASCIIPrintf(viewer, "coupling: drag %s, %d DEM steps per fluid step of %g s, cube kernel %g x the volume-equivalent side, porosity floor %g%s\n", CplDragNames[cpl->law], (int)cpl->substeps, (double)(cpl->adaptive ? (cpl->frozen ? cpl->dtf : cpl->substeps * cpl->dtd) : cpl->dt), (double)cpl->kscale, (double)cpl->eps_floor, cpl->frozen ? ", frozen bed (no DEM steps)" : ""));
  if (cpl->filter_n > 0) PetscCall(PetscViewerASCIIPrintf(viewer, "coupling: diffusion filter -cpl_filter_width %g x mean diameter %g m: Gaussian sigma %g m, %d sweeps per field\n", (double)cpl->filter_width, (double)cpl->filter_d, (double)PetscSqrtReal(cpl->filter_var), (int)cpl->filter_n));
  if (cpl->pw_width > 0) PetscCall(PetscViewerASCIIPrintf(viewer, "coupling: the drag's porosity -cpl_porosity_width %g x mean diameter %g m: Gaussian sigma %g m on a grid %d x %d x %d times finer than the fluid's\n", (double)cpl->pw_width, (double)cpl->pw_d, (double)cpl->pw_sigma, (int)cpl->pw_n[0], (int)cpl->pw_n[1], (int)cpl->pw_n[2]));
  if (cpl->mode == CPL_MODE_ONEWAY) PetscCall(PetscViewerASCIIPrintf(viewer, "coupling: one-way (-cpl_mode oneway): the fluid acts on the particles only; the fluid is single phase (porosity 1, no drag reaction)\n"));
  if (cpl->adaptive && cpl->frozen) PetscCall(PetscViewerASCIIPrintf(viewer, "coupling: adaptive fluid step (-fluid_adaptive_dt): at most -fluid_dt %g s, within 0.9 of the fluid's stability limit\n", (double)cpl->dtf));
  else if (cpl->adaptive) PetscCall(PetscViewerASCIIPrintf(viewer, "coupling: adaptive fluid step (-fluid_adaptive_dt): 1 to %d DEM steps of %g s per fluid step, within 0.9 of the fluid's stability limit\n", (int)cpl->substeps, (double)cpl->dtd));
  if (cpl->init != CPL_INIT_REST) PetscCall(PetscViewerASCIIPrintf(viewer, "coupling: initial fluid %s%s\n", CplInitNames[cpl->init], cpl->restarting ? " (not applied: the fluid comes from the checkpoint)" : ""));
  if (cpl->init == CPL_INIT_STEADY && !cpl->restarting) PetscCall(PetscViewerASCIIPrintf(viewer, "coupling: the steady start converged in %d pseudo steps of %g s (-cpl_init_fluid_rtol %g)\n", (int)cpl->init_its, (double)(cpl->frozen ? cpl->dt : cpl->substeps * cpl->dtd), (double)cpl->init_rtol));
  PetscCall(CplPreflight(cpl, viewer, PETSC_FALSE));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CplDestroy(Cpl *cpl)
{
  PetscFunctionBeginUser;
  if (!*cpl) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(VecDestroy(&(*cpl)->cloc));
  for (int s = 0; s < 3; s++) PetscCall(VecDestroy(&(*cpl)->floc[s]));
  PetscCall(VecDestroy(&(*cpl)->kv));
  PetscCall(VecDestroy(&(*cpl)->jf));
  PetscCall(VecDestroy(&(*cpl)->owed));
  PetscCall(PetscFree4((*cpl)->side, (*cpl)->vol, (*cpl)->diam, (*cpl)->mass));
  PetscCall(PetscFree((*cpl)->stc));
  PetscCall(CplSelfTableDestroy(*cpl));
  PetscCall(CplSmoothDestroy(*cpl));
  PetscCall(PetscFree(*cpl));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CplGetTime(Cpl cpl, PetscReal *t, PetscInt *step)
{
  PetscFunctionBeginUser;
  if (t) *t = cpl->t;
  if (step) *step = cpl->step;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CplGetFluidTime(Cpl cpl, PetscLogDouble *t)
{
  PetscFunctionBeginUser;
  *t = cpl->t_fluid;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CplGetSubsteps(Cpl cpl, PetscInt *substeps)
{
  PetscFunctionBeginUser;
  *substeps = cpl->substeps;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CplGetClippedCount(Cpl cpl, PetscInt *count)
{
  PetscFunctionBeginUser;
  *count = cpl->clipped_total;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CplGetSelfCappedCount(Cpl cpl, PetscInt *count)
{
  PetscFunctionBeginUser;
  *count = cpl->self_capped_total;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CplGetStepQuantum(Cpl cpl, PetscReal *dq)
{
  PetscFunctionBeginUser;
  *dq = cpl->adaptive ? (cpl->frozen ? 1e-9 * cpl->dtf : cpl->dtd) : cpl->dt;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CplSetRestarting(Cpl cpl, PetscBool on)
{
  PetscFunctionBeginUser;
  cpl->restarting = on;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CplGetMode(Cpl cpl, CplMode *mode)
{
  PetscFunctionBeginUser;
  *mode = cpl->mode;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CplGetTimeStep(Cpl cpl, PetscReal *dt)
{
  PetscFunctionBeginUser;
  *dt = cpl->dt;
  PetscFunctionReturn(PETSC_SUCCESS);
}
