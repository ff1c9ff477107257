#!/bin/sh
# Fluid benchmark: cost per cell per time step of a periodic box (3-D Taylor-Green start,
# rho = 1, mu = 1e-3, dt = 0.1 h) at 32^3, 64^3 and 128^3 cells, Poisson to rtol 1e-8 with
# CG + hypre BoomerAMG, on 1 and 2 ranks. Prints a markdown table of medians over the steps
# (the first step, which builds the AMG hierarchy, is excluded and shown apart).
#   tools/bench_fluid.sh                 all sizes, 1 and 2 ranks
#   SIZES="32 64" RANKS=1 tools/bench_fluid.sh
#   EXTRA="-fluid_poisson_pc_hypre_boomeramg_strong_threshold 0.5" tools/bench_fluid.sh
set -eu
cd "$(dirname "$0")/.."
BUILD=${BUILD:-build}
SIZES=${SIZES:-32 64 128}
RANKS=${RANKS:-1 2}
EXTRA=${EXTRA:-}
[ "$(id -u)" -eq 0 ] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
exe="$BUILD/tests/fluid/test_bench"
[ -x "$exe" ] || make -s -j2 "$exe"
echo "| cells | ranks | steps | first step (s) | median step (s) | us / cell / step | core-us / cell / step | median BoomerAMG its (max) |"
echo "|---|---|---|---|---|---|---|---|"
for n in $SIZES; do
  case $n in 32) steps=30 ;; 64) steps=12 ;; *) steps=6 ;; esac
  for r in $RANKS; do
    line=$(mpiexec -n "$r" "$exe" -test_cells "$n" -test_steps "$steps" -fluid_poisson_ksp_rtol 1e-8 $EXTRA | grep '^# bench')
    # "# bench ranks R cells N^3 steps S: first step F s; median step M s, C us per cell per step (x ranks: K); median Poisson its I (max J)"
    echo "$line" | sed -E 's/^# bench ranks ([0-9]+) cells ([0-9]+)\^3 steps ([0-9]+): first step ([0-9.e+-]+) s; median step ([0-9.e+-]+) s, ([0-9.e+-]+) us per cell per step \(x ranks: ([0-9.e+-]+)\); median Poisson its ([0-9.]+) \(max ([0-9]+)\)/| \2^3 | \1 | \3 | \4 | \5 | \6 | \7 | \8 (\9) |/'
  done
done
