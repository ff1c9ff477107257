#!/bin/sh
# Exact checkpoints of the dry scenes beyond spheres in a box, on 1 and 2 ranks: cubes (the convex
# narrow phase and its separating-axis cache), a sinking plate removed after the restart point (and,
# on 2 ranks, one removed before it), a turning drum with co-rotating caps, and a bi-periodic
# column. For each, a run to T and a run to T/2 that writes a checkpoint then continued with
# -restart to T end with bitwise the same final frame (every dataset compared with h5py). The
# column's frames hold positions wrapped into the box along the periodic axes.
cd "$(dirname "$0")/../.." || exit 1
S=$(pwd)/${BIN:-bin}/sable
[ "$(id -u)" -eq 0 ] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1
W=$(mktemp -d)
trap 'rm -rf "$W"' EXIT
# 180 cubes thrown from a randomly oriented lattice into a box: at T/2 they collide and land
CUBES="-domain_lo 0,0,0 -domain_hi 0.14,0.14,0.2 -dem_box 0,0,0,0.14,0.14,0.2 -dem_shape cube -dem_shape_deq 0.0138 -dem_density 2500 -dem_contact_law linear -dem_kn 2e5 -dem_restitution 0.75 -dem_friction 0.3 -dem_dt 2e-5 -dem_lattice 6,6,5 -dem_lattice_spacing 0.02 -dem_lattice_origin 0.02,0.02,0.02 -dem_lattice_random_orientation -dem_lattice_speed 0.3"
# 288 spheres on a plate at z = 0.1 m sinking at 0.1 m/s, removed at t = 0.2 s (after the
# restart point 0.15 s): the bed then falls onto the box's floor
PLATE="-domain_lo 0,0,0 -domain_hi 0.1449,0.1449,0.3 -dem_box 0,0,0,0.1449,0.1449,0.3 -dem_plane_0 0,0,0.1,0,0,1 -dem_plane_0_velocity 0,0,-0.1 -dem_plane_0_remove_time 0.2 -dem_radius 0.0069 -dem_density 2500 -dem_contact_law linear -dem_kn 2e5 -dem_restitution 0.75 -dem_friction 0.3 -dem_dt 2e-5 -dem_lattice 8,8,4 -dem_lattice_spacing 0.01449 -dem_lattice_origin 0.0145,0.0145,0.12 -dem_lattice_speed 0.05"
# 256 beads falling in a drum (radius 0.05 m, axis y, 3 rad/s) between co-rotating caps
DRUM="-domain_lo -0.052,0,-0.052 -domain_hi 0.052,0.03,0.052 -dem_cylinder 0,0,0,0,1,0,0.05 -dem_cylinder_omega 3 -dem_cylinder_caps 0,0.03 -dem_radius 0.003 -dem_density 2500 -dem_contact_law hertz -dem_youngs_modulus 1e7 -dem_poisson_ratio 0.24 -dem_restitution 0.9 -dem_friction 0.3 -dem_dt 4e-5 -dem_lattice 8,4,8 -dem_lattice_spacing 0.0065 -dem_lattice_origin -0.026,0.002,-0.026 -dem_lattice_speed 0.1"
# 216 spheres thrown about in a column periodic along x and y, on a floor (2 ranks: split along x,
# so the periodic images cross ranks)
COLUMN="-domain_lo 0,0,0 -domain_hi 0.0828,0.0828,0.207 -domain_cell 0.0207 -domain_periodic_x -domain_periodic_y -dem_plane_0 0,0,0,0,0,1 -dem_radius 0.0069 -dem_density 2500 -dem_contact_law linear -dem_kn 2e5 -dem_restitution 0.8 -dem_friction 0.5 -dem_dt 2e-5 -dem_lattice 6,6,6 -dem_lattice_spacing 0.0138 -dem_lattice_origin 0.0069,0.0069,0.01 -dem_lattice_speed 0.5"
cat >"$W/wrapped.py" <<'PY'
#!/usr/bin/python3
import sys, h5py
x = h5py.File(sys.argv[1], "r")["particles/position"][()]
lo, hi = [float(v) for v in sys.argv[2].split(",")], [float(v) for v in sys.argv[3].split(",")]
out = sum(int(((x[:, k] < lo[k]) | (x[:, k] >= hi[k])).sum()) for k in (0, 1))
print(len(x), out)
PY
chmod +x "$W/wrapped.py"
run() { # np, dir, args...
  rnp=$1; rd=$2; shift 2
  mkdir -p "$rd"
  (cd "$rd" && mpiexec -n "$rnp" "$S" $SC -dem_progress_interval 0 -io_dir out "$@" >log 2>&1)
}
scene() { # name, T, T/2, np, extra args for 2 ranks
  name=$1; T=$2; H=$3; np=$4; X=""; last=""
  [ "$np" -eq 2 ] && X=$5
  d=$W/$name.$np
  run "$np" "$d/full" $X -dem_t_end "$T" -io_interval "$T"
  run "$np" "$d/half" $X -dem_t_end "$H" -io_interval 0 -io_checkpoint_interval "$H"
  ck=$(sed -n 's/^checkpoint: //p' "$d/half/log" | tail -n 1)
  run "$np" "$d/rest" $X -dem_t_end "$T" -io_interval "$T" -restart "../half/$ck"
  a=$(ls "$d/full/out/"sable_*.h5 2>/dev/null | tail -n 1); b=$(ls "$d/rest/out/"sable_*.h5 2>/dev/null | tail -n 1)
  if [ -z "$ck" ] || [ -z "$a" ] || [ -z "$b" ]; then
    echo "FAIL checkpoint $name np=$np: a run failed; $(cat "$d"/*/log | grep 'error' | head -n 2)"
    return
  fi
  set -- $(tests/common/frames_equal.py "$a" "$b")
  if [ "$1" -gt 0 ] && [ "$2" -eq 0 ]; then
    echo "PASS checkpoint $name np=$np: final frames at t=$T bitwise equal, $1 datasets compared, 0 differing (restart from $ck)"
  else
    echo "FAIL checkpoint $name np=$np: $1 datasets compared, $2 differing: $3 $4 $5"
  fi
  last=$a
}
for np in 1 2; do
  SC=$CUBES
  scene cubes 0.2 0.1 "$np" "-da_processors_x 1 -da_processors_y 1 -da_processors_z 2"
  SC=$PLATE
  scene plate_removal 0.3 0.15 "$np" "-da_processors_x 1 -da_processors_y 1 -da_processors_z 2"
  # the plate was removed between the restart point and the end: had it stayed (at 0.07 m at
  # t = 0.3 s), no centre would be below 0.07 m + r - the overlap, ~0.076 m
  if [ -n "$last" ]; then
    z=$(/usr/bin/python3 -c "import h5py, sys; print('%.4f' % h5py.File(sys.argv[1], 'r')['particles/position'][:, 2].min())" "$last")
    if /usr/bin/python3 -c "import sys; sys.exit(not float(sys.argv[1]) < 0.06)" "$z"; then echo "PASS plate removal np=$np: the lowest sphere is at z = $z m at t = 0.3 s, below the plate's place (< 0.06 m): the plate was gone"
    else echo "FAIL plate removal np=$np: the lowest sphere is at z = $z m at t = 0.3 s, expected < 0.06 m (the plate removed at 0.2 s)"; fi
  fi
  # removed before the restart point (0.1 s): the checkpoint holds the removed flag
  [ "$np" -eq 2 ] && SC=$(printf '%s' "$PLATE" | sed 's/remove_time 0.2/remove_time 0.1/') && scene plate_removed_before 0.3 0.15 2 "-da_processors_x 1 -da_processors_y 1 -da_processors_z 2"
  SC=$DRUM
  scene drum 0.2 0.1 "$np" "-da_processors_x 2 -da_processors_y 1 -da_processors_z 1"
  SC=$COLUMN
  scene periodic_column 0.2 0.1 "$np" "-da_processors_x 2 -da_processors_y 1 -da_processors_z 1"
  if [ -n "$last" ]; then
    set -- $("$W/wrapped.py" "$last" 0,0 0.0828,0.0828)
    if [ "$1" -gt 0 ] && [ "$2" -eq 0 ]; then echo "PASS periodic frame np=$np: $1 positions, all inside [0, 0.0828) m along x and y"
    else echo "FAIL periodic frame np=$np: $2 of $1 positions outside [0, 0.0828) m along x or y"; fi
  fi
done
