#!/bin/sh
# Particle sources (-dem_insert_<k>_*), against the values set and the geometry:
# - rate: 2000 particles/s between start and stop, batches every P = 5 ms: at every frame (every
#   2.5 ms) the count N(t) lies within [rate t - 1, rate t + rate P] (a batch holds what is due by
#   the end of its window); a total count is exact; a total mass M by a mass rate ends within
#   [M, M + m_p) (the last particle passes it by less than its mass);
# - placement: a box region already holding a sparse lattice that straddles the boundary between
#   the ranks, no gravity: right after the batch no new particle overlaps another or a wall by
#   more than 1e-9 d, and the inserted set (ids, positions, velocities, radii) is bitwise the
#   same on 1, 2 and 4 ranks;
# - shortfall: a total of 100 in a region that holds fewer (its random close packing holds 78):
#   the first batch places fewer, the summary reports the rest, one note says so, and the
#   carried particles are all placed once the first ones have fallen away (no warning);
# - restart: a run with an active source stopped at T/2 and continued ends bitwise as the
#   uninterrupted run, on 1 and 2 ranks, and continued on 1 rank it holds the rate's count;
# - a pour of 21 batches with -dem_deterministic: the same set on 1, 2 and 4 ranks, bitwise;
# - bad input (a region outside the domain, a rate that cannot fit, start after stop, no rate and
#   no total, a negative rate, count or mass) stops with one line naming the option, on 1 and 2 ranks.
cd "$(dirname "$0")/../.." || exit 1
S=$(pwd)/${BIN:-bin}/sable
C=$(pwd)/tests/common/sources_check.py
[ "$(id -u)" -eq 0 ] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1
W=$(mktemp -d)
trap 'rm -rf "$W"' EXIT
BOX="0,0,0 0.1,0.1,0.2"
SCENE="-domain_lo 0,0,0 -domain_hi 0.1,0.1,0.2 -dem_box 0,0,0,0.1,0.1,0.2 -dem_radius 0.005 -dem_density 2500 -dem_kn 1e4 -dem_dt 2e-5 -dem_progress_interval 0 -da_processors_x 1 -da_processors_y 1"
POUR="-dem_insert_0_region box -dem_insert_0_box 0.01,0.01,0.12,0.09,0.09,0.19 -dem_insert_0_period 0.005 -dem_insert_0_velocity 0,0,-0.5 -dem_insert_0_velocity_spread 0.1"
run() { # np, dir, args...
  rnp=$1; rd=$2; shift 2
  mkdir -p "$rd"
  (cd "$rd" && mpiexec -n "$rnp" "$S" $SCENE -da_processors_z "$rnp" -io_dir out "$@" >log 2>&1)
}
last() { ls "$1"/out/sable_*.h5 2>/dev/null | tail -n 1; }
ok() { awk "BEGIN { exit !($1) }"; }

