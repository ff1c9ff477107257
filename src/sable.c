/* Sable-wide helpers: the unused-option check (DESIGN §9) and the check of the values given to
 * Sable's own options (finite numbers, a value where one is needed, the count of a list). */
#include "sable.h"
#include <math.h>
#include <stdlib.h>

/* Sable's options that are flags: given alone they mean true. Every other option of Sable's
 * prefixes takes a value (tests/test_options_values.sh keeps this list complete). */
static const char *const SableFlags[] = {"dem_convex_sat", "dem_deterministic", "dem_frozen", "dem_lattice_random_orientation", "domain_periodic_x", "domain_periodic_y", "domain_periodic_z", "fluid_adaptive_dt", "lb_verbose"};

/* Sable's options whose values are words (file, directory, shape and model names): no number
 * check; every other value-taking option of Sable's takes numbers (tests/test_options_values.sh
 * keeps this list complete). */
static const char *const SableWords[] = {"io_dir", "io_prefix", "dem_init_file", "dem_shape_file", "dem_shape", "dem_contact_law", "dem_convex_contact_point", "cpl_drag", "fluid_advection", "fluid_inlet_interpolation", "fluid_viscous", "fluid_bc_xlo", "fluid_bc_xhi", "fluid_bc_ylo", "fluid_bc_yhi", "fluid_bc_zlo", "fluid_bc_zhi", "lb_scheme", "lb_weight"};

/* Sable's own option prefixes; fluid_poisson_ and fluid_viscous_ are PETSc solvers' prefixes
 * (their flags, such as -fluid_poisson_ksp_monitor, are PETSc's business) except for the three
 * options of Sable's that share them. */
static PetscBool SableOwnOption(const char *name)
{
  const char *own[] = {"dem_", "fluid_", "cpl_", "domain_", "io_", "lb_"};
  const char *shared[] = {"fluid_poisson_pc_lag", "fluid_poisson_pc_lag_growth", "fluid_viscous_number_max"};
  for (size_t k = 0; k < sizeof shared / sizeof shared[0]; k++)
    if (!strcmp(name, shared[k])) return PETSC_TRUE;
  if (!strncmp(name, "fluid_poisson_", 14) || !strncmp(name, "fluid_viscous_", 14)) return PETSC_FALSE;
  for (size_t k = 0; k < sizeof own / sizeof own[0]; k++)
    if (!strncmp(name, own[k], strlen(own[k]))) return PETSC_TRUE;
  return PETSC_FALSE;
}

/* One option's value: a flag needs none, every other option one; a numeric option's
 * comma-separated items must each be a finite number (PETSc's own message for "abc" names no
 * option, and no option of Sable's means "forever" by inf). */
