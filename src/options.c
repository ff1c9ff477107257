/* How Sable's options are read and shown. Two parts:
 *  - the readers of options (SableOptionsReal, SableOptionsInt, SableOptionsRealArray,
 *    SableOptionsRealN, SableOptionsIntN; SableOptionsEnum, SableOptionsBool, SableOptionsString), called inside the PetscOptionsBegin block of the object that owns the
 *    option, with the option's literal name. Each prints its own -help line, with the true
 *    default ("<none>" when the option has none: a default outside the valid range, or no
 *    default values), the value given, the unit and the valid range, and refuses a value out
 *    of range with one line naming the option, the value and the range. A range is written as
 *    in mathematics: "(0,1]", "[0,inf)", NULL for none.
 *  - the -help printer: installed before PetscInitialize (SableHelpBegin), it keeps the help
 *    text that PETSc and Sable print through PetscHelpPrintf, and prints it at the end of the
 *    help pass (SableHelpFlush, also registered to run in PetscFinalize and at exit): Sable's
 *    sections grouped by prefix (-domain_, -dem_, -fluid_, -cpl_,
 *    -lb_, -io_, -mon_, -avg_, -sable_), then PETSc's sections in the order PETSc printed them. PETSc's
 *    "(None)" (no manual page) at the end of a line is left out. An indexed family (a name
 *    with an all-digit word: -dem_plane_3_velocity, -mon_probe_12) is printed once, where its
 *    first member was, as -dem_plane_<k>_velocity with its index range, then the members the
 *    run's options give, each with its value. Without -help the printer passes everything
 *    through at once. */
#include "sable.h"
#include <signal.h>
#include <stdarg.h>
#include <stdlib.h>

/* A range "(a,b]": bounds and whether each is open; the bound texts as written. */
typedef struct {
  PetscReal lo, hi;
  PetscBool lo_open, hi_open;
  char      lo_text[32], hi_text[32];
} SableRange;

