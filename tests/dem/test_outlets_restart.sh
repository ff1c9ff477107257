#!/bin/sh
# Outlets across a restart, and their bad input.
# Restart: 384 glass spheres fall from a jittered lattice in a box whose floor is a domain side
# outlet (zlo) and through a patch outlet, with -dem_check_every 1. On 1 and 2 ranks, a run to T
# and a run to T/2 that writes a checkpoint (particles already removed), continued with -restart
# to T, end with bitwise the same final frame (tests/common/frames_equal.py) and the same
# "flow:" summary line (the counters travel in the checkpoint). The 2-rank checkpoint restarted
# on 1 rank (redistributed) keeps the balance.
# A check that can fail: the same checkpoint with its flow counters deleted (the removals
# uncounted) must stop the restarted run at its first balance check, with one error line.
# Bad input: an outlet outside the domain, a degenerate patch, an unknown side, start after
# stop, two regions for one outlet, a time without a region, a side across a periodic axis: exit
# non-zero with one error line naming the option.
cd "$(dirname "$0")/../.." || exit 1
S=$(pwd)/${BIN:-bin}/sable
[ "$(id -u)" -eq 0 ] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1
W=$(mktemp -d)
trap 'rm -rf "$W"' EXIT
SCENE="-domain_lo 0,0,0 -domain_hi 0.1449,0.1449,0.24633 -dem_plane_0 0,0,0,1,0,0 -dem_plane_1 0.1449,0,0,-1,0,0 -dem_plane_2 0,0,0,0,1,0 -dem_plane_3 0,0.1449,0,0,-1,0 -dem_radius 0.0069 -dem_density 2500 -dem_kn 7.2e5 -dem_friction 0.3 -dem_dt 1e-5 -dem_gravity 0,0,-30 -dem_lattice 8,8,6 -dem_lattice_spacing 0.01449 -dem_lattice_origin 0,0,0.1 -dem_lattice_jitter 0.3 -dem_lattice_speed 0.05 -dem_progress_interval 0 -dem_check_every 1 -dem_outlet_0_side zlo -dem_outlet_1_patch 0,0,0.08,0.07,0,0.08,0,0.1449,0.08 -dem_outlet_1_start 0.02"
T=0.08
H=0.05
run() { # np, dir, args...
  rnp=$1; rd=$2; shift 2
  mkdir -p "$rd"
  (cd "$rd" && mpiexec -n "$rnp" "$S" $SCENE -io_dir out "$@" >log 2>&1)
}
for np in 1 2; do
  d=$W/np$np
  run "$np" "$d/full" -dem_t_end $T -io_interval $T
  run "$np" "$d/half" -dem_t_end $H -io_interval 0 -io_checkpoint_interval $H
  ck=$(sed -n 's/^checkpoint: //p' "$d/half/log" | tail -n 1)
  run "$np" "$d/rest" -dem_t_end $T -io_interval $T -restart "../half/$ck"
  a=$(ls "$d/full/out/"sable_*.h5 2>/dev/null | tail -n 1); b=$(ls "$d/rest/out/"sable_*.h5 2>/dev/null | tail -n 1)
  if [ -z "$ck" ] || [ -z "$a" ] || [ -z "$b" ]; then
    echo "FAIL outlets restart np=$np: a run failed; $(cat "$d"/*/log | grep 'error' | head -n 2)"
    continue
  fi
  half=$(sed -n 's/^flow: .* - \([0-9]*\) removed.*/\1/p' "$d/half/log")
  set -- $(tests/common/frames_equal.py "$a" "$b")
  if [ "$1" -gt 0 ] && [ "$2" -eq 0 ] && [ "${half:-0}" -gt 0 ]; then
    echo "PASS outlets restart np=$np: final frames at t=$T bitwise equal, $1 datasets compared, 0 differing ($half particles removed before the checkpoint)"
  else
    echo "FAIL outlets restart np=$np: $1 datasets compared, $2 differing: $3 $4 $5; removed before the checkpoint: $half"
  fi
  fa=$(grep '^flow:' "$d/full/log"); fb=$(grep '^flow:' "$d/rest/log")
  if [ -n "$fa" ] && [ "$fa" = "$fb" ]; then echo "PASS outlets restart np=$np: the same summary, \"$fa\""
  else echo "FAIL outlets restart np=$np: summary \"$fa\" against the restarted run's \"$fb\""; fi
