#!/bin/sh
# Exact checkpoints with mesh walls (walls_mesh.c): a run to T and a run to T/2 that writes a
# checkpoint then continued with -restart to T end with bitwise the same final frame (every
# dataset compared with h5py), on 1 and 2 ranks, for a bed falling into a closed mesh box (3 x 3
# cells of 2 triangles per side; linear and hertz laws, the hertz one with the mesh's own Young's
# modulus and friction) and into the same box turning about its vertical axis after an
# -dem_mesh_0_omega_table (the pose is a function of time; its travel, local triangles,
# candidates and tangential-spring slots are in the checkpoint). A 2-rank checkpoint continues on
# 1 and 4 ranks (the remap), bitwise with -dem_deterministic.
cd "$(dirname "$0")/../.." || exit 1
S=$(pwd)/${BIN:-bin}/sable
[ "$(id -u)" -eq 0 ] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1
W=$(mktemp -d)
trap 'rm -rf "$W"' EXIT
tests/common/box_stl.py "$W/box.stl" 0,0,0,0.1449,0.1449,0.24633 3
BED="-dem_radius 0.0069 -dem_density 2500 -dem_restitution 0.75 -dem_friction 0.3 -dem_dt 1e-5 -dem_lattice 8,8,6 -dem_lattice_spacing 0.01449 -dem_lattice_speed 0.05 -dem_progress_interval 0 -dem_mesh_0_file $W/box.stl"
STATIC="-domain_lo 0,0,0 -domain_hi 0.1449,0.1449,0.24633 $BED"
TURN="-domain_lo -0.035,-0.035,0 -domain_hi 0.1799,0.1799,0.24633 $BED -dem_lattice_origin 0,0,0 -dem_mesh_0_omega_table 0,0,0.05,3,0.2,-1 -dem_mesh_0_axis_point 0.07245,0.07245,0 -dem_mesh_0_axis 0,0,1"
T=0.2
H=0.1
run() { # np, dir, args...
  rnp=$1; rd=$2; shift 2
  mkdir -p "$rd"
  (cd "$rd" && mpiexec -n "$rnp" "$S" -io_dir out "$@" >log 2>&1)
}
for c in static.linear static.hertz turn.linear; do
  case $c in static.*) SC=$STATIC ;; *) SC=$TURN ;; esac
  case $c in *hertz) M="-dem_contact_law hertz -dem_youngs_modulus 5e6 -dem_mesh_0_youngs_modulus 2e7 -dem_mesh_0_friction 0.5" ;; *) M="-dem_contact_law linear -dem_kn 7.2e5" ;; esac
  for np in 1 2; do
    d=$W/$c.$np
    run "$np" "$d/full" $SC $M -dem_t_end $T -io_interval $T
    run "$np" "$d/half" $SC $M -dem_t_end $H -io_interval 0 -io_checkpoint_interval $H
    ck=$(sed -n 's/^checkpoint: //p' "$d/half/log" | tail -n 1)
    run "$np" "$d/rest" $SC $M -dem_t_end $T -io_interval $T -restart "../half/$ck"
    a=$(ls "$d/full/out/"sable_*.h5 2>/dev/null | tail -n 1); b=$(ls "$d/rest/out/"sable_*.h5 2>/dev/null | tail -n 1)
    if [ -z "$ck" ] || [ -z "$a" ] || [ -z "$b" ]; then
      echo "FAIL mesh checkpoint $c np=$np: a run failed; $(cat "$d"/*/log | grep 'error' | head -n 2)"
      continue
    fi
    set -- $(tests/common/frames_equal.py "$a" "$b")
    if [ "$1" -gt 0 ] && [ "$2" -eq 0 ]; then
      echo "PASS mesh checkpoint $c np=$np: final frames at t=$T bitwise equal, $1 datasets compared, 0 differing (restart from $ck)"
    else
      echo "FAIL mesh checkpoint $c np=$np: $1 datasets compared, $2 differing: $3 $4 $5"
    fi
  done
done
# another rank count: a 2-rank checkpoint continued on 1 and on 4 ranks (the springs of the mesh
# slots travel with their particles as id-keyed records, checkpoint_remap.c); with
# -dem_deterministic the continued run equals the uninterrupted 2-rank run bitwise, every dataset
# compared by particle id (dropping the mesh springs in the remap moves the bed by 0.46 d)
cat >"$W/cmp.py" <<'PY'
#!/usr/bin/python3
import sys, h5py, numpy as np
a, b = h5py.File(sys.argv[1], "r"), h5py.File(sys.argv[2], "r")
ia, ib = a["particles/id"][()], b["particles/id"][()]
n = len(ia)
if not (len(ib) == n and len(np.unique(ib)) == n and np.array_equal(np.sort(ia), np.sort(ib))):
    print(n, 0, "nan", 1, "particles/id"); sys.exit()
oa, ob = np.argsort(ia), np.argsort(ib)
names = []
a.visit(lambda k: names.append(k) if isinstance(a[k], h5py.Dataset) else None)
diff = []
for k in names:
    x, y = a[k][()], b[k][()] if k in b else None
    if y is None or x.shape != y.shape or x.dtype != y.dtype: diff.append(k); continue
    if x.ndim and x.shape[0] == n and k != "particles/vertex": x, y = x[oa], y[ob]
    if x.tobytes() != y.tobytes(): diff.append(k)
d = 2 * a["particles/radius"][()].max()
dx = np.abs(a["particles/position"][()][oa] - b["particles/position"][()][ob]).max() / d
print(n, 1, "%.3e" % dx, len(diff), " ".join(diff) if diff else "-")
PY
chmod +x "$W/cmp.py"
M="-dem_contact_law linear -dem_kn 7.2e5 -dem_deterministic"
for c in static turn; do
  case $c in static) SC=$STATIC ;; *) SC=$TURN ;; esac
  d=$W/remap.$c
  run 2 "$d/full" $SC $M -dem_t_end $T -io_interval $T
  run 2 "$d/half" $SC $M -dem_t_end $H -io_interval 0 -io_checkpoint_interval $H
  ck=$(sed -n 's/^checkpoint: //p' "$d/half/log" | tail -n 1)
  a=$(ls "$d/full/out/"sable_*.h5 2>/dev/null | tail -n 1)
  for np in 1 4; do
    run "$np" "$d/rest$np" $SC $M -dem_t_end $T -io_interval $T -restart "../half/$ck"
    b=$(ls "$d/rest$np/out/"sable_*.h5 2>/dev/null | tail -n 1)
    if [ -z "$ck" ] || [ -z "$a" ] || [ -z "$b" ]; then
      echo "FAIL mesh checkpoint $c 2 -> $np ranks: a run failed; $(cat "$d"/*/log | grep 'error' | head -n 2)"
      continue
    fi
    set -- $("$W/cmp.py" "$a" "$b")
    if [ "$2" -eq 1 ] && [ "$4" -eq 0 ]; then
      echo "PASS mesh checkpoint $c 2 -> $np ranks (-dem_deterministic): final frame at t=$T bitwise equal to the uninterrupted 2-rank run, every dataset by id; $1 ids, each once"
    else
      echo "FAIL mesh checkpoint $c 2 -> $np ranks: $4 datasets differ ($5), largest position difference $3 d, ids each once: $2"
    fi
  done
done
