#!/bin/sh
# Terminal velocity at Re 0.1 with the self corrections (-cpl_self_porosity -cpl_self_velocity;
# tools/grid_settle): d = 1, Schiller-Naumann, a sphere held at a cell centre on cells of 8 d in a
# column 128 d wide (periodic across) and 192 d tall, fed at the law's u_t, started steady, coupling
# step 10 tau. Stokes flow feels the box: the same run in columns 32, 64, 128 and 256 d wide reads
# -3.4, -1.3, -0.50 and -0.25%, shrinking faster than 1/L; extrapolated, 128 d leaves -0.3 to
# -0.4% of box effect (at most -0.5% for a pure 1/L tail), so the box is wide enough for the 2%
# bound (doc/validation.md, "Re 0.1 in wider columns"). References:
#   (a) the terminal slip within 2% of the law's u_t (measured -0.50%);
#   (b) without the corrections the same run is more than 2% off (+13.4%): the check discriminates.
# Cells of 4 d take 2-4 min per place and 2 d and 1 d cells 35 min to hours here: not in the suite.
# The two runs (1 rank each) run side by side: the suite runs one test at a time.
cd "$(dirname "$0")/../.." || exit 1
G=$(pwd)/${BUILD:-build}/tools/grid_settle
A="-gs_re 0.1 -gs_cell 8 -gs_width 128 -gs_height 192 -gs_hold 1 -gs_init steady -gs_step_tau 10 -cpl_drag schiller"
W=$(mktemp -d)
trap 'rm -rf "$W"' EXIT
for c in on off; do
  X=$([ $c = on ] && echo "-cpl_self_porosity -cpl_self_velocity")
  "$G" $A $X >"$W/$c" 2>&1 &
done
wait
for c in on off; do
  line=$(grep '^result:' "$W/$c")
  e=$(printf '%s\n' "$line" | tr ' ' '\n' | sed -n 's/^err=//p' | tr -d '%')
  if [ -z "$e" ]; then echo "FAIL terminal_re01: corrections $c: no result"; continue; fi
  a=$(awk -v e="$e" 'BEGIN { printf "%.3f", e < 0 ? -e : e }')
  if [ $c = on ]; then
    ok=$(awk -v e="$e" 'BEGIN { print (e < 2 && e > -2) }')
    echo "$([ "$ok" = 1 ] && echo PASS || echo FAIL) terminal_re01: Re 0.1, cells of 8 d, centre, 128 d column: |terminal slip / Schiller-Naumann's u_t - 1|: $a% (bound < 2%)"
  else
    ok=$(awk -v e="$e" 'BEGIN { print (e > 2 || e < -2) }')
    echo "$([ "$ok" = 1 ] && echo PASS || echo FAIL) terminal_re01: uncorrected, the same run: |slip / u_t - 1|: $a% (bound > 2%: the correction is what holds it)"
  fi
done
