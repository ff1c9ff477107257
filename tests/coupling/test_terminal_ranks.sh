#!/bin/sh
# A free sphere crossing a rank boundary with the self corrections on (-cpl_self_porosity
# -cpl_self_velocity; tools/grid_settle): d = 1, Schiller-Naumann, Re 10, cells of 4 d, a 32 d
# periodic column 48 d tall split in two along z at z = 24 on 2 ranks; the sphere starts 22 d above
# the inlet in a flow of 1.05 u_t and rises through the boundary. References:
#   (a) its terminal slip within 2% of the law's u_t on 1 and on 2 ranks;
#   (b) the 2-rank slip equal to the 1-rank one to the 6 printed digits (a rank count);
#   (c) the path crosses z = 24 (its lowest point below, its highest above).
cd "$(dirname "$0")/../.." || exit 1
[ "$(id -u)" -eq 0 ] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
G=$(pwd)/${BUILD:-build}/tools/grid_settle
A="-gs_re 10 -gs_cell 4 -gs_hold 0 -gs_inflow 1.05 -gs_below 22 -cpl_drag schiller -cpl_self_porosity -cpl_self_velocity"
r1=$("$G" $A 2>&1 | grep '^result:')
r2=$(mpiexec -n 2 "$G" $A -da_processors_z 2 2>&1 | grep '^result:')
val() { printf '%s\n' "$1" | tr ' ' '\n' | sed -n "s/^$2=//p"; }
for r in 1 2; do
  line=$([ $r -eq 1 ] && echo "$r1" || echo "$r2")
  if [ -z "$line" ]; then echo "FAIL terminal_ranks: the $r-rank run printed no result"; continue; fi
  e=$(val "$line" err | tr -d '%')
  if awk -v e="$e" 'BEGIN { exit !(e < 2 && e > -2) }'; then
    echo "PASS terminal_ranks: $r rank(s), |terminal slip / u_t - 1|: ${e#-}% (bound < 2%)"
  else
    echo "FAIL terminal_ranks: $r rank(s), |terminal slip / u_t - 1|: $e% (bound < 2%)"
  fi
done
s1=$(val "$r1" slip); s2=$(val "$r2" slip); z=$(val "$r2" z)
if [ -n "$s1" ] && [ "$s1" = "$s2" ]; then
  echo "PASS terminal_ranks: the 2-rank slip equals the 1-rank one to 6 digits ($s2)"
else
  echo "FAIL terminal_ranks: slips $s1 (1 rank) and $s2 (2 ranks)"
fi
if awk -v z="$z" 'BEGIN { split(z, a, "\\.\\."); exit !(a[1] < 24 && a[2] > 24) }'; then
  echo "PASS terminal_ranks: the path crosses the rank boundary at z = 24 (z = $z)"
else
  echo "FAIL terminal_ranks: the path z = $z does not cross z = 24"
fi
