#!/bin/sh
# A real client reads our output: ParaView's XDMF reader (pvpython, headless) opens the time
# series of a short coupled run and finds every frame, every particle with its arrays, and the
# fluid grid with eps, p and velocity on its cells; Extract Block finds the particles at every
# time (a fixed block name), and the Xdmf3 reader gives them vertex cells (so they draw).
# Rendering needs an X display (Debian's pvpython has no offscreen build: with
# --force-offscreen-rendering it crashes): xvfb-run (package xvfb) provides one, and a picture of
# the last frame's particles as sphere glyphs must show them (a fair share of pixels unlike the
# background, more than one colour).
cd "$(dirname "$0")/../.." || exit 1
command -v pvpython >/dev/null || { echo "FAIL paraview: pvpython not found (tools/install-deps.sh installs paraview)"; exit 1; }
D=$(mktemp -d); trap 'rm -rf "$D"' EXIT
${BIN:-bin}/sable -options_file cases/fluidized_bed/small.opts -cpl_t_end 10 -io_interval 5 -io_dir "$D" > "$D/log" 2>&1 || { echo "FAIL paraview: the run failed: $(tail -3 "$D/log")"; exit 1; }
cat > "$D/read.py" <<PY
from paraview.simple import XDMFReader, Xdmf3ReaderS, ExtractBlock, servermanager
r = XDMFReader(FileNames=["$D/sable.xmf"])
r.UpdatePipelineInformation()
t = list(r.TimestepValues)
r.UpdatePipeline(t[-1])
d = servermanager.Fetch(r)
p, f = d.GetBlock(0), d.GetBlock(1)
pa = sorted(p.GetPointData().GetArrayName(k) for k in range(p.GetPointData().GetNumberOfArrays()))
fa = sorted(f.GetCellData().GetArrayName(k) for k in range(f.GetCellData().GetNumberOfArrays()))
ok = len(t) == 3 and p.GetNumberOfPoints() == 384 and f.GetNumberOfCells() == 192 and {"velocity", "radius", "id", "quaternion"} <= set(pa) and {"eps", "p", "velocity"} <= set(fa)
print(("PASS" if ok else "FAIL") + " paraview reads the series: %d frames (expected 3), %d particles (384) with %s, fluid %d cells (192) with %s" % (len(t), p.GetNumberOfPoints(), ",".join(pa), f.GetNumberOfCells(), ",".join(fa)))
# the README's recipe: Extract Block "particles" at every time (the block keeps its name)
eb = ExtractBlock(Input=r, Selectors=["/Root/particles"])
n = []
for tt in t:
    eb.UpdatePipeline(tt)
    n.append(eb.GetDataInformation().GetNumberOfPoints())
print(("PASS" if n == [384] * len(t) else "FAIL") + " paraview Extract Block /Root/particles at every frame: %s points (384 each)" % n)
# the Xdmf3 readers (pvpython's default for .xmf) need the vertex connectivity to draw points
r3 = Xdmf3ReaderS(FileName=["$D/sable.xmf"])
r3.UpdatePipeline(t[-1])
d3 = servermanager.Fetch(r3)
c, it = [], d3.NewIterator()
it.InitTraversal()
while not it.IsDoneWithTraversal():
    c.append(it.GetCurrentDataObject().GetNumberOfCells())
    it.GoToNextItem()
print(("PASS" if sorted(c) == [192, 384] else "FAIL") + " paraview Xdmf3ReaderS: cells per leaf block %s (384 particle vertices, 192 fluid cells)" % c)
PY
timeout 300 pvpython "$D/read.py" 2>&1 | grep -E '^(PASS|FAIL)' || echo "FAIL paraview: pvpython could not read the series"

