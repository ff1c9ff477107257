#!/bin/sh
# Bad input for a source's size distribution (src/dem/psd.c): one line naming the option, the
# value and the valid range, and a non-zero exit status. The options are read by test_psd in its
# options-only mode, under source 0's prefix (-dem_insert_0_psd*), with sable's own checks of the
# values given (a word for the kind, an integer for the classes) and of options nobody reads.
cd "$(dirname "$0")/../.." || exit 1
T=${BUILD:-build}/tests/dem/test_psd
P=-dem_insert_0_psd
expect() { # name, pattern the message must match, arguments...
  name=$1; pat=$2; shift 2
  out=$($T "$@" 2>&1 >/dev/null); rc=$?
  lines=$(printf '%s\n' "$out" | grep -c '^error: ')
  if [ "$rc" -ne 0 ] && [ "$lines" -eq 1 ] && printf '%s' "$out" | grep -q -- "$pat"; then
    echo "PASS bad input, $name: exit $rc, \"$(printf '%s' "$out" | grep '^error: ')\""
  else
    echo "FAIL bad input, $name: exit $rc, $lines error lines, expected /$pat/; got: $out"
  fi
}
expect "unknown kind" "$P gamma is not known; valid values: single, number, mass, normal, lognormal, uniform" $P gamma
expect "table without diameters" "$P number needs ${P}_diameters" $P number ${P}_fractions 1
expect "empty table" "${P}_diameters needs a value" $P number ${P}_diameters ${P}_fractions 1
expect "counts differ" "${P}_fractions has 1 values for the 2 diameters" $P number ${P}_diameters 1e-3,2e-3 ${P}_fractions 0.5
expect "negative diameter" "${P}_diameters: diameter 2 is -0.002 m, must be > 0" $P mass ${P}_diameters 1e-3,-2e-3 ${P}_fractions 0.5,0.5
expect "zero diameter" "${P}_diameters: diameter 1 is 0.\{0,1\} m, must be > 0" $P number ${P}_diameters 0,2e-3 ${P}_fractions 0.5,0.5
expect "negative fraction" "${P}_fractions: fraction 2 is -0.1, must be >= 0" $P number ${P}_diameters 1e-3,2e-3 ${P}_fractions 0.5,-0.1
expect "all fractions zero" "${P}_fractions: all 2 fractions are 0" $P mass ${P}_diameters 1e-3,2e-3 ${P}_fractions 0,0
expect "too many entries" "${P}_diameters takes at most 64 comma-separated values, got 65" $P number ${P}_diameters $(seq -s, 1 65) ${P}_fractions 1
expect "table cut to nothing" "${P}_min 0.003 m leaves no diameter of ${P}_diameters with a fraction > 0 inside" $P number ${P}_diameters 1e-3,2e-3 ${P}_fractions 1,1 ${P}_min 3e-3
expect "zero mean" "${P}_mean 0.\{0,1\} must be > 0 (m)" $P normal ${P}_mean 0 ${P}_std 1e-4
expect "negative mean" "${P}_mean -0.001 must be > 0 (m)" $P lognormal ${P}_mean -1e-3 ${P}_std 1e-4
expect "negative std" "${P}_std -0.0001 must be >= 0 (m)" $P lognormal ${P}_mean 1e-3 ${P}_std -1e-4
expect "normal without std" "$P normal needs ${P}_mean and ${P}_std" $P normal ${P}_mean 1e-3
expect "min above max" "${P}_min 0.002 m must be below ${P}_max 0.001 m" $P uniform ${P}_min 2e-3 ${P}_max 1e-3
expect "max below the default min" "${P}_min 0.0001 m (default) must be below ${P}_max 5e-05 m" $P normal ${P}_mean 1e-3 ${P}_std 5e-4 ${P}_max 5e-5
expect "uniform without max" "$P uniform needs ${P}_min and ${P}_max" $P uniform ${P}_min 1e-3
expect "cut-offs keep nothing of a normal" "${P}_min 0.003 m and ${P}_max 0.004 m keep a probability of .* of the normal law.*at least 1e-12" $P normal ${P}_mean 1e-3 ${P}_std 1e-4 ${P}_min 3e-3 ${P}_max 4e-3
expect "negative classes" "${P}_classes -1 must be >= 0" $P lognormal ${P}_mean 1e-3 ${P}_std 1e-4 ${P}_classes -1
expect "classes not an integer" "option ${P}_classes 2.5: '2.5' is not an integer" $P lognormal ${P}_mean 1e-3 ${P}_std 1e-4 ${P}_classes 2.5
expect "option of another kind" "${P}_std is not an option of $P uniform" $P uniform ${P}_min 1e-3 ${P}_max 2e-3 ${P}_std 1e-4
expect "typo" "did you mean ${P}_mean?" $P lognormal ${P}_mean 1e-3 ${P}_std 1e-4 ${P}_maen 2e-3
out=$($T $P lognormal ${P}_mean 1e-3 ${P}_std 4e-4 ${P}_classes 8 2>&1); rc=$?
if [ "$rc" -eq 0 ] && printf '%s' "$out" | grep -q '^psd: lognormal'; then echo "PASS good input is read: exit 0, \"$out\""; else echo "FAIL good input is read: exit $rc, $out"; fi