done
# the 2-rank checkpoint on 1 rank: redistributed, the balance (-dem_check_every 1) holds
ck2=$(ls "$W"/np2/half/out/*checkpoint*.h5 2>/dev/null | tail -n 1)
run 1 "$W/remap" -dem_t_end $T -io_interval 0 -restart "$ck2"
fr=$(grep '^flow:' "$W/remap/log")
case "$fr" in
  *"balance 0") echo "PASS outlets restart 2 -> 1 ranks: every step balanced, \"$fr\"" ;;
  *) echo "FAIL outlets restart 2 -> 1 ranks: \"$fr\"; $(grep error "$W/remap/log" | head -n 2)" ;;
esac
# removals uncounted: the checkpoint without dem/flow
ck1=$(ls "$W"/np1/half/out/*checkpoint*.h5 2>/dev/null | tail -n 1)
cp "$ck1" "$W/noflow.h5" && /usr/bin/python3 -c "import h5py, sys; f = h5py.File(sys.argv[1], 'a'); del f['dem/flow']; f.close()" "$W/noflow.h5"
out=$(cd "$W" && "$S" $SCENE -dem_t_end $T -io_interval 0 -io_dir noflow.d -restart "$W/noflow.h5" 2>&1 >/dev/null); rc=$?
lines=$(printf '%s\n' "$out" | grep -c 'sable: error')
if [ "$rc" -ne 0 ] && [ "$lines" -eq 1 ] && printf '%s' "$out" | grep -q "not counted"; then
  echo "PASS outlets uncounted removals stop the balance check: exit $rc, \"$(printf '%s' "$out" | grep 'sable: error' | cut -c1-160)\""
else
  echo "FAIL outlets uncounted removals stop the balance check: exit $rc, $lines error lines: $(printf '%s' "$out" | head -n 3)"
fi
expect() { # name, pattern, options...
  name=$1; pat=$2; shift 2
  out=$(cd "$W" && "$S" $SCENE -dem_t_end 0.001 -io_interval 0 -io_dir bad.d "$@" 2>&1 >/dev/null); rc=$?
  lines=$(printf '%s\n' "$out" | grep -c 'sable: error')
  if [ "$rc" -ne 0 ] && [ "$lines" -eq 1 ] && printf '%s' "$out" | grep -q -- "$pat"; then
    echo "PASS outlets bad input, $name: exit $rc, \"$(printf '%s' "$out" | grep 'sable: error')\""
  else
    echo "FAIL outlets bad input, $name: exit $rc, $lines error lines, expected /$pat/; got: $out"
  fi
}
# Nine numbers that are a rectangle read either way: taken as corners, with a note naming the old reading's.
out=$(cd "$W" && "$S" $SCENE -dem_t_end 0.0001 -io_interval 0 -io_dir note.d -dem_outlet_3_patch 0.05,0.05,0,0.05,0,0,0,0.05,0 2>&1); rc=$?
note=$(printf '%s\n' "$out" | grep '^note: -dem_outlet_3_patch is read as three corners')
if [ "$rc" -eq 0 ] && [ "$(printf '%s\n' "$out" | grep -c '^note:')" -eq 1 ] && printf '%s' "$note" | grep -q "corners p, p + e1, p + e2 = 0.05,0.05,0,0.1,0.05,0,0.05,0.1,0:"; then
  echo "PASS outlets ambiguous patch noted: exit $rc, \"$(printf '%s' "$note" | cut -c1-160)\""
else
  echo "FAIL outlets ambiguous patch noted: exit $rc, expected one note line with the old corners; got: $(printf '%s' "$out" | head -n 5)"
fi
expect "box outside the domain" "-dem_outlet_3_box: the box is outside the domain" -dem_outlet_3_box 0,0,-0.2,0.1,0.1,-0.1
expect "patch outside the domain" "-dem_outlet_3_patch: corner" -dem_outlet_3_patch 0,0,0.3,0.1,0,0.3,0,0.1,0.3
expect "old patch spelling p,e1,e2" "-dem_outlet_3_patch takes three corners p0,p1,p2 now.*write 0,0,0.08,0.07,0,0.08,0,0.1449,0.08" -dem_outlet_3_patch 0,0,0.08,0.07,0,0,0,0.1449,0
expect "degenerate patch" "-dem_outlet_3_patch: the edges" -dem_outlet_3_patch 0,0,0.1,0.1,0,0,0.1,0,0
expect "unknown side" "-dem_outlet_3_side bottom is not known; valid values: xlo, xhi, ylo, yhi, zlo, zhi" -dem_outlet_3_side bottom
expect "start after stop" "-dem_outlet_3_start 0.5 s is after -dem_outlet_3_stop 0.2 s" -dem_outlet_3_box 0,0,0,0.1,0.1,0.01 -dem_outlet_3_start 0.5 -dem_outlet_3_stop 0.2
expect "two regions" "-dem_outlet_3: give one of" -dem_outlet_3_box 0,0,0,0.1,0.1,0.01 -dem_outlet_3_side zhi
expect "time without a region" "-dem_outlet_4_stop given without" -dem_outlet_4_stop 1
expect "side across a periodic axis" "-dem_outlet_3_side xlo.*periodic" -domain_periodic_x -dem_outlet_3_side xlo