static PetscErrorCode SableRangeParse(const char *range, SableRange *r)
{
  const char *comma = range ? strchr(range, ',') : NULL;
  size_t      len   = range ? strlen(range) : 0;
  char       *end;

  PetscFunctionBeginUser;
  PetscCheck(comma && len >= 5 && (range[0] == '(' || range[0] == '[') && (range[len - 1] == ')' || range[len - 1] == ']'), PETSC_COMM_SELF, PETSC_ERR_PLIB, "range '%s' is not written as (a,b], [a,b), ...", range ? range : "(null)");
  r->lo_open = (PetscBool)(range[0] == '(');
  r->hi_open = (PetscBool)(range[len - 1] == ')');
  PetscCall(PetscSNPrintf(r->lo_text, sizeof r->lo_text, "%.*s", (int)(comma - range - 1), range + 1));
  PetscCall(PetscSNPrintf(r->hi_text, sizeof r->hi_text, "%.*s", (int)(range + len - 1 - comma - 1), comma + 1));
  r->lo = strtod(r->lo_text, &end);
  PetscCheck(end != r->lo_text && !*end, PETSC_COMM_SELF, PETSC_ERR_PLIB, "range '%s': lower bound is not a number", range);
  r->hi = strtod(r->hi_text, &end);
  PetscCheck(end != r->hi_text && !*end, PETSC_COMM_SELF, PETSC_ERR_PLIB, "range '%s': upper bound is not a number", range);
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscBool SableRangeHolds(const SableRange *r, PetscReal v)
{
  return (PetscBool)((r->lo_open ? v > r->lo : v >= r->lo) && (r->hi_open ? v < r->hi : v <= r->hi));
}

/* The range as the messages say it: "> 0", ">= 1", "< 0.5", "in (0,1]". */
static void SableRangeText(const char *range, const SableRange *r, char *buf, size_t size)
{
  if (PetscIsInfReal(r->hi) && r->hi > 0 && !(PetscIsInfReal(r->lo) && r->lo < 0)) snprintf(buf, size, "%s %s", r->lo_open ? ">" : ">=", r->lo_text);
  else if (PetscIsInfReal(r->lo) && r->lo < 0 && !(PetscIsInfReal(r->hi) && r->hi > 0)) snprintf(buf, size, "%s %s", r->hi_open ? "<" : "<=", r->hi_text);
  else snprintf(buf, size, "in %s", range);
}

/* Whether the help lines of this block are printed now (PETSc's own test). */
static PetscBool SableHelpDue(PetscOptionItems *PetscOptionsObject)
{
  return (PetscBool)(PetscOptionsObject->printhelp && PetscOptionsObject->count == 1 && !PetscOptionsObject->alreadyprinted);
}

/* One help line: "  -name <value>: text (unit; range)". */
static PetscErrorCode SableHelpLine(PetscOptionItems *PetscOptionsObject, const char *opt, const char *value, const char *text, const char *unit, const char *range)
{
  char rt[96] = "", paren[160] = "";

  PetscFunctionBeginUser;
  if (range) {
    SableRange r;
    PetscCall(SableRangeParse(range, &r));
    SableRangeText(range, &r, rt, sizeof rt);
  }
  if ((unit && unit[0]) || rt[0]) PetscCall(PetscSNPrintf(paren, sizeof paren, " (%s%s%s)", unit && unit[0] ? unit : "", unit && unit[0] && rt[0] ? "; " : "", rt));
  PetscCall((*PetscHelpPrintf)(PetscOptionsObject->comm, "  -%s%s <%s>: %s%s\n", PetscOptionsObject->prefix ? PetscOptionsObject->prefix : "", opt + 1, value, text, paren));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The value part of a help line: the default ("none" when has_def is false), and the value
 * given when the option is set: "<0.9 (default 0.75)>". */
static void SableHelpValue(const char *def, PetscBool has_def, const char *given, char *buf, size_t size)
{
  if (given) snprintf(buf, size, "%s (default %s)", given, has_def ? def : "none");
  else snprintf(buf, size, "%s", has_def ? def : "none");
}

/* A value out of range: "<opt> <value> must be <range> (<unit>)". */
static PetscErrorCode SableRangeError(MPI_Comm comm, const char *opt, const char *value, const char *unit, const char *range, const SableRange *r)
{
  char rt[96];

  PetscFunctionBeginUser;
  SableRangeText(range, r, rt, sizeof rt);
  SETERRQ(comm, PETSC_ERR_ARG_OUTOFRANGE, "%s %s must be %s%s%s%s", opt, value, rt, unit && unit[0] ? " (" : "", unit && unit[0] ? unit : "", unit && unit[0] ? ")" : "");
}

PetscErrorCode SableOptionsReal_Private(PetscOptionItems *PetscOptionsObject, const char opt[], const char text[], const char unit[], const char range[], PetscReal def, PetscReal *v, PetscBool *set)
{
  SableRange r   = {PETSC_NINFINITY, PETSC_INFINITY, PETSC_FALSE, PETSC_FALSE, "-inf", "inf"};
  PetscBool  flg = PETSC_FALSE;
  char       dtext[64], gtext[64], line[160];

  PetscFunctionBeginUser;
  if (range) PetscCall(SableRangeParse(range, &r));
  *v = def;
  PetscCall(PetscOptionsGetReal(PetscOptionsObject->options, PetscOptionsObject->prefix, opt, v, &flg));
  if (set) *set = flg;
  if (SableHelpDue(PetscOptionsObject)) {
    PetscCall(PetscSNPrintf(dtext, sizeof dtext, "%g", (double)def));
    PetscCall(PetscSNPrintf(gtext, sizeof gtext, "%g", (double)*v));
    SableHelpValue(dtext, SableRangeHolds(&r, def), flg ? gtext : NULL, line, sizeof line);
    PetscCall(SableHelpLine(PetscOptionsObject, opt, line, text, unit, range));
  }
  if (flg && !SableRangeHolds(&r, *v)) {
    PetscCall(PetscSNPrintf(gtext, sizeof gtext, "%g", (double)*v));
    PetscCall(SableRangeError(PetscOptionsObject->comm, opt, gtext, unit, range, &r));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SableOptionsInt_Private(PetscOptionItems *PetscOptionsObject, const char opt[], const char text[], const char unit[], const char range[], PetscInt def, PetscInt *v, PetscBool *set)
{
  SableRange r   = {PETSC_NINFINITY, PETSC_INFINITY, PETSC_FALSE, PETSC_FALSE, "-inf", "inf"};
  PetscBool  flg = PETSC_FALSE;
  char       dtext[64], gtext[64], line[160];

  PetscFunctionBeginUser;
  if (range) PetscCall(SableRangeParse(range, &r));
  *v = def;
  PetscCall(PetscOptionsGetInt(PetscOptionsObject->options, PetscOptionsObject->prefix, opt, v, &flg));
  if (set) *set = flg;
  PetscCall(PetscSNPrintf(gtext, sizeof gtext, "%" PetscInt_FMT, *v));
  if (SableHelpDue(PetscOptionsObject)) {
    PetscCall(PetscSNPrintf(dtext, sizeof dtext, "%" PetscInt_FMT, def));
    SableHelpValue(dtext, SableRangeHolds(&r, (PetscReal)def), flg ? gtext : NULL, line, sizeof line);
    PetscCall(SableHelpLine(PetscOptionsObject, opt, line, text, unit, range));
  }
  if (flg && !SableRangeHolds(&r, (PetscReal)*v)) PetscCall(SableRangeError(PetscOptionsObject->comm, opt, gtext, unit, range, &r));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SableOptionsEnum_Private(PetscOptionItems *PetscOptionsObject, const char opt[], const char text[], const char *const names[], PetscInt n, PetscInt def, PetscInt *v, PetscBool *set)
{
  char      buf[256], all[512] = "", paren[600];
  PetscBool flg = PETSC_FALSE, match = PETSC_FALSE;

  PetscFunctionBeginUser;
  PetscCheck(def >= 0 && def < n, PETSC_COMM_SELF, PETSC_ERR_PLIB, "%s: default %" PetscInt_FMT " is not one of its %" PetscInt_FMT " names", opt, def, n);
  *v = def;
  for (PetscInt i = 0; i < n; i++) {
    const size_t len = strlen(all);
    PetscCall(PetscSNPrintf(all + len, sizeof all - len, "%s%s", i ? ", " : "", names[i]));
  }
  PetscCall(PetscOptionsGetString(PetscOptionsObject->options, PetscOptionsObject->prefix, opt, buf, sizeof buf, &flg));
  if (set) *set = flg;
  for (PetscInt i = 0; flg && i < n && !match; i++) {
    PetscCall(PetscStrcasecmp(buf, names[i], &match));
    if (match) *v = i;
  }
  if (SableHelpDue(PetscOptionsObject)) {
    char line[320];
    SableHelpValue(names[def], PETSC_TRUE, flg ? buf : NULL, line, sizeof line);
    PetscCall(PetscSNPrintf(paren, sizeof paren, "%s (one of %s)", text, all));
    PetscCall(SableHelpLine(PetscOptionsObject, opt, line, paren, NULL, NULL));
  }
  PetscCheck(!flg || match, PetscOptionsObject->comm, PETSC_ERR_ARG_OUTOFRANGE, "%s %s is not known; valid values: %s", opt, buf, all);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SableOptionsBool_Private(PetscOptionItems *PetscOptionsObject, const char opt[], const char text[], PetscBool def, PetscBool *v, PetscBool *set)
{
  PetscBool flg = PETSC_FALSE;

  PetscFunctionBeginUser;
  *v = def;
  { /* PETSc's own refusal of a word names the first option given that word, not this one */
    static const char *const words[] = {"true", "false", "yes", "no", "on", "off", "1", "0"};
    char                     buf[64] = "";
    PetscBool                given = PETSC_FALSE, ok = PETSC_FALSE;

    PetscCall(PetscOptionsGetString(PetscOptionsObject->options, PetscOptionsObject->prefix, opt, buf, sizeof buf, &given));
    for (size_t i = 0; given && buf[0] && !ok && i < sizeof words / sizeof words[0]; i++) PetscCall(PetscStrcasecmp(buf, words[i], &ok));
    PetscCheck(!given || !buf[0] || ok, PetscOptionsObject->comm, PETSC_ERR_ARG_OUTOFRANGE, "%s %s is not a flag; valid values: true, false (or yes, no, on, off, 1, 0; alone, it means true)", opt, buf);
  }
  PetscCall(PetscOptionsGetBool(PetscOptionsObject->options, PetscOptionsObject->prefix, opt, v, &flg));
  if (set) *set = flg;
  if (SableHelpDue(PetscOptionsObject)) {
    char line[64];
    SableHelpValue(def ? "true" : "false", PETSC_TRUE, flg ? (*v ? "true" : "false") : NULL, line, sizeof line);
    PetscCall(SableHelpLine(PetscOptionsObject, opt, line, text, NULL, NULL));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SableOptionsString_Private(PetscOptionItems *PetscOptionsObject, const char opt[], const char text[], char v[], size_t size, PetscBool *set)
{
  const char *given = NULL;
  PetscBool   flg   = PETSC_FALSE;
  size_t      len   = 0;

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsFindPair(PetscOptionsObject->options, PetscOptionsObject->prefix, opt, &given, &flg));
  if (set) *set = flg;
  if (SableHelpDue(PetscOptionsObject)) {
    char line[2 * PETSC_MAX_PATH_LEN + 16];
    SableHelpValue(v, (PetscBool)(v[0] != 0), flg ? (given ? given : "") : NULL, line, sizeof line);
    PetscCall(SableHelpLine(PetscOptionsObject, opt, line, text, "text", NULL)); /* "(text)": a word, not a number */
  }
  if (!flg) PetscFunctionReturn(PETSC_SUCCESS);
  if (given) PetscCall(PetscStrlen(given, &len));
  PetscCheck(len<size, PetscOptionsObject->comm, PETSC_ERR_ARG_SIZ, "%s %.200s%s: at most %zu characters", opt, given, len> 200 ? "..." : "", size - 1); /* a long value cut short: PETSc's message has little room */
  PetscCall(PetscOptionsGetString(PetscOptionsObject->options, PetscOptionsObject->prefix, opt, v, size, &flg));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* "a,b,c" of n reals. */
static PetscErrorCode SableRealList(const PetscReal *v, PetscInt n, char *buf, size_t size)
{
  size_t len = 0;

  PetscFunctionBeginUser;
  buf[0] = 0;
  for (PetscInt i = 0; i < n && len + 1 < size; i++) {
    PetscCall(PetscSNPrintf(buf + len, size - len, "%s%g", i ? "," : "", (double)v[i]));
    PetscCall(PetscStrlen(buf, &len));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SableOptionsRealArray_Private(PetscOptionItems *PetscOptionsObject, const char opt[], const char text[], const char unit[], PetscReal v[], PetscInt ndef, PetscInt *n, PetscBool exact, PetscBool *set)
{
  const PetscInt cap = *n;
  PetscInt       got = cap, count = 0;
  PetscBool      flg        = PETSC_FALSE;
  char           dtext[512] = "", gtext[512] = "", line[1040];

  PetscFunctionBeginUser;
  PetscCall(SableRealList(v, PetscMin(ndef, cap), dtext, sizeof dtext));
  PetscCall(PetscOptionsGetRealArray(PetscOptionsObject->options, PetscOptionsObject->prefix, opt, v, &got, &flg));
  if (set) *set = flg;
  *n = flg ? got : 0;
  if (SableHelpDue(PetscOptionsObject)) {
    PetscCall(SableRealList(v, *n, gtext, sizeof gtext));
    SableHelpValue(dtext, (PetscBool)(ndef > 0), flg ? gtext : NULL, line, sizeof line);
    PetscCall(SableHelpLine(PetscOptionsObject, opt, line, text, unit, NULL));
  }
  if (!flg) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(SableOptionCount(opt, &count)); /* PETSc stops at the array's size without a word */
  if (exact) PetscCheck(count == cap, PetscOptionsObject->comm, PETSC_ERR_ARG_SIZ, "%s takes %d comma-separated values, got %d", opt, (int)cap, (int)count);
  else PetscCheck(count <= cap, PetscOptionsObject->comm, PETSC_ERR_ARG_SIZ, "%s takes at most %d comma-separated values, got %d", opt, (int)cap, (int)count);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SableOptionsIntArray_Private(PetscOptionItems *PetscOptionsObject, const char opt[], const char text[], const char unit[], const char range[], PetscInt v[], PetscInt ndef, PetscInt *n, PetscBool exact, PetscBool *set)
{
  const PetscInt cap = *n;
  SableRange     r   = {PETSC_NINFINITY, PETSC_INFINITY, PETSC_FALSE, PETSC_FALSE, "-inf", "inf"};
  PetscInt       got = cap, count = 0;
  PetscBool      flg        = PETSC_FALSE;
  char           dtext[512] = "", gtext[512] = "", line[1040];

  PetscFunctionBeginUser;
  if (range) PetscCall(SableRangeParse(range, &r));
  for (PetscInt i = 0; i < PetscMin(ndef, cap); i++) {
    const size_t len = strlen(dtext);
    PetscCall(PetscSNPrintf(dtext + len, sizeof dtext - len, "%s%" PetscInt_FMT, i ? "," : "", v[i]));
  }
  PetscCall(PetscOptionsGetIntArray(PetscOptionsObject->options, PetscOptionsObject->prefix, opt, v, &got, &flg));
  if (set) *set = flg;
  *n = flg ? got : 0;
  if (SableHelpDue(PetscOptionsObject)) {
    for (PetscInt i = 0; i < *n; i++) {
      const size_t len = strlen(gtext);
      PetscCall(PetscSNPrintf(gtext + len, sizeof gtext - len, "%s%" PetscInt_FMT, i ? "," : "", v[i]));
    }
    SableHelpValue(dtext, (PetscBool)(ndef > 0), flg ? gtext : NULL, line, sizeof line);
    PetscCall(SableHelpLine(PetscOptionsObject, opt, line, text, unit, range));
  }
  if (!flg) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(SableOptionCount(opt, &count)); /* PETSc stops at the array's size without a word */
  if (exact) PetscCheck(count == cap, PetscOptionsObject->comm, PETSC_ERR_ARG_SIZ, "%s takes %d comma-separated values, got %d", opt, (int)cap, (int)count);
  else PetscCheck(count <= cap, PetscOptionsObject->comm, PETSC_ERR_ARG_SIZ, "%s takes at most %d comma-separated values, got %d", opt, (int)cap, (int)count);
  for (PetscInt i = 0; i < *n; i++)
    if (!SableRangeHolds(&r, (PetscReal)v[i])) {
      PetscCall(PetscSNPrintf(gtext, sizeof gtext, "%" PetscInt_FMT, v[i]));
      PetscCall(SableRangeError(PetscOptionsObject->comm, opt, gtext, unit, range, &r));
    }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* ------------------------------------------------------------------------------------------
 * The -help printer. The text is kept in one growing buffer (plain malloc: it is filled while
 * PETSc starts, before its allocator is set up, and printed after PETSc may be gone). */
static struct {
  char     *text;
  size_t    len, cap;
  PetscBool help, decided, registered;
  PetscErrorCode (*vfprintf)(FILE *, const char[], va_list); /* PETSc's own, for the rest */
} SableHelp;

static PetscErrorCode SableHelpFinalize(void);
static void           SableHelpAtExit(void);

/* Keeps n bytes of help text; the first ones register the printing at PetscFinalize. */
static PetscErrorCode SableHelpAppend(const char *s, size_t n)
{
  PetscFunctionBeginUser;
  if (!SableHelp.registered) { /* -help intro ends the process in PetscInitialize, without PetscFinalize */
    PetscCall(PetscRegisterFinalize(SableHelpFinalize));
    PetscCheck(!atexit(SableHelpAtExit), PETSC_COMM_SELF, PETSC_ERR_SYS, "atexit() failed");
  }
  SableHelp.registered = PETSC_TRUE;
  if (SableHelp.len + n + 1 > SableHelp.cap) {
    size_t cap = PetscMax(2 * SableHelp.cap, SableHelp.len + n + 65536);
    char  *t   = (char *)realloc(SableHelp.text, cap);
    PetscCheck(t, PETSC_COMM_SELF, PETSC_ERR_MEM, "out of memory keeping the -help text (%zu bytes)", cap);
    SableHelp.text = t;
    SableHelp.cap  = cap;
  }
  memcpy(SableHelp.text + SableHelp.len, s, n);
  SableHelp.len += n;
  SableHelp.text[SableHelp.len] = 0;
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode SableHelpFinalize(void)
{
  return SableHelpFlush();
}

static void SableHelpAtExit(void)
{
  (void)SableHelpFlush();
}

/* PetscHelpPrintf's signature. Printed by the first rank of comm only, as PETSc's own. */
static PetscErrorCode SableHelpPrintf(MPI_Comm comm, const char fmt[], ...)
{
  char        small[4096], *buf = small;
  size_t      full = 0;
  va_list     ap;
  PetscMPIInt rank = 0;

  PetscFunctionBeginUser;
  if (!SableHelp.decided) { /* the first call comes after PETSc has read the options */
    PetscCall(PetscOptionsHasHelp(NULL, &SableHelp.help));
    SableHelp.decided = PETSC_TRUE;
  }
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (rank) PetscFunctionReturn(PETSC_SUCCESS);
  va_start(ap, fmt);
  PetscCall(PetscVSNPrintf(small, sizeof small, fmt, &full, ap));
  va_end(ap);
  if (full >= sizeof small) { /* a long line (a solver's list of types): format it again in full */
    buf = (char *)malloc(full + 1);
    PetscCheck(buf, PETSC_COMM_SELF, PETSC_ERR_MEM, "out of memory formatting a -help line");
    va_start(ap, fmt);
    PetscCall(PetscVSNPrintf(buf, full + 1, fmt, &full, ap));
    va_end(ap);
  }
  if (!SableHelp.help) PetscCall(PetscHelpPrintfDefault(comm, "%s", buf));
  else {
    PetscCall(SableHelpAppend(buf, strlen(buf)));
  }
  if (buf != small) free(buf);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* PetscVFPrintf's signature. PETSc prints a few help lines (the types of a solver, -ksp_type
 * <now cg : formerly cg> ...; its separators) straight to stdout: with -help, text to stdout
 * that starts an option line or a separator, or continues a kept line, is kept too. */
static PetscErrorCode SableHelpVFPrintf(FILE *fd, const char fmt[], va_list ap)
{
  char    small[4096], *buf = small;
  size_t  full = 0;
  va_list aq;

  if ((SableHelp.decided && !SableHelp.help) || (fd != stdout && fd != PETSC_STDOUT)) return SableHelp.vfprintf(fd, fmt, ap);
  va_copy(aq, ap);
  PetscCall(PetscVSNPrintf(small, sizeof small, fmt, &full, aq));
  va_end(aq);
  if (!SableHelp.decided && !strcmp(small, "----------------------------------------\n")) { /* PETSc's first help line */
    PetscCall(PetscOptionsHasHelp(NULL, &SableHelp.help));
    SableHelp.decided = PETSC_TRUE;
  }
  if (!SableHelp.help || (!(SableHelp.len && SableHelp.text[SableHelp.len - 1] != '\n') && strncmp(small, "  -", 3) && strcmp(small, "----------------------------------------\n"))) return SableHelp.vfprintf(fd, fmt, ap);
  if (full >= sizeof small) {
    buf = (char *)malloc(full + 1);
    PetscCheck(buf, PETSC_COMM_SELF, PETSC_ERR_MEM, "out of memory formatting a -help line");
    va_copy(aq, ap);
    PetscCall(PetscVSNPrintf(buf, full + 1, fmt, &full, aq));
    va_end(aq);
  }
  PetscCall(SableHelpAppend(buf, strlen(buf)));
  if (buf != small) free(buf);
  return PETSC_SUCCESS;
}

void SableHelpBegin(void)
{
  PetscHelpPrintf    = SableHelpPrintf;
  SableHelp.vfprintf = PetscVFPrintf;
  PetscVFPrintf      = SableHelpVFPrintf;
}

/* A section of the kept text: its lines, split at PETSc's separator lines. */
typedef struct {
  char    **line;
  int       n, group;
  PetscBool named; /* group set from the section's first option */
} SableHelpSection;

/* The name of the option a help line shows (no dash), or an empty string. */
static void SableHelpLineOption(const char *l, char *name, size_t size)
{
  const char *c = l;
  size_t      k = 0;

  while (*c == ' ') c++;
  if (c != l && c[0] == '-' && c[1] != '-')
    for (c++; *c && *c != ' ' && *c != ':' && *c != '<' && k + 1 < size; c++) name[k++] = *c;
  name[k] = 0;
}

/* Splits the kept text (modified: lines end at NUL) into sections, each starting at PETSc's
 * separator line (the first one at the start of the text), and sets each one's group from its
 * first option (-1: PETSc's, or none). Returns the count. */
static int SableHelpSections(char *text, SableHelpSection *sec, int max, char **lines)
{
  int ns = 0, nl = 0;

  for (char *l = text, *next; l && *l; l = next) {
    char name[128];
    next = strchr(l, '\n');
    if (next) *next++ = 0;
    if (ns == 0 || !strcmp(l, "----------------------------------------")) {
      if (ns == max) break;
      sec[ns] = (SableHelpSection){lines + nl, 0, -1, PETSC_FALSE};
      ns++;
    }
    lines[nl++] = l;
    sec[ns - 1].n++;
    SableHelpLineOption(l, name, sizeof name);
    if (name[0] && !sec[ns - 1].named) {
      sec[ns - 1].group = SableOptionGroup(name);
      sec[ns - 1].named = PETSC_TRUE;
    }
  }
  return ns;
}

/* A help line as printed: PETSc's "(None)" (no manual page) at its end left out. */
static void SableHelpPut(const char *l, const char *tail)
{
  const size_t len = strlen(l);
  const int    cut = len >= 7 && !strcmp(l + len - 7, " (None)") ? 7 : 0;
  printf("%.*s%s\n", (int)(len - cut), l, tail ? tail : "");
}

/* One kept line, in the order printed: its option's indexed family (the name with its first
 * all-digit word as %d; the first member's position, -1 for none), its index, whether the run's
 * options give it. */
typedef struct {
  char     *l;
  char      pat[128];
  long      index;
  int       family;
  PetscBool given;
} SableHelpKept;

/* The value a line shows, "<...>" after the option's name (empty when none), as a span of l. */
static void SableHelpValueSpan(const char *l, const char **b, const char **e)
{
  const char *c = strchr(l, '-'), *lt = c ? strchr(c, '<') : NULL, *gt = lt ? strchr(lt, '>') : NULL;
  *b = *e = l;
  if (gt) {
    *b = lt;
    *e = gt + 1;
  }
}

/* An indexed family (lines[f] its first member) printed once: the line of its first member the
 * run's options do not give (the default), named -prefix_<k>_suffix, with the index range; then
 * the members given, name and value, one a line. */
static void SableHelpPrintFamily(SableHelpKept *lines, int n, int f)
{
  char        tail[160], range[96] = "", name[160], *pct;
  const char *b0, *e0;
  long        lo = -1, hi = -1, count = 0, prev = -1;
  int         rep = -1, varies = 0;

  for (int i = f; i < n; i++) { /* members' indices: contiguous "a..b" or a list */
    if (lines[i].family != f) continue;
    if (rep < 0 && !lines[i].given) rep = i;
    count++;
    lo = lo < 0 || lines[i].index < lo ? lines[i].index : lo;
    hi = lines[i].index > hi ? lines[i].index : hi;
  }
  if (rep < 0) rep = f;
  SableHelpValueSpan(lines[rep].l, &b0, &e0);
  for (int i = f; i < n; i++) { /* a default that changes with the index (a seed k + 1) */
    const char *b, *e;
    if (lines[i].family != f || lines[i].given) continue;
    SableHelpValueSpan(lines[i].l, &b, &e);
    if (e - b != e0 - b0 || strncmp(b, b0, (size_t)(e - b))) varies = 1;
  }
  if (strstr(lines[rep].l, "any k >= 0")) range[0] = 0; /* an open family (the monitor's): its text says so */
  else if (hi - lo + 1 == count) snprintf(range, sizeof range, lo == hi ? "k = %ld" : "k = %ld..%ld", lo, hi);
  else
    for (long k = lo; k <= hi; k++)
      for (int i = f; i < n; i++)
        if (lines[i].family == f && lines[i].index == k && k != prev) {
          const size_t len = strlen(range);
          snprintf(range + len, sizeof range - len, "%s%ld", len ? ", " : "k = ", k);
          prev = k;
        }
  if (range[0] || varies) snprintf(tail, sizeof tail, " (%s%s)", range[0] ? range : "k", varies ? "; the default shown is the first one's, it depends on k" : "");
  else tail[0] = 0;
  /* the line with its name as a pattern: "  -dem_plane_%d_velocity <...>" -> "-dem_plane_<k>_velocity" */
  {
    const char *dash = strchr(lines[rep].l, '-'), *after = dash;
    while (*after && *after != ' ' && *after != ':' && *after != '<') after++;
    snprintf(name, sizeof name, "-%s", lines[f].pat);
    if ((pct = strstr(name, "%d"))) {
      memmove(pct + 3, pct + 2, strlen(pct + 2) + 1);
      memcpy(pct, "<k>", 3);
    }
    printf("%.*s%s", (int)(dash - lines[rep].l), lines[rep].l, name);
    SableHelpPut(after, tail);
  }
  for (int i = f; i < n; i++) { /* the members given: name and value */
    const char *b, *e, *dash = strchr(lines[i].l, '-');
    if (lines[i].family != f || !lines[i].given) continue;
    SableHelpValueSpan(lines[i].l, &b, &e);
    if (e == b) e = dash + strcspn(dash, " :");
    printf("%.*s    %.*s\n", (int)(dash - lines[i].l), lines[i].l, (int)(e - dash), dash);
  }
}

/* Whether the run's options give option name (no dash): only while PETSc's options exist. */
static PetscBool SableHelpGiven(const char *name)
{
  char      opt[160];
  PetscBool flg = PETSC_FALSE;

  if (!PetscInitializeCalled || PetscFinalizeCalled) return PETSC_FALSE;
  snprintf(opt, sizeof opt, "-%s", name);
  if (PetscOptionsHasName(NULL, NULL, opt, &flg)) return PETSC_FALSE;
  return flg;
}

/* Prints the lines in order, each indexed family once (SableHelpPrintFamily) where its first
 * member was; PETSc's families as Sable's. */
static void SableHelpPrintLines(SableHelpKept *lines, int from, int to)
{
  for (int i = from; i < to; i++) {
    if (lines[i].family < 0) SableHelpPut(lines[i].l, NULL);
    else if (lines[i].family == i) SableHelpPrintFamily(lines, to, i);
  }
}

/* Fills line[i] for the n lines of the sections in sec of the groups wanted (Sable's in prefix
 * order, or PETSc's in the order printed), starting at position at; returns the new count. */
static int SableHelpOrder(const SableHelpSection *sec, int ns, PetscBool own, SableHelpKept *line, int at)
{
  const int first = at; /* families form within one pass: a PETSc line never joins one of Sable's */

  for (int g = own ? 0 : -1; g < (own ? 9 : 0); g++)
    for (int k = 0; k < ns; k++) {
      if (sec[k].group != g) continue;
      for (int j = 0; j < sec[k].n; j++) {
        SableHelpKept *L = &line[at];
        char           name[128], index[16];
        *L = (SableHelpKept){sec[k].line[j], "", -1, -1, PETSC_FALSE};
        SableHelpLineOption(L->l, name, sizeof name);
        if (name[0]) SableIndexPattern(name, L->pat, sizeof L->pat, index, sizeof index);
        if (name[0] && index[0]) {
          L->index = atol(index);
          L->given = SableHelpGiven(name);
          for (int i = first; i < at && L->family < 0; i++)
            if (line[i].family >= 0 && !strcmp(line[i].pat, L->pat)) L->family = line[i].family;
          if (L->family < 0) L->family = at;
        }
        at++;
      }
    }
  return at;
}

PetscErrorCode SableHelpFlush(void)
{
  SableHelpSection *sec;
  SableHelpKept    *line;
  char            **lines;
  int               nlines = 1;

  if (!SableHelp.len) return PETSC_SUCCESS;
  signal(SIGPIPE, SIG_IGN); /* "-help | less" quit early: the rest is dropped, not a crash report */
  for (size_t i = 0; i < SableHelp.len; i++) nlines += SableHelp.text[i] == '\n';
  sec   = (SableHelpSection *)malloc(sizeof *sec * (size_t)(nlines + 1));
  lines = (char **)malloc(sizeof *lines * (size_t)(nlines + 1));
  line  = (SableHelpKept *)malloc(sizeof *line * (size_t)(nlines + 1));
  if (!sec || !lines || !line) fputs(SableHelp.text, stdout); /* no room to sort: as it came */
  else {
    const int ns  = SableHelpSections(SableHelp.text, sec, nlines + 1, lines);
    const int own = SableHelpOrder(sec, ns, PETSC_TRUE, line, 0);
    const int all = SableHelpOrder(sec, ns, PETSC_FALSE, line, own);
    if (own) printf("Sable's options, by prefix (-domain_, -dem_, -fluid_, -cpl_, -lb_, -io_, -mon_, -avg_, -sable_); PETSc's follow\n");
    SableHelpPrintLines(line, 0, own);
    if (own) printf("========================================\nPETSc's options:\n");
    SableHelpPrintLines(line, own, all); /* in the order PETSc printed them (all of it with -help intro) */
  }
  fflush(stdout);
  free(sec);
  free(lines);
  free(line);
  free(SableHelp.text);
  SableHelp.text = NULL;
  SableHelp.len = SableHelp.cap = 0;
  return PETSC_SUCCESS;
}
