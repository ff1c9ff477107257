#!/bin/sh
# Particles leaving a coupled run through the fluid's outlet face (tests/coupling/
# outlet_blowout.opts: an inlet velocity well above the terminal velocity carries every sphere
# up to the outlet face z = 24). With -cpl_outlet_remove, on 1 and 2 ranks, with the balance
# checked every DEM step (-dem_check_every 1): the run ends normally, every one of the 128
# spheres is removed at that face, the removed mass is 128 x rho_p pi d^3 / 6 (to the printed
# digits) and the summary's balance initial + inserted - removed - present is 0.
# Checks that can fail: without -cpl_outlet_remove the first sphere to cross the face stops the
# run (one error line: it left the domain); -cpl_outlet_remove with no fluid outlet face is
# refused in one line.
cd "$(dirname "$0")/../.." || exit 1
S=$(pwd)/${BIN:-bin}/sable
[ "$(id -u)" -eq 0 ] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1
W=$(mktemp -d)
trap 'rm -rf "$W"' EXIT
O="-options_file $(pwd)/tests/coupling/outlet_blowout.opts -io_interval 0 -cpl_progress_interval 0 -dem_check_every 1 -cpl_t_end 8"
for np in 1 2; do
  out=$(cd "$W" && mpiexec -n $np "$S" $O -cpl_outlet_remove -io_dir np$np 2>&1); rc=$?
  flow=$(printf '%s\n' "$out" | grep '^flow:'); face=$(printf '%s\n' "$out" | grep '^outlet -cpl_outlet_remove zhi:')
  echo "$rc|$flow|$face" | awk -F'|' -v np=$np '{
    n = split($2, w, " "); removed = w[10]; mass = w[12]; gsub(/[()]/, "", mass); present = w[15]; bal = w[n]
    split($3, v, " "); at = v[4]
    ref = 128 * 2 * 3.14159265358979 / 6; e = (mass - ref) / ref; if (e < 0) e = -e
    ok = ($1 == 0 && removed == 128 && at == 128 && present == 0 && bal == "0" && e < 1e-5)
    printf "%s outlet_coupled np=%d: exit %d, %s removed (%s at the outlet face zhi), mass %s kg (reference %.6g, rel. error %.1e, bound < 1e-5), %s present, balance %s\n", ok ? "PASS" : "FAIL", np, $1, removed, at, mass, ref, e, present, bal }'
done
out=$(cd "$W" && "$S" $O -io_dir none 2>&1 >/dev/null); rc=$?
lines=$(printf '%s\n' "$out" | grep -c 'sable: error')
if [ "$rc" -ne 0 ] && [ "$lines" -eq 1 ] && printf '%s' "$out" | grep -q "left the domain across its upper z side"; then
  echo "PASS outlet_coupled without -cpl_outlet_remove the run stops: exit $rc, \"$(printf '%s' "$out" | grep 'sable: error' | cut -c1-150)\""
else
  echo "FAIL outlet_coupled without -cpl_outlet_remove the run stops: exit $rc, $lines error lines: $(printf '%s' "$out" | head -n 3)"
fi
out=$(cd "$W" && "$S" $O -cpl_outlet_remove -fluid_bc_zhi wall -io_dir none2 2>&1 >/dev/null); rc=$?
lines=$(printf '%s\n' "$out" | grep -c 'sable: error')
if [ "$rc" -ne 0 ] && [ "$lines" -eq 1 ] && printf '%s' "$out" | grep -q -- "-cpl_outlet_remove: the fluid has no outlet face"; then
  echo "PASS outlet_coupled bad input, no fluid outlet: exit $rc, \"$(printf '%s' "$out" | grep 'sable: error')\""
else
  echo "FAIL outlet_coupled bad input, no fluid outlet: exit $rc, $lines error lines: $(printf '%s' "$out" | head -n 3)"
fi
