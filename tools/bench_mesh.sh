#!/bin/sh
# Cost of mesh walls (walls_mesh.c): a settled bed of spheres (one rank, linear law with friction,
# r = 5 mm, in a 0.16 x 0.16 x 0.4 m box) run for 0.05 s from the same frame against
#   box        the six analytic planes of -dem_box,
#   mesh12     the same box as one STL of 12 triangles (tests/common/box_stl.py),
#   mesh768    the same box with every side in 8 x 8 cells (768 triangles: several candidates
#              per wall particle, edges crossed),
# alternating the three, N_RUNS times, and reports the median microseconds per particle-step
# (wall time the run reports / (particles x steps)) and the ratio to the box. The bed is dropped
# from a 15 x 15 x 14 lattice and settled for 0.6 s in the analytic box first. Usage:
# tools/bench_mesh.sh [N_RUNS] (default 3). Output in bench-out/mesh/. Last, mesh768 once more
# with -lb_weight measured on one rank: the load balancer's c_m, the time of one candidate
# triangle over that of a particle-step without the mesh contacts (-lb_mesh_cost's default).
set -eu
cd "$(dirname "$0")/.."
[ "$(id -u)" -eq 0 ] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
R=${1:-3}
O=bench-out/mesh
rm -rf $O && mkdir -p $O
median() { sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }
BOX=0,0,0,0.16,0.16,0.4
B="-domain_lo 0,0,0 -domain_hi 0.16,0.16,0.4 -dem_radius 0.005 -dem_density 2500 -dem_kn 2e4 -dem_restitution 0.3 -dem_friction 0.3 -dem_dt 2e-5 -dem_progress_interval 0"
tests/common/box_stl.py $O/box12.stl $BOX 1
tests/common/box_stl.py $O/box768.stl $BOX 8
bin/sable $B -dem_box $BOX -dem_lattice 15,15,14 -dem_lattice_spacing 0.0105 -dem_lattice_jitter 0.3 -dem_t_end 0.6 -io_interval 0.6 -io_dir $O/settle > $O/settle.log
cp "$(ls $O/settle/sable_*.h5 | tail -n 1)" $O/bed.h5
N=$(sed -n 's/^DEM: \([0-9][0-9]*\) spheres.*/\1/p' $O/settle.log)
for r in $(seq "$R"); do
  for c in box mesh12 mesh768; do
    case $c in box) W="-dem_box $BOX" ;; mesh12) W="-dem_mesh_0_file $O/box12.stl" ;; mesh768) W="-dem_mesh_0_file $O/box768.stl" ;; esac
    bin/sable $B $W -dem_init_file $O/bed.h5 -dem_t_end 0.05 -io_interval 0 > $O/run_${c}_$r.log
  done
done
printf "%-8s %12s %8s %s\n" walls "us/p-step" "vs box" "(median of $R; load average at the start: $(cut -d' ' -f1 /proc/loadavg))"
ub=
for c in box mesh12 mesh768; do
  us=$(for r in $(seq "$R"); do sed -n 's/^done: .* \([0-9]*\) steps in \([0-9.]*\) s.*/\2 \1/p' $O/run_${c}_$r.log | awk -v n="${N:-3150}" '{print $1 * 1e6 / ($2 * n)}'; done | median)
  [ -z "$ub" ] && ub=$us
  printf "%-8s %12.4f %8.3f\n" $c "$us" "$(echo "$us $ub" | awk '{print $1 / $2}')"
done | tee $O/results.txt
bin/sable $B -dem_mesh_0_file $O/box768.stl -dem_init_file $O/bed.h5 -dem_t_end 0.05 -io_interval 0 \
  -lb_scheme frequent -lb_weight measured -lb_interval 1000 > $O/run_cm.log
echo "c_m (-lb_weight measured, mesh768, last check): $(sed -n 's/.*c_m \([0-9.e+-]*\) per candidate.*/\1/p' $O/run_cm.log | tail -n 1)" | tee -a $O/results.txt
