#!/bin/sh
# tools/balance-sim on a small settled bed (the make-run case, 1,200 spheres settled for 0.3 s),
# 5 mm cells, minimum width 2 cells: every row of its table must be sane, 1 <= optimised
# L_max/L_avg <= marginal's and uniform's, L_min/L_avg <= 1, S = P L_avg / L_max <= P; the 1x1x4
# column grid is balanced to within 10% (about 29 loaded planes, each ~3.5% of the load).
cd "$(dirname "$0")/../.." || exit 1
D=$(mktemp -d); trap 'rm -rf "$D"' EXIT
${BIN:-bin}/sable -options_file cases/settle/quick.opts -dem_t_end 0.3 -dem_progress_interval 1 -io_interval 0.3 -io_dir "$D" > "$D/log" 2>&1 || { echo "FAIL balance-sim: settle run exit $?"; tail -3 "$D/log"; exit 1; }
frame=$(ls "$D"/*.h5 | tail -n 1)
BUILD=${BUILD:-build} tools/balance-sim -bsim_frame "$frame" -domain_lo 0,0,0 -domain_hi 0.1449,0.1449,0.24633 -bsim_cell 0.005 -bsim_minw 2 -bsim_ranks 8,64 -bsim_grid 1,1,4 > "$D/table" 2>&1 || { echo "FAIL balance-sim: exit $?"; tail -5 "$D/table"; exit 1; }
awk -F'|' -v col=1.10 '/^\| [0-9]/ {
  P = $2 + 0; grid = $3; gsub(/ /, "", grid)
  um = $4 + 0; mm = $7 + 0; om = $10 + 0; on = $11 + 0; os = $12 + 0
  ok = (om >= 1 - 1e-9 && om <= um + 1e-9 && om <= mm + 1e-9 && on <= 1 + 1e-9 && os <= P + 0.05)
  printf "%s balance-sim %d ranks (%s): optimised L_max/L_avg %.3f (bounds >= 1, <= uniform %.3f, <= marginal %.3f), L_min/L_avg %.3f (<= 1), S %.1f (<= %d)\n", ok ? "PASS" : "FAIL", P, grid, om, um, mm, on, os, P
  if (grid == "1x1x4") printf "%s balance-sim column 1x1x4: optimised L_max/L_avg %.3f (bound %.2f), uniform %.3f\n", om <= col ? "PASS" : "FAIL", om, col, um
  rows++
}
END { if (rows != 3) print "FAIL balance-sim: " rows + 0 " table rows (expected 3)" }' "$D/table"
