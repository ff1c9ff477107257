#!/usr/bin/python3
"""vblender_check.py: whether the particles of a V-blender run stay inside the V.

  vblender_check.py DIR R L ANGLE AXIS_Z OMEGA [PREFIX]

The V of `tools/make_stl vblender --radius R --length L --angle ANGLE` (apex at the origin, in
the x-z plane, opening upward) turning at the constant OMEGA (rad/s) about the y axis through
(0, 0, AXIS_Z) from t = 0 (right hand). Every frame of the run in DIR: each centre is turned
back by -OMEGA t into the V's frame, where arm -/+ is {s <= L, d <= R, -/+x >= 0}, s the
distance along the arm's axis from the apex, d the distance from it. Prints one line: frames,
particles in the last frame, its id sum, and the largest depth outside the V over all centres
and frames in radii (d - (R - r) or s - (L - r) of the nearer arm; <= 0 inside).
"""
import math
import sys

import h5py
import numpy as np

sys.path.insert(0, __file__.rsplit("/", 3)[0] + "/tools")
from sable_frames import run_frames  # noqa: E402


def depth(x, r, R, L, half):
    out = np.full(len(x), np.inf)
    for sgn in (-1.0, 1.0):
        u = np.array([sgn * math.sin(half), 0.0, math.cos(half)])
        s = x @ u
        d = np.linalg.norm(x - np.outer(s, u), axis=1)
        e = np.maximum(d - (R - r), s - (L - r)) / r
        e = np.where(sgn * x[:, 0] >= -r, e, np.inf)  # the mitre x = 0: the arm's own side
        out = np.minimum(out, e)
    return out


def main(a):
    d, R, L, ang, az, w = a[0], *map(float, a[1:6])
    prefix = a[6] if len(a) > 6 else "sable"
    worst, n, ids, files = -np.inf, 0, 0, run_frames(d, prefix, "particles")
    for name in files:
        with h5py.File(name, "r") as f:
            t = float(f.attrs["time"])
            p = f["particles"]
            x, r, i = p["position"][()], p["radius"][()].ravel(), p["id"][()].ravel()
        th = -w * t  # back into the V's frame: turn by -theta about y through (0, 0, az)
        c, s = math.cos(th), math.sin(th)
        px, pz = x[:, 0], x[:, 2] - az
        v = np.column_stack([c * px + s * pz, x[:, 1], -s * px + c * pz + az])
        if len(v):
            worst = max(worst, float(np.max(depth(v, r, R, L, math.radians(ang) / 2))))
        n, ids = len(i), int(np.sum(i.astype(np.int64)))
    print(len(files), n, ids, worst)


main(sys.argv[1:])
