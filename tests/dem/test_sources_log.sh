#!/bin/sh
# What a particle source says about particles it could not place at once, against what it did
# (the particles in the last frame) and what its summary line reports:
# - a pour of 4,000 spheres of a normal size law (0.9 +- 0.15 mm, cut to 0.6-1.2 mm) placed at
#   once in a box about 15% full: random placement runs out of candidates for one particle before
#   the batch is done, and the rest go in at the next batches. The source catches up, so: no
#   warning line, at most one note, every particle asked for is in the frame (4,000 exactly), the
#   summary's shortfall 0, and the note's carried number is the summary's largest carried;
# - the same pour into an STL cylinder (tools/make_stl, 512 triangles; region about 30% full by
#   the count asked): the same checks, over about 40 batches;
# - a real shortfall: 100 spheres asked of a box region that holds fewer (no gravity: nothing
#   leaves it), on 1 and 2 ranks: exactly one warning, the summary's shortfall equals 100 minus
#   the particles in the frame, and the warning's number is at least that (a later batch may still
#   find a hole).
# The log before these lines said "its region is full" of a region 15% full, warned again at
# every batch until the shortfall passed a doubling threshold (ten lines for the cylinder), and
# then reported "shortfall 0 particles".
cd "$(dirname "$0")/../.." || exit 1
case ${BIN:-bin} in /*) S=$BIN/sable ;; *) S=$(pwd)/${BIN:-bin}/sable ;; esac
C=$(pwd)/tests/common/sources_check.py
M=$(pwd)/tools/make_stl
[ "$(id -u)" -eq 0 ] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1
W=$(mktemp -d)
trap 'rm -rf "$W"' EXIT
run() { # np, dir, args...
  rnp=$1; rd=$2; shift 2
  mkdir -p "$rd"
  (cd "$rd" && mpiexec -n "$rnp" "$S" -dem_progress_interval 0 -da_processors_x 1 -da_processors_y 1 -da_processors_z "$rnp" -io_dir out "$@" >log 2>&1) || echo "FAIL sources log: the run in $(basename "$rd") on $rnp rank(s) exited with status $?: $(grep error "$rd/log" | head -n 2)"
}
count() { f=$(ls "$1"/out/sable_*.h5 2>/dev/null | tail -n 1); [ -n "$f" ] && $C count "$f"; }
# the practitioner's pour (a coater study): Hertz glass-like beads, dt 5e-6 s, batches every 1 ms
POUR="-domain_lo 0,0,0 -domain_hi 0.016,0.016,0.064 -dem_box 0,0,0,0.016,0.016,0.064 -dem_radius 0.00045 -dem_density 2500 -dem_contact_law hertz -dem_youngs_modulus 1e7 -dem_poisson_ratio 0.25 -dem_restitution 0.9 -dem_friction 0.3 -dem_dt 5e-6 -dem_insert_0_count 4000 -dem_insert_0_velocity 0,0,-0.3 -dem_insert_0_psd normal -dem_insert_0_psd_mean 0.9e-3 -dem_insert_0_psd_std 0.15e-3 -dem_insert_0_psd_min 0.6e-3 -dem_insert_0_psd_max 1.2e-3"

caught_up() { # name, dir, asked
  name=$1; d=$2; asked=$3
  n=$(count "$d")
  nw=$(grep -c '^warning: .*source -dem_insert_0' "$d/log")
  nn=$(grep -c '^source -dem_insert_0: t = ' "$d/log")
  sh=$(sed -n 's/^source -dem_insert_0 (.*; shortfall \([0-9]*\) particles.*/\1/p' "$d/log")
  carried=$(sed -n 's/^source -dem_insert_0: t = .* the other \([0-9]*\) are carried.*/\1/p' "$d/log")
  most=$(sed -n 's/^source -dem_insert_0 (.*up to \([0-9]*\) carried.*/\1/p' "$d/log")
  if [ "$n" = "$asked" ] && [ "$nw" -eq 0 ] && [ "$nn" -le 1 ] && [ "$sh" = 0 ] && [ "${carried:-0}" = "${most:-0}" ]; then
    echo "PASS sources log, $name: $n particles in the frame (asked $asked), summary shortfall $sh, $nw warning lines, $nn note ($carried carried at the first batch; the summary: up to $most)"
  else echo "FAIL sources log, $name: $n particles in the frame (asked $asked), summary shortfall '$sh' (expected 0), $nw warning lines (expected 0), $nn note lines (at most 1), carried '$carried' against the summary's '$most'; $(grep -m 3 'source -dem_insert_0' "$d/log" | tr '\n' ' ')"; fi
}

run 1 "$W/box" $POUR -dem_insert_0_region box -dem_insert_0_box 0.0006,0.0006,0.015,0.0154,0.0154,0.062 -dem_t_end 0.004 -io_interval 0.004
caught_up "4000 spheres in a box 15% full" "$W/box" 4000

mkdir -p "$W/cyl"
"$M" cylinder --point 0.008,0.008,0 --axis 0,0,1 --radius 0.008 --s0 0 --s1 0.064 --n 64 --nlen 4 -o "$W/cyl/cyl.stl" >/dev/null || echo "FAIL sources log: tools/make_stl cylinder failed"
run 1 "$W/cyl" $POUR -dem_mesh_0_file cyl.stl -dem_insert_0_region cylinder -dem_insert_0_cylinder 0.008,0.008,0.0475,0,0,1,0.0074,0.029 -dem_t_end 0.045 -io_interval 0.045
caught_up "4000 spheres in an STL cylinder (region 30% full by the count asked)" "$W/cyl" 4000

FULL="-domain_lo 0,0,0 -domain_hi 0.1,0.1,0.2 -dem_box 0,0,0,0.1,0.1,0.2 -dem_radius 0.005 -dem_density 2500 -dem_kn 1e4 -dem_dt 2e-5 -dem_gravity 0,0,0 -dem_insert_0_region box -dem_insert_0_box 0.03,0.03,0.15,0.07,0.07,0.19 -dem_insert_0_count 100 -dem_insert_0_period 0.01 -dem_t_end 0.1 -io_interval 0.1"
for np in 1 2; do
  d=$W/full$np
  run $np "$d" $FULL
  n=$(count "$d")
  nw=$(grep -c '^warning: .*source -dem_insert_0' "$d/log")
  w=$(sed -n 's/^warning: .*source -dem_insert_0 is \([0-9]*\) particles behind.*/\1/p' "$d/log" | head -n 1)
  sh=$(sed -n 's/^source -dem_insert_0 (.*; shortfall \([0-9]*\) particles.*/\1/p' "$d/log")
  if [ -n "$n" ] && [ "$nw" -eq 1 ] && [ -n "$sh" ] && [ "$sh" -gt 0 ] && [ $((n + sh)) -eq 100 ] && [ "${w:-0}" -ge "$sh" ] && grep -q 'shortfall .* see the warning' "$d/log"; then
    echo "PASS sources log, a full region np=$np: $n of 100 placed, summary shortfall $sh (= 100 - $n), one warning ($w behind when it stopped catching up)"
  else echo "FAIL sources log, a full region np=$np: $n of 100 placed, summary shortfall '$sh' (expected 100 - $n > 0), $nw warning lines (expected 1, its number '$w' >= the shortfall); $(grep -m 3 'source -dem_insert_0' "$d/log" | tr '\n' ' ')"; fi
done
