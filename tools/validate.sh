#!/bin/sh
# make validate: the measured beds at full length, each against its record (tools/bed_record),
# with the wall time each took. NP ranks (default 2); OUT (default out/validate) holds each run's
# log, monitor, frames and the plot of its record. ONLY=<case> runs one of them.
cd "$(dirname "$0")/.." || exit 1
ROOT=$(pwd)
NP=${NP:-2}
OUT=${OUT:-$ROOT/out/validate}
[ "$(id -u)" -eq 0 ] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
mkdir -p "$OUT"
total0=$(date +%s)
status=0
# case directory, options file, extra options
for spec in "wachem_bed wachem.opts" "muller_bed muller_u09.opts" "muller_bed muller_u06.opts"; do
  set -- $spec
  case=$1; opts=$2; name=${opts%.opts}
  [ -n "$ONLY" ] && [ "$ONLY" != "$case" ] && [ "$ONLY" != "$name" ] && continue
  [ -f "cases/$case/$opts" ] || continue
  d=$OUT/$name
  rm -rf "$d"; mkdir -p "$d"
  t0=$(date +%s)
  if ! mpiexec -n "$NP" "$ROOT/bin/sable" -options_file "$ROOT/cases/$case/$opts" -io_dir "$d" >"$d/log" 2>&1; then
    echo "validate: $name: the run stopped: $(grep 'error' "$d/log" | head -n 1)"
    status=1
    continue
  fi
  t1=$(date +%s)
  echo "validate: $name: $((t1 - t0)) s of wall time on $NP ranks ($(sed -n 's/^done: //p' "$d/log"))"
  tools/bed_record "cases/$case/record/$name.txt" "$d" --plot "$d/record.png" || status=1
done
echo "validate: done in $(($(date +%s) - total0)) s"
exit $status
