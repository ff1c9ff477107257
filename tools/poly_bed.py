#!/usr/bin/python3
"""poly_bed.py: an initial file (-dem_init_file) of spheres of their own sizes, for the
polydisperse tests and the bench (tools/bench_poly.sh).

N spheres whose diameters are drawn from a lognormal distribution (median d50, geometric
standard deviation sigma_g), cut to [cut_lo, cut_hi] x d50 by redrawing, placed on a cubic
lattice of spacing 1.05 x the largest cut diameter filling x, y first from the box's lower
corner, each moved off its site by up to 0.9 of its own gap per axis and given a velocity
uniform in +-0.1 m/s per axis (so that the columns do not stack), ids 0..N-1. With --mono every sphere has the number-mean diameter of the lognormal draw
instead (the monodisperse bed of the same mean size and count). The draw is a function of the
seed only. Sable reads it with -dem_init_file FILE -dem_init_file_radii own.

Usage: tools/poly_bed.py OUT N D50 SIGMA_G LX LY Z0 [--seed S] [--cut LO,HI] [--mono]
(lengths in m; the lattice covers [0, LX] x [0, LY] from height Z0)."""
import argparse
import h5py
import numpy as np


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("out")
    ap.add_argument("n", type=int)
    ap.add_argument("d50", type=float)
    ap.add_argument("sigma_g", type=float)
    ap.add_argument("lx", type=float)
    ap.add_argument("ly", type=float)
    ap.add_argument("z0", type=float)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--cut", default="0.5,2")
    ap.add_argument("--mono", action="store_true")
    a = ap.parse_args()
    lo, hi = (float(c) * a.d50 for c in a.cut.split(","))
    rng = np.random.RandomState(a.seed)
    d = np.empty(a.n)
    for i in range(a.n):
        x = a.d50 * np.exp(np.log(a.sigma_g) * rng.standard_normal())
        while not lo <= x <= hi:
            x = a.d50 * np.exp(np.log(a.sigma_g) * rng.standard_normal())
        d[i] = x
    if a.mono:
        d[:] = d.mean()
    s = 1.05 * hi
    nx, ny = int(a.lx / s), int(a.ly / s)
    if nx < 1 or ny < 1:
        raise SystemExit("poly_bed.py: the box %g x %g m holds no lattice site of spacing %g m" % (a.lx, a.ly, s))
    k = np.arange(a.n)
    pos = np.stack([(k % nx + 0.5) * s, (k // nx % ny + 0.5) * s, a.z0 + (k // (nx * ny) + 0.5) * s], axis=1)
    pos += 0.9 * (0.5 * (s - d))[:, None] * rng.uniform(-1, 1, (a.n, 3))
    vel = rng.uniform(-0.1, 0.1, (a.n, 3))
    q = np.zeros((a.n, 4))
    q[:, 0] = 1
    with h5py.File(a.out, "w") as f:
        f["particles/position"] = pos
        f["particles/velocity"] = vel
        f["particles/angular_velocity"] = np.zeros((a.n, 3))
        f["particles/quaternion"] = q
        f["particles/id"] = k.astype(np.float64)
        f["particles/radius"] = 0.5 * d
    print("%d spheres, d %.4g to %.4g m, number mean %.4g m, top %.4g m" % (a.n, d.min(), d.max(), d.mean(), pos[:, 2].max() + 0.5 * d.max()))


if __name__ == "__main__":
    main()
