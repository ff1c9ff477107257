#!/bin/sh
# Cost of spheres of their own sizes: a settled lognormal bed (d50 10 mm, sigma_g 1.3, cut to
# 0.5-2 d50; tools/poly_bed.py) against a monodisperse bed of the same count and the same
# number-mean diameter, one rank, linear law with friction, in a 0.3 x 0.3 m box. Each bed is
# dropped from a lattice and settled for 1.5 s; the bench then runs 0.05 s from that frame, as
#   lognormal   each sphere its own size (-dem_init_file_radii own: per-pair m*, R*),
#   mono        one shape (-dem_init_file_radii shapes: the path of every scene without own sizes),
#   mono-own    the same spheres through the own-size path (the price of the path alone),
# alternating the three, N_RUNS times, and reports the median microseconds per particle-step
# (wall time the run reports / (particles x steps)) and the contacts per particle (twice the
# particle-particle contacts over the particles, the bed line of the log). Usage:
# tools/bench_poly.sh [N_PARTICLES] [N_RUNS] (default 3000, 5). Output in bench-out/poly/.
set -eu
cd "$(dirname "$0")/.."
[ "$(id -u)" -eq 0 ] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
N=${1:-3000}
R=${2:-5}
O=bench-out/poly
rm -rf $O && mkdir -p $O
median() { sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }
B="-domain_lo 0,0,0 -domain_hi 0.3,0.3,0.6 -dem_box 0,0,0,0.3,0.3,0.6 -dem_radius 0.005 -dem_density 2500 -dem_kn 2e4 -dem_restitution 0.3 -dem_friction 0.3 -dem_dt 2e-5 -dem_progress_interval 0"
tools/poly_bed.py $O/lognormal0.h5 "$N" 0.01 1.3 0.3 0.3 0 > $O/lognormal.txt
tools/poly_bed.py $O/mono0.h5 "$N" 0.01 1.3 0.3 0.3 0 --mono > $O/mono.txt
for b in lognormal mono; do
  bin/sable $B -dem_init_file $O/${b}0.h5 -dem_init_file_radii own -dem_t_end 1.5 -io_interval 1.5 -io_dir $O/settle_$b > $O/settle_$b.log
  cp "$(ls $O/settle_$b/sable_*.h5 | tail -n 1)" $O/$b.h5
done
for r in $(seq "$R"); do
  for c in lognormal mono mono-own; do
    case $c in lognormal) F=lognormal M=own ;; mono) F=mono M=shapes ;; mono-own) F=mono M=own ;; esac
    bin/sable $B -dem_init_file $O/$F.h5 -dem_init_file_radii $M -dem_t_end 0.05 -io_interval 0 > $O/run_${c}_$r.log
  done
done
printf "%-10s %12s %10s %s\n" bed "us/p-step" contacts/p "(median of $R, $N spheres)"
for c in lognormal mono mono-own; do
  us=$(for r in $(seq "$R"); do sed -n 's/^done: .* \([0-9]*\) steps in \([0-9.]*\) s.*/\2 \1/p' $O/run_${c}_$r.log | awk -v n="$N" '{print $1 * 1e6 / ($2 * n)}'; done | median)
  z=$(sed -n 's/^bed: .*coordination number \([0-9.]*\).*/\1/p' $O/run_${c}_1.log)
  printf "%-10s %12.4f %10s\n" $c "$us" "$z"
done | tee $O/results.txt
