#!/bin/sh
# Decomposition benchmark: on 2 ranks, Sable's default decomposition (chosen from the particles,
# the "decomposition:" line) against every hand-chosen process grid (-da_processors_x/y/z 2;
# PETSc's own default, the decomposition before Sable chose one, is the z split in all three
# tall boxes). Cases: the settled bed of cases/settle (10,000 spheres, 2,000 steps from a settled
# frame), the silo fill of cases/silo (14,000 spheres, its first 2,000 steps) and the coupled
# fluidized bed of cases/fluidized_bed/bed.opts (4,800 spheres, 252 fluid steps, 2 DEM steps
# each) and the SI bubbling bed of cases/bubbling_bed (3,200 beads, its first 0.1 s: 2,000 fluid
# steps of 5 DEM steps; its column is 2 cells deep in y, so no y split). Medians of 3 runs, the variants alternating within each round; microseconds of wall
# time per particle-step, and the default over the best hand-chosen grid.
#   tools/bench_decomp.sh                  (SETTLED=frame.h5 reuses a settled 10k bed)
set -eu
cd "$(dirname "$0")/.."
[ "$(id -u)" -eq 0 ] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
O=bench-out/decomp; mkdir -p $O
median() { sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }
SETTLED=${SETTLED:-}
if [ -z "$SETTLED" ]; then
  SETTLED=$(ls bench-out/settle_10k/*.h5 2>/dev/null | tail -n 1 || true)
fi
if [ -z "$SETTLED" ]; then
  bin/sable -options_file cases/settle/settle.opts -dem_t_end 0.8 -io_interval 0.8 -dem_progress_interval 0 -io_dir $O/settled > $O/settled.log
  SETTLED=$(ls $O/settled/*.h5 | tail -n 1)
fi
SETTLE="-options_file cases/settle/settle.opts -dem_lattice 0,0,0 -dem_init_file $SETTLED -dem_t_end 0.02 -dem_progress_interval 0 -io_interval 0"
SILO="-options_file cases/silo/fill.opts -dem_t_end 0.02 -dem_progress_interval 0 -io_interval 0"
BED="-options_file cases/fluidized_bed/bed.opts -cpl_t_end 3 -cpl_progress_interval 0 -io_interval 0"
SIBED="-options_file cases/bubbling_bed/bubbling.opts -cpl_t_end 0.1 -cpl_progress_interval 0 -io_interval 0 -mon_interval 0"
CASES=${CASES:-settle silo bed sibed}
VARIANTS="default x y z"
args() { case $1 in default) echo "" ;; x) echo "-da_processors_x 2" ;; y) echo "-da_processors_y 2" ;; z) echo "-da_processors_z 2" ;; esac; }
ROUNDS=${ROUNDS:-3}
for k in $(seq "$ROUNDS"); do
  for c in $CASES; do
    case $c in settle) A=$SETTLE ;; silo) A=$SILO ;; bed) A=$BED ;; sibed) A=$SIBED ;; esac
    for v in $VARIANTS; do
      [ $c = sibed ] && [ $v = y ] && continue
      # shellcheck disable=SC2046,SC2086
      mpiexec -n 2 bin/sable $A $(args $v) > $O/$c.$v.$k.log 2>&1 || { echo "$c $v failed: $O/$c.$v.$k.log"; exit 1; }
    done
  done
done
# us per particle-step of one log: N from the case, steps from the done line (DEM steps)
ups() {
  case $1 in
    settle) sed -n 's/^done: .*, \([0-9]*\) steps in \([0-9.]*\) s.*/\1 \2/p' "$2" | awk '{printf "%.6f\n", $2 * 1e6 / ($1 * 10000)}' ;;
    silo) sed -n 's/^done: .*, \([0-9]*\) steps in \([0-9.]*\) s.*/\1 \2/p' "$2" | awk '{printf "%.6f\n", $2 * 1e6 / ($1 * 14000)}' ;;
    bed) sed -n 's/^done: .*, \([0-9]*\) fluid steps in \([0-9.]*\) s.*/\1 \2/p' "$2" | awk '{printf "%.6f\n", $2 * 1e6 / (2 * $1 * 4800)}' ;;
    sibed) sed -n 's/^done: .*, \([0-9]*\) fluid steps in \([0-9.]*\) s.*/\1 \2/p' "$2" | awk '{printf "%.6f\n", $2 * 1e6 / (5 * $1 * 3200)}' ;;
  esac
}
echo "2 ranks, us per particle-step (wall), median of $ROUNDS; default = Sable's choice, x/y/z = -da_processors_x, _y or _z 2 (z: PETSc's default)"
echo "| case | default | x | y | z | default / best hand-chosen | default chose |"
echo "|---|---|---|---|---|---|---|"
for c in $CASES; do
  row="| $c"
  m_y=1e30
  for v in $VARIANTS; do
    if [ $c = sibed ] && [ $v = y ]; then row="$row | -"; continue; fi
    m=$(for k in $(seq "$ROUNDS"); do ups $c $O/$c.$v.$k.log; done | median)
    eval "m_$v=$m"
    row="$row | $(printf '%.4f' "$m")"
  done
  best=$(printf '%s\n%s\n%s\n' "$m_x" "$m_y" "$m_z" | sort -g | head -n 1)
  chose=$(sed -n 's/^decomposition: \([0-9]* x [0-9]* x [0-9]*\) ranks, \([^:]*\):.*/\1, \2/p' $O/$c.default.1.log)
  echo "$row | $(echo "$m_default / $best" | bc -l | xargs printf '%.3f') | $chose |"
done
