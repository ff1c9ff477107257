#!/bin/sh
# Checkpoints of a run with load balancing, on 2 ranks stacked along z: for the schemes frequent
# (step cadence), dynamic (time cadence, threshold) and once, a run to T and a run to T/2 that
# moved its cuts before writing a checkpoint, continued with -restart to T, end with bitwise the
# same final frame (every dataset compared with h5py); the restarted run checks at the same
# steps with the same loads and decisions as the uninterrupted one after the restart point, and
# the balancer's summary (scheme, checks, rebalances) is the same. A restart on another rank
# count, or another process grid on the same rank count, says that it starts from the default
# cuts (the DEM redistributes its particles) and runs to the end.
cd "$(dirname "$0")/../.." || exit 1
S=$(pwd)/${BIN:-bin}/sable
[ "$(id -u)" -eq 0 ] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1
W=$(mktemp -d)
trap 'rm -rf "$W"' EXIT
# 384 glass spheres falling from a lattice onto the floor of a box (the scene of
# dem/test_checkpoint): the load moves down the column while the balancer watches it
SCENE="-domain_lo 0,0,0 -domain_hi 0.1449,0.1449,0.24633 -dem_box 0,0,0,0.1449,0.1449,0.24633 -dem_radius 0.0069 -dem_density 2500 -dem_restitution 0.75 -dem_friction 0.3 -dem_dt 1e-5 -dem_lattice 8,8,6 -dem_lattice_spacing 0.01449 -dem_lattice_speed 0.05 -dem_progress_interval 0 -dem_contact_law linear -dem_kn 7.2e5"
GRID="-da_processors_x 1 -da_processors_y 1 -da_processors_z 2"
T=0.02
H=0.01
run() { # np, dir, args...
  rnp=$1; rd=$2; shift 2
  mkdir -p "$rd"
  (cd "$rd" && mpiexec -n "$rnp" "$S" $SCENE -io_dir out "$@" >log 2>&1)
}
checks_after() { # log, step: the check lines after that step, their wall-time cost left out
  sed -n 's/^\(lb: step \([0-9]*\) .*\), cost .*/\2 \1/p' "$1" | awk -v s="$2" '$1 > s { $1 = ""; print }'
}
summary() { sed -n 's/^\(load balancing: .* rebalances\), .*/\1/p' "$1"; }
for scheme in frequent dynamic once; do
  case $scheme in
  frequent) LB="-lb_scheme frequent -lb_interval 700" ;;
  dynamic) LB="-lb_scheme dynamic -lb_interval_time 0.007 -lb_threshold 0.05" ;;
  once) LB="-lb_scheme once -lb_step 500" ;;
  esac
  d=$W/$scheme
  run 2 "$d/full" $GRID $LB -dem_t_end $T -io_interval $T
  run 2 "$d/half" $GRID $LB -dem_t_end $H -io_interval 0 -io_checkpoint_interval $H
  ck=$(sed -n 's/^checkpoint: //p' "$d/half/log" | tail -n 1)
  run 2 "$d/rest" $GRID $LB -dem_t_end $T -io_interval $T -restart "../half/$ck"
  a=$(ls "$d/full/out/"sable_*.h5 2>/dev/null | tail -n 1); b=$(ls "$d/rest/out/"sable_*.h5 2>/dev/null | tail -n 1)
  if [ -z "$ck" ] || [ -z "$a" ] || [ -z "$b" ]; then
    echo "FAIL checkpoint $scheme: a run failed; $(cat "$d"/*/log | grep 'error' | head -n 2)"
    continue
  fi
  step=$(echo "$ck" | sed 's/.*checkpoint_0*\([0-9][0-9]*\)\.h5$/\1/')
  moved=$(sed -n '/^checkpoint: /q; /-> rebalanced/p' "$d/half/log" | wc -l)
  set -- $(tests/common/frames_equal.py "$a" "$b")
  if [ "$moved" -gt 0 ] && [ "$1" -gt 0 ] && [ "$2" -eq 0 ]; then
    echo "PASS checkpoint $scheme: cuts moved $moved times before the checkpoint at step $step; final frames at t=$T bitwise equal, $1 datasets compared, 0 differing"
  else
    echo "FAIL checkpoint $scheme: cuts moved $moved times before the checkpoint at step $step (needs > 0); $1 datasets compared, $2 differing: $3 $4 $5"
  fi
  checks_after "$d/full/log" "$step" >"$d/full.checks"
  checks_after "$d/rest/log" "$step" >"$d/rest.checks"
  n=$(wc -l <"$d/full.checks"); nm=$(grep -c 'rebalanced' "$d/full.checks")
  sf=$(summary "$d/full/log"); sr=$(summary "$d/rest/log")
  if cmp -s "$d/full.checks" "$d/rest.checks" && [ -n "$sf" ] && [ "$sf" = "$sr" ]; then
    echo "PASS checkpoint $scheme schedule: the $n checks after step $step equal ($nm rebalanced), summary \"$sf\" equal"
  else
    echo "FAIL checkpoint $scheme schedule: checks after step $step: $(wc -l <"$d/full.checks") uninterrupted, $(wc -l <"$d/rest.checks") restarted, first difference: $(diff "$d/full.checks" "$d/rest.checks" | sed -n 2p); summary \"$sf\" vs \"$sr\""
  fi
done
ck=$(ls "$W"/frequent/half/out/*checkpoint*.h5 | tail -n 1)
for grid in "1 x" "2 y"; do # another rank count; the same on another process grid
  set -- $grid
  np=$1; procs="-da_processors_x 1 -da_processors_y 1 -da_processors_z 1"; [ "$2" = y ] && procs="-da_processors_x 1 -da_processors_y 2 -da_processors_z 1"
  out=$(cd "$W" && mpiexec -n "$np" "$S" $SCENE $procs -lb_scheme frequent -lb_interval 700 -dem_t_end $T -io_interval 0 -io_dir "other$np" -restart "$ck" 2>&1); rc=$?
  line=$(printf '%s\n' "$out" | grep "^lb: restart on $np ranks .*: default cuts, not the checkpoint's")
  if [ "$rc" -eq 0 ] && [ -n "$line" ] && printf '%s\n' "$out" | grep -q '^done:'; then echo "PASS another layout ($np ranks, $procs): runs to the end, \"$line\""
  else echo "FAIL another layout ($np ranks, $procs): exit $rc, no line on the default cuts or no end; got: $(printf '%s' "$out" | tail -n 3)"; fi
done