# Frames a user can afford. A bubbling bed's frames (3,200 beads, 2,000 cells; 5 ms into the
# run), plain, compressed (-io_compress 6: lossless, every dataset bitwise the plain run's) and
# compressed in single precision (-io_precision single, on 2 ranks): the compressed frame must be
# smaller, the single-precision one at least 2x smaller (lossless deflate alone does not reach 2x
# on these doubles: doc/output.md), each run's output line must give its frames, MB and write
# time, and pvpython must read both with the values h5py reads. Then the two cadences and
# -io_fields: particles every 5 s, fluid every 2.5 s, a few datasets; ParaView's XDMF reader
# must see the five times in order and both blocks, with only the chosen arrays, at each.
[ "$(id -u)" -eq 0 ] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
BB="-options_file cases/bubbling_bed/bubbling.opts -cpl_t_end 0.005 -io_interval 0.005 -mon_interval 0 -cpl_progress_interval 0.005"
${BIN:-bin}/sable $BB -io_dir "$D/bu" > "$D/log_bu" 2>&1 || echo "FAIL paraview bubbling plain run: exit $?: $(tail -n 1 "$D/log_bu")"
${BIN:-bin}/sable $BB -io_dir "$D/bz" -io_compress 6 > "$D/log_bz" 2>&1 || echo "FAIL paraview bubbling -io_compress 6 run: exit $?: $(tail -n 1 "$D/log_bz")"
mpiexec --oversubscribe -n 2 ${BIN:-bin}/sable $BB -io_dir "$D/bs" -io_compress 6 -io_precision single > "$D/log_bs" 2>&1 || echo "FAIL paraview bubbling single-precision run (2 ranks): exit $?: $(tail -n 1 "$D/log_bs")"
/usr/bin/python3 - "$D" <<'PY' || echo "FAIL paraview compressed frames: the checking script exited with status $?"
import sys, os, re, h5py
d = sys.argv[1]
name = "sable_000001.h5"  # t = 5 ms
size = lambda k: os.path.getsize("%s/%s/%s" % (d, k, name)) if os.path.exists("%s/%s/%s" % (d, k, name)) else 0
diff, n = [], 0
if size("bz") and size("bu"):
    with h5py.File("%s/bz/%s" % (d, name), "r") as z, h5py.File("%s/bu/%s" % (d, name), "r") as u:
        def each(k, o):
            global n
            if isinstance(o, h5py.Dataset):
                n += 1
                if o[()].tobytes() != u[k][()].tobytes() or o.dtype != u[k].dtype:
                    diff.append(k)
        z.visititems(each)
rz = size("bu") / max(size("bz"), 1)
rs = size("bu") / max(size("bs"), 1)
print("%s paraview bubbling frame compressed losslessly: %d bytes against %d plain (ratio %.2f, bound > 1.25), %d of %d datasets unlike the plain frame's %s" % ("PASS" if rz > 1.25 and n > 10 and not diff else "FAIL", size("bz"), size("bu"), rz, len(diff), n, " ".join(diff)))
print("%s paraview bubbling frame in single precision, compressed (2 ranks): %d bytes against %d plain (ratio %.2f, bound >= 2)" % ("PASS" if rs >= 2 and size("bs") > 0 else "FAIL", size("bs"), size("bu"), rs))
for k in ("bu", "bz", "bs"):
    if not os.path.isdir("%s/%s" % (d, k)):
        print("FAIL paraview bubbling %s: no frames written" % k)
        continue
    line = [l.strip() for l in open("%s/log_%s" % (d, k)) if l.startswith("output:")]
    m = re.search(r"output: \S+ \(open it in ParaView\), (\d+) frames, ([0-9.]+) MB, ([0-9.e-]+) s writing \(([0-9.]+)% of the run's ([0-9.e+-]+) s\)", line[0]) if line else None
    tot = sum(os.path.getsize("%s/%s/%s" % (d, k, f)) for f in os.listdir("%s/%s" % (d, k)) if f.endswith(".h5"))
    ok = m and int(m.group(1)) == 2 and abs(float(m.group(2)) - tot / 1e6) < 1e-3 and 0 < float(m.group(3)) < float(m.group(5)) and 0 < float(m.group(4)) < 100
    print("%s paraview bubbling %s: the output line gives the frames, MB (%d bytes on disk) and write time: %s" % ("PASS" if ok else "FAIL", k, tot, line[0] if line else "none"))
PY
cat > "$D/readz.py" <<PY
import h5py
from paraview.simple import XDMFReader, servermanager
from vtk.util.numpy_support import vtk_to_numpy
for k in ("bz", "bs"):
    r = XDMFReader(FileNames=["$D/%s/sable.xmf" % k])
    r.UpdatePipelineInformation()
    t = list(r.TimestepValues)
    r.UpdatePipeline(t[-1])
    d = servermanager.Fetch(r)
    p, f = d.GetBlock(0), d.GetBlock(1)
    h = h5py.File("$D/%s/sable_000001.h5" % k, "r")
    ex = abs(vtk_to_numpy(p.GetPoints().GetData()) - h["particles/position"][()]).max()
    ee = abs(vtk_to_numpy(f.GetCellData().GetArray("eps")) - h["fluid/eps"][()].ravel()).max()
    ok = len(t) == 2 and p.GetNumberOfPoints() == 3200 and f.GetNumberOfCells() == 2000 and ex == 0 and ee == 0
    print("%s paraview reads the %s bubbling frames: %d times (2), %d particles (3200), %d cells (2000); largest difference to h5py's positions %g, eps %g (bound 0)" % ("PASS" if ok else "FAIL", "compressed" if k == "bz" else "single-precision compressed", len(t), p.GetNumberOfPoints(), f.GetNumberOfCells(), ex, ee))
