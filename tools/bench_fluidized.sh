#!/bin/sh
# Coupled benchmark: the fluidized bed of cases/fluidized_bed/bed.opts (4,800
# spheres, 3,000 cells, 2 DEM steps per fluid step) from t = 0 to 12 (1,008 fluid steps), on 1
# and 2 ranks, 3 runs each. From -log_view (max over ranks): DEM = CplDemSubsteps (all DEM work
# with its exchange), fluid = FluidPredict + FluidPoisson + FluidCorrect, coupling = CplProject +
# CplDrag + CplExchange, in ns per particle per fluid step; the medians of the 3 runs, the wall
# time and the ratio (fluid + coupling) / DEM (at most 1: the fluid and coupling no dearer than the DEM).
#   tools/bench_fluidized.sh            1 and 2 ranks
#   RANKS=1 EXTRA="-fluid_poisson_pc_lag 0" tools/bench_fluidized.sh
set -eu
cd "$(dirname "$0")/.."
RANKS=${RANKS:-1 2}
EXTRA=${EXTRA:-}
[ "$(id -u)" -eq 0 ] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
O=bench-out/fluidized; mkdir -p $O
NP=4800
median() { sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }
# event time (max over ranks, seconds) summed over the named events of one -log_view
ev() { f=$1; shift; for e in "$@"; do awk -v e="$e" '$1==e {print $4}' "$f"; done | awk '{s+=$1} END {printf "%.6f\n", s}'; }
echo "| ranks | DEM ns | fluid ns | coupling ns | (fluid + coupling) / DEM | wall (s) | ms per fluid step |"
echo "|---|---|---|---|---|---|---|"
for r in $RANKS; do
  for k in 1 2 3; do
    log=$O/np$r.$k.log
    mpiexec -n "$r" bin/sable -options_file cases/fluidized_bed/bed.opts -cpl_t_end 12 -io_interval 0 -cpl_progress_interval 0 -log_view $EXTRA > "$log"
  done
  steps=$(sed -n 's/^done: .*, \([0-9]*\) fluid steps in .*/\1/p' $O/np$r.1.log)
  dem=$(for k in 1 2 3; do ev $O/np$r.$k.log CplDemSubsteps; done | median)
  flu=$(for k in 1 2 3; do ev $O/np$r.$k.log FluidPredict FluidPoisson FluidCorrect; done | median)
  cpl=$(for k in 1 2 3; do ev $O/np$r.$k.log CplProject CplDrag CplExchange; done | median)
  wall=$(for k in 1 2 3; do sed -n 's/^done: .* fluid steps in \([0-9.]*\) s.*/\1/p' $O/np$r.$k.log; done | median)
  awk -v r="$r" -v d="$dem" -v f="$flu" -v c="$cpl" -v n="$NP" -v s="$steps" -v w="$wall" 'BEGIN {
    k = 1e9 / (n * s); printf "| %d | %.0f | %.0f | %.0f | %.1f | %.2f | %.2f |\n", r, d * k, f * k, c * k, (f + c) / d, w, 1000 * w / s }'
done
