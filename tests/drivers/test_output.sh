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

# What a frame holds and when: -io_fields (unknown and ambiguous names refused in one line, 1 and
# 2 ranks; the chosen datasets with the full run's values, position always), the two cadences
# (particles every 0.01 s, fluid and averages every 0.004 s: each frame holds the kinds due, the
# index lists every time in order in both series, repeating a kind's latest grid), a restart
# between them continuing both cadences (frames and index as the uninterrupted run's),
# -io_compress (every dataset bitwise the uncompressed run's, chunked, shuffle + deflate; 1 and
# 2 ranks) and the output line (frames, MB and write time of the files written).
for bad in "veloc:-io_fields veloc: not a dataset of a frame; valid: particles, fluid, particles/position, particles/velocity," "velocity:-io_fields velocity: both particles/velocity and fluid/velocity: say which"; do
  v=${bad%%:*}; pat=${bad#*:}
  nps=1; [ "$v" = veloc ] && nps="1 2"
  for np in $nps; do
    if [ "$np" -eq 1 ]; then out=$(${BIN:-bin}/sable $OPTS -io_dir "$D/bad" -io_fields position,$v 2>&1); rc=$?
    else out=$(mpiexec --oversubscribe -n $np ${BIN:-bin}/sable $OPTS -io_dir "$D/bad" -io_fields position,$v 2>&1); rc=$?; fi
    n=$(printf '%s\n' "$out" | grep -c 'sable: error')
    if [ "$rc" -ne 0 ] && [ "$n" -eq 1 ] && printf '%s\n' "$out" | grep -qF "sable: error: $pat"; then echo "PASS -io_fields $v refused on $np rank(s): exit $rc, $(printf '%s\n' "$out" | grep 'sable: error' | cut -c1-110)..."
    else echo "FAIL -io_fields $v on $np rank(s): exit $rc, $n error lines, expected one with '$pat'; got: $(printf '%s\n' "$out" | grep -m1 'error' | cut -c1-200)"; fi
  done
done
${BIN:-bin}/sable $OPTS -io_dir "$D/fields" -io_fields radius,particles/id > "$D/log7" 2>&1 || echo "FAIL -io_fields run: exit $?: $(tail -n 1 "$D/log7")"
/usr/bin/python3 - "$D" <<'PY' || echo "FAIL -io_fields: the checking script exited with status $?"
import sys, glob, h5py, xml.dom.minidom
d = sys.argv[1]
files = sorted(glob.glob(d + "/fields/*.h5"))
bad, diff = [], 0
for name in files:
    with h5py.File(name, "r") as f, h5py.File(name.replace("/fields/", "/a/"), "r") as g:
        if sorted(f) != ["fluid", "particles"] or sorted(f["particles"]) != ["id", "position", "radius", "vertex"] or len(f["fluid"]):
            bad.append(name)
        diff += sum(f["particles"][n][()].tobytes() != g["particles"][n][()].tobytes() for n in f["particles"])
attrs = sorted({a.getAttribute("Name") for a in xml.dom.minidom.parse(d + "/fields/sable.xmf").getElementsByTagName("Attribute")})
ok = len(files) == 5 and not bad and diff == 0 and attrs == ["id", "radius"]
print("%s -io_fields radius,particles/id: %d frames, %d holding other than position, radius, id, vertex; %d datasets unlike the full run's; index attributes %s (expected 5, 0, 0, id,radius)" % ("PASS" if ok else "FAIL", len(files), len(bad), diff, ",".join(attrs)))
PY
SPLIT="-io_particle_interval 0.01 -io_fluid_interval 0.004 -avg_start 0 -domain_cell 0.03"
${BIN:-bin}/sable $OPTS $SPLIT -io_dir "$D/split" -io_checkpoint_interval 0.0075 -io_checkpoint_keep 4 > "$D/log8" 2>&1 || echo "FAIL split intervals run: exit $?: $(tail -n 1 "$D/log8")"
mkdir -p "$D/split_ref" && cp "$D"/split/*.h5 "$D"/split/sable.xmf "$D/split_ref/" 2>/dev/null
/usr/bin/python3 - "$D" <<'PY' || echo "FAIL split intervals: the checking script exited with status $?"
import sys, glob, h5py, xml.dom.minidom
d = sys.argv[1]
got = []
for name in sorted(glob.glob(d + "/split/sable_0*.h5")):
    with h5py.File(name, "r") as f:
        got.append((round(float(f.attrs["time"]), 6), "position" in f["particles"], "avg_solids_fraction" in f["fluid"]))
# particles at 0, 0.01, 0.02; fluid (the averages, from the first sample on) every 0.004 s and at the end
want = [(0.0, True, False), (0.004, False, True), (0.008, False, True), (0.01, True, False), (0.012, False, True), (0.016, False, True), (0.02, True, True)]
doc = xml.dom.minidom.parse(d + "/split/sable.xmf")
series = {}
for c in doc.getElementsByTagName("Grid"):
    if c.getAttribute("GridType") == "Collection":
        grids = [g for g in c.getElementsByTagName("Grid") if g.getAttribute("GridType") == "Uniform"]
        series[c.getAttribute("Name")] = [(round(float(g.getElementsByTagName("Time")[0].getAttribute("Value")), 6), g.getElementsByTagName("DataItem")[-1].firstChild.data.split(":")[0][-9:-3]) for g in grids]
tp = [t for t, _ in series.get("particles", [])]
pfiles = sorted({f for _, f in series.get("particles", [])})
tf = [t for t, _ in series.get("fluid", [])]
ok = got == want and tp == [g[0] for g in want] and pfiles == ["000000", "000003", "000006"] and tf == [g[0] for g in want[1:]]
print("%s split intervals: frames (time, particles, averages) %s; index: particles at %s from files %s, fluid at %s (expected %s; the particles series every time, from the particle frames only)" % ("PASS" if ok else "FAIL", got, tp, pfiles, tf, want))
PY
${BIN:-bin}/sable $OPTS $SPLIT -io_dir "$D/split" -restart "$D/split/sable_checkpoint_000750.h5" > "$D/log9" 2>&1 || echo "FAIL split intervals restart: exit $?: $(tail -n 1 "$D/log9")"
nd=0; nf=0
for f in "$D"/split_ref/sable_0*.h5; do
  nf=$((nf + 1)); r=$(/usr/bin/python3 tests/common/frames_equal.py "$f" "$D/split/$(basename "$f")" 2>&1)
  [ "$(echo "$r" | cut -d' ' -f2)" = "0" ] || nd=$((nd + 1))
done
n=$(ls "$D"/split/sable_0*.h5 | wc -l)
if [ "$nd" -eq 0 ] && [ "$n" -eq 7 ] && cmp -s "$D/split_ref/sable.xmf" "$D/split/sable.xmf"; then echo "PASS split intervals restart at t = 0.0075 (next fluid frame 0.008, particles 0.01): $n frames, $nd of $nf unlike the uninterrupted run's, the index the same"
else echo "FAIL split intervals restart at t = 0.0075: $n frames (expected 7), $nd of $nf unlike the uninterrupted run's; index $(cmp -s "$D/split_ref/sable.xmf" "$D/split/sable.xmf" && echo same || echo differs)"; fi
${BIN:-bin}/sable $OPTS -io_dir "$D/z1" -io_compress 6 > "$D/log10" 2>&1 || echo "FAIL -io_compress run: exit $?: $(tail -n 1 "$D/log10")"
mpiexec --oversubscribe -n 2 ${BIN:-bin}/sable $OPTS -io_dir "$D/z2" -io_compress 6 -da_processors_x 2 -da_processors_y 1 -da_processors_z 1 -domain_cell 0.03 > "$D/log11" 2>&1 || echo "FAIL 2-rank -io_compress run: exit $?: $(tail -n 1 "$D/log11")"
for pair in "z1:a:1:log10" "z2:c:2:log11"; do
  z=$(echo $pair | cut -d: -f1); u=$(echo $pair | cut -d: -f2); np=$(echo $pair | cut -d: -f3); lg=$(echo $pair | cut -d: -f4)
  /usr/bin/python3 - "$D/$z" "$D/$u" "$np" "$D/$lg" <<'PY' || echo "FAIL -io_compress: the checking script exited with status $?"
import sys, glob, os, re, h5py
z, u, np_, log = sys.argv[1:5]
files = sorted(glob.glob(z + "/sable_0*.h5"))
n, diff, plain = 0, 0, 0
for name in files:
    with h5py.File(name, "r") as f, h5py.File(os.path.join(u, os.path.basename(name)), "r") as g:
        def each(k, o):
            global n, diff, plain
            if isinstance(o, h5py.Dataset):
                n += 1
                diff += o[()].tobytes() != g[k][()].tobytes() or o.dtype != g[k].dtype
                plain += o.size > 0 and not (o.chunks and o.compression == "gzip" and o.shuffle)
        f.visititems(each)
size = lambda d: sum(os.path.getsize(x) for x in glob.glob(d + "/sable_0*.h5"))
line = [l for l in open(log) if l.startswith("output:")]
m = re.search(r"output: \S+ \(open it in ParaView\), (\d+) frames, ([0-9.]+) MB, ([0-9.e-]+) s writing \(([0-9.]+)% of the run's", line[0]) if line else None
lineok = m and int(m.group(1)) == len(files) and abs(float(m.group(2)) - size(z) / 1e6) < 1e-3 and float(m.group(3)) > 0 and 0 < float(m.group(4)) <= 100
ok = len(files) == 5 and n > 0 and diff == 0 and plain == 0 and lineok and size(z) < size(u)
print("%s -io_compress 6 on %s rank(s): %d frames, %d datasets, %d unlike the uncompressed run's, %d not chunked + shuffle + gzip; %d bytes against %d (ratio %.2f, bound > 1); %s" % ("PASS" if ok else "FAIL", np_, len(files), n, diff, plain, size(z), size(u), size(u) / max(size(z), 1), (line[0].strip() if line else "no output: line")))
PY
done

# -io_fields with fluid datasets only: no particle dataset in any frame, no particle grid in the index
${BIN:-bin}/sable -options_file cases/fluidized_bed/small.opts -cpl_t_end 2 -io_interval 1 -io_fields fluid -io_dir "$D/fluidonly" > "$D/log9" 2>&1 || echo "FAIL -io_fields fluid run: exit $?: $(tail -n 1 "$D/log9")"
/usr/bin/python3 - "$D/fluidonly" <<'PY' || echo "FAIL -io_fields fluid: the checking script exited with status $?"
import sys, glob, h5py
files = sorted(glob.glob(sys.argv[1] + "/sable_[0-9]*.h5"))
npart = sum(len(h5py.File(f, "r").get("particles", {})) for f in files)
nfluid = sum(len(h5py.File(f, "r").get("fluid", {})) for f in files)
grids = open(sys.argv[1] + "/sable.xmf").read().count('Name="particles"')
ok = len(files) == 3 and npart == 0 and nfluid == 9 and grids == 0
print("%s -io_fields fluid: %d frames (3), %d particle datasets (0), %d fluid datasets (9), %d particle grids in the index (0)" % ("PASS" if ok else "FAIL", len(files), npart, nfluid, grids))
PY
