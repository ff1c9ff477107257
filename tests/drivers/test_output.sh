#!/bin/sh
# Output and restart: a short settle run writes HDF5 frames and an XDMF index (well-formed XML
# that lists every frame), leaves no temporary file, and a run started from its last frame
# (-dem_init_file) holds the same particles (count and id checksum) with the same positions; an
# edited frame with a repeated id or a zero quaternion is refused, and a lattice added to a
# file continues after its ids; a run whose end is off the output grid still writes its final
# state; along periodic axes every frame holds its positions wrapped into the box.
cd "$(dirname "$0")/../.." || exit 1
D=$(mktemp -d); trap 'rm -rf "$D"' EXIT
OPTS="-domain_lo 0,0,0 -domain_hi 0.0725,0.0725,0.1 -dem_box 0,0,0,0.0725,0.0725,0.1 -dem_radius 0.0069 -dem_kn 7.2e5 -dem_lattice 5,5,4 -dem_lattice_spacing 0.0145 -dem_lattice_speed 0.05 -dem_t_end 0.02 -io_interval 0.005 -io_dir $D/a"
${BIN:-bin}/sable $OPTS > "$D/log" 2>&1 || { echo "FAIL output run: exit $?"; exit 1; }
n=$(ls "$D/a"/*.h5 2>/dev/null | wc -l)
[ "$n" -eq 5 ] && echo "PASS output: $n frames for t = 0..0.02 s every 0.005 s (expected 5)" || echo "FAIL output: $n frames (expected 5)"
tmp=$(ls "$D/a" | grep -c '\.tmp$')
[ "$tmp" -eq 0 ] && echo "PASS output: no temporary file left" || echo "FAIL output: $tmp temporary files left"
/usr/bin/python3 - "$D/a/sable.xmf" "$D/a" <<'PY' || echo "FAIL output XDMF: the checking script exited with status $?"
import sys, xml.dom.minidom, h5py, numpy as np
doc = xml.dom.minidom.parse(sys.argv[1])
grids = [g for g in doc.getElementsByTagName("Grid") if g.getAttribute("Name") == "particles" and g.getAttribute("GridType") == "Uniform"]
ok = len(grids) == 5
last = sorted(__import__("glob").glob(sys.argv[2] + "/*.h5"))[-1]
f = h5py.File(last, "r")
p = f["particles/position"][:]
ids = f["particles/id"][:]
finite = np.isfinite(p).all()
print(("PASS" if ok and finite and len(ids) == 100 else "FAIL") + " output: XDMF lists %d particle frames, last frame %d particles, all finite: %s" % (len(grids), len(ids), finite))
np.save(sys.argv[2] + "/../ref.npy", p[np.argsort(ids)])
PY
last=$(ls "$D/a"/*.h5 | tail -n 1)
${BIN:-bin}/sable -domain_lo 0,0,0 -domain_hi 0.0725,0.0725,0.1 -dem_box 0,0,0,0.0725,0.0725,0.1 -dem_radius 0.0069 -dem_kn 7.2e5 -dem_init_file "$last" -dem_t_end 0 -io_interval 1 -io_dir "$D/b" > "$D/log2" 2>&1 || { echo "FAIL restart: exit $?"; cat "$D/log2"; exit 1; }
/usr/bin/python3 - "$D" <<'PY' || echo "FAIL restart: the checking script exited with status $?"
import sys, glob, h5py, numpy as np
d = sys.argv[1]
f = h5py.File(sorted(glob.glob(d + "/b/*.h5"))[0], "r")
p = f["particles/position"][:][np.argsort(f["particles/id"][:])]
ref = np.load(d + "/ref.npy")
err = np.abs(p - ref).max() if p.shape == ref.shape else float("inf")
print(("PASS" if err == 0 else "FAIL") + " restart from -dem_init_file: %d particles, max position difference %g m (bound 0)" % (len(p), err))
PY
# the same on 2 ranks: one file per frame written collectively, every id once, then read back on 1
[ "$(id -u)" -eq 0 ] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
mpiexec --oversubscribe -n 2 ${BIN:-bin}/sable $OPTS -io_dir "$D/c" -da_processors_x 2 -da_processors_y 1 -da_processors_z 1 -domain_cell 0.03 > "$D/log3" 2>&1 || { echo "FAIL 2-rank output run: exit $?"; exit 1; }
/usr/bin/python3 - "$D" <<'PY' || echo "FAIL 2-rank output: the checking script exited with status $?"
import sys, glob, h5py, numpy as np
d = sys.argv[1]
f = h5py.File(sorted(glob.glob(d + "/c/*.h5"))[-1], "r")
ids = f["particles/id"][:]
p = f["particles/position"][:][np.argsort(ids)]
ref = np.load(d + "/ref.npy")
err = np.abs(p - ref).max() if p.shape == ref.shape else float("inf")
ok = len(ids) == 100 and len(set(ids.tolist())) == 100 and err < 1e-12
print(("PASS" if ok else "FAIL") + " 2-rank output: %d rows, %d distinct ids, max position difference to the 1-rank run %.2e m (bound 1e-12)" % (len(ids), len(set(ids.tolist())), err))
PY
# a frame edited into bad input: a repeated id, a zero quaternion (each an error naming the file
# and the row or id); a lattice added to a file's particles continues after the file's ids
last=$(ls "$D/a"/*.h5 | tail -n 1)
/usr/bin/python3 - "$last" "$D" <<'PY' || echo "FAIL init file edits: the editing script exited with status $?"
import sys, shutil, h5py
src, d = sys.argv[1], sys.argv[2]
shutil.copy(src, d + "/dup.h5"); shutil.copy(src, d + "/quat.h5")
with h5py.File(d + "/dup.h5", "r+") as f:
    i = f["particles/id"]; a = i[:]; a[5] = a[3]; i[...] = a
with h5py.File(d + "/quat.h5", "r+") as f:
    q = f["particles/quaternion"]; a = q[:]; a[7] = 0; q[...] = a
PY
B="-domain_lo 0,0,0 -domain_hi 0.0725,0.0725,0.1 -dem_box 0,0,0,0.0725,0.0725,0.1 -dem_radius 0.0069 -dem_kn 7.2e5 -dem_t_end 0 -io_interval 0"
for bad in "dup.h5:particle id [0-9]* appears more than once in /particles/id" "quat.h5:row 7 of /particles/quaternion, (0., 0., 0., 0.), is not a rotation"; do
  f=${bad%%:*}; pat=${bad#*:}
  out=$(${BIN:-bin}/sable $B -dem_init_file "$D/$f" 2>&1); rc=$?
  if [ "$rc" -eq 1 ] && printf '%s\n' "$out" | grep -q "sable: error: -dem_init_file $D/$f: $pat"; then echo "PASS init file $f: exit 1, $(printf '%s\n' "$out" | grep 'sable: error')"
  else echo "FAIL init file $f: exit $rc, expected /$pat/; got: $(printf '%s\n' "$out" | tail -n 1)"; fi
done
${BIN:-bin}/sable $B -dem_init_file "$last" -dem_lattice 2,2,1 -dem_lattice_origin 0,0,0.07 -io_interval 1 -io_dir "$D/e" > "$D/log5" 2>&1 || echo "FAIL init file + lattice: exit $?: $(tail -n 1 "$D/log5")"
/usr/bin/python3 - "$D/e/sable_000000.h5" <<'PY' || echo "FAIL init file + lattice: the checking script exited with status $?"
import sys, h5py
ids = h5py.File(sys.argv[1], "r")["particles/id"][:].tolist()
ok = len(ids) == 104 and len(set(ids)) == 104 and max(ids) == 103
print(("PASS" if ok else "FAIL") + " init file + lattice: %d particles, %d distinct ids, largest %d (expected 104, 104, 103)" % (len(ids), len(set(ids)), max(ids)))
PY
# the end time off the output grid: the final state still gets a frame (t = 0.012 after 0.010)
${BIN:-bin}/sable $OPTS -dem_t_end 0.012 -io_dir "$D/f" > "$D/log6" 2>&1 || echo "FAIL final frame run: exit $?: $(tail -n 1 "$D/log6")"
/usr/bin/python3 - "$D/f" <<'PY' || echo "FAIL final frame: the checking script exited with status $?"
import sys, glob, h5py
t = [float(h5py.File(f, "r").attrs["time"]) for f in sorted(glob.glob(sys.argv[1] + "/*.h5"))]
ok = len(t) == 4 and abs(t[-1] - 0.012) < 1e-9 and abs(t[-2] - 0.010) < 1e-9
print(("PASS" if ok else "FAIL") + " final frame: frames at t = %s s for -dem_t_end 0.012, -io_interval 0.005 (expected 0, 0.005, 0.010 and the end 0.012)" % ", ".join("%.4g" % x for x in t))
PY

# Periodic axes: every frame's positions lie in the box along them ([lo, hi)), though a particle
# may be up to skin/2 past a periodic side between list builds; the convex surface moves with its
# particle (every surface point within the bounding radius of its centre).
P="-domain_lo 0,0,0 -domain_hi 0.06,0.06,0.12 -domain_periodic_x -domain_periodic_y -dem_plane_0 0,0,0,0,0,1 -dem_kn 1e4 -dem_lattice 4,4,4 -dem_lattice_spacing 0.015 -dem_lattice_origin 0,0,0.001 -dem_lattice_speed 0.5 -dem_t_end 0.1 -io_interval 0.002"
for s in sphere cube; do
  [ $s = sphere ] && shp="-dem_radius 0.005" || shp="-dem_shape cube -dem_shape_deq 0.01"
  ${BIN:-bin}/sable $P $shp -io_dir "$D/per_$s" > "$D/log_per" 2>&1 || { echo "FAIL output periodic $s: exit $?"; tail -n 3 "$D/log_per"; continue; }
  /usr/bin/python3 - "$D/per_$s" $s <<'PY' || echo "FAIL output periodic: the checking script exited with status $?"
import sys, glob, h5py, numpy as np
lo, hi = np.array([0.0, 0.0]), np.array([0.06, 0.06])
frames = sorted(glob.glob(sys.argv[1] + "/*.h5"))
out = 0
far = 0.0
for name in frames:
    with h5py.File(name, "r") as f:
        x = f["particles/position"][:, :2]
        out += int(((x < lo) | (x >= hi)).any())
        if "surface" in f:
            c = dict(zip(f["particles/id"][:], f["particles/position"][:]))
            pts, pid = f["surface/points"][:], f["surface/tag"][:]
            far = max(far, max(np.linalg.norm(p - c[i]) for p, i in zip(pts, pid)))
surf = "" if sys.argv[2] == "sphere" else ", farthest surface point %.5f m from its centre (bound 0.00699, the bounding radius)" % far
ok = out == 0 and (sys.argv[2] == "sphere" or 0 < far <= 0.00699)
print("%s output periodic %s: %d of %d frames with a position outside [lo, hi) along x or y (bound 0)%s" % ("PASS" if ok else "FAIL", sys.argv[2], out, len(frames), surf))
PY
done
