#!/usr/bin/python3
"""mesh_weight.py FRAME STL CM: the loads the balancer must reach on the bed of
test_mesh_weight.sh, computed independently of Sable. From the particles of FRAME, each
particle's candidate triangles of the (planar) mesh STL by brute force (closest-point distance
< r + skin, skin 0.2 r), the cell weights W = n_p + CM n_c + 0.02 on the 20 x 4 x 4 grid of the
box 0..0.1 x 0..0.02 x 0..0.02, and the best cut of x between 2 ranks (the nearest to the middle
among equal ones). Prints: cut, L_min, L_max, candidates in all, the cut with CM = 0."""
import sys

import h5py
import numpy as np


def read_stl(path):
    v = [list(map(float, ln.split()[1:4])) for ln in open(path) if ln.strip().startswith("vertex")]
    return np.array(v).reshape(-1, 3, 3)


def seg_dist2(p, a, b):
    ab = b - a
    t = np.clip(np.sum((p - a) * ab, axis=1) / np.sum(ab * ab, axis=1), 0, 1)
    d = a + t[:, None] * ab - p
    return np.sum(d * d, axis=1)


def cand(x, reach, tri):
    # the plane x = const: distance^2 = dx^2 + (in-plane distance to the triangle)^2
    dx = x[0] - tri[:, 0, 0]
    q = tri[:, :, 1:]
    p = np.broadcast_to(x[1:], (len(tri), 2))
    s = [np.sign(np.cross(q[:, (k + 1) % 3] - q[:, k], p - q[:, k])) for k in range(3)]
    inside = ((s[0] >= 0) & (s[1] >= 0) & (s[2] >= 0)) | ((s[0] <= 0) & (s[1] <= 0) & (s[2] <= 0))
    e2 = np.minimum.reduce([seg_dist2(p, q[:, k], q[:, (k + 1) % 3]) for k in range(3)])
    return int(np.sum(dx * dx + np.where(inside, 0, e2) < reach * reach))


def best_cut(w):
    wx = w.sum(axis=(1, 2))
    best = None
    for k in range(1, len(wx)):
        lo, hi = wx[:k].sum(), wx[k:].sum()
        key = (max(lo, hi), abs(k - len(wx) // 2))
        if best is None or key < best[0]:
            best = (key, k, min(lo, hi), max(lo, hi))
    return best[1:]


f = h5py.File(sys.argv[1], "r")
x, r = f["particles"]["position"][()], f["particles"]["radius"][()].ravel()
tri, cm = read_stl(sys.argv[2]), float(sys.argv[3])
n = np.zeros((20, 4, 4))
nc = np.zeros((20, 4, 4))
for i in range(len(x)):
    c = tuple(np.minimum((x[i] / 0.005).astype(int), [19, 3, 3]))
    n[c] += 1
    nc[c] += cand(x[i], 1.2 * r[i], tri)
k, lmin, lmax = best_cut(n + cm * nc + 0.02)
k0 = best_cut(n + 0.02)[0]
print(k, lmin, lmax, int(nc.sum()), k0)
