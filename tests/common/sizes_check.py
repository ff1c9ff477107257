#!/usr/bin/python3
"""sizes_check.py: the figures tests/dem/test_sources_sizes.sh compares with the set values, read
from Sable's HDF5 frames (diameter d = 2 x the frame's radius, mass rho pi d^3 / 6). Commands:
  moments LABEL FRAME SEL LAW NMIN  the particles of FRAME selected by SEL (x:lo:hi, the centre's
      x in [lo, hi); "-": all), at least NMIN of them, against LAW: number- and mass-weighted mean, std, d10, d50, d90, each within 3
      standard errors of the law's exact value (a table's quantiles must be its exact entry), and
      a table's fractions by number (table by number) or by MASS (table by mass) within 3 SE.
      Prints PASS/FAIL lines. LAW: number:d1,d2,..:f1,f2,..  mass:d1,..:f1,..  lognormal:m:s:lo:hi
      (m, s the number-weighted mean and std before the cut to [lo, hi], as -dem_insert_<k>_psd).
  sameseq A SELA B SELB        diameters of B (selected, in id order) against the first ones of A:
      the number compared and the number differing in any bit
  massrate DIR RHO RATE START  over the frames of DIR, M(t) the mass present against
      RATE (t - START): the largest shortfall RATE (t - START) - M, the largest lead M - RATE (t -
      START), the number of frames, the largest particle mass seen
  mass FRAME RHO               the mass present and the mass of the particle with the largest id
  flow DIR RHO MONITOR         every id seen in the frames of DIR: the mass of all of them
      (inserted) and of those not in the last frame (removed), against the monitor's last row
      (inserted_mass, removed_mass): count seen, count removed, both relative differences
  cylinder FRAME PREV C A R L  the particles of FRAME whose id is not in PREV ("-": all): their
      number and the largest of (distance from the axis + r - R) / d and (|h| + r - L/2) / d
  patch FRAME PREV P0 P1 P2 DEPTH  new particles (as above) against the slab of DEPTH in front of
      the patch: number, largest lateral excess / d, largest (r - h) / d, largest (h + r - DEPTH) / d;
      then over the ids of both frames the smallest increase of the distance h from the patch
  orient FRAME                 the quaternions: count, distinct ones, the largest |<q_i^2> - 1/4|
      in standard errors (uniform random rotations: q uniform on S^3, <q_i^2> = 1/4, var 1/16)
"""
import csv
import glob
import math
import sys

import h5py
import numpy as np


def frame(path):
    f = h5py.File(path, "r")
    p = f["particles"]
    g = {k: p[k][()] for k in ("id", "position", "velocity", "radius", "quaternion")}
    g["id"], g["radius"], g["t"] = g["id"].ravel(), g["radius"].ravel(), float(f.attrs["time"])
    return g


def select(g, sel):
    if sel == "-":
        return np.ones(len(g["id"]), bool)
    ax, lo, hi = sel.split(":")
    x = g["position"][:, "xyz".index(ax)]
    return (x >= float(lo)) & (x < float(hi))


def phi(z):
    return 0.5 * (1 + math.erf(z / math.sqrt(2)))


class Table:
    def __init__(self, d, f, by_mass):
        self.d, self.f = np.array(d), np.array(f) / np.sum(f)
        self.p = self.f / self.d**3 if by_mass else self.f
        self.p = self.p / self.p.sum()
        self.atoms = True

    def partial(self, k, x):  # E[d^k 1{d <= x}]
        return float(np.sum(self.p[self.d <= x * (1 + 1e-12)] * self.d[self.d <= x * (1 + 1e-12)] ** k))


class Lognormal:
    def __init__(self, m, s, lo, hi):
        self.sg = math.sqrt(math.log1p(s * s / (m * m)))
        self.mu = math.log(m) - 0.5 * self.sg**2
        self.a, self.b = (math.log(lo) - self.mu) / self.sg, (math.log(hi) - self.mu) / self.sg
        self.z = phi(self.b) - phi(self.a)
        self.atoms = False

    def partial(self, k, x):  # closed form: E[d^k 1{d <= x}] of the cut law
        u = min((math.log(x) - self.mu) / self.sg, self.b) if x > 0 else -1e300
        if u <= self.a:
            return 0.0
        return math.exp(k * self.mu + 0.5 * (k * self.sg) ** 2) * (phi(u - k * self.sg) - phi(self.a - k * self.sg)) / self.z


def law(spec):
    w = spec.split(":")
    if w[0] in ("number", "mass"):
        return Table([float(s) for s in w[1].split(",")], [float(s) for s in w[2].split(",")], w[0] == "mass")
    return Lognormal(*[float(s) for s in w[1:5]])


