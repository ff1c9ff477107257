/* Inlet velocities that change during a run (Grains3D Part II §4.3.2 runs its bed at 2 U_mf up
 * to t = 1785, then at 3 U_mf). Per inlet face, -fluid_bc_<face>_velocity_table t1,u1,v1,w1,
 * t2,u2,v2,w2,... (s, m/s; times strictly increasing, >= 0, at most FLUID_INLET_TABLE_MAX rows)
 * gives the velocity from t1 on; before t1 the face keeps -fluid_bc_<face>_velocity. Between
 * rows the value holds (-fluid_inlet_interpolation step, the default: a switch) or is
 * interpolated linearly (linear: a ramp); after the last row it holds. The fluid's clock is the
 * sum of its steps; a step from t to t + dt uses the velocity at t + dt, the level at which the
 * projection enforces continuity, so the flux through the outlet follows the table within the
 * solver tolerance from the step that crosses a row's time on.
 * The log: at the first step, the row each table is at when the run starts, at the fluid's true
 * time (a restart's rows are the checkpoint's, reached before it: "is at row r ... reached at
 * t = ..., before this run's start at t = ..."); then one line each time a step reaches a new
 * row. */
#include "fluid/fluid_impl.h"

typedef enum {
  FLUID_INLET_STEP,
  FLUID_INLET_LINEAR
} FluidInletInterp;
static const char *const FluidInletInterpNames[] = {"step", "linear", "FluidInletInterp", "FLUID_INLET_", NULL};

