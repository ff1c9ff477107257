#!/bin/sh
# Particles poured into a coupled run (tests/coupling/pour_coupled.opts: lognormal glass beads
# falling into still air above a closed inlet, a batch every 1 ms, 0.02 s), on 1 and 2 ranks.
# Physics: the air column is at rest and closed below, so the pressure drop across it holds the
# drag on the falling beads, and a bead slower than its terminal velocity (about 7 m/s; these
# fall at 0.5-0.7 m/s) feels less drag than its buoyant weight: at every monitor row (one after
# each batch) dp0 <= W, the buoyant weight per area of the beads present, from the monitor's
# inserted_mass. A bead that appeared as a volume flux would push its volume out of its cell
# within one fluid step: dp0 of 100 W at the first batch. The summary's weight per area is
# that of the beads poured (from the flow line's mass; a weight taken at the empty start is 0).
cd "$(dirname "$0")/../.." || exit 1
S=$(pwd)/${BIN:-bin}/sable
[ "$(id -u)" -eq 0 ] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1
W=$(mktemp -d)
trap 'rm -rf "$W"' EXIT
O="-options_file $(pwd)/tests/coupling/pour_coupled.opts -cpl_progress_interval 0"
for np in 1 2; do
  out=$(cd "$W" && mpiexec -n $np "$S" $O -io_dir np$np 2>&1); rc=$?
  # rows: dp0 against the buoyant weight per area of the mass inserted so far (area 0.02 x 0.006 m)
  awk -F, -v np=$np -v rc=$rc 'NR == 1 { for (i = 1; i <= NF; i++) { if ($i ~ /^inserted_mass/) cm = i; if ($i ~ /^dp0/) cd = i }; next }
    $cm > 0 { w = $cm * 9.81 * (1 - 1.2 / 2500) / (0.02 * 0.006); r = $cd / w; if (r > max) { max = r; at = $1 }; n++ }
    END { ok = (rc == 0 && n >= 19 && max <= 1)
      printf "%s pour_coupled np=%d dp0 / buoyant weight of the beads present: %.4f at most (t = %.3f s, %d rows; bound <= 1)\n", ok ? "PASS" : "FAIL", np, max, at, n }' "$W/np$np/sable_monitor.csv"
  col=$(printf '%s\n' "$out" | grep '^column:'); flow=$(printf '%s\n' "$out" | grep '^flow:')
  echo "$col|$flow" | awk -F'|' -v np=$np '{
    w = $1; sub(/.*weight per area /, "", w); sub(/ Pa.*/, "", w)
    m = $2; sub(/.*inserted \(/, "", m); sub(/ kg.*/, "", m)
    ref = m * 9.81 * (1 - 1.2 / 2500) / (0.02 * 0.006); e = (w - ref) / ref; if (e < 0) e = -e
    printf "%s pour_coupled np=%d summary weight per area: %s Pa (the poured %s kg: %.6g Pa, rel. error %.1e, bound < 1e-5)\n", (ref > 0 && e < 1e-5) ? "PASS" : "FAIL", np, w, m, ref, e }'
done
