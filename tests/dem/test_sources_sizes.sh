#!/bin/sh
# Sources of spheres of their own sizes, end to end (the frames' radii; mass rho pi d^3/6):
# - distributions: 10,000 particles from each of three sources in one run (a table by number, a
#   table by mass, a lognormal cut to [1, 3.5] mm; dilute, no gravity): number- and mass-weighted
#   mean, std, d10, d50, d90 within 3 standard errors of the law's exact values (closed forms,
#   tests/common/sizes_check.py), a table's quantiles its exact entry, the number table's
#   fractions by number and the mass table's by MASS within 3 SE;
# - no size bias from rejection: the lognormal source poured into a 4 cm box until it is full (a
#   particle finds no room in 50 candidates) places the very diameters, in id order, of the first
#   particles of the dilute run (the n-th particle's size is a function of (seed, k, n) only), and
#   its moments stay within 3 SE. A check that can fail: the earlier per-candidate size draw put
#   4000 particles in that box with a number-weighted mean of 1.718 mm against the law's 1.975 mm
#   (z = -31; d90 z = -33): in a crowded region small sizes win;
# - a mass rate of 0.02 kg/s with own sizes: at every frame the mass present is within
#   [rate t, rate (t + P)] + one particle; a total of 2 g ends in [2 g, 2 g + the last particle);
# - a lognormal source placed into a lognormal bed (another source) across the ranks' boundaries:
#   no new particle overlaps another or a wall by more than 1e-9 d, and the set (ids, positions,
#   velocities, radii) is bitwise the same on 1, 2 and 4 ranks;
# - a lognormal pour falling out through an outlet (side zlo) with -dem_check_every 1 on 1, 2, 4
#   ranks: the run's balance holds at every step, and the monitor's inserted and removed masses
#   equal the sums of the own masses of the particles seen in the frames to 1e-12 (inserted: every
#   id seen; removed: those gone at the end); the same run stopped mid-window at T/2 and continued
#   with -restart ends bitwise as the uninterrupted run (1 and 2 ranks);
# - a tilted cylinder and a patch stream of lognormal sizes: every placed particle wholly inside its
#   region (1e-9 d); every particle of the stream further from its patch at the next frame;
# - a source of cubes: placed without overlap of bounding spheres, their orientations uniformly
#   random (<q_i^2> = 1/4 within 3 SE for each quaternion component, all distinct).
cd "$(dirname "$0")/../.." || exit 1
S=$(pwd)/${BIN:-bin}/sable
C=$(pwd)/tests/common/sizes_check.py
P=$(pwd)/tests/common/sources_check.py
[ "$(id -u)" -eq 0 ] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1
W=$(mktemp -d)
trap 'rm -rf "$W"' EXIT
run() { # np, dir, args...
  rnp=$1; rd=$2; shift 2
  mkdir -p "$rd"
  (cd "$rd" && mpiexec -n "$rnp" "$S" -dem_density 2500 -dem_kn 1e3 -dem_progress_interval 0 -da_processors_x 1 -da_processors_y 1 -da_processors_z "$rnp" -io_dir out "$@" >log 2>&1) || echo "FAIL sources sizes: the run in $(basename "$rd") on $rnp rank(s) exited with status $?: $(grep error "$rd/log" | head -n 2)"
}
last() { ls "$1"/out/sable_*.h5 2>/dev/null | tail -n 1; }
ok() { awk "BEGIN { exit !($1) }"; }
LOGN="lognormal -dem_insert_2_psd_mean 2e-3 -dem_insert_2_psd_std 6e-4 -dem_insert_2_psd_min 1e-3 -dem_insert_2_psd_max 3.5e-3"

# distributions
ONE="-dem_radius 0.001 -dem_gravity 0,0,0 -dem_dt 5e-6 -dem_t_end 5e-6 -io_interval 5e-6"
run 1 "$W/dist" $ONE -domain_lo 0,0,0 -domain_hi 0.6,0.2,0.2 -dem_box 0,0,0,0.6,0.2,0.2 \
  -dem_insert_0_region box -dem_insert_0_box 0,0,0,0.2,0.2,0.2 -dem_insert_0_count 10000 -dem_insert_0_psd number -dem_insert_0_psd_diameters 1e-3,2e-3,3e-3 -dem_insert_0_psd_fractions 0.3,0.45,0.25 \
  -dem_insert_1_region box -dem_insert_1_box 0.2,0,0,0.4,0.2,0.2 -dem_insert_1_count 10000 -dem_insert_1_psd mass -dem_insert_1_psd_diameters 1e-3,1.5e-3,2.5e-3 -dem_insert_1_psd_fractions 0.25,0.35,0.4 \
  -dem_insert_2_region box -dem_insert_2_box 0.4,0,0,0.6,0.2,0.2 -dem_insert_2_count 10000 -dem_insert_2_psd $LOGN
