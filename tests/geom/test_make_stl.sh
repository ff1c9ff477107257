#!/bin/sh
# The meshes of tools/make_stl, read back by the C reader (build/tests/geom/test_stl FILE prints
# "mesh <triangles> <zero-area> <duplicates> <area> <enclosed volume>").
# Each mesh is written in ASCII and in binary; make_stl's own checks must pass (exit 0), and the
# reader must find the triangle count of the construction, nothing skipped, and
#   closed meshes (box, capped cylinder, V-blender): the enclosed volume of the polygonal solid,
#     n/2 r^2 sin(2 pi/n) L per cylinder of n facets (an oblique mitre through the axis point
#     changes nothing), a b c for the box, to 1e-12 relative in ASCII and 1e-6 in binary
#     (float32 vertices), and the smooth volume (pi r^2 L) within the facet error
#     1 - n sin(2 pi/n)/(2 pi) to the same tolerance;
#   open meshes (plane, hopper, open cylinder): the area, |u x v| for the parallelogram,
#     4 (a_top + a_bot) slant for the hopper (half-widths a, slant sqrt(h^2 + (a_top - a_bot)^2)),
#     2 n r sin(pi/n) L for the open cylinder.
cd "$(dirname "$0")/../.." || exit 1
BUILD=${BUILD:-build}
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
/usr/bin/python3 - "$OUT" "$BUILD/tests/geom/test_stl" <<'PY' || echo "FAIL make_stl meshes: the checking script exited with status $?"
import math, subprocess, sys

out, reader = sys.argv[1], sys.argv[2]


def prism(n, r, length):
    return n / 2 * r * r * math.sin(2 * math.pi / n) * length


def facet(n):
    return 1 - n * math.sin(2 * math.pi / n) / (2 * math.pi)


at, ab, h = 0.05, 0.0075, 0.2
cases = [  # name, make_stl arguments, triangles, what, reference, smooth reference or None, facet error
    ("plane 4x3 tilted", ["plane", "--p1", "0.2,0,0", "--p2", "0,0.1,0.05", "--n", "4", "--m", "3"], 24,
     "area", 0.2 * math.hypot(0.1, 0.05), None, 0),
    ("box", ["box", "--lo=-0.01,0,0", "--hi", "0.03,0.02,0.05"], 12, "volume", 0.04 * 0.02 * 0.05, None, 0),
    ("box n=3", ["box", "--lo=-0.01,0,0", "--hi", "0.03,0.02,0.05", "--n", "3"], 108, "volume", 0.04 * 0.02 * 0.05, None, 0),
    ("hopper", ["hopper", "--hopper", "0.05,0.05,0.3,%g,0.1,%g" % (at, ab)], 8,
     "area", 4 * (at + ab) * math.hypot(h, at - ab), None, 0),
    ("hopper n=2", ["hopper", "--hopper", "0.05,0.05,0.3,%g,0.1,%g" % (at, ab), "--n", "2"], 32,
     "area", 4 * (at + ab) * math.hypot(h, at - ab), None, 0),
    ("drum, 96 facets, caps", ["cylinder", "--axis", "1,0,0", "--radius", "0.05", "--s1", "0.1", "--n", "96", "--caps"], 384,
     "volume", prism(96, 0.05, 0.1), math.pi * 0.05 ** 2 * 0.1, facet(96)),
    ("open cylinder, tilted axis", ["cylinder", "--axis", "1,2,2", "--radius", "0.02", "--s0=-0.05", "--s1", "0.05", "--n", "64", "--nlen", "2"], 256,
     "area", 2 * 64 * 0.02 * math.sin(math.pi / 64) * 0.1, None, 0),
    ("V-blender", ["vblender"], 2 * 48 * 3, "volume", 2 * prism(48, 0.025, 0.1), 2 * math.pi * 0.025 ** 2 * 0.1, facet(48)),
    ("V-blender 60 deg, nlen 3", ["vblender", "--angle", "60", "--radius", "0.03", "--length", "0.12", "--n", "36", "--nlen", "3", "--apex", "0.1,0.1,0.05"],
     2 * 36 * 7, "volume", 2 * prism(36, 0.03, 0.12), 2 * math.pi * 0.03 ** 2 * 0.12, facet(36)),
]
for name, args, ntri, what, ref, smooth, fac in cases:
    for binary in (False, True):
        form = "binary" if binary else "ASCII"
        tol = 1e-6 if binary else 1e-12
        path = "%s/m.stl" % out
        cmd = ["tools/make_stl"] + args + ["-o", path] + (["--binary"] if binary else [])
        r = subprocess.run(cmd, capture_output=True, text=True)
        ok = r.returncode == 0
        print("%s make_stl %s (%s): its own checks: exit status %d (0)" % ("PASS" if ok else "FAIL", name, form, r.returncode))
        if not ok:
            print("    " + (r.stdout + r.stderr).strip().replace("\n", "\n    "))
            continue
        r = subprocess.run([reader, path], capture_output=True, text=True)
        line = [l for l in r.stdout.splitlines() if l.startswith("mesh ")]
        if r.returncode or not line:
            print("FAIL make_stl %s (%s): the reader failed: %s" % (name, form, (r.stdout + r.stderr).strip()[-300:]))
            continue
        f = line[0].split()
        n, nd, nu, area, vol = int(f[1]), int(f[2]), int(f[3]), float(f[4]), float(f[5])
        ok = n == ntri and nd == 0 and nu == 0
        print("%s make_stl %s (%s): triangles read %d, skipped %d + %d (reference %d, 0 + 0)" % ("PASS" if ok else "FAIL", name, form, n, nd, nu, ntri))
        got = area if what == "area" else vol
        e = abs(got - ref) / ref
        print("%s make_stl %s (%s): %s %.12g (reference %.12g, relative error %.1e, bound %g)" % ("PASS" if e <= tol else "FAIL", name, form, what, got, ref, e, tol))
        if smooth:
            d = 1 - vol / smooth
            print("%s make_stl %s (%s): volume below the smooth one by %.4e (facet error %.4e, bound %g)" % ("PASS" if abs(d - fac) <= tol else "FAIL", name, form, d, fac, tol))
PY
