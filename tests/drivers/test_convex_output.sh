#!/bin/sh
# Output of convex particles for ParaView: a short run of 25 cubes with random orientations
# writes, per frame, the particle arrays (position, quaternion, shape, ...) and the surface of
# every cube in the world frame (/surface: 8 points and 12 triangles per cube, listed in the
# XDMF as a Triangle grid). Checks: counts; every surface point lies at the cube's corner
# distance a sqrt(3)/2 from its particle's centre and equals x + R(q) v for a corner v of the
# cube (to 1e-12 a); triangle corners belong to one particle. Restart from the last frame
# (-dem_init_file) gives the same positions and quaternions.
cd "$(dirname "$0")/../.." || exit 1
D=$(mktemp -d); trap 'rm -rf "$D"' EXIT
A=0.01
GEO="-domain_lo 0,0,0 -domain_hi 0.1,0.1,0.1 -dem_box 0,0,0,0.1,0.1,0.1 -dem_shape cube -dem_shape_size $A -dem_kn 1e4"
${BIN:-bin}/sable $GEO -dem_lattice 5,5,1 -dem_lattice_spacing 0.018 -dem_lattice_random_orientation -dem_t_end 0.02 -io_interval 0.01 -io_dir "$D/a" > "$D/log" 2>&1 || { echo "FAIL convex output run: exit $?"; tail -3 "$D/log"; exit 1; }
/usr/bin/python3 - "$D" $A <<'PY' || echo "FAIL convex output: the checking script exited with status $?"
import sys, glob, itertools, xml.dom.minidom, h5py, numpy as np
d, a = sys.argv[1], float(sys.argv[2])
doc = xml.dom.minidom.parse(d + "/a/sable.xmf")
surf = [g for g in doc.getElementsByTagName("Grid") if g.getAttribute("Name") == "surface" and g.getAttribute("GridType") == "Uniform"]
last = sorted(glob.glob(d + "/a/*.h5"))[-1]
f = h5py.File(last, "r")
x, q, ids = f["particles/position"][:], f["particles/quaternion"][:], f["particles/id"][:]
pts, tag, tri = f["surface/points"][:], f["surface/tag"][:], f["surface/triangles"][:]
n = len(ids)
ok = len(surf) == 3 and pts.shape == (8 * n, 3) and tri.shape == (12 * n, 3)
print(("PASS" if ok else "FAIL") + " convex output: %d frames with a surface grid (expected 3), %d points and %d triangles for %d cubes (expected 8 and 12 each)" % (len(surf), len(pts), len(tri), n))
def R(q):
    w, x_, y, z = q / np.linalg.norm(q)
    return np.array([[1-2*(y*y+z*z), 2*(x_*y-w*z), 2*(x_*z+w*y)], [2*(x_*y+w*z), 1-2*(x_*x_+z*z), 2*(y*z-w*x_)], [2*(x_*z-w*y), 2*(y*z+w*x_), 1-2*(x_*x_+y*y)]])
corners = np.array(list(itertools.product([-a/2, a/2], repeat=3)))
err = 0.0
for i in range(n):
    p = pts[tag == ids[i]]
    world = x[i] + corners @ R(q[i]).T
    for v in p:
        err = max(err, np.min(np.linalg.norm(world - v, axis=1)) / a)
same = all(len(set(tag[t])) == 1 for t in tri)
print(("PASS" if err < 1e-12 and same else "FAIL") + " convex output: surface points = x + R(q) v to %.1e a (bound 1e-12), triangles within one particle: %s" % (err, same))
np.save(d + "/ref.npy", np.hstack([x, q])[np.argsort(ids)])
PY
last=$(ls "$D/a"/*.h5 | tail -n 1)
${BIN:-bin}/sable $GEO -dem_init_file "$last" -dem_t_end 0 -io_interval 1 -io_dir "$D/b" > "$D/log2" 2>&1 || { echo "FAIL convex restart: exit $?"; tail -3 "$D/log2"; exit 1; }
/usr/bin/python3 - "$D" <<'PY' || echo "FAIL convex restart: the checking script exited with status $?"
import sys, glob, h5py, numpy as np
d = sys.argv[1]
f = h5py.File(sorted(glob.glob(d + "/b/*.h5"))[0], "r")
ids = f["particles/id"][:]
s = np.hstack([f["particles/position"][:], f["particles/quaternion"][:]])[np.argsort(ids)]
ref = np.load(d + "/ref.npy")
err = np.abs(s - ref).max() if s.shape == ref.shape else float("inf")
print(("PASS" if err == 0 else "FAIL") + " convex restart from -dem_init_file: %d cubes, max position/quaternion difference %g (bound 0)" % (len(s), err))
PY
# two shapes with the same bounding radius: the restart keeps each particle's shape index
G2="-domain_lo 0,0,0 -domain_hi 0.1,0.1,0.1 -dem_box 0,0,0,0.1,0.1,0.1 -dem_shape cube,cube -dem_shape_size $A,$A -dem_radius_fraction 1,1 -dem_kn 1e4"
${BIN:-bin}/sable $G2 -dem_lattice 5,5,1 -dem_lattice_spacing 0.018 -dem_t_end 0 -io_interval 1 -io_dir "$D/c" > "$D/log3" 2>&1 || { echo "FAIL convex restart with two shapes: exit $?"; tail -3 "$D/log3"; exit 1; }
${BIN:-bin}/sable $G2 -dem_init_file "$D/c/sable_000000.h5" -dem_t_end 0 -io_interval 1 -io_dir "$D/d" > "$D/log4" 2>&1 || { echo "FAIL convex restart with two shapes: exit $?"; tail -3 "$D/log4"; exit 1; }
/usr/bin/python3 - "$D" <<'PY' || echo "FAIL convex restart two shapes: the checking script exited with status $?"
import sys, h5py, numpy as np
d = sys.argv[1]
a, b = h5py.File(d + "/c/sable_000000.h5", "r"), h5py.File(d + "/d/sable_000000.h5", "r")
sa = a["particles/shape"][:][np.argsort(a["particles/id"][:])]
sb = b["particles/shape"][:][np.argsort(b["particles/id"][:])]
ok = len(sa) == 25 and (sa == sb).all() and 0 < sa.sum() < 25
print(("PASS" if ok else "FAIL") + " convex restart, two shapes of equal bounding radius: %d of %d shape indices kept (%d of shape 1)" % ((sa == sb).sum(), len(sa), sa.sum()))
PY
