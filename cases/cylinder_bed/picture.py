#!/usr/bin/python3
"""picture.py: a picture of the cylindrical bed (cases/cylinder_bed) from its output, as PNG.

  cases/cylinder_bed/picture.py [OUT_DIR (out/cylinder_bed)] [PNG (OUT_DIR/cylinder_bed.png)]

Left: the last frame cut through the axis: the gas's vertical superficial velocity eps u_z in the
cell row through y = 0 (colour; the cells outside the cylinder carry none), the beads whose
centres lie within one diameter of that plane (grey circles to scale) and the wall (black lines).
Right: the monitor's pressure drop from the inlet face over the bed's buoyant weight per area
against the inlet velocity over Wen and Yu's U_mf (the face pressure, the probe on the inlet
face, column p_probe0, less the top one, p_probe3). Reads the
case's numbers (R, the table, the beads) from the options below; matplotlib and h5py only."""
import csv
import glob
import math
import os
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.patches import Circle  # noqa: E402

R, RHO_P, RHO_F, MU, G = 0.016, 2500.0, 1.2, 1.8e-5, 9.81
TABLE = (0.0, 0.0, 0.3, 1.345)  # t0, U0, t1, U1 of -fluid_bc_zlo_velocity_table


def wen_yu(d):
    ar = RHO_F * (RHO_P - RHO_F) * G * d ** 3 / MU ** 2
    return (math.sqrt(33.7 ** 2 + 0.0408 * ar) - 33.7) * MU / (RHO_F * d)


def inlet(t):
    t0, u0, t1, u1 = TABLE
    return u0 if t <= t0 else u1 if t >= t1 else u0 + (u1 - u0) * (t - t0) / (t1 - t0)


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "out/cylinder_bed"
    png = sys.argv[2] if len(sys.argv) > 2 else os.path.join(out, "cylinder_bed.png")
    frames = sorted(glob.glob(os.path.join(out, "sable_[0-9]*.h5")))
    if not frames:
        sys.exit("picture.py: no frames in %s" % out)
    f = h5py.File(frames[-1], "r")
    x = f["particles/position"][:]
    r = f["particles/radius"][:]
    t = float(f.attrs["time"])
    eps = f["fluid/eps"][:]
    u = f["fluid/velocity"][:]
    nz, ny, nx = eps.shape
    lo = (-R, -R, 0.0)
    hi = (R, R, 0.048)
    j = ny // 2
    q = eps[:, j, :] * u[:, j, :, 2]
    fig, (a, b) = plt.subplots(1, 2, figsize=(11, 5.5), gridspec_kw={"width_ratios": [1, 1.2]})
    im = a.imshow(q, origin="lower", extent=(lo[0] * 1e3, hi[0] * 1e3, lo[2] * 1e3, hi[2] * 1e3), cmap="viridis")
    fig.colorbar(im, ax=a, label="eps u_z (m/s), cell row through y = 0")
    for k in range(len(r)):
        if abs(x[k][1]) < 2 * r[k]:
            a.add_patch(Circle((x[k][0] * 1e3, x[k][2] * 1e3), r[k] * 1e3, fc="0.85", ec="0.3", lw=0.3))
    for s in (-1, 1):
        a.axvline(s * R * 1e3, color="k", lw=1.5)
    a.set_xlabel("x (mm)")
    a.set_ylabel("z (mm)")
    a.set_title("t = %.3f s: beads within 1 d of y = 0, gas flux" % t)
    a.set_aspect("equal")
    mon = os.path.join(out, "sable_monitor.csv")
    d = 2 * float(r.mean())
    n = len(r)
    w = sum((4.0 / 3.0) * math.pi * rk ** 3 for rk in r) * (RHO_P - RHO_F) * G / (math.pi * R * R)
    umf = wen_yu(d)
    with open(mon) as fh:
        rows = list(csv.reader(fh))
    col = {h.split(" ")[0]: i for i, h in enumerate(rows[0])}
    us, dps = [], []
    for row in rows[1:]:
        tt = float(row[0])
        p0, pt = float(row[col["p_probe0"]]), float(row[col["p_probe3"]])
        us.append(inlet(tt) / umf)
        dps.append((p0 - pt) / w)
    b.plot(us, dps, ".", ms=2)
    b.axhline(1, color="k", lw=0.8)
    b.axvline(1, color="r", lw=0.8, ls="--", label="Wen-Yu U_mf %.3f m/s" % umf)
    b.set_xlabel("inlet velocity / U_mf (Wen-Yu)")
    b.set_ylabel("dp (inlet face to top) / W")
    b.set_title("%d beads, W = %.1f Pa" % (n, w))
    b.legend(loc="lower right")
    fig.tight_layout()
    fig.savefig(png, dpi=110)
    print("picture: %s" % png)


if __name__ == "__main__":
    main()
