#!/bin/sh
# Cost of convex particles against spheres: the settle scene with 10,000 spheres
# (cases/settle/settle.opts), cubes and icosahedra (settle_cubes.opts, settle_icosahedra.opts:
# same count, same volume per particle, random orientations), one rank. For each: microseconds
# per particle-step of the falling phase (the first 2,000 steps from the lattice) and of the
# settled bed (2,000 steps from the state at 0.4 s, when the convex beds have come to rest;
# 0.8 s for the spheres as in tools/bench.sh), median of 3 runs, from the wall time the run
# reports, and the ratio to the spheres. Usage: tools/bench_convex_settle.sh. Output in
# bench-out/convex/.
set -eu
cd "$(dirname "$0")/.."
[ "$(id -u)" -eq 0 ] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
O=bench-out/convex; mkdir -p $O; : > $O/results.txt
N=10000
median() { sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }
steps_time() { sed -n 's/^done: .* steps in \([0-9.]*\) s.*/\1/p'; }
Q="-dem_progress_interval 0 -io_interval 0 -dem_t_end 0.02"
for s in spheres cubes icosahedra; do
  case $s in spheres) F=cases/settle/settle.opts T=0.8 ;; *) F=cases/settle/settle_$s.opts T=0.4 ;; esac
  fall=$(for r in 1 2 3; do bin/sable -options_file $F $Q | steps_time; done | median)
  bin/sable -options_file $F -dem_t_end $T -io_interval $T -io_dir $O/$s -dem_progress_interval 0 > $O/settle_$s.log
  last=$(ls $O/$s/*.h5 | tail -n 1)
  dense=$(for r in 1 2 3; do bin/sable -options_file $F $Q -dem_lattice 0,0,0 -dem_init_file $last | steps_time; done | median)
  echo "$s $(echo "$fall * 1000000 / ($N * 2000)" | bc -l) $(echo "$dense * 1000000 / ($N * 2000)" | bc -l)" >> $O/results.txt
done
awk '{f[$1]=$2; d[$1]=$3} END {for (s in f) printf "%-10s fall %.4f us/particle-step (%.1fx spheres)  dense %.4f us/particle-step (%.1fx spheres)\n", s, f[s], f[s]/f["spheres"], d[s], d[s]/d["spheres"]}' $O/results.txt