static PetscErrorCode SableCheckOptionValue(MPI_Comm comm, const char *name, const char *value)
{
  char   buf[4096], *tok, *save = NULL;
  size_t k;

  PetscFunctionBeginUser;
  if (!SableOwnOption(name)) PetscFunctionReturn(PETSC_SUCCESS);
  for (k = 0; k < sizeof SableFlags / sizeof SableFlags[0]; k++)
    if (!strcmp(name, SableFlags[k])) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCheck(value && value[0], comm, PETSC_ERR_ARG_WRONG, "option -%s needs a value (-help lists it with its default)", name);
  for (k = 0; k < sizeof SableWords / sizeof SableWords[0]; k++) /* a file named "inf" is a file */
    if (!strcmp(name, SableWords[k])) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscStrncpy(buf, value, sizeof buf));
  for (tok = strtok_r(buf, ",", &save); tok; tok = strtok_r(NULL, ",", &save)) {
    char        *end;
    const double x = strtod(tok, &end);
    PetscCheck(end != tok && !*end, comm, PETSC_ERR_ARG_WRONG, "option -%s %s: '%s' is not a number", name, value, tok);
    PetscCheck(isfinite(x), comm, PETSC_ERR_ARG_OUTOFRANGE, "option -%s %s: '%s' is not a finite number", name, value, tok);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SableCheckOptionValues(MPI_Comm comm)
{
  char *all, *save = NULL, *tok, *name = NULL;

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsGetAll(NULL, &all));
  /* "-name value -flag -name2 -1,2 ...": a token is a key when PETSc says so (a dash and a
     letter), else the value of the key before it */
  for (tok = strtok_r(all, " ", &save); tok; tok = strtok_r(NULL, " ", &save)) {
    PetscBool key;
    PetscCall(PetscOptionsValidKey(tok, &key));
    if (key) {
      if (name) PetscCall(SableCheckOptionValue(comm, name, NULL));
      name = tok + 1;
    } else if (name) {
      PetscCall(SableCheckOptionValue(comm, name, tok));
      name = NULL;
    }
  }
  if (name) PetscCall(SableCheckOptionValue(comm, name, NULL));
  PetscCall(PetscFree(all));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SableOptionCount(const char *opt, PetscInt *count)
{
  const char *v;
  PetscBool   set;

  PetscFunctionBeginUser;
  *count = 0;
  PetscCall(PetscOptionsFindPair(NULL, NULL, opt, &v, &set));
  if (!set || !v || !v[0]) PetscFunctionReturn(PETSC_SUCCESS);
  *count = 1;
  for (; *v; v++) *count += *v == ',';
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Options of a multigrid preconditioner's levels are read when the solver is set up, after the
 * start-up check: they are checked at the end of the run instead (SableWarnOptionsUnused). */
static PetscBool SableReadAtSolverSetUp(const char *name)
{
  const PetscBool solver = (PetscBool)(!strncmp(name, "fluid_poisson_", 14) || !strncmp(name, "fluid_viscous_", 14));
  return (PetscBool)(solver && (strstr(name, "_mg_levels_") || strstr(name, "_mg_coarse_")));
}

PetscErrorCode SableWarnOptionsUnused(MPI_Comm comm)
{
  PetscInt n;
  char   **names, **values;

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsLeftGet(NULL, &n, &names, &values));
  for (PetscInt i = 0; i < n; i++)
    if (SableReadAtSolverSetUp(names[i])) PetscCall(PetscPrintf(comm, "warning: option -%s %s was never read (a typo? -help lists the valid options)\n", names[i], values[i] ? values[i] : ""));
  PetscCall(PetscOptionsLeftRestore(NULL, &n, &names, &values));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SableCheckOptionsUsed(MPI_Comm comm)
{
  PetscInt n, bad = -1;
  char   **names, **values;
  char     msg[512] = "";

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsLeftGet(NULL, &n, &names, &values));
  for (PetscInt i = 0; i < n && bad < 0; i++) {
    /* options that steer PETSc's run-time system, read after us or not at all */
    const char *skip[] = {"options_left", "log_view", "log_view_memory", "log_view_gpu_time", "log_trace", "malloc_debug", "malloc_dump", "malloc_test", "malloc_view", "malloc_view_threshold", "options_view", "help", "on_error_abort", "on_error_attach_debugger", "info", "history", "options_file", "options_monitor", "fp_trap", "check_pointer_intensity", "use_gpu_aware_mpi"};
    PetscBool   ok     = SableReadAtSolverSetUp(names[i]);
    for (size_t k = 0; k < sizeof skip / sizeof skip[0]; k++) /* whole names: -log_vieww is a typo */
      if (!strcmp(names[i], skip[k])) ok = PETSC_TRUE;
    if (!ok) {
      bad = i;
      PetscCall(PetscSNPrintf(msg, sizeof msg, "option -%s %s was given but nothing reads it (a typo? -help lists the valid options)", names[i], values[i] ? values[i] : ""));
    }
  }
  PetscCall(PetscOptionsLeftRestore(NULL, &n, &names, &values));
  PetscCheck(bad < 0, comm, PETSC_ERR_ARG_WRONG, "%s", msg);
  PetscFunctionReturn(PETSC_SUCCESS);
}
