/* Sable-wide helpers: the unused-option check (DESIGN §9) and the check of the values given to
 * Sable's own options (finite numbers, a value where one is needed, the count of a list, an
 * integer that fits in PetscInt). The names of the options Sable reads come from the sources
 * themselves: the Makefile writes sable_options.h (tools/gen-options.sh) with every option name
 * written in src/, those read as integers, as flags (no value needed) and as words (no number
 * check); a typo is compared with the names ("did you mean"). Reading and showing options (the
 * readers with units and ranges, the -help printer) is options.c. */
#include "sable.h"
#include "sable_options.h"
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <strings.h>

/* Sable's option groups, in the order -help lists them: a name's prefix, or the one unprefixed
 * option, -restart, listed with the output options. fluid_poisson_ and fluid_viscous_ are PETSc
 * solvers' prefixes (their options, such as -fluid_poisson_ksp_monitor, are PETSc's business)
 * except for the options of Sable's that share them (-fluid_poisson_pc_lag, ...: read by name in
 * src/, hence in the generated SableReadOptions). Returns -1 for PETSc's. */
int SableOptionGroup(const char *name)
{
  const char *pre[] = {"domain_", "dem_", "fluid_", "cpl_", "lb_", "io_", "mon_", "avg_", "sable_"};

  if (!strcmp(name, "restart")) return 5;
  if (!strncmp(name, "fluid_poisson_", 14) || !strncmp(name, "fluid_viscous_", 14)) {
    for (size_t k = 0; SableReadOptions[k]; k++)
      if (!strcmp(name, SableReadOptions[k])) return 2;
    return -1;
  }
  for (int k = 0; k < (int)(sizeof pre / sizeof pre[0]); k++)
    if (!strncmp(name, pre[k], strlen(pre[k]))) return k;
  return -1;
}

/* One of the options whose values Sable checks (every group but the driver's -sable_ flags). */
PetscBool SableOptionIsOwn(const char *name)
{
  const int g = SableOptionGroup(name);
  return (PetscBool)(g >= 0 && g != 8);
}

/* PETSc's integer options that Sable's cases and tools give (PETSc reads them, not Sable, so no
 * source of ours names them all): the DMDA's, read by DMSetFromOptions (PETSc 3.18,
 * src/dm/impls/da/dacreate.c), and the solver ones, matched as the end of a name under Sable's
 * solver prefixes (-fluid_poisson_ksp_max_it, -fluid_poisson_mg_levels_ksp_max_it). */
static const char *const SablePetscIntOptions[]        = {"da_grid_x", "da_grid_y", "da_grid_z", "da_processors_x", "da_processors_y", "da_processors_z", "da_overlap", "da_overlap_x", "da_overlap_y", "da_overlap_z", "da_refine", "da_refine_x", "da_refine_y", "da_refine_z", "da_refine_hierarchy_x", "da_refine_hierarchy_y", "da_refine_hierarchy_z"};
static const char *const SablePetscSolverIntSuffixes[] = {"ksp_max_it", "ksp_gmres_restart", "pc_mg_levels", "pc_hypre_boomeramg_max_iter", "pc_hypre_boomeramg_max_levels", "pc_hypre_boomeramg_agg_nl", "pc_gamg_agg_nsmooths"};

void SableIndexPattern(const char *name, char *pat, size_t size, char *index, size_t isize)
{
  const char *s = name;

  index[0] = 0;
  snprintf(pat, size, "%s", name);
  for (; *s; s++) {
    size_t n = 0;
    if (s != name && s[-1] != '_') continue;
    while (isdigit((unsigned char)s[n])) n++;
    if (n && n < isize && (!s[n] || s[n] == '_')) {
      memcpy(index, s, n);
      index[n] = 0;
      snprintf(pat, size, "%.*s%%d%s", (int)(s - name), name, s + n);
      return;
    }
  }
}

/* Whether name is in the list, or is an indexed name ("dem_insert_3_psd") whose pattern
 * ("dem_insert_%d_psd") is. */
