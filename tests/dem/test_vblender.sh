#!/bin/sh
# The V-blender scene (cases/vblender) on 2 ranks while the V turns: 500 beads placed at rest in
# the arms by the case's two sources (one batch each), the V turning from t = 0 at a constant
# 60 rad/s about its horizontal axis (23 deg in 500 steps of 1.35e-5 s), with the particle
# count and id checksum checked every 10 steps (-dem_check_every: a lost or duplicated particle
# stops the run). Checks: the run ends with all 500 beads and the id sum 0 + ... + 499; and no
# centre leaves the V: every frame turned back by the mesh's angle (60 t) lies inside the two
# mitred arms of the tool's geometry (tests/common/vblender_check.py: the largest depth outside,
# in radii, must be <= 0.1, the overlap a wall contact may reach), which fails if the
# particles did not follow the V (1.4 radii out when the V is taken at rest) or the sense of its
# rotation (9.8 radii).
cd "$(dirname "$0")/../.." || exit 1
S=$(pwd)/${BIN:-bin}/sable
[ "$(id -u)" -eq 0 ] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1
W=$(mktemp -d)
trap 'rm -rf "$W"' EXIT
W0=60
mpiexec -n 2 "$S" -options_file cases/vblender/vblender.opts -dem_mesh_0_omega_table 0,$W0,1,$W0 \
  -dem_insert_0_rate 1e5 -dem_insert_0_count 250 -dem_insert_1_rate 1e5 -dem_insert_1_count 250 \
  -dem_t_end 0.00675 -dem_check_every 10 -io_dir "$W/out" -io_prefix vb -io_interval 0.00135 -dem_progress_interval 0 >"$W/log" 2>&1
rc=$?
if [ $rc -ne 0 ]; then
  echo "FAIL vblender 2 ranks: exit $rc; $(grep -m 2 'error' "$W/log")"
  exit 0
fi
set -- $(tests/common/vblender_check.py "$W/out" 0.01 0.04 80 0.0145044476 $W0 vb)
nf=$1 n=$2 ids=$3 worst=$4
steps=$(sed -n 's/^done: .* \([0-9]*\) steps in.*/\1/p' "$W/log")
if [ "$n" -eq 500 ] && [ "$ids" -eq 124750 ] && [ "${steps:-0}" -ge 500 ]; then
  echo "PASS vblender count and ids on 2 ranks: $n beads, id sum $ids after $steps steps turning (500, 124750; checked every 10 steps)"
else
  echo "FAIL vblender count and ids on 2 ranks: $n beads, id sum $ids after ${steps:-?} steps (500, 124750)"
fi
if awk -v w="$worst" 'BEGIN { exit !(w <= 0.1 && w > -50) }' && [ "$nf" -ge 5 ]; then
  echo "PASS vblender particles inside the V: largest depth outside $worst radii over $nf frames (<= 0.1)"
else
  echo "FAIL vblender particles inside the V: largest depth outside $worst radii over $nf frames (<= 0.1)"
fi