F=$W/dist/out/sable_000001.h5
$C moments "table by number" "$F" x:0:0.2 number:1e-3,2e-3,3e-3:0.3,0.45,0.25 10000
$C moments "table by mass" "$F" x:0.2:0.4 mass:1e-3,1.5e-3,2.5e-3:0.25,0.35,0.4 10000
$C moments "lognormal" "$F" x:0.4:0.6 lognormal:2e-3:6e-4:1e-3:3.5e-3 10000

# the same lognormal source (k = 2, same seed) into a box it fills
run 1 "$W/full" $ONE -domain_lo 0,0,0 -domain_hi 0.04,0.04,0.04 -dem_box 0,0,0,0.04,0.04,0.04 -dem_insert_2_region box -dem_insert_2_box 0,0,0,0.04,0.04,0.04 -dem_insert_2_count 4000 -dem_insert_2_psd $LOGN
set -- $($C sameseq "$F" x:0.4:0.6 "$W/full/out/sable_000001.h5" -)
short=$(sed -n 's/^source -dem_insert_2.*; shortfall \([0-9]*\) particles.*/\1/p' "$W/full/log")
phi=$(sed -n 's/^bed: packing fraction \([0-9.]*\).*/\1/p' "$W/full/log")
if [ $# -eq 2 ] && [ "$1" -gt 500 ] && [ "$2" = 0 ] && [ "${short:-0}" -gt 0 ]; then
  echo "PASS sources sizes full region: $1 particles placed before one found no room (shortfall $short, solids fraction $phi), their diameters bitwise those of the dilute run's first $1, in id order"
else echo "FAIL sources sizes full region: $1 compared, $2 differing from the dilute run (expected > 500, 0), shortfall $short (expected > 0)"; fi
$C moments "full region" "$W/full/out/sable_000001.h5" - lognormal:2e-3:6e-4:1e-3:3.5e-3 500

# mass rate and total mass
RHO=2500
BIG="-domain_lo 0,0,0 -domain_hi 0.1,0.1,0.2 -dem_box 0,0,0,0.1,0.1,0.2 -dem_radius 0.001 -dem_gravity 0,0,0 -dem_dt 5e-6 -dem_insert_2_region box -dem_insert_2_box 0.01,0.01,0.01,0.09,0.09,0.19 -dem_insert_2_period 0.005 -dem_insert_2_psd $LOGN"
run 1 "$W/mrate" $BIG -dem_insert_2_mass_rate 0.02 -dem_insert_2_start 0.01 -dem_t_end 0.06 -io_interval 0.0025
set -- $($C massrate "$W/mrate/out" $RHO 0.02 0.01)
if [ $# -eq 4 ] && ok "$1 <= 1e-12 && $2 <= 0.02 * 0.005 + $4 && $3 >= 24"; then
  echo "PASS sources sizes mass rate: M(t) against 0.02 kg/s x (t - 0.01 s) at $3 frames: shortfall $1 kg (bound 0), lead $2 kg (bound rate x period + largest particle = $(awk "BEGIN { print 0.02 * 0.005 + $4 }"))"
else echo "FAIL sources sizes mass rate: shortfall, lead, frames, m_max = $* (bounds 0, 1e-4 + m_max, >= 24)"; fi
run 1 "$W/mtot" $BIG -dem_insert_2_mass_rate 0.02 -dem_insert_2_mass 0.002 -dem_t_end 0.2 -io_interval 0.2
set -- $($C mass "$(last "$W/mtot")" $RHO)
if [ $# -eq 2 ] && ok "$1 >= 0.002 && $1 - 0.002 < $2"; then
  echo "PASS sources sizes total mass: $1 kg (set 0.002 kg, bound [0.002, 0.002 + the last particle's $2 kg))"
else echo "FAIL sources sizes total mass: present, last particle = $* kg (set 0.002)"; fi

# placement into a lognormal bed across the ranks' boundaries (z = 0.1; 0.05, 0.1, 0.15)
BED="-domain_lo 0,0,0 -domain_hi 0.1,0.1,0.2 -dem_box 0,0,0,0.1,0.1,0.2 -dem_radius 0.0015 -dem_gravity 0,0,0 -dem_dt 1e-5 -dem_t_end 2e-4 -io_interval 1e-4
  -dem_insert_0_region box -dem_insert_0_box 0,0,0.06,0.1,0.1,0.14 -dem_insert_0_count 3000 -dem_insert_0_psd lognormal -dem_insert_0_psd_mean 3e-3 -dem_insert_0_psd_std 9e-4 -dem_insert_0_psd_min 1.5e-3 -dem_insert_0_psd_max 6e-3
  -dem_insert_1_region box -dem_insert_1_box 0,0,0.06,0.1,0.1,0.14 -dem_insert_1_count 500 -dem_insert_1_start 2e-4 -dem_insert_1_velocity_spread 0.2 -dem_insert_1_psd lognormal -dem_insert_1_psd_mean 3e-3 -dem_insert_1_psd_std 1.5e-3 -dem_insert_1_psd_min 1.5e-3 -dem_insert_1_psd_max 7e-3"
for np in 1 2 4; do
  run $np "$W/bed$np" $BED
  set -- $($P overlap "$W/bed$np/out/sable_000002.h5" "$W/bed$np/out/sable_000001.h5" 0,0,0 0.1,0.1,0.2)
  if [ $# -eq 3 ] && ok "$1 == 500 && $2 <= 1e-9 && $3 <= 1e-9"; then
    echo "PASS sources sizes placement np=$np: $1 lognormal particles placed among the 3000 of a lognormal bed, largest overlap / d with a particle $2, with a wall $3 (bound 1e-9)"
  else echo "FAIL sources sizes placement np=$np: placed, overlaps = $* (expected 500, bound 1e-9)"; fi
done
for np in 2 4; do
  set -- $($P same "$W/bed1/out/sable_000002.h5" "$W/bed$np/out/sable_000002.h5")
  if [ "$1" = 0 ] && [ "$2" = 0 ]; then echo "PASS sources sizes same set np=$np: every id of the 1-rank run, with bitwise the same position, velocity and radius"
  else echo "FAIL sources sizes same set np=$np: $1 ids in one run only, $2 particles differing"; fi
done

# a lognormal pour through an outlet: balance at every step, masses, restart
POUR="-domain_lo 0,0,0 -domain_hi 0.1,0.1,0.15 -dem_plane_0 0,0,0,1,0,0 -dem_plane_1 0.1,0,0,-1,0,0 -dem_plane_2 0,0,0,0,1,0 -dem_plane_3 0,0.1,0,0,-1,0 -dem_radius 0.0015 -dem_gravity 0,0,-30 -dem_dt 1e-5 -dem_check_every 1 -dem_outlet_0_side zlo
  -dem_insert_0_region box -dem_insert_0_box 0.01,0.01,0.11,0.09,0.09,0.145 -dem_insert_0_rate 4000 -dem_insert_0_period 0.0025 -dem_insert_0_velocity 0,0,-0.5 -dem_insert_0_velocity_spread 0.1 -dem_insert_0_psd lognormal -dem_insert_0_psd_mean 3e-3 -dem_insert_0_psd_std 9e-4 -dem_insert_0_psd_min 1.5e-3 -dem_insert_0_psd_max 6e-3"
T=0.12
for np in 1 2 4; do
  run $np "$W/out$np" $POUR -dem_t_end $T -io_interval 0.0025 -mon_interval 0.0025
  set -- $($C flow "$W/out$np/out" $RHO "$W/out$np/out/sable_monitor.csv")
  fl=$(grep '^flow:' "$W/out$np/log")
  case "$fl" in *"balance 0") bal=1 ;; *) bal=0 ;; esac
  if [ $# -eq 5 ] && [ $bal = 1 ] && ok "$2 > 50 && $3 <= 1e-12 && $4 <= 1e-12 && $5 > $T - 1e-9"; then
    echo "PASS sources sizes outlet np=$np: balance at every step (\"$fl\"); inserted mass of the $1 ids seen and removed mass of the $2 gone against the monitor's: relative $3, $4 (bound 1e-12)"
  else echo "FAIL sources sizes outlet np=$np: seen, removed, rel. inserted, rel. removed, monitor time = $* (bound 1e-12, > 50 removed); \"$fl\" $(grep error "$W/out$np/log" | head -n 1)"; fi
done
for np in 1 2; do
  d=$W/restart$np
  run $np "$d/half" $POUR -dem_t_end 0.0613 -io_interval 0 -io_checkpoint_interval 0.0613
  ck=$(sed -n 's/^checkpoint: //p' "$d/half/log" | tail -n 1)
  run $np "$d/rest" $POUR -dem_t_end $T -io_interval $T -restart "../half/$ck"
  a=$(last "$W/out$np"); b=$(last "$d/rest")
  if [ -z "$ck" ] || [ -z "$a" ] || [ -z "$b" ]; then echo "FAIL sources sizes restart np=$np: a run failed"; continue; fi
  set -- $(tests/common/frames_equal.py "$a" "$b")
  if [ "$1" -gt 0 ] && [ "$2" -eq 0 ]; then echo "PASS sources sizes restart np=$np: final frames at t = $T s bitwise equal, $1 datasets compared, 0 differing (restart at 0.0613 s, mid-window, particles already removed)"
  else echo "FAIL sources sizes restart np=$np: $1 datasets compared, $2 differing: $3 $4 $5"; fi
done

# a tilted cylinder and a patch stream
REG="-domain_lo 0,0,0 -domain_hi 0.1,0.1,0.2 -dem_box 0,0,0,0.1,0.1,0.2 -dem_radius 0.0015 -dem_gravity 0,0,0 -dem_dt 1e-5 -dem_insert_0_psd lognormal -dem_insert_0_psd_mean 3e-3 -dem_insert_0_psd_std 9e-4 -dem_insert_0_psd_min 1.5e-3 -dem_insert_0_psd_max 6e-3"
run 1 "$W/cyl" $REG -dem_insert_0_region cylinder -dem_insert_0_cylinder 0.05,0.05,0.1,0,1,1,0.03,0.08 -dem_insert_0_count 500 -dem_t_end 1e-5 -io_interval 1e-5
set -- $($C cylinder "$W/cyl/out/sable_000001.h5" - 0.05,0.05,0.1 0,1,1 0.03 0.08)
if [ $# -eq 3 ] && ok "$1 == 500 && $2 <= 1e-9 && $3 <= 1e-9"; then echo "PASS sources sizes cylinder: $1 particles, largest excess / d beyond the mantle $2, beyond the ends $3 (bound 1e-9)"
else echo "FAIL sources sizes cylinder: placed, excesses = $* (expected 500, bound 1e-9)"; fi
run 1 "$W/patch" $REG -dem_insert_0_region patch -dem_insert_0_patch 0.02,0.02,0.02,0.08,0.02,0.02,0.02,0.08,0.02 -dem_insert_0_rate 2000 -dem_insert_0_period 0.005 -dem_insert_0_start 0.005 -dem_insert_0_velocity 0,0,2 -dem_insert_0_velocity_spread 0.3 -dem_t_end 0.02 -io_interval 0.005
for f in 2 3 4; do
  set -- $($C patch "$W/patch/out/sable_00000$f.h5" "$W/patch/out/sable_00000$((f - 1)).h5" 0.02,0.02,0.02 0.08,0.02,0.02 0.02,0.08,0.02 0.01)
  if [ $# -eq 6 ] && ok "$1 >= 5 && $2 <= 1e-9 && $3 <= 1e-9 && $4 <= 1e-9 && ($f == 2 || ($5 > 0 && $6 > 0))"; then
    echo "PASS sources sizes patch, frame $f: $1 new particles in the 10 mm slab in front of the patch (largest excess / d: sides $2, behind $3, beyond $4; bound 1e-9); the $5 of the frame before all further from the patch (smallest step $6 m)"
  else echo "FAIL sources sizes patch, frame $f: new, excesses, earlier, smallest step = $* (bound 1e-9, step > 0)"; fi
done

# cubes
run 1 "$W/cubes" -domain_lo 0,0,0 -domain_hi 0.3,0.3,0.3 -dem_box 0,0,0,0.3,0.3,0.3 -dem_shape cube -dem_shape_deq 0.01 -dem_contact_law linear -dem_kn 2e5 -dem_gravity 0,0,0 -dem_dt 1e-5 -dem_t_end 1e-5 -io_interval 1e-5 \
  -dem_insert_0_region box -dem_insert_0_box 0.02,0.02,0.02,0.28,0.28,0.28 -dem_insert_0_count 2000
set -- $($P overlap "$W/cubes/out/sable_000001.h5" - 0,0,0 0.3,0.3,0.3)
o1=$1; o2=$2; o3=$3
set -- $($C orient "$W/cubes/out/sable_000001.h5")
if [ "$o1" = 2000 ] && ok "$o2 <= 1e-9 && $o3 <= 1e-9" && [ "$2" = 2000 ] && ok "$3 < 3"; then
  echo "PASS sources sizes cubes: $o1 placed, largest overlap / d of bounding spheres $o2, with a wall $o3 (bound 1e-9); $2 distinct orientations, largest |<q_i^2> - 1/4| $3 SE (bound 3)"
else echo "FAIL sources sizes cubes: placed $o1, overlaps $o2 $o3 (bound 1e-9), orientations: count, distinct, z = $* (bound 3)"; fi
