/* How Sable's options are read: the readers of numeric options (SableOptionsReal,
 * SableOptionsInt, SableOptionsRealArray, SableOptionsRealN), called inside the PetscOptionsBegin
 * block of the object that owns the option, with the option's literal name. Each prints its own
 * -help line, with the true default ("<none>" when the option has none: a default outside the
 * valid range, or no default values), the value given, the unit and the valid range, and
 * refuses a value out of range with one line naming the option, the value and the range. A
 * range is written as in mathematics: "(0,1]", "[0,inf)", NULL for none. */
#include "sable.h"
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
  PetscBool      flg = PETSC_FALSE;
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
