#!/bin/sh
# Bad input for rolling resistance: one clear line naming the option, the value and the valid
# range, a non-zero exit status, nothing run; and the good input runs.
cd "$(dirname "$0")/../.." || exit 1
S=${BIN:-bin}/sable
OK="-domain_lo 0,0,0 -domain_hi 0.1,0.1,0.1 -dem_box 0,0,0,0.1,0.1,0.1 -dem_kn 1e4 -dem_lattice 2,2,2 -dem_t_end 0.001"
expect() { # name, pattern the message must match, arguments...
  name=$1; pat=$2; shift 2
  out=$($S "$@" 2>&1 >/dev/null); rc=$?
  lines=$(printf '%s\n' "$out" | grep -c 'sable: error')
  if [ "$rc" -ne 0 ] && [ "$lines" -eq 1 ] && printf '%s' "$out" | grep -q -- "$pat"; then
    echo "PASS bad input, $name: exit $rc, \"$(printf '%s' "$out" | grep 'sable: error')\""
  else
    echo "FAIL bad input, $name: exit $rc, $lines error lines, expected /$pat/; got: $out"
  fi
}
expect "unknown model" "-dem_rolling_model foo is not known; valid values: none, constant, viscous, kms" $OK -dem_rolling_model foo -dem_rolling_friction 0.1
expect "model without coefficient" "-dem_rolling_model constant needs -dem_rolling_friction" $OK -dem_rolling_model constant
expect "coefficient without model" "-dem_rolling_friction is ignored by -dem_rolling_model none" $OK -dem_rolling_friction 0.1
expect "wall coefficient without model" "-dem_wall_rolling_friction is ignored by -dem_rolling_model none" $OK -dem_wall_rolling_friction 0.1
expect "negative coefficient" "-dem_rolling_friction -0.1 must be >= 0" $OK -dem_rolling_model constant -dem_rolling_friction -0.1
expect "negative wall coefficient" "-dem_wall_rolling_friction -0.2 must be >= 0" $OK -dem_rolling_model viscous -dem_rolling_friction 0.1 -dem_wall_rolling_friction -0.2
expect "convex shapes" "-dem_rolling_model constant applies to spheres; convex shapes (-dem_shape) take none" $OK -dem_shape cube -dem_shape_size 0.01 -dem_rolling_model constant -dem_rolling_friction 0.1
for m in constant viscous kms; do
  if $S $OK -dem_rolling_model $m -dem_rolling_friction 0.1 -dem_wall_rolling_friction 0.05 >/dev/null 2>&1; then echo "PASS good rolling input runs ($m): exit 0"; else echo "FAIL good rolling input runs ($m): exit $?"; fi
done
