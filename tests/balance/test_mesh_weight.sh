#!/bin/sh
# Load balancing with a mesh wall: a particle counts 1 + c_m (its candidate triangles). A static
# lattice of 25 x 5 x 5 spheres (r = 1 mm, no gravity) in a 0.1 x 0.02 x 0.02 m box of 20 x 4 x 4
# cells on 2 ranks split along x, its first column 1.1 mm from a mesh plane of 5,000 triangles
# (tools/make_stl plane, 0.4 mm squares): those 25 spheres each test about 20 triangles.
# With -lb_mesh_cost 0.5 and -lb_scheme frequent, the loads after the first move must equal
# those of the best x cut of W = n_p + 0.5 n_c + 0.02 computed from the frame by brute force
# (tests/balance/mesh_weight.py: closest-point distances < r + skin to every triangle), to the
# 4 digits printed, and that cut must lie on the mesh side of the one without the mesh term.
# With -lb_weight measured the balancer reports a finite, positive measured c_m.
cd "$(dirname "$0")/../.." || exit 1
S=$(pwd)/${BIN:-bin}/sable
[ "$(id -u)" -eq 0 ] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1
W=$(mktemp -d)
trap 'rm -rf "$W"' EXIT
tools/make_stl plane --p0 0.0009,0,0 --p1 0.0009,0.02,0 --p2 0.0009,0,0.02 --n 50 --m 50 -o "$W/plane.stl" >/dev/null
B="-domain_lo 0,0,0 -domain_hi 0.1,0.02,0.02 -da_grid_x 20 -da_grid_y 4 -da_grid_z 4 -da_processors_x 2 -da_processors_y 1 -da_processors_z 1
  -dem_radius 0.001 -dem_density 2500 -dem_kn 1e3 -dem_dt 1e-5 -dem_gravity 0,0,0 -dem_lattice 25,5,5 -dem_lattice_spacing 0.004
  -dem_mesh_0_file $W/plane.stl -dem_t_end 5e-5 -dem_progress_interval 0 -lb_scheme frequent -lb_interval 2"
mpiexec -n 2 "$S" $B -lb_mesh_cost 0.5 -io_interval 5e-5 -io_dir "$W/out" >"$W/log" 2>&1 || echo "FAIL mesh weight run: $(grep -m 1 error "$W/log")"
set -- $(tests/balance/mesh_weight.py "$(ls "$W"/out/sable_*.h5 | head -n 1)" "$W/plane.stl" 0.5)
k=$1 pmin=$2 pmax=$3 nc=$4 k0=$5
set -- $(sed -n 's/^lb: step 3 .*load min\/avg\/max \([0-9.e+]*\)\/[0-9.e+]*\/\([0-9.e+]*\) .*/\1 \2/p' "$W/log")
if awk -v a="$1" -v b="$2" -v p="$pmin" -v q="$pmax" -v k="$k" -v k0="$k0" -v nc="$nc" \
  'BEGIN { e = (a - p) / p; f = (b - q) / q; e = e < 0 ? -e : e; f = f < 0 ? -f : f; exit !(e < 6e-4 && f < 6e-4 && k < k0 && nc > 0) }'; then
  echo "PASS mesh weight moves the cut: loads after the move $1/$2 vs brute force $pmin/$pmax (4 digits; $nc candidates), cut at cell $k of 20 vs $k0 without the mesh term"
else
  echo "FAIL mesh weight moves the cut: loads after the move ${1:-?}/${2:-?} vs brute force $pmin/$pmax, cut $k vs $k0 without the mesh term, $nc candidates"
fi
mpiexec -n 2 "$S" $B -lb_weight measured -io_interval 0 >"$W/logm" 2>&1
cm=$(sed -n 's/.*c_m \([0-9.e+-]*\) per candidate.*/\1/p' "$W/logm" | tail -n 1)
if awk -v c="${cm:-nan}" 'BEGIN { exit !(c + 0 > 0 && c + 0 < 1e3) }'; then
  echo "PASS mesh weight measured: c_m $cm per candidate triangle (finite, > 0)"
else
  echo "FAIL mesh weight measured: c_m '${cm}'; $(grep -m 1 'lb:' "$W/logm")"
fi