static PetscBool SableInList(const char *name, const char *const *list, size_t n)
{
  char pat[128], index[16];

  SableIndexPattern(name, pat, sizeof pat, index, sizeof index);
  for (size_t k = 0; k < n && list[k]; k++)
    if (!strcmp(name, list[k]) || (index[0] && !strcmp(pat, list[k]))) return PETSC_TRUE;
  return PETSC_FALSE;
}

/* Whether option name (no dash) takes integers; *petsc: PETSc reads it (it also takes PETSc's
 * words DECIDE, DEFAULT, DETERMINE). */
static PetscBool SableIntOption(const char *name, PetscBool *petsc)
{
  const size_t len = strlen(name);

  *petsc = PETSC_FALSE;
  if (SableInList(name, SableIntOptions, sizeof SableIntOptions / sizeof SableIntOptions[0])) return PETSC_TRUE;
  *petsc = PETSC_TRUE;
  if (SableInList(name, SablePetscIntOptions, sizeof SablePetscIntOptions / sizeof SablePetscIntOptions[0])) return PETSC_TRUE;
  if (strncmp(name, "fluid_poisson_", 14) && strncmp(name, "fluid_viscous_", 14)) return PETSC_FALSE;
  for (size_t k = 0; k < sizeof SablePetscSolverIntSuffixes / sizeof SablePetscSolverIntSuffixes[0]; k++) {
    const size_t ls = strlen(SablePetscSolverIntSuffixes[k]);
    if (len > ls && name[len - ls - 1] == '_' && !strcmp(name + len - ls, SablePetscSolverIntSuffixes[k])) return PETSC_TRUE;
  }
  return PETSC_FALSE;
}

/* An integer option's items: each a whole number that fits in PetscInt. PETSc itself would
 * wrap 2147483648 to -2147483648 and report that number without the option's name. */
