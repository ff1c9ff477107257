#!/usr/bin/python3
"""sources_check.py: the figures tests/dem/test_sources.sh compares with the set values, read
from Sable's HDF5 frames. Each command prints one line of numbers:
  rate DIR RATE START STOP     frames of DIR: with due = rate (min(max(t, start), stop) - start),
                               the largest due - N(t) (lag) and the largest N(t) - due (lead)
                               over every frame, and the number of frames
  count FRAME                  particles in the frame
  overlap FRAME PREV LO HI     the particles of FRAME whose id is not in PREV (PREV "-": all):
                               their number, the largest overlap with any other particle and the
                               largest with the box LO..HI (x,y,z,x,y,z), both over the diameter
  same A B                     particles of A and B matched by id: ids only in one of them, and
                               particles whose position, velocity or radius differ in any bit
"""
import glob
import sys

import h5py
import numpy as np


def frame(path):
    f = h5py.File(path, "r")
    p = f["particles"]
    return float(f.attrs["time"]), p["id"][()].ravel(), p["position"][()], p["velocity"][()], p["radius"][()].ravel()


def rate(d, r, start, stop):
    lag = lead = -1e300
    files = sorted(glob.glob(d + "/*_[0-9]*.h5"))
    for name in files:
        t, ids, *_ = frame(name)
        due = r * (min(max(t, start), stop) - start)
        lag, lead = max(lag, due - len(ids)), max(lead, len(ids) - due)
    print(lag, lead, len(files))


def overlap(path, prev, lo, hi):
    t, ids, x, v, rad = frame(path)
    old = set(frame(prev)[1].tolist()) if prev != "-" else set()
    new = np.array([i not in old for i in ids.tolist()])
    worst_p = worst_w = -1e300
    for i in np.nonzero(new)[0]:
        d = np.linalg.norm(x - x[i], axis=1)
        d[i] = 1e300
        worst_p = max(worst_p, np.max((rad + rad[i] - d) / (2 * rad[i])))
        gap = np.concatenate([x[i] - lo, hi - x[i]])
        worst_w = max(worst_w, np.max((rad[i] - gap) / (2 * rad[i])))
    print(int(new.sum()), worst_p, worst_w)


def same(a, b):
    _, ia, xa, va, ra = frame(a)
    _, ib, xb, vb, rb = frame(b)
    oa, ob = np.argsort(ia), np.argsort(ib)
    if len(ia) != len(ib) or np.any(ia[oa] != ib[ob]):
        print(len(set(ia.tolist()) ^ set(ib.tolist())), -1)
        return
    diff = np.any(xa[oa] != xb[ob], axis=1) | np.any(va[oa] != vb[ob], axis=1) | (ra[oa] != rb[ob])
    print(0, int(diff.sum()))


cmd = sys.argv[1]
if cmd == "rate":
    rate(sys.argv[2], float(sys.argv[3]), float(sys.argv[4]), float(sys.argv[5]))
elif cmd == "count":
    print(len(frame(sys.argv[2])[1]))
elif cmd == "overlap":
    box = [float(s) for s in sys.argv[4].split(",")] + [float(s) for s in sys.argv[5].split(",")]
    overlap(sys.argv[2], sys.argv[3], np.array(box[:3]), np.array(box[3:6]))
elif cmd == "same":
    same(sys.argv[2], sys.argv[3])
