#!/bin/sh
# make bench: the settle scene of cases/settle at 10,000 and 102,400 spheres (the LIGGGHTS peer
# decks' sizes), linear law with history, one rank. Prints microseconds per particle-step for
# the falling phase (the first 2,000 steps from the lattice) and for the settled bed (2,000 steps
# from the state at 0.8 s simulated), median of 3 runs, and the peak memory per particle
# (marginal: the difference of peak RSS between the two sizes over the difference in count);
# then the fluid (tools/bench_fluid.sh), the coupled fluidized bed (tools/bench_fluidized.sh) and
# the checkpoints of 10^5 and 10^6 settled spheres (tools/bench_checkpoint.sh) and the default
# decomposition on 2 ranks against the hand-chosen process grids (tools/bench_decomp.sh, on the
# settled 10k bed of this run when there is one) and a lognormal bed against a monodisperse one
# (tools/bench_poly.sh).
# Usage: tools/bench.sh [sizes], sizes among 10k 100k (default both). Output in bench-out/.
set -eu
cd "$(dirname "$0")/.."
[ "$(id -u)" -eq 0 ] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
O=bench-out; mkdir -p $O; rm -f $O/results.txt
A=0.01449
sizes=${*:-10k 100k}
median() { sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }
steps_time() { sed -n 's/^done: .* steps in \([0-9.]*\) s.*/\1/p'; }
peak_mb() { sed -n 's/.*peak memory \([0-9.]*\) MB.*/\1/p'; }
for s in $sizes; do
  case $s in 10k) NX=20 NY=20 NZ=25 ;; 100k) NX=64 NY=64 NZ=25 ;; *) echo "unknown size $s"; exit 1 ;; esac
  N=$((NX * NY * NZ))
  LX=$(echo "$NX * $A" | bc -l); LY=$(echo "$NY * $A" | bc -l); LZ=$(echo "($NZ + 5) * $A" | bc -l)
  GEO="-domain_lo 0,0,0 -domain_hi $LX,$LY,$LZ -dem_box 0,0,0,$LX,$LY,$LZ -dem_lattice $NX,$NY,$NZ -dem_progress_interval 0"
  fall=$(for r in 1 2 3; do bin/sable -options_file cases/settle/settle.opts $GEO -dem_t_end 0.02 -io_interval 0 | steps_time; done | median)
  # BENCH_REUSE=1 keeps a settled bed from an earlier bench run (the starting state only)
  if [ "${BENCH_REUSE:-0}" != 1 ] || [ ! -f $O/settle_$s/sable_000001.h5 ]; then
    bin/sable -options_file cases/settle/settle.opts $GEO -dem_t_end 0.8 -io_interval 0.8 -io_dir $O/settle_$s > $O/settle_$s.log
  fi
  last=$(ls $O/settle_$s/*.h5 | tail -n 1)
  grep '^bed:' $O/settle_$s.log
  for r in 1 2 3; do
    bin/sable -options_file cases/settle/settle.opts -domain_lo 0,0,0 -domain_hi $LX,$LY,$LZ -dem_box 0,0,0,$LX,$LY,$LZ -dem_lattice 0,0,0 -dem_progress_interval 0 -dem_init_file $last -dem_t_end 0.02 -io_interval 0 > $O/dense_$s.$r.log
  done
  dense=$(cat $O/dense_$s.*.log | steps_time | median)
  mem=$(cat $O/dense_$s.1.log | peak_mb)
  echo "$s $N $(echo "$fall * 1000000 / ($N * 2000)" | bc -l) $(echo "$dense * 1000000 / ($N * 2000)" | bc -l) $mem" >> $O/results.txt
  printf '%s: N = %d  fall %.4f us/particle-step  dense %.4f us/particle-step  peak RSS %s MB\n' $s $N \
    "$(echo "$fall * 1000000 / ($N * 2000)" | bc -l)" "$(echo "$dense * 1000000 / ($N * 2000)" | bc -l)" "$mem"
done
if [ "$(grep -c . $O/results.txt)" -ge 2 ]; then
  awk '$1=="10k"{n1=$2;m1=$5} $1=="100k"{n2=$2;m2=$5} END {if (n2>n1) printf "memory per particle (marginal, 10k -> 100k): %.0f bytes\n", (m2-m1)*1048576/(n2-n1)}' $O/results.txt
fi
[ -x build/tools/bench_fluid ] || [ ! -x tools/bench_fluid.sh ] || tools/bench_fluid.sh
tools/bench_fluidized.sh
tools/bench_checkpoint.sh
tools/bench_decomp.sh
tools/bench_poly.sh
