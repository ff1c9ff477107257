#!/bin/sh
# Adaptive coupling steps in the program (-fluid_adaptive_dt, coupling/exchange.c): the small
# fluidized bed (384 spheres) on cells of 1 d, coupling steps of 20 DEM steps (0.1), its inlet
# ramped from 0.3054 (3 U_mf) to 1.2 over t = 0..4, -fluid_cfl_max 0.2. The fluid's velocity
# rises until the fixed step breaks the CFL limit:
#  1. without adaptive steps the run stops in one error line that names -fluid_cfl_max and the
#     options that set the step (-cpl_substeps x -dem_dt) and advises -fluid_adaptive_dt;
#  2. with it the run reaches t = 8 in more than 80 steps (some cut below 20 DEM steps) and ends
#     within half a DEM step of -cpl_t_end or one step after it;
#  3. on 1 and 2 ranks, a run to 8 and the run's checkpoint of the first step end past t = 4
#     (-io_checkpoint_interval 4; the steps do not land on 4), continued with -restart to 8, end
#     with bitwise the same final frame (every dataset) and the same "column:" line (its means
#     start at 4, before the checkpoint): the steps depend on the fields only, and the
#     checkpoint holds them. (A run to 4 would end past 4, so its checkpoint's column sums,
#     from 2, do not serve a run to 8, whose window starts at 4: the driver warns, and
#     the means of such a restart start at the checkpoint.)
cd "$(dirname "$0")/../.." || exit 1
S=$(pwd)/${BIN:-bin}/sable
[ "$(id -u)" -eq 0 ] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1
W=$(mktemp -d)
trap 'rm -rf "$W"' EXIT
SCENE="-options_file $(pwd)/cases/fluidized_bed/small.opts -da_grid_x 8 -da_grid_y 4 -da_grid_z 48 -cpl_substeps 20 -fluid_bc_zlo_velocity_table 0,0,0,0.3054,4,0,0,1.2 -fluid_inlet_interpolation linear -fluid_cfl_max 0.2 -cpl_progress_interval 0"
run() { # np, dir, args...
  rnp=$1; rd=$2; shift 2
  mkdir -p "$rd"
  (cd "$rd" && mpiexec -n "$rnp" "$S" $SCENE -io_dir out "$@" >log 2>&1)
}
run 1 "$W/fixed" -cpl_t_end 8 -io_interval 0; rc=$?
e=$(grep -c 'error' "$W/fixed/log")
if [ "$rc" -ne 0 ] && [ "$e" -eq 1 ] && grep 'error' "$W/fixed/log" | grep -q -- '-fluid_cfl_max 0.2: lower dt (-cpl_substeps 20 x -dem_dt 0.005 s) below .* or use -fluid_adaptive_dt'; then
  echo "PASS adaptive: the fixed step stops at the CFL limit in one line naming the step's options: $(grep -o 'CFL number [0-9.]*' "$W/fixed/log")"
else
  echo "FAIL adaptive: the fixed-step run: exit $rc, $e error lines: $(grep error "$W/fixed/log" | head -n 1)"
fi
for np in 1 2; do
  d=$W/bed.$np
  run "$np" "$d/full" -fluid_adaptive_dt -cpl_t_end 8 -io_interval 8
  run "$np" "$d/half" -fluid_adaptive_dt -cpl_t_end 8 -io_interval 0 -io_checkpoint_interval 4
  ck=$(sed -n 's/^checkpoint: //p' "$d/half/log" | head -n 1)
  run "$np" "$d/rest" -fluid_adaptive_dt -cpl_t_end 8 -io_interval 8 -restart "../half/$ck"
  a=$(ls "$d/full/out/"sable_*.h5 2>/dev/null | grep -v checkpoint | tail -n 1); b=$(ls "$d/rest/out/"sable_*.h5 2>/dev/null | grep -v checkpoint | tail -n 1)
  if [ -z "$ck" ] || [ -z "$a" ] || [ -z "$b" ]; then
    echo "FAIL adaptive restart np=$np: a run failed; $(cat "$d"/*/log | grep 'error' | head -n 2)"
    continue
  fi
  set -- $(sed -n 's/^done: t = \([0-9.e+-]*\), \([0-9]*\) fluid steps.*/\1 \2/p' "$d/full/log")
  if [ "$np" -eq 1 ] && [ "$2" -gt 80 ] && awk -v t="$1" 'BEGIN { exit !(t >= 8 - 0.0025 && t < 8.1) }'; then
    echo "PASS adaptive: the run reaches t = $1 in $2 coupling steps (80 at the fixed step), ending within [8 - dt_dem/2, 8 + 0.1)"
  elif [ "$np" -eq 1 ]; then
    echo "FAIL adaptive: the run ended at t = $1 after $2 steps (need > 80 steps, t in [7.9975, 8.1))"
  fi
  set -- $(tests/common/frames_equal.py "$a" "$b")
  if [ "$1" -gt 0 ] && [ "$2" -eq 0 ]; then
    echo "PASS adaptive restart np=$np: final frames bitwise equal, $1 datasets compared, 0 differing (restart from $ck)"
  else
    echo "FAIL adaptive restart np=$np: $1 datasets compared, $2 differing: $3 $4 $5 $6"
  fi
  cf=$(grep '^column:' "$d/full/log"); cr=$(grep '^column:' "$d/rest/log")
  if [ -n "$cf" ] && [ "$cf" = "$cr" ]; then
    echo "PASS adaptive restart summary np=$np: the restarted run's \"column:\" line is the uninterrupted run's"
  else
    echo "FAIL adaptive restart summary np=$np: uninterrupted \"$cf\", restarted \"$cr\""
  fi
done
