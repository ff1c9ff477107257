#!/bin/sh
# Load-balancing benchmark (Golshan & Blais 2022, Figure 10): the silo of cases/silo
# discharging on 2 ranks split along z (the DMDA's uniform cut sits at z = 0.2 m, just above the
# hopper, so at the start the upper rank owns nearly every bead and the lower one the empty bin),
# run with -lb_scheme none, once, frequent and dynamic from the same filled state, for
# BB_T seconds of discharge (default 3 s: the full 30 s discharge takes hours here). Prints, per
# scheme, the wall time of the loop, the number of rebalances, the time spent in checks and moves,
# and the ratio to none. Repeats the series BB_REPEAT times (default 1), interleaved so that a
# change of machine load hits every scheme alike; quote medians. The filled state is
# out/silo/fill_000001.h5 (tools/silo.sh makes it; BB_FILL names another). Not a test.
set -eu
cd "$(dirname "$0")/.."
[ "$(id -u)" -eq 0 ] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
T=${BB_T:-3}
FILL=${BB_FILL:-out/silo/fill_000001.h5}
REPEAT=${BB_REPEAT:-1}
OUT=${BB_OUT:-bench-out/balance}
[ -f "$FILL" ] || { echo "bench_balance: no filled silo at $FILL: run tools/silo.sh first (or set BB_FILL)" >&2; exit 1; }
make -s bin/sable
mkdir -p "$OUT"
COMMON="-options_file cases/silo/discharge.opts -dem_init_file $FILL -dem_t_end $T -dem_progress_interval 0 -io_interval 0 -io_dir $OUT -domain_cell 0.02 -da_processors_x 1 -da_processors_y 1 -da_processors_z 2"
res="$OUT/results.txt"
: > "$res"
for r in $(seq 1 "$REPEAT"); do
  for s in none once frequent dynamic; do
    case $s in
      none) extra="" ;;
      once) extra="-lb_scheme once -lb_step 0" ;;
      frequent) extra="-lb_scheme frequent -lb_interval_time 0.1" ;;
      dynamic) extra="-lb_scheme dynamic -lb_interval_time 0.1 -lb_threshold 0.3" ;;
    esac
    mpiexec -n 2 bin/sable $COMMON $extra -lb_verbose 0 > "$OUT/$s.$r.log" 2>&1
    wall=$(sed -n 's/^done: t = .* steps in \([0-9.]*\) s.*/\1/p' "$OUT/$s.$r.log")
    reb=$(sed -n 's/^load balancing: .*, \([0-9]*\) rebalances, \([0-9.e+-]*\) s in checks.*/\1 \2/p' "$OUT/$s.$r.log")
    echo "$r $s $wall ${reb:-0 0}" | tee -a "$res"
  done
done
median() { grep " $1 " "$res" | awk '{ print $3 }' | sort -n | awk '{ a[NR] = $1 } END { print (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2 }'; }
ref=$(median none)
printf '\n| scheme | wall time (s, median of %s) | rebalances | checks + moves (s) | / none |\n|---|---|---|---|---|\n' "$REPEAT"
for s in none once frequent dynamic; do
  m=$(median $s)
  last=$(grep " $s " "$res" | tail -n 1)
  echo "$s $m $ref $last" | awk '{ printf "| %s | %.1f | %s | %s | %.2f |\n", $1, $2, $7, $8, $2 / $3 }'
done