static PetscErrorCode SableCheckIntValue(MPI_Comm comm, const char *name, const char *value, PetscBool petsc)
{
  const char *const words[] = {"decide", "petsc_decide", "default", "petsc_default", "determine", "petsc_determine"};
  char              buf[4096], *tok, *save = NULL;

  PetscFunctionBeginUser;
  PetscCheck(value && value[0], comm, PETSC_ERR_ARG_WRONG, "option -%s needs a value: an integer in [%" PetscInt_FMT ", %" PetscInt_FMT "]", name, (PetscInt)PETSC_MIN_INT, (PetscInt)PETSC_MAX_INT);
  PetscCall(PetscStrncpy(buf, value, sizeof buf));
  for (tok = strtok_r(buf, ",", &save); tok; tok = strtok_r(NULL, ",", &save)) {
    char     *end;
    long long v;
    PetscBool word = PETSC_FALSE;
    for (size_t k = 0; petsc && k < sizeof words / sizeof words[0]; k++)
      if (!strcasecmp(tok, words[k])) word = PETSC_TRUE;
    if (word) continue;
    errno = 0;
    v     = strtoll(tok, &end, 10);
    PetscCheck(end != tok && !*end && !isspace((unsigned char)tok[0]), comm, PETSC_ERR_ARG_WRONG, "option -%s %s: '%s' is not an integer (an integer in [%" PetscInt_FMT ", %" PetscInt_FMT "])", name, value, tok, (PetscInt)PETSC_MIN_INT, (PetscInt)PETSC_MAX_INT);
    PetscCheck(errno != ERANGE && v >= PETSC_MIN_INT && v <= PETSC_MAX_INT, comm, PETSC_ERR_ARG_OUTOFRANGE, "option -%s %s: '%s' does not fit in PetscInt (an integer in [%" PetscInt_FMT ", %" PetscInt_FMT "])", name, value, tok, (PetscInt)PETSC_MIN_INT, (PetscInt)PETSC_MAX_INT);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* One option's value: a flag needs none, every other option one; a numeric option's
 * comma-separated items must each be a finite number (PETSc's own message for "abc" names no
 * option, and no option of Sable's means "forever" by inf). */
static PetscErrorCode SableCheckOptionValue(MPI_Comm comm, const char *name, const char *value)
{
  char      buf[4096], *tok, *save = NULL;
  PetscBool petsc;

  PetscFunctionBeginUser;
  if (SableIntOption(name, &petsc)) PetscCall(SableCheckIntValue(comm, name, value, petsc));
  if (!SableOptionIsOwn(name)) PetscFunctionReturn(PETSC_SUCCESS);
  if (SableInList(name, SableFlagOptions, sizeof SableFlagOptions / sizeof SableFlagOptions[0])) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCheck(value && value[0], comm, PETSC_ERR_ARG_WRONG, "option -%s needs a value (-help lists it with its default)", name);
  if (SableInList(name, SableWordOptions, sizeof SableWordOptions / sizeof SableWordOptions[0])) PetscFunctionReturn(PETSC_SUCCESS); /* a file named "inf" is a file */
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

/* Optimal string alignment distance: insertions, deletions, substitutions and swaps of two
 * neighbours ("-dem_nk" -> "-dem_kn" is 1); names longer than 63 characters count as far. */
static int SableEditDistance(const char *a, const char *b)
{
  const int la = (int)strlen(a), lb = (int)strlen(b);
  int       d[3][64], *p2 = d[0], *p1 = d[1], *c = d[2];

  if (la > 63 || lb > 63) return 64;
  for (int j = 0; j <= lb; j++) p1[j] = j;
  for (int i = 1; i <= la; i++) {
    c[0] = i;
    for (int j = 1; j <= lb; j++) {
      int v = PetscMin(p1[j] + 1, c[j - 1] + 1);
      v     = PetscMin(v, p1[j - 1] + (a[i - 1] != b[j - 1]));
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) v = PetscMin(v, p2[j - 2] + 1);
      c[j] = v;
    }
    int *t = p2;
    p2     = p1;
    p1     = c;
    c      = t;
  }
  return p1[lb];
}

/* The words of a name (split at '_') sorted: "dem_kn_wall" and "dem_wall_kn" share it. */
static void SableSortedWords(const char *name, char *key, size_t size)
{
  char buf[128], *w[32], *save = NULL;
  int  n = 0;

  key[0] = 0;
  if (strlen(name) >= sizeof buf) return;
  strcpy(buf, name);
  for (char *t = strtok_r(buf, "_", &save); t && n < 32; t = strtok_r(NULL, "_", &save)) w[n++] = t;
  for (int i = 1; i < n; i++) /* insertion sort: a handful of words */
    for (int j = i; j > 0 && strcmp(w[j - 1], w[j]) > 0; j--) {
      char *t  = w[j];
      w[j]     = w[j - 1];
      w[j - 1] = t;
    }
  for (int i = 0; i < n; i++) {
    if (i) strncat(key, "_", size - strlen(key) - 1);
    strncat(key, w[i], size - strlen(key) - 1);
  }
}

/* The known option (SableKnownOptions) closest to an unknown name: at most 2 edits away, or the
 * same words in another order; an empty string when none is. */
static void SableSuggest(const char *name, char *best, size_t size)
{
  char pat[128], index[16], key[128], kkey[128];
  int  bd = 3;

  best[0] = 0;
  SableIndexPattern(name, pat, sizeof pat, index, sizeof index);
  SableSortedWords(name, key, sizeof key);
  for (size_t k = 0; SableKnownOptions[k]; k++) {
    const char     *known   = SableKnownOptions[k];
    const PetscBool indexed = (PetscBool)(strstr(known, "%d") != NULL);
    const char     *given   = indexed ? pat : name;
    int             d;
    if (indexed && !index[0]) continue;
    d = SableEditDistance(given, known);
    SableSortedWords(known, kkey, sizeof kkey);
    if (d > 1 && key[0] && !strcmp(key, kkey)) d = 1;
    if (d == 0 || d >= bd) continue; /* 0: a known name unread here (e.g. an index past the last) */
    bd = d;
    if (indexed) {
      const char *f = strstr(known, "%d");
      snprintf(best, size, "%.*s%s%s", (int)(f - known), known, index, f + 2);
    } else snprintf(best, size, "%s", known);
  }
}

/* The error text of an option that nothing reads (value NULL: none), with the closest known name. */
static void SableUnknownMessage(const char *name, const char *value, char *msg, size_t size)
{
  char guess[128], hint[160] = "a typo?";

  SableSuggest(name, guess, sizeof guess);
  if (guess[0]) snprintf(hint, sizeof hint, "did you mean -%s?", guess);
  snprintf(msg, size, "option -%s%s%s was given but nothing reads it (%s -help lists the valid options)", name, value && value[0] ? " " : "", value && value[0] ? value : "", hint);
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
      SableUnknownMessage(names[i], values[i], msg, sizeof msg);
    }
  }
  PetscCall(PetscOptionsLeftRestore(NULL, &n, &names, &values));
  PetscCheck(bad < 0, comm, PETSC_ERR_ARG_WRONG, "%s", msg);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SableCheckOptionsKnown(MPI_Comm comm, const char *prefix)
{
  char        *all, *save = NULL, *tok, *name = NULL, msg[512] = "";
  const size_t lp = strlen(prefix);

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsGetAll(NULL, &all));
  /* "-name value -flag ...", as SableCheckOptionValues reads it; the first unknown name counts */
  for (tok = strtok_r(all, " ", &save); tok && !msg[0]; tok = strtok_r(NULL, " ", &save)) {
    PetscBool key;
    PetscCall(PetscOptionsValidKey(tok, &key));
    if (!key) {
      if (name) SableUnknownMessage(name, tok, msg, sizeof msg);
      name = NULL;
      continue;
    }
    if (name) SableUnknownMessage(name, NULL, msg, sizeof msg);
    name = NULL;
    /* a PETSc solver's option under Sable's prefix (SableOptionGroup < 0) is PETSc's to judge */
    if (!strncmp(tok + 1, prefix + 1, lp - 1) && SableOptionGroup(tok + 1) >= 0 && !SableInList(tok + 1, SableKnownOptions, sizeof SableKnownOptions / sizeof SableKnownOptions[0])) name = tok + 1;
  }
  if (name && !msg[0]) SableUnknownMessage(name, NULL, msg, sizeof msg);
  PetscCall(PetscFree(all));
  PetscCheck(!msg[0], comm, PETSC_ERR_ARG_WRONG, "%s", msg);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SableCheckRunLength(MPI_Comm comm, const SableRunLength *r)
{
  const double steps = (r->t_end - r->t) / r->dt * r->per_step;

  PetscFunctionBeginUser;
  PetscCheck(r->end_set, comm, PETSC_ERR_ARG_WRONG, "the run has no end: give -%s_t_end, the simulated time to reach (s)", r->prefix);
  PetscCheck(steps <= (double)(PETSC_MAX_INT - r->counter), comm, PETSC_ERR_ARG_OUTOFRANGE, "-%s_t_end %g s at a %s of %g s (%s) takes %.4g %s, more than the step counter holds (%" PetscInt_FMT "): lower -%s_t_end or raise %s", r->prefix, (double)r->t_end, r->step, (double)r->dt, r->dt_text, steps, r->counted, (PetscInt)PETSC_MAX_INT, r->prefix, r->raise);
  PetscCheck(r->progress_dt == 0 || r->progress_dt >= r->dt, comm, PETSC_ERR_ARG_OUTOFRANGE, "-%s_progress_interval %g s is shorter than the %s %g s (%s): give 0 (no progress lines) or at least one step", r->prefix, (double)r->progress_dt, r->step, (double)r->dt, r->dt_text);
  PetscCheck(r->io_dt == 0 || r->io_dt >= r->dt, comm, PETSC_ERR_ARG_OUTOFRANGE, "%s %g s is shorter than the %s %g s (%s): give 0 (no output) or at least one step", r->io_opt ? r->io_opt : "-io_interval", (double)r->io_dt, r->step, (double)r->dt, r->dt_text);
  if (r->t < r->t_end - 0.5 * r->dt) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscPrintf(comm, "run: -%s_t_end %g s is not after the start time %g s: 0 steps, the initial state only\n", r->prefix, (double)r->t_end, (double)r->t));
  PetscFunctionReturn(PETSC_SUCCESS);
}