def stats(d, q):
    """Sample mean, std and the weighted quantiles (weights d^q) of the diameters d."""
    w = d**q
    mean = np.sum(w * d) / np.sum(w)
    std = math.sqrt(np.sum(w * d * d) / np.sum(w) - mean**2)
    o = np.argsort(d, kind="stable")
    c = np.cumsum(w[o]) / np.sum(w)
    return mean, std, [d[o][np.searchsorted(c, p)] for p in (0.1, 0.5, 0.9)]


def exact(L, q, n):
    """The law's weighted mean, std, quantiles and their standard errors for n samples (delta
    method on the sample moments of d^q, d^(q+1), d^(q+2); quantiles in probability: the SE of the
    weighted CDF at the quantile)."""
    M = lambda k: L.partial(k, 1e300)
    e = [q, q + 1, q + 2]
    A, B, C = (M(k) for k in e)
    mean, var = B / A, C / A - (B / A) ** 2
    std = math.sqrt(var)
    cov = np.array([[M(i + j) - M(i) * M(j) for j in e] for i in e])
    gm = np.array([-B / A**2, 1 / A, 0])
    gs = np.array([-C / A**2 + 2 * B * B / A**3, -2 * B / A**2, 1 / A]) / (2 * std)
    se = [math.sqrt(gm @ cov @ gm / n), math.sqrt(gs @ cov @ gs / n)]
    return mean, std, se


def cdf(L, q, x):
    return L.partial(q, x) / L.partial(q, 1e300)


def cdf_se(L, q, x, n):  # SE of the sample's weighted CDF at x: E[w^2 (1{d<=x} - F)^2] / E[w]^2 / n
    F, W = cdf(L, q, x), L.partial(q, 1e300)
    return math.sqrt((L.partial(2 * q, x) * (1 - 2 * F) + F * F * L.partial(2 * q, 1e300)) / n) / W


def quantile(L, q, p):  # the law's weighted quantile (a table: its entry; else bisection)
    if L.atoms:
        return min(x for x in L.d if cdf(L, q, x) >= p - 1e-12)
    lo, hi = math.exp(L.mu + L.sg * L.a), math.exp(L.mu + L.sg * L.b)
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if cdf(L, q, mid) < p else (lo, mid)
    return 0.5 * (lo + hi)


def moments(label, path, sel, spec, nmin):
    g = frame(path)
    d = 2 * g["radius"][select(g, sel)]
    L, n = law(spec), len(d)
    if n < int(nmin):
        print("FAIL sizes %s: %d particles, fewer than %s" % (label, n, nmin))
        return
    for q, wname in ((0, "number"), (3, "mass")):
        mean, std, qs = stats(d, q)
        emean, estd, se = exact(L, q, n)
        z = [(mean - emean) / se[0], (std - estd) / se[1]]
        cells = ["mean %.4f / %.4f mm (z %.2f)" % (1e3 * mean, 1e3 * emean, z[0]), "std %.4f / %.4f (z %.2f)" % (1e3 * std, 1e3 * estd, z[1])]
        ok = True
        for p, x in zip((0.1, 0.5, 0.9), qs):
            ex = quantile(L, q, p)
            if L.atoms:  # the entry must be the exact one; the law's CDF kept >= 4 SE from p
                step = min(abs(cdf(L, q, y) - p) / cdf_se(L, q, y, n) for y in L.d if cdf(L, q, y) < 1 - 1e-12)
                ok &= bool(x == ex) and step >= 4
                cells.append("d%d %.4f / %.4f (atom)" % (100 * p, 1e3 * x, 1e3 * ex))
            else:
                z.append((cdf(L, q, x) - p) / cdf_se(L, q, ex, n))
                cells.append("d%d %.4f / %.4f (z %.2f)" % (100 * p, 1e3 * x, 1e3 * ex, z[-1]))
        ok &= max(abs(v) for v in z) < 3
        print("%s sizes %s %s-weighted, %d particles: %s; bound |z| < 3" % ("PASS" if ok else "FAIL", label, wname, n, ", ".join(cells)))
    if L.atoms:
        q = 3 if spec.startswith("mass") else 0
        target = L.f if q == 3 else L.p
        w = d**q
        frac = [np.sum(w[np.abs(d - x) <= 1e-12 * x]) / np.sum(w) for x in L.d]
        W, W2 = L.partial(q, 1e300), L.partial(2 * q, 1e300)  # SE^2 = E[w^2 (1{d = x} - t)^2] / E[w]^2 / n
        zs = [(fr - t) / (math.sqrt((pi * x ** (2 * q) * (1 - 2 * t) + t * t * W2) / n) / W) for fr, t, x, pi in zip(frac, target, L.d, L.p)]
        whole = abs(sum(frac) - 1) < 1e-12
        ok = whole and max(abs(v) for v in zs) < 3
        print("%s sizes %s fractions by %s: %s against the set %s (z %s); every diameter an entry: %s; bound |z| < 3" % ("PASS" if ok else "FAIL", label, "MASS" if q else "number", ", ".join("%.4f" % v for v in frac), ", ".join("%.4f" % v for v in target), ", ".join("%.2f" % v for v in zs), whole))


