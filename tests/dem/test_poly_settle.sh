#!/bin/sh
# A polydisperse bed settling: 300 glass spheres of lognormal diameters (d50 10 mm, sigma_g 1.3,
# cut to 0.5-2 d50; tools/poly_bed.py) dropped from a lattice into a box, each keeping its own
# radius (-dem_init_file_radii auto: 300 distinct radii are more than shapes can hold), friction,
# linear law. References are other runs of the same
# physics and conservation:
#   -dem_deterministic on 1 and 2 ranks: the final frames equal bit for bit, particle by particle
#     (by id: position, velocity, angular velocity, radius);
#   count and id checksum at the end equal the file's; every sphere's radius is the file's, bitwise;
#   a checkpoint at T/2 continued with -restart (2 ranks) ends bitwise on the uninterrupted run;
#   the bed has come to rest: kinetic energy per particle below 1e-4 m g d50 (dropped from up to
#     14 d50, it had about 7 m g d50 on its way down);
#   a bad radius in a file (0) is refused with one line naming the file and the row.
cd "$(dirname "$0")/../.." || exit 1
S=$(pwd)/${BIN:-bin}/sable
[ "$(id -u)" -eq 0 ] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1
W=$(mktemp -d)
trap 'rm -rf "$W"' EXIT
tools/poly_bed.py "$W/bed.h5" 300 0.01 1.3 0.15 0.15 0 >/dev/null || echo "FAIL poly settle: tools/poly_bed.py exited with status $?"
SCENE="-domain_lo 0,0,0 -domain_hi 0.15,0.15,0.2 -dem_box 0,0,0,0.15,0.15,0.2 -dem_radius 0.005 -dem_density 2500 -dem_kn 2e4 -dem_restitution 0.5 -dem_friction 0.3 -dem_dt_tc 0.05 -dem_init_file $W/bed.h5 -dem_deterministic -dem_check_every 100 -dem_progress_interval 0"
T=0.6
H=0.3
run() { # np, dir, args...
  rnp=$1; rd=$2; shift 2
  mkdir -p "$rd"
  (cd "$rd" && mpiexec -n "$rnp" "$S" $SCENE -io_dir out "$@" >log 2>&1) || echo "FAIL poly settle: the run in $(basename "$rd") on $rnp rank(s) exited with status $?: $(grep error "$rd/log" | head -n 2)"
}
run 1 "$W/n1" -dem_t_end $T -io_interval $T
run 2 "$W/n2" -dem_t_end $T -io_interval $T -da_processors_z 2
run 2 "$W/half" -dem_t_end $H -io_interval 0 -io_checkpoint_interval $H -da_processors_z 2
ck=$(sed -n 's/^checkpoint: //p' "$W/half/log" | tail -n 1)
run 2 "$W/rest" -dem_t_end $T -io_interval $T -da_processors_z 2 -restart "../half/$ck"
/usr/bin/python3 - "$W" <<'PY'
import sys, glob, h5py, numpy as np
w = sys.argv[1]
def last(d):
    f = sorted(glob.glob(w + "/" + d + "/out/sable_*.h5"))
    return h5py.File(f[-1], "r") if f else None
def by_id(f):
    o = np.argsort(f["particles/id"][()].ravel())
    return {k: f["particles/" + k][()][o] for k in ("id", "position", "velocity", "angular_velocity", "radius")}
init = h5py.File(w + "/bed.h5", "r")
ids0, r0 = init["particles/id"][()].ravel(), init["particles/radius"][()].ravel()
a, b, c = last("n1"), last("n2"), last("rest")
if a is None or b is None or c is None:
    print("FAIL poly settle: a final frame is missing (1 rank %s, 2 ranks %s, restart %s)" % (a is not None, b is not None, c is not None))
    sys.exit(0)
A, B, C = by_id(a), by_id(b), by_id(c)
diff = [k for k in A if A[k].tobytes() != B[k].tobytes()]
print(("PASS" if not diff else "FAIL") + " poly settle deterministic, 1 vs 2 ranks: %d of 5 per-particle datasets differ (by id, bitwise)%s" % (len(diff), ": " + " ".join(diff) if diff else ""))
diff = [k for k in B if B[k].tobytes() != C[k].tobytes()]
print(("PASS" if not diff else "FAIL") + " poly settle restart at t=0.3 s, 2 ranks: %d of 5 per-particle datasets differ from the uninterrupted run (bitwise)%s" % (len(diff), ": " + " ".join(diff) if diff else ""))
n, s = len(A["id"]), A["id"].sum()
print(("PASS" if n == len(ids0) and s == ids0.sum() else "FAIL") + " poly settle count and id checksum kept: %d particles, checksum %.0f (file: %d, %.0f)" % (n, s, len(ids0), ids0.sum()))
o = np.argsort(ids0)
same = A["radius"].ravel().tobytes() == r0[o].tobytes()
print(("PASS" if same else "FAIL") + " poly settle radii kept: %d distinct radii, every one the file's bitwise" % len(np.unique(r0)))
m = 2500 * 4 / 3 * np.pi * A["radius"].ravel() ** 3
ke = 0.5 * (m * (A["velocity"] ** 2).sum(axis=1)).sum() / n
ref = 2500 * np.pi / 6 * 0.01 ** 3 * 9.81 * 0.01
print(("PASS" if ke < 1e-4 * ref else "FAIL") + " poly settle at rest (dropped from up to 14 d50): kinetic energy per particle / (m g d of a d50 sphere): %.3g (bound < 1e-4)" % (ke / ref))
PY
/usr/bin/python3 -c "import h5py, sys; f = h5py.File(sys.argv[1], 'a'); r = f['particles/radius']; r[7] = 0; f.close()" "$W/bed.h5"
out=$(cd "$W" && "$S" $SCENE -dem_t_end 0 -io_interval 0 -io_dir bad 2>&1 >/dev/null); rc=$?
lines=$(printf '%s\n' "$out" | grep -c 'sable: error')
if [ "$rc" -ne 0 ] && [ "$lines" -eq 1 ] && printf '%s' "$out" | grep -q "row 7 of /particles/radius, 0.*must be > 0"; then
  echo "PASS poly settle bad radius in the file: exit $rc, \"$(printf '%s' "$out" | grep 'sable: error')\""
else
  echo "FAIL poly settle bad radius in the file: exit $rc, $lines error lines; got: $out"
fi