PY
timeout 300 pvpython "$D/readz.py" 2>&1 | grep -E '^(PASS|FAIL)' || echo "FAIL paraview: pvpython could not read the compressed frames"
${BIN:-bin}/sable -options_file cases/fluidized_bed/small.opts -cpl_t_end 10 -io_particle_interval 5 -io_fluid_interval 2.5 -io_fields position,radius,id,eps,fluid/velocity -io_compress 6 -io_dir "$D/split" > "$D/log_split" 2>&1 || echo "FAIL paraview split run: exit $?: $(tail -n 1 "$D/log_split")"
cat > "$D/split.py" <<PY
from paraview.simple import XDMFReader, servermanager
from vtk.util.numpy_support import vtk_to_numpy
r = XDMFReader(FileNames=["$D/split/sable.xmf"])
r.UpdatePipelineInformation()
t = list(r.TimestepValues)
seen, x0 = [], None
for tt in t:
    r.UpdatePipeline(tt)
    d = servermanager.Fetch(r)
    p, f = d.GetBlock(0), d.GetBlock(1)
    pa = sorted(p.GetPointData().GetArrayName(k) for k in range(p.GetPointData().GetNumberOfArrays())) if p else []
    fa = sorted(f.GetCellData().GetArrayName(k) for k in range(f.GetCellData().GetNumberOfArrays())) if f else []
    x = vtk_to_numpy(p.GetPoints().GetData()).copy() if p else None
    if x0 is None:
        x0 = x
    seen.append((round(tt, 6), p.GetNumberOfPoints() if p else 0, pa, f.GetNumberOfCells() if f else 0, fa, bool(x is not None and (x == x0).all())))
ok = [s[:5] for s in seen] == [(tt, 384, ["id", "radius"], 192, ["eps", "velocity"]) for tt in (0.0, 2.5, 5.0, 7.5, 10.0)] and seen[1][5] and not seen[2][5]
print("%s paraview reads -io_particle_interval 5 -io_fluid_interval 2.5 -io_fields position,radius,id,eps,fluid/velocity: (time, points, arrays, cells, arrays, particles as at t = 0) %s (expected times 0, 2.5, 5, 7.5, 10 in order, both blocks with these arrays at each, the particles at 2.5 those of 0)" % ("PASS" if ok else "FAIL", seen))
PY
timeout 300 pvpython "$D/split.py" 2>&1 | grep -E '^(PASS|FAIL)' || echo "FAIL paraview: pvpython could not read the split series"
command -v xvfb-run >/dev/null || { echo "FAIL paraview render: xvfb-run not found (tools/install-deps.sh installs xvfb and xauth)"; exit 1; }
cat > "$D/render.py" <<PY
from paraview.simple import XDMFReader, ExtractBlock, Glyph, GetActiveViewOrCreate, Show, ResetCamera, Render, SaveScreenshot
r = XDMFReader(FileNames=["$D/sable.xmf"])
r.UpdatePipelineInformation()
v = GetActiveViewOrCreate("RenderView")
v.ViewTime = list(r.TimestepValues)[-1]
g = Glyph(Input=ExtractBlock(Input=r, Selectors=["/Root/particles"]), GlyphType="Sphere", ScaleArray=["POINTS", "radius"], ScaleFactor=2)
Show(g, v)
ResetCamera(v)
Render(v)
SaveScreenshot("$D/particles.png", v, ImageResolution=[400, 300])
PY
timeout 120 xvfb-run -a pvpython "$D/render.py" > "$D/render.log" 2>&1
rc=$?
/usr/bin/python3 - "$D/particles.png" "$rc" <<'PY' || echo "FAIL paraview render: the checking script exited with status $?"
import os, sys
import matplotlib.image
png, rc = sys.argv[1], sys.argv[2]
if not os.path.exists(png):
    print("FAIL paraview render: xvfb-run -a pvpython exited %s and wrote no PNG" % rc)
    sys.exit(0)
im = matplotlib.image.imread(png)[:, :, :3]
colours = len({tuple(p) for p in im.reshape(-1, 3).tolist()})
share = float((abs(im - im[0, 0]).sum(axis=2) > 0.05).mean())  # pixels unlike the corner (background)
ok = im.shape[:2] == (300, 400) and colours > 1 and share > 0.02
print("%s paraview render with xvfb-run -a pvpython: %dx%d PNG, %d colours, %.1f%% of pixels not background (bounds: > 1 colour, > 2%%)" % ("PASS" if ok else "FAIL", im.shape[1], im.shape[0], colours, 100 * share))
PY