def sameseq(a, sela, b, selb):
    ga, gb = frame(a), frame(b)
    ma, mb = select(ga, sela), select(gb, selb)
    da = ga["radius"][ma][np.argsort(ga["id"][ma])]
    db = gb["radius"][mb][np.argsort(gb["id"][mb])]
    n = min(len(da), len(db))
    print(n, int(np.sum(da[:n] != db[:n])) + (len(db) - n))


def masses(g, rho):
    return rho * math.pi / 6 * (2 * g["radius"]) ** 3


def massrate(d, rho, rate, start):
    lag = lead = mmax = -1e300
    files = sorted(glob.glob(d + "/*_[0-9]*.h5"))
    for name in files:
        g = frame(name)
        m = masses(g, rho)
        due = rate * max(g["t"] - start, 0)
        lag, lead = max(lag, due - m.sum()), max(lead, m.sum() - due)
        mmax = max(mmax, m.max(initial=0))
    print(lag, lead, len(files), mmax)


def mass(path, rho):
    g = frame(path)
    m = masses(g, rho)
    print(repr(m.sum()), repr(m[np.argmax(g["id"])]))


def flow(d, rho, monitor):
    files = sorted(glob.glob(d + "/*_[0-9]*.h5"))
    seen = {}
    for name in files:
        g = frame(name)
        for i, m in zip(g["id"].tolist(), masses(g, rho).tolist()):
            seen.setdefault(i, m)
    last = set(frame(files[-1])["id"].tolist())
    ins = math.fsum(seen.values())
    rem = math.fsum(m for i, m in seen.items() if i not in last)
    with open(monitor) as fh:
        rows = [r for r in csv.reader(line for line in fh if not line.startswith("#"))]
    col = {name.split(" [")[0].strip(): j for j, name in enumerate(rows[0])}
    mi, mr = float(rows[-1][col["inserted_mass"]]), float(rows[-1][col["removed_mass"]])
    print(len(seen), len(seen) - len(last), abs(mi - ins) / ins, abs(mr - rem) / max(rem, 1e-300), float(rows[-1][col["time"]]))


def new_ids(g, prev):
    old = set(frame(prev)["id"].tolist()) if prev != "-" else set()
    return np.array([i not in old for i in g["id"].tolist()], bool)


def vec(s):
    return np.array([float(v) for v in s.split(",")])


def cylinder(path, prev, c, a, R, L):
    g = frame(path)
    m = new_ids(g, prev)
    a = a / np.linalg.norm(a)
    x, r = g["position"][m] - c, g["radius"][m]
    h = x @ a
    rho = np.linalg.norm(x - np.outer(h, a), axis=1)
    print(int(m.sum()), np.max((rho + r - R) / (2 * r)), np.max((np.abs(h) + r - L / 2) / (2 * r)))


def patch(path, prev, p0, p1, p2, depth):
    g = frame(path)
    m = new_ids(g, prev)
    e1, e2 = p1 - p0, p2 - p0
    nrm = np.cross(e1, e2)
    nrm /= np.linalg.norm(nrm)
    x, r = g["position"][m] - p0, g["radius"][m]
    lat = -1e300
    for e in (e1, e2):
        s = x @ e / np.linalg.norm(e)
        lat = max(lat, np.max((r - s) / (2 * r)), np.max((s + r - np.linalg.norm(e)) / (2 * r)))
    h = x @ nrm
    gp = frame(prev)
    both = np.intersect1d(g["id"], gp["id"])
    hx = lambda gg: dict(zip(gg["id"].tolist(), ((gg["position"] - p0) @ nrm).tolist()))
    h1, h0 = hx(g), hx(gp)
    dh = min((h1[i] - h0[i] for i in both.tolist()), default=-1e300)
    print(int(m.sum()), lat, np.max((r - h) / (2 * r)), np.max((h + r - depth) / (2 * r)), len(both), dh)


def orient(path):
    q = frame(path)["quaternion"]
    n = len(q)
    z = np.max(np.abs(np.mean(q * q, axis=0) - 0.25) / (0.25 / math.sqrt(n)))
    print(n, len({tuple(v) for v in q.tolist()}), z)


cmd, a = sys.argv[1], sys.argv[2:]
if cmd == "moments":
    moments(*a)
elif cmd == "sameseq":
    sameseq(*a)
elif cmd == "massrate":
    massrate(a[0], float(a[1]), float(a[2]), float(a[3]))
elif cmd == "mass":
    mass(a[0], float(a[1]))
elif cmd == "flow":
    flow(a[0], float(a[1]), a[2])
elif cmd == "cylinder":
    cylinder(a[0], a[1], vec(a[2]), vec(a[3]), float(a[4]), float(a[5]))
elif cmd == "patch":
    patch(a[0], a[1], vec(a[2]), vec(a[3]), vec(a[4]), float(a[5]))
elif cmd == "orient":
    orient(a[0])
