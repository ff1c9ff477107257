/* The checks of the test executables. A check takes the measured value, its reference and its
 * bound, makes the comparison itself and prints one line on rank 0 with the same numbers,
 *   PASS <name>: <measured> (reference <r>, relative error <e>, bound < <b>)   or   FAIL ...
 * so the bound printed is the bound compared against, and counts failures in check_failures
 * (main returns check_failures ? 1 : 0; tests/run.sh counts the lines). The comparisons:
 *   CheckClose     |m - r| / |r| <  b        CheckCloseAbs  |m - r| <  b
 *   CheckBelow     m <  b                    CheckAtMost    m <= b
 *   CheckAbove     m >  b                    CheckAtLeast   m >= b
 *   CheckEqual     m == r (integers)         CheckEqualReal m == r (bitwise: roundoff-free results)
 *   CheckTrue      a condition with a line saying what was seen (messages, found/not found)
 * A NaN fails every comparison. Names are fixed text or CheckName("...%s...", ...); a figure that
 * is reported but not compared goes after the bound through CheckDetail(), which the next check
 * prints and clears. */
#pragma once
#include "sable.h" /* PETSc, and PETSC_SUCCESS on 3.18 */

static int  check_failures = 0;
static char check_detail[512];

/* printf-style name for one check call: a ring of buffers, so a few may be alive at once. */
static inline const char *CheckName(const char *fmt, ...)
{
  static char buf[4][512];
  static int  next = 0;
  char       *s    = buf[next];
  va_list     ap;

  next = (next + 1) % 4;
  va_start(ap, fmt);
  vsnprintf(s, sizeof buf[0], fmt, ap);
  va_end(ap);
  return s;
}

/* A figure printed after the next check's bound, not compared. */
static inline void CheckDetail(const char *fmt, ...)
{
  va_list ap;

  va_start(ap, fmt);
  vsnprintf(check_detail, sizeof check_detail, fmt, ap);
  va_end(ap);
}

/* The line of one check: "<PASS|FAIL> <name>: <what>[; <detail>]". */
static inline PetscErrorCode CheckReport(PetscBool ok, const char *name, const char *what)
{
  PetscFunctionBeginUser;
  if (!ok) check_failures++;
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "%s %s: %s%s%s\n", ok ? "PASS" : "FAIL", name, what, check_detail[0] ? "; " : "", check_detail));
  check_detail[0] = 0;
  PetscFunctionReturn(PETSC_SUCCESS);
}

static inline PetscErrorCode CheckTrue(const char *name, PetscBool ok, const char *seen)
{
  PetscFunctionBeginUser;
  PetscCall(CheckReport(ok, name, seen ? seen : (ok ? "yes" : "no")));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* relation: "<", "<=", ">" or ">=" */
static inline PetscErrorCode CheckCompare(const char *name, PetscReal m, const char *relation, PetscReal b)
{
  char      what[128];
  PetscBool ok;

  PetscFunctionBeginUser;
  if (relation[0] == '<') ok = (PetscBool)(relation[1] ? m <= b : m < b);
  else ok = (PetscBool)(relation[1] ? m >= b : m > b);
  snprintf(what, sizeof what, "%.6g (bound %s %g)", (double)m, relation, (double)b);
  PetscCall(CheckReport(ok, name, what));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static inline PetscErrorCode CheckBelow(const char *name, PetscReal measured, PetscReal bound)
{
  PetscFunctionBeginUser;
  PetscCall(CheckCompare(name, measured, "<", bound));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static inline PetscErrorCode CheckAtMost(const char *name, PetscReal measured, PetscReal bound)
{
  PetscFunctionBeginUser;
  PetscCall(CheckCompare(name, measured, "<=", bound));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static inline PetscErrorCode CheckAbove(const char *name, PetscReal measured, PetscReal bound)
{
  PetscFunctionBeginUser;
  PetscCall(CheckCompare(name, measured, ">", bound));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static inline PetscErrorCode CheckAtLeast(const char *name, PetscReal measured, PetscReal bound)
{
  PetscFunctionBeginUser;
  PetscCall(CheckCompare(name, measured, ">=", bound));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* |measured - reference| / |reference| < bound */
static inline PetscErrorCode CheckClose(const char *name, PetscReal measured, PetscReal reference, PetscReal bound)
{
  const PetscReal e = PetscAbsReal(measured - reference) / PetscAbsReal(reference);
  char            what[192];

  PetscFunctionBeginUser;
  snprintf(what, sizeof what, "%.8g (reference %.8g, relative error %.2e, bound < %g)", (double)measured, (double)reference, (double)e, (double)bound);
  PetscCall(CheckReport((PetscBool)(e < bound), name, what));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* |measured - reference| < bound */
static inline PetscErrorCode CheckCloseAbs(const char *name, PetscReal measured, PetscReal reference, PetscReal bound)
{
  const PetscReal e = PetscAbsReal(measured - reference);
  char            what[192];

  PetscFunctionBeginUser;
  snprintf(what, sizeof what, "%.10g (reference %.10g, error %.2e, bound < %g)", (double)measured, (double)reference, (double)e, (double)bound);
  PetscCall(CheckReport((PetscBool)(e < bound), name, what));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static inline PetscErrorCode CheckEqual(const char *name, PetscInt measured, PetscInt reference)
{
  char what[96];

  PetscFunctionBeginUser;
  snprintf(what, sizeof what, "%" PetscInt_FMT " (reference %" PetscInt_FMT ", equal)", measured, reference);
  PetscCall(CheckReport((PetscBool)(measured == reference), name, what));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static inline PetscErrorCode CheckEqualReal(const char *name, PetscReal measured, PetscReal reference)
{
  char what[96];

  PetscFunctionBeginUser;
  snprintf(what, sizeof what, "%.17g (reference %.17g, bitwise equal)", (double)measured, (double)reference);
  PetscCall(CheckReport((PetscBool)(measured == reference), name, what));
  PetscFunctionReturn(PETSC_SUCCESS);
}
