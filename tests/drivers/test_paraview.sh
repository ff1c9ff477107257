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