# rates and totals
run 1 "$W/rate" $POUR -dem_insert_0_rate 2000 -dem_insert_0_start 0.02 -dem_insert_0_stop 0.15 -dem_t_end 0.2 -io_interval 0.0025
set -- $($C rate "$W/rate/out" 2000 0.02 0.15)
if [ $# -eq 3 ] && ok "$1 <= 1 && $2 <= 2000 * 0.005 + 1e-6 && $3 >= 80"; then
  echo "PASS sources rate: N(t) against 2000/s x (t - 0.02 s), start 0.02 s, stop 0.15 s, at $3 frames: lag $1, lead $2 (bounds 1, rate x period = 10)"
else echo "FAIL sources rate: lag, lead, frames = $* (bounds 1, 10, >= 80); $(grep error "$W/rate/log" | head -n 1)"; fi
run 1 "$W/count" $POUR -dem_insert_0_rate 2000 -dem_insert_0_count 150 -dem_t_end 0.2 -io_interval 0.2
n=$($C count "$(last "$W/count")")
if [ "$n" = 150 ]; then echo "PASS sources total count: $n particles (set 150)"; else echo "FAIL sources total count: $n particles, set 150"; fi
run 1 "$W/mass" $POUR -dem_insert_0_mass_rate 1 -dem_insert_0_mass 0.1 -dem_t_end 0.2 -io_interval 0.2
n=$($C count "$(last "$W/mass")")
mp=$(awk 'BEGIN { printf "%.17g", 2500 * 4 / 3 * atan2(0, -1) * 0.005 ^ 3 }')
if [ -n "$n" ] && ok "$n * $mp >= 0.1 && $n * $mp - 0.1 < $mp"; then
  echo "PASS sources total mass: $n particles of $mp kg = $(awk "BEGIN { print $n * $mp }") kg (set 0.1 kg, bound [0.1, 0.1 + m_p))"
else echo "FAIL sources total mass: $n particles of $mp kg, set 0.1 kg"; fi

# placement into a region holding particles on both sides of the ranks' boundary (z = 0.1, 0.05, 0.15)
FILL="-dem_gravity 0,0,0 -dem_lattice 4,4,3 -dem_lattice_spacing 0.025 -dem_lattice_origin 0,0,0.06 -dem_insert_0_region box -dem_insert_0_box 0,0,0.06,0.1,0.1,0.14 -dem_insert_0_count 300 -dem_insert_0_velocity_spread 0.2 -dem_t_end 2e-5 -io_interval 2e-5"
for np in 1 2 4; do
  run $np "$W/fill$np" $FILL
  set -- $($C overlap "$W/fill$np/out/sable_000001.h5" "$W/fill$np/out/sable_000000.h5" $BOX)
  if [ $# -eq 3 ] && ok "$1 > 0 && $2 <= 1e-9 && $3 <= 1e-9"; then
    echo "PASS sources placement np=$np: $1 particles placed among 48 at rest, largest overlap / d with a particle $2, with a wall $3 (bound 1e-9)"
  else echo "FAIL sources placement np=$np: placed, overlaps = $* (bound 1e-9); $(grep error "$W/fill$np/log" | head -n 1)"; fi
done
for np in 2 4; do
  set -- $($C same "$W/fill1/out/sable_000001.h5" "$W/fill$np/out/sable_000001.h5")
  if [ "$1" = 0 ] && [ "$2" = 0 ]; then echo "PASS sources same set np=$np: every id of the 1-rank run, with bitwise the same position, velocity and radius"
  else echo "FAIL sources same set np=$np: $1 ids in one run only, $2 particles differing"; fi
done

# a pour over many batches, with -dem_deterministic (bitwise the same run on any rank count): the
# whole set at 0.1 s is the same on 2 and 4 ranks as on 1
for np in 1 2 4; do run $np "$W/det$np" $POUR -dem_insert_0_rate 2000 -dem_deterministic -dem_t_end 0.1 -io_interval 0.1; done
for np in 2 4; do
  set -- $($C same "$(last "$W/det1")" "$(last "$W/det$np")")
  n=$($C count "$(last "$W/det1")")
  if [ "$1" = 0 ] && [ "$2" = 0 ] && [ "$n" = 210 ]; then echo "PASS sources same pour np=$np: the $n particles of 21 batches at 0.1 s (set: 2000/s x (0.1 s + 5 ms)), bitwise as on 1 rank"
  else echo "FAIL sources same pour np=$np: $n particles (expected 210), $1 ids in one run only, $2 particles differing"; fi
done

# shortfall
SHORT="-dem_insert_0_region box -dem_insert_0_box 0.03,0.03,0.15,0.07,0.07,0.19 -dem_insert_0_count 100 -dem_insert_0_period 0.01"
run 1 "$W/short1" $SHORT -dem_t_end 2e-5 -io_interval 2e-5
n=$($C count "$W/short1/out/sable_000001.h5")
rep=$(sed -n 's/.*; shortfall \([0-9]*\) particles.*/\1/p' "$W/short1/log")
note=$(grep -c "^source -dem_insert_0: t = .*: placed $n of the 100 particles due .* the other $rep are carried" "$W/short1/log")
if [ -n "$n" ] && [ -n "$rep" ] && [ "$n" -lt 78 ] && [ $((n + rep)) -eq 100 ] && [ "$note" -eq 1 ]; then
  echo "PASS sources shortfall: the first batch placed $n of 100 (random close packing of the region holds 78), $rep reported carried, the note says the same"
else echo "FAIL sources shortfall: placed $n, reported $rep (expected a sum of 100, placed < 78, and one note saying so); $(grep 'source -dem' "$W/short1/log")"; fi
run 1 "$W/short2" $SHORT -dem_t_end 0.5 -io_interval 0.5
n=$($C count "$(last "$W/short2")")
if [ "$n" = 100 ] && grep -q 'shortfall 0 particles' "$W/short2/log" && ! grep -q '^warning' "$W/short2/log"; then echo "PASS sources shortfall carried: all 100 placed by t = 0.5 s, shortfall 0 reported, no warning"
else echo "FAIL sources shortfall carried: $n of 100 by t = 0.5 s; $(grep 'source -dem' "$W/short2/log")"; fi

# restart with an active source
for np in 1 2; do
  d=$W/restart$np
  run $np "$d/full" $POUR -dem_insert_0_rate 2000 -dem_t_end 0.1 -io_interval 0.1
  run $np "$d/half" $POUR -dem_insert_0_rate 2000 -dem_t_end 0.0503 -io_interval 0 -io_checkpoint_interval 0.0503
  ck=$(sed -n 's/^checkpoint: //p' "$d/half/log" | tail -n 1)
  run $np "$d/rest" $POUR -dem_insert_0_rate 2000 -dem_t_end 0.1 -io_interval 0.1 -restart "../half/$ck"
  a=$(last "$d/full"); b=$(last "$d/rest")
  if [ -z "$ck" ] || [ -z "$a" ] || [ -z "$b" ]; then echo "FAIL sources restart np=$np: a run failed; $(cat "$d"/*/log | grep error | head -n 2)"; continue; fi
  set -- $(tests/common/frames_equal.py "$a" "$b")
  if [ "$1" -gt 0 ] && [ "$2" -eq 0 ]; then echo "PASS sources restart np=$np: final frames at t = 0.1 s bitwise equal, $1 datasets compared, 0 differing (restart at 0.0503 s, mid-window)"
  else echo "FAIL sources restart np=$np: $1 datasets compared, $2 differing: $3 $4 $5"; fi
done

# a checkpoint with an active source continued on another rank count (2 -> 1): the count at the
# end is the rate's, floor(2000 x (0.1 s + 5 ms)) = 210, every id once (the remap's check)
run 1 "$W/remap" $POUR -dem_insert_0_rate 2000 -dem_t_end 0.1 -io_interval 0.1 -restart "../restart2/half/$(sed -n 's/^checkpoint: //p' "$W/restart2/half/log" | tail -n 1)"
n=$($C count "$(last "$W/remap")")
if [ "$n" = 210 ] && grep -q '^restart: the particles of the checkpoint.s 2 rank' "$W/remap/log"; then echo "PASS sources restart 2 -> 1 ranks: $n particles at 0.1 s (set: 210)"
else echo "FAIL sources restart 2 -> 1 ranks: $n particles at 0.1 s (set: 210); $(grep error "$W/remap/log" | head -n 1)"; fi

# bad input
# (1 rank without mpiexec: mpiexec lingers 2 s after any non-zero exit)
bad() { # name, expected pattern, args...
  name=$1; pat=$2; shift 2
  for np in 1 2; do
    L=$([ $np -gt 1 ] && echo "mpiexec -n $np")
    out=$(cd "$W" && $L "$S" $SCENE -io_interval 0 -dem_t_end 0.01 "$@" 2>&1 >/dev/null); rc=$?
    lines=$(printf '%s\n' "$out" | grep -c 'sable: error')
    if [ "$rc" -ne 0 ] && [ "$lines" -eq 1 ] && printf '%s' "$out" | grep -q -- "$pat"; then
      echo "PASS sources bad input, $name np=$np: exit $rc, \"$(printf '%s' "$out" | grep 'sable: error')\""
    else echo "FAIL sources bad input, $name np=$np: exit $rc, $lines error lines, expected /$pat/; got: $out"; fi
  done
}
R="-dem_insert_0_region box -dem_insert_0_box 0.01,0.01,0.12,0.09,0.09,0.19"
bad "region outside the domain" "-dem_insert_0_box: the region spans" -dem_insert_0_region box -dem_insert_0_box 0.01,0.01,0.12,0.09,0.09,0.25 -dem_insert_0_rate 100
bad "rate that cannot fit" "-dem_insert_0_rate 1e+06 x period" $R -dem_insert_0_rate 1e6
bad "start after stop" "-dem_insert_0_stop 0.05 must be after -dem_insert_0_start" $R -dem_insert_0_rate 100 -dem_insert_0_start 0.1 -dem_insert_0_stop 0.05
bad "no rate and no total" "-dem_insert_0_region: give a rate" $R
bad "negative rate" "-dem_insert_0_rate -5" $R -dem_insert_0_rate -5
bad "negative count" "-dem_insert_0_count -3" $R -dem_insert_0_count -3
bad "negative mass" "-dem_insert_0_mass -0.1" $R -dem_insert_0_mass -0.1
