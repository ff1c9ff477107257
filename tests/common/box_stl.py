#!/usr/bin/python3
"""Writes the six sides of the box lo..hi as an ASCII STL file for the mesh-wall shell tests:
each side n x n cells, each cell split into 2 triangles along alternating diagonals.
Usage: box_stl.py out.stl xlo,ylo,zlo,xhi,yhi,zhi [n] [open]  (open: no top side)."""
import sys


def side(lo, hi, d, s, n):
    a, b = (d + 1) % 3, (d + 2) % 3
    tris = []
    for i in range(n):
        for j in range(n):
            c = []
            for q in range(4):
                p = [0.0, 0.0, 0.0]
                p[d] = hi[d] if s else lo[d]
                p[a] = lo[a] + (hi[a] - lo[a]) * (i + (q & 1)) / n
                p[b] = lo[b] + (hi[b] - lo[b]) * (j + (q >> 1)) / n
                c.append(p)
            if (i + j) % 2:
                tris += [(c[0], c[1], c[2]), (c[1], c[3], c[2])]
            else:
                tris += [(c[0], c[1], c[3]), (c[0], c[3], c[2])]
    return tris


def main():
    out, box = sys.argv[1], [float(x) for x in sys.argv[2].split(",")]
    n = int(sys.argv[3]) if len(sys.argv) > 3 else 1
    lo, hi = box[:3], box[3:]
    tris = []
    for d in range(3):
        for s in range(2):
            if d == 2 and s == 1 and "open" in sys.argv[4:]:
                continue
            tris += side(lo, hi, d, s, n)
    with open(out, "w") as f:
        f.write("solid box\n")
        for t in tris:
            f.write("facet normal 0 0 0\nouter loop\n")
            for v in t:
                f.write("vertex %.17g %.17g %.17g\n" % tuple(v))
            f.write("endloop\nendfacet\n")
        f.write("endsolid box\n")


main()
