#!/bin/sh
# Bad input stops with one clear line naming the option, the value and the valid range, and a
# non-zero exit status; nothing is run.
cd "$(dirname "$0")/.." || exit 1
S=bin/sable
OK="-domain_lo 0,0,0 -domain_hi 0.1,0.1,0.1 -dem_box 0,0,0,0.1,0.1,0.1 -dem_kn 1e4 -dem_lattice 2,2,2 -dem_radius 0.005 -dem_t_end 0.001"
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
expect "negative radius" "-dem_radius -0.005 must be > 0" $OK -dem_radius -0.005
expect "missing options file" "-options_file cases/none.opts: cannot open" -options_file cases/none.opts
expect "unknown option" "option -dem_resitution 0.5 was given but nothing reads it" $OK -dem_resitution 0.5
expect "restitution above 1" "-dem_restitution 1.5 must be in (0,1]" $OK -dem_restitution 1.5
expect "restitution zero" "-dem_restitution 0. must be in (0,1]" $OK -dem_restitution 0
expect "time step above Tc/10" "-dem_dt 0.0001 s exceeds -dem_dt_max_fraction 0.1 x the contact time" $OK -dem_dt 1e-4
expect "lattice outside the domain" "lie outside the domain box" $OK -dem_lattice 20,2,2
expect "hertz without modulus" "-dem_contact_law hertz needs -dem_youngs_modulus" $OK -dem_contact_law hertz
expect "wrong vector length" "-dem_gravity takes 3 comma-separated values, got 2" $OK -dem_gravity 0,1
# a good run for contrast: exit 0
if $S $OK >/dev/null 2>&1; then echo "PASS good input runs: exit 0"; else echo "FAIL good input runs: exit $?"; fi
