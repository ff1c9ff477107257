#!/bin/sh
# The test suite. Tests live in tests/<folder>/, one folder per part of src/ (geom, dem, fluid,
# coupling, balance, io) and drivers/ for the program as a whole; tests/common/ holds the shared
# harness (not tests). Every tests/<folder>/*.c is a self-checking executable, built as
# $BUILD/tests/<folder>/<name>, that prints one line per check (tests/common/check.h),
#   PASS <check>: <measured> (reference <r>, bound <b>)   or   FAIL <check>: ...
# and may print NOTE lines: a figure reported against a known limitation, not counted.
# A line "/* ranks: 1 2 4 */" in its source runs it on each of those rank counts (default 1).
# Every tests/<folder>/*.sh is a shell test printing the same kind of lines.
# A test's label is <folder>/<name> (e.g. dem/test_verlet, dem/test_parallel[np=2]);
# ONLY=<substring> runs the tests whose label holds it (ONLY=verlet, ONLY=coupling/).
# TIER=check runs only the tests named in tests/check.list (`make check`, the quick tier a kernel
# change runs first; a name there that is no test is one failure), a C test on its rank counts up
# to 2; no TIER: the whole suite.
# TIMES=1 adds a line "TIME <label>: <seconds> s" after each test (not counted).
# A test that exits non-zero without printing a FAIL line counts as one failure; a test still
# running after TEST_TIMEOUT seconds (default 900) is stopped and counts as one failure.
# Last line: "N passed, N failed"; exit status non-zero when anything failed.
set -u
cd "$(dirname "$0")/.."
BUILD=${BUILD:-build}
BIN=${BIN:-bin} # the driver the shell tests run (make DEBUG=1 test: build-debug/bin)
export BUILD BIN
[ "$(id -u)" -eq 0 ] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1
LOG=$(mktemp -d)
trap 'rm -rf "$LOG"' EXIT
pass=0; fail=0
ONLY=${ONLY:-}
TIER=${TIER:-}
TIMES=${TIMES:-0}
TEST_TIMEOUT=${TEST_TIMEOUT:-900}
if [ -n "$TIER" ]; then # the tier's labels, one a line, without comments and blank lines
  [ -f "tests/$TIER.list" ] || { echo "FAIL tests/run.sh: TIER=$TIER: no tests/$TIER.list"; echo "0 passed, 1 failed"; exit 1; }
  sed 's/#.*//; s/[[:space:]]*$//; /^$/d' "tests/$TIER.list" >"$LOG/tier"
  for name in $(cat "$LOG/tier"); do
    [ -f "tests/$name.c" ] || [ -f "tests/$name.sh" ] || { echo "FAIL tests/$TIER.list: names $name, no such test"; fail=$((fail + 1)); }
  done
fi
selected() { # label without [np=..]: in ONLY and in the tier
  case "$1" in common/*) return 1 ;; esac
  case "$1" in *$ONLY*) ;; *) return 1 ;; esac
  [ -z "$TIER" ] || grep -qx "$1" "$LOG/tier"
}

run_one() { # label, command...
  label=$1; shift
  out="$LOG/out"
  t0=$(date +%s.%N)
  timeout -k 10 "$TEST_TIMEOUT" "$@" >"$out" 2>"$LOG/err"
  rc=$?
  timedout=0 # timeout's TERM (124) or, when the test ignored it, KILL 10 s later (137)
  { [ "$rc" -eq 124 ] || [ "$rc" -eq 137 ]; } && timedout=1 && echo "timed out after $TEST_TIMEOUT s (TEST_TIMEOUT)" >>"$out"
  grep -E '^(PASS|FAIL|NOTE) ' "$out" | sed "s#^\(PASS\|FAIL\|NOTE\) #\1 $label #" # a label holds a /
  np=$(grep -c '^PASS ' "$out"); nf=$(grep -c '^FAIL ' "$out")
  if [ "$rc" -ne 0 ] && { [ "$nf" -eq 0 ] || [ "$timedout" -eq 1 ]; }; then
    echo "FAIL $label: exit status $rc; last lines:"; tail -n 5 "$out" "$LOG/err" | sed 's/^/    /'
    nf=$((nf + 1))
  fi
  [ "$np" -eq 0 ] && [ "$nf" -eq 0 ] && { echo "FAIL $label: printed no check"; nf=1; }
  pass=$((pass + np)); fail=$((fail + nf))
  [ "$TIMES" = 1 ] && echo "TIME $label: $(echo "$t0 $(date +%s.%N)" | awk '{printf "%.1f", $2 - $1}') s"
  return 0
}

for src in tests/*/*.c; do
  name=${src#tests/}; name=${name%.c} # <folder>/<name>
  selected "$name" || continue
  ranks=$(sed -n 's|^/\* ranks: \(.*\) \*/$|\1|p' "$src" | head -n 1)
  for n in ${ranks:-1}; do
    # the quick tier stops at 2 ranks (4 ranks on 2 cores: oversubscribed, slow); the suite runs all
    [ "$TIER" = check ] && [ "$n" -gt 2 ] && continue
    if [ "$n" -eq 1 ]; then run_one "$name" "$BUILD/tests/$name"
    else run_one "$name[np=$n]" mpiexec -n "$n" "$BUILD/tests/$name"; fi
  done
done
for t in tests/*/*.sh; do
  name=${t#tests/}; name=${name%.sh}
  selected "$name" || continue
  run_one "$name" sh "$t"
done
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
