#!/bin/sh
# The same coupled run on 1, 2 and 4 ranks gives the same answer: a disordered frozen bed (the
# packed-bed case with a jittered lattice of spacing 1.2 d; 3 x 3 x 20 cells, split along z on
# 2 and 4 ranks, so spheres near a rank boundary spread into the neighbour's cells) must give
# the same pressure gradient and mean porosity to 1e-9 relative (the Poisson tolerance is 1e-8
# relative to the residual; the steady state is reached in a few steps; the run prints dp/L and
# the porosity to 15 digits).
# Then a short fluidized bed (the make-run case: bi-periodic sides, 80 fluid steps at 3 U_mf
# from a touching lattice) on process grids 1x1x1, 2x1x1 and 1x1x4 (rank boundaries at x = 4 and
# at z = 12, inside the bed: particles migrate, contacts cross through ghost particles, kernels
# spread into the neighbour's cells) must give the same mean pressure drop and particle drag to
# 1e-7 relative (the Poisson tolerance is 1e-8; longer runs drift apart as any chaotic flow).
cd "$(dirname "$0")/../.."
[ "$(id -u)" -eq 0 ] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1
out=$(mktemp)
trap 'rm -rf "$out" "$out.d"' EXIT
opts="-options_file cases/packed_bed/packed_bed.opts -io_dir $out.d -domain_hi 3.6,3.6,24 -da_grid_x 3 -da_grid_y 3 -da_grid_z 20 -dem_lattice 3,3,15 -dem_lattice_spacing 1.2 -dem_lattice_origin 0,0,3 -dem_lattice_jitter 1 -dem_seed 7 -cpl_probe_z 6,18 -cpl_t_end 3 -cpl_progress_interval 0"
ref=""
for n in 1 2 4; do
  if [ "$n" -eq 1 ]; then ${BIN:-bin}/sable $opts >"$out" 2>&1; else mpiexec -n $n ${BIN:-bin}/sable $opts >"$out" 2>&1; fi
  rc=$?
  line=$(grep '^packed bed:' "$out")
  dp=$(echo "$line" | sed -n 's/.*dp\/L \([-0-9.e+]*\) Pa\/m, porosity \([0-9.]*\),.*/\1 \2/p')
  if [ "$rc" -ne 0 ] || [ -z "$dp" ]; then echo "FAIL cpl_ranks_np$n: exit $rc"; tail -n 3 "$out" | sed 's/^/    /'; continue; fi
  if [ -z "$ref" ]; then ref=$dp; continue; fi # the 1-rank reference: no check of its own
  echo "$ref $dp" | awk -v n=$n -v b1=1e-9 -v b2=1e-12 '{ e1 = ($1 - $3) / $1; if (e1 < 0) e1 = -e1; e2 = ($2 - $4) / $2; if (e2 < 0) e2 = -e2;
    ok = (e1 < b1 && e2 < b2); printf "%s cpl_ranks_np%d: dp/L rel. diff %.2e (< %g), porosity rel. diff %.2e (< %g) vs 1 rank\n", ok ? "PASS" : "FAIL", n, e1, b1, e2, b2 }'
done

opts="-options_file cases/fluidized_bed/small.opts -io_dir $out.d -cpl_t_end 2 -cpl_progress_interval 0 -io_interval 0 -da_processors_y 1"
ref=""
for grid in 1,1,1 2,1,1 1,1,4; do
  px=${grid%%,*}; pz=${grid##*,}; n=$((px * pz)); label=$(echo "$grid" | tr , x)
  if [ "$n" -eq 1 ]; then ${BIN:-bin}/sable $opts >"$out" 2>&1; else mpiexec -n $n ${BIN:-bin}/sable $opts -da_processors_x $px -da_processors_z $pz >"$out" 2>&1; fi
  rc=$?
  v=$(sed -n 's/^column: pressure drop \/ bed buoyant weight per area \([0-9.]*\), drag on the particles \/ buoyant weight \([0-9.]*\).*/\1 \2/p' "$out")
  if [ "$rc" -ne 0 ] || [ -z "$v" ]; then echo "FAIL cpl_ranks_fluidized_$label: exit $rc"; tail -n 3 "$out" | sed 's/^/    /'; continue; fi
  if [ -z "$ref" ]; then ref=$v; continue; fi # the 1-rank reference
  echo "$ref $v" | awk -v g=$label -v b=1e-7 '{ e1 = ($1 - $3) / $1; if (e1 < 0) e1 = -e1; e2 = ($2 - $4) / $2; if (e2 < 0) e2 = -e2;
    ok = (e1 < b && e2 < b); printf "%s cpl_ranks_fluidized_%s: dp/W rel. diff %.2e, drag/W rel. diff %.2e (< %g) vs 1 rank\n", ok ? "PASS" : "FAIL", g, e1, e2, b }'
done

# Fast spheres in the fully periodic box (tests/coupling/test_conserve.opts at 10 d/s with 40 DEM
# steps per fluid step): between list rebuilds a sphere crosses a periodic side, where a rank
# still owns it on the far side; its kernel must land in that rank's ghost cells of the other
# side. On 2 (z cut) and 4 (y and z cuts) ranks every sphere's position (nearest periodic image)
# and velocity must equal the 1-rank run's within 1e-8 of the initial speed (the Poisson
# tolerance, 1e-8, bounds the difference).
opts="-options_file tests/coupling/test_conserve.opts -dem_lattice_speed 10 -cpl_substeps 40 -cpl_t_end 0.8 -io_interval 0.8 -cpl_progress_interval 0"
${BIN:-bin}/sable $opts -io_dir "$out.d/1" >"$out" 2>&1 || { echo "FAIL cpl_ranks_periodic_np1: exit $?"; tail -n 3 "$out" | sed 's/^/    /'; }
for n in 2 4; do
  mpiexec -n $n ${BIN:-bin}/sable $opts -io_dir "$out.d/$n" >"$out" 2>&1
  rc=$?
  if [ "$rc" -ne 0 ]; then echo "FAIL cpl_ranks_periodic_np$n: exit $rc"; tail -n 3 "$out" | sed 's/^/    /'; continue; fi
  /usr/bin/python3 - "$out.d/1/sable_000001.h5" "$out.d/$n/sable_000001.h5" $n <<'PY'
import sys
import h5py
import numpy as np
a, b = h5py.File(sys.argv[1], "r"), h5py.File(sys.argv[2], "r")
ia, ib = np.argsort(a["particles/id"][()]), np.argsort(b["particles/id"][()])
dx = np.abs(a["particles/position"][()][ia] - b["particles/position"][()][ib])
dx = np.minimum(dx, 8 - dx).max() / 10 # box side 8; per unit initial speed
dv = np.abs(a["particles/velocity"][()][ia] - b["particles/velocity"][()][ib]).max() / 10
ok = len(ia) == 64 and len(ib) == 64 and dx < 1e-8 and dv < 1e-8
print("%s cpl_ranks_periodic_np%s: %d spheres, position diff %.2e, velocity diff %.2e (< 1e-8 x speed) vs 1 rank" % ("PASS" if ok else "FAIL", sys.argv[3], len(ib), dx, dv))
PY
done