/* Collective. Reads the tables and -fluid_inlet_interpolation; call after the face types are known. */
PetscErrorCode FluidSetFromOptionsInlet(Fluid fl)
{
  /* written out so that grep (and the option list the Makefile builds) finds them */
  const char *const table[3][2] = {{"-fluid_bc_xlo_velocity_table", "-fluid_bc_xhi_velocity_table"}, {"-fluid_bc_ylo_velocity_table", "-fluid_bc_yhi_velocity_table"}, {"-fluid_bc_zlo_velocity_table", "-fluid_bc_zhi_velocity_table"}};
  const char       *side[2] = {"lo", "hi"}, *ax = "xyz";
  PetscBool         set;
  PetscInt          interp = fl->inlet.linear ? FLUID_INLET_LINEAR : FLUID_INLET_STEP;
  PetscReal         buf[4 * FLUID_INLET_TABLE_MAX + 4]; /* one row more than allowed: PETSc stops silently at the array's size */

  PetscFunctionBeginUser;
  PetscOptionsBegin(fl->comm, NULL, "Fluid inlet tables", NULL);
  PetscCall(SableOptionsEnum("-fluid_inlet_interpolation", "Between rows of an inlet table: step (hold the earlier row) or linear (default step)", FluidInletInterpNames, 2, interp, &interp, NULL));
  fl->inlet.linear = interp == FLUID_INLET_LINEAR ? PETSC_TRUE : PETSC_FALSE;
  for (int d = 0; d < 3; d++)
    for (int s = 0; s < 2; s++) {
      FluidBC    *bc  = &fl->bc.face[d][s];
      PetscInt    n   = 4 * FLUID_INLET_TABLE_MAX + 4;
      const char *opt = table[d][s];

      for (int k = 0; k < 3; k++) bc->vel0[k] = bc->vel[k];
      PetscCall(SableOptionsRealArray(opt, "Inlet velocity from each time on: t1,u1,v1,w1,t2,...", "s, m/s", buf, 0, &n, &set));
      if (!set) continue;
      PetscCheck(bc->type == FLUID_BC_INLET, fl->comm, PETSC_ERR_ARG_WRONG, "%s is given but -fluid_bc_%c%s is %s, not inlet", opt, ax[d], side[s], FluidBCNames[bc->type]);
      PetscCheck(n > 0 && n % 4 == 0 && n <= 4 * FLUID_INLET_TABLE_MAX, fl->comm, PETSC_ERR_ARG_SIZ, "%s takes rows of 4 values t,u,v,w, 1 to %d rows; got %s%d values", opt, FLUID_INLET_TABLE_MAX, n > 4 * FLUID_INLET_TABLE_MAX ? "more than " : "", (int)(n > 4 * FLUID_INLET_TABLE_MAX ? 4 * FLUID_INLET_TABLE_MAX : n));
      PetscCall(PetscArraycpy(bc->tab, buf, n));
      bc->ntab = n / 4;
      bc->row  = -1;
      for (PetscInt r = 0; r < bc->ntab; r++) {
        const PetscReal *row = &bc->tab[4 * r];
        PetscCheck(!PetscIsInfOrNanReal(row[0]), fl->comm, PETSC_ERR_ARG_OUTOFRANGE, "%s: time %g of row %d is not finite", opt, (double)row[0], (int)r + 1);
        PetscCheck(row[0] >= 0, fl->comm, PETSC_ERR_ARG_OUTOFRANGE, "%s: time %g of row %d must be >= 0 (s)", opt, (double)row[0], (int)r + 1);
        PetscCheck(r == 0 || row[0] > row[-4], fl->comm, PETSC_ERR_ARG_OUTOFRANGE, "%s: times must increase strictly, row %d has %g after %g", opt, (int)r + 1, (double)row[0], (double)row[-4]);
        for (int k = 1; k < 4; k++) PetscCheck(!PetscIsInfOrNanReal(row[k]), fl->comm, PETSC_ERR_ARG_OUTOFRANGE, "%s: velocity %g,%g,%g of row %d is not finite", opt, (double)row[1], (double)row[2], (double)row[3], (int)r + 1);
      }
    }
  PetscOptionsEnd();
  PetscCall(FluidUpdateInlets(fl, fl->clock.time, NULL));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. Once, at the first step of a run (fresh or restarted): the row each table is at
 * at the fluid's time, as "reaches row r ... at t = ..." when the row's time is the start's, else
 * as a row reached earlier (a restart, or a run started after a row's time). */
static PetscErrorCode FluidAnnounceInlets(Fluid fl)
{
  const char     *side[2] = {"lo", "hi"}, *ax = "xyz";
  const PetscReal t = fl->clock.time, tol = 1e-9 * PetscMax(1.0, PetscAbsReal(t));

  PetscFunctionBeginUser;
  fl->inlet.told = PETSC_TRUE;
  for (int d = 0; d < 3; d++)
    for (int s = 0; s < 2; s++) {
      const FluidBC *bc = &fl->bc.face[d][s];
      if (!bc->ntab || bc->row < 0) continue;
      const PetscReal *row  = &bc->tab[4 * bc->row];
      const char      *ramp = fl->inlet.linear && bc->row + 1 < bc->ntab ? ", ramping to the next row" : "";
      if (row[0] >= t - tol) PetscCall(PetscPrintf(fl->comm, "fluid: inlet %c%s reaches row %d of its table at t = %g s: velocity %g,%g,%g m/s%s\n", ax[d], side[s], (int)bc->row + 1, (double)t, (double)row[1], (double)row[2], (double)row[3], ramp));
      else PetscCall(PetscPrintf(fl->comm, "fluid: inlet %c%s is at row %d of its table (reached at t = %g s, before this run's start at t = %g s): velocity %g,%g,%g m/s%s\n", ax[d], side[s], (int)bc->row + 1, (double)row[0], (double)t, (double)row[1], (double)row[2], (double)row[3], ramp));
    }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. Sets every tabled inlet to its velocity at t; when one changes, rewrites the
 * fixed faces of u and makes the implicit viscous operator rebuild its boundary part. Before
 * the set-up (the options' call, at the clock's 0) it says nothing: at the first step the rows
 * at the start are announced (FluidAnnounceInlets: after a restart the clock and rows are the
 * checkpoint's), then a line is printed when a face reaches a new row of its table;
 * *changed_out (may be NULL) says whether any inlet velocity changed. */
PetscErrorCode FluidUpdateInlets(Fluid fl, PetscReal t, PetscBool *changed_out)
{
  const char *side[2] = {"lo", "hi"}, *ax = "xyz";
  PetscBool   changed = PETSC_FALSE;

  PetscFunctionBeginUser;
  if (fl->setup && !fl->inlet.told) PetscCall(FluidAnnounceInlets(fl));
  for (int d = 0; d < 3; d++)
    for (int s = 0; s < 2; s++) {
      FluidBC  *bc = &fl->bc.face[d][s];
      PetscReal v[3];
      PetscInt  r;
      if (!bc->ntab) continue;
      r = fluid_inlet_at(bc, fl->inlet.linear, t, v);
      if (r != bc->row && r >= 0 && fl->setup) PetscCall(PetscPrintf(fl->comm, "fluid: inlet %c%s reaches row %d of its table at t = %g s: velocity %g,%g,%g m/s%s\n", ax[d], side[s], (int)r + 1, (double)t, (double)bc->tab[4 * r + 1], (double)bc->tab[4 * r + 2], (double)bc->tab[4 * r + 3], fl->inlet.linear && r + 1 < bc->ntab ? ", ramping to the next row" : ""));
      bc->row = r;
      for (int k = 0; k < 3; k++) {
        if (v[k] != bc->vel[k]) changed = PETSC_TRUE;
        bc->vel[k] = v[k];
      }
    }
  if (fl->patch) PetscCall(FluidUpdatePatches(fl, t, &changed));
  if (changed && fl->setup) {
    PetscCall(FluidBoundaryFaceValues(fl, fl->fld.u));
    fl->vimp.dt_mat = -1; /* the implicit viscous right-hand side holds the inlet values (a ramp rebuilds it every step) */
  }
  if (changed_out) *changed_out = changed;
  PetscFunctionReturn(PETSC_SUCCESS);
}
