#!/bin/sh
# The monitor file (-mon_interval) against the frames written at the same times, recomputed from
# the frame's datasets alone (positions, velocities, spins, radii; density 2500 kg/m^3):
#   (a) dry, 1 and 2 ranks (settle quick.opts, 1,200 spheres): particle count, translational and
#       rotational kinetic energy (sum of m v^2/2, I w^2/2 with I = 2/5 m r^2), the 95% solids
#       mass height (exactly a particle's height), the centre-of-mass height, and the mass and
#       count of a box, each within 1e-12 relative (round-off of sums in another order);
#   (b) coupled (the small fluidized bed): each probe's pressure equals the frame's cell-centred
#       pressure interpolated trilinearly at the probe (nearest centre row within half a cell of
#       a wall), and dp0 the difference of two probes, within 1e-12 of the pressure scale;
#   (c) a run continued from a checkpoint leaves the same monitor file as the uninterrupted run
#       (every column but the wall-clock ones, as text);
#   (d) tools/plot_monitor finds the frequency of a 3 Hz sine within the spectrum's resolution;
#   (e) a probe in a dry run and an empty box are refused in one line naming the option;
#   (f) a lattice bed at rest: the 95% height is the centre of the lattice's layer k = ceil(0.95 nz)
#       - 1, z0 + (k + 1/2) a, exactly, and the centre-of-mass height z0 + nz a / 2 (1e-12).
cd "$(dirname "$0")/../.." || exit 1
ROOT=$(pwd)
S=$ROOT/${BIN:-bin}/sable
[ "$(id -u)" -eq 0 ] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1
W=$(mktemp -d)
trap 'rm -rf "$W"' EXIT
DRY="-options_file $ROOT/cases/settle/quick.opts -dem_t_end 0.05 -io_interval 0.01 -mon_interval 0.01 -mon_box_0 0,0,0,0.0725,0.0725,0.05"
cat >"$W/dry.py" <<'PY'
#!/usr/bin/python3
import sys, os, glob, h5py, numpy as np
d = sys.argv[1]
rows = np.genfromtxt(os.path.join(d, "sable_monitor.csv"), delimiter=",", names=True)
worst, n = {}, 0
for f in sorted(glob.glob(os.path.join(d, "sable_[0-9]*.h5"))):
    h = h5py.File(f, "r")
    t = float(h.attrs["time"])
    k = np.argmin(np.abs(rows["time_s"] - t))
    if abs(rows["time_s"][k] - t) > 1e-12:
        continue
    r, x = h["particles/radius"][()].ravel(), h["particles/position"][()]
    v, w = h["particles/velocity"][()], h["particles/angular_velocity"][()]
    m = 2500 * 4 / 3 * np.pi * r**3
    z = x[:, 2]
    o = np.argsort(z, kind="stable")
    c = np.cumsum(m[o])
    h95 = z[o][np.searchsorted(c, 0.95 * m.sum() * (1 - 1e-12))]  # the first reaching 95% (Sable's slack)
    inb = (x[:, 0] < 0.0725) & (x[:, 1] < 0.0725) & (x[:, 2] < 0.05)
    ref = {"particles_": len(r), "kinetic_energy_J": 0.5 * (m * (v**2).sum(1)).sum(),
           "rotational_energy_J": 0.5 * (0.4 * m * r**2 * (w**2).sum(1)).sum(),
           "bed_height_95_m": h95, "mean_height_m": (m * z).sum() / m.sum(),
           "box0_mass_kg": m[inb].sum(), "box0_count_": inb.sum()}
    for name, val in ref.items():
        got = rows[name][k]
        e = abs(got - val) / max(abs(val), 1e-300)
        worst[name] = max(worst.get(name, 0), e)
    n += 1
print(n, " ".join("%s=%.1e" % (k, v) for k, v in worst.items()), int(n > 0 and max(worst.values()) <= 1e-12))
PY
chmod +x "$W/dry.py"
for np in 1 2; do
  d=$W/dry$np
  mkdir -p "$d"
  (cd "$d" && mpiexec -n $np "$S" $DRY -io_dir out >log 2>&1)
  set -- $("$W/dry.py" "$d/out" 2>&1)
  if [ "$#" -eq 9 ] && [ "$9" -eq 1 ] && [ "$1" -ge 5 ]; then echo "PASS monitor vs frames, dry np=$np: $1 frames, largest relative differences $2 $3 $4 $5 $6 $7 $8 (bound 1e-12)"
  else echo "FAIL monitor vs frames, dry np=$np: $*; $(grep 'sable:' "$d/log" | head -n 1)"; fi
done
# (b) probes
WET="-options_file $ROOT/cases/fluidized_bed/small.opts -cpl_t_end 2 -io_interval 0.5 -mon_interval 0.5 -mon_probe_0 4,2,0.3 -mon_probe_1 3.1,1.2,20.7 -mon_probe_2 8,4,48 -mon_dp_0 0,1"
cat >"$W/wet.py" <<'PY'
#!/usr/bin/python3
import sys, os, glob, h5py, numpy as np
sys.path.insert(0, sys.argv[2])
from sable_frames import fluid_mesh
d = sys.argv[1]
(lo, h) = fluid_mesh(d)
rows = np.genfromtxt(os.path.join(d, "sable_monitor.csv"), delimiter=",", names=True)
probes = [(4, 2, 0.3), (3.1, 1.2, 20.7), (8, 4, 48)]
def interp(p, x):  # p[z, y, x], cell centres at lo + (i + 1/2) h, no periodic axis here
    n = p.shape[::-1]
    idx, wt = [], []
    for a in range(3):
        s = (x[a] - lo[a]) / h[a] - 0.5
        i = int(np.floor(s))
        if i < 0: i, f = 0, 0.0
        elif i >= n[a] - 1: i, f = n[a] - 1, 0.0
        else: f = s - i
        idx.append(i); wt.append(f)
    v = 0.0
    for c in range(8):
        b = [(c >> a) & 1 for a in range(3)]
        ww = np.prod([wt[a] if b[a] else 1 - wt[a] for a in range(3)])
        if ww: v += ww * p[idx[2] + b[2], idx[1] + b[1], idx[0] + b[0]]
    return v
worst, n = 0.0, 0
for f in sorted(glob.glob(os.path.join(d, "sable_[0-9]*.h5"))):
    hf = h5py.File(f, "r")
    t = float(hf.attrs["time"])
    k = np.argmin(np.abs(rows["time_s"] - t))
    if abs(rows["time_s"][k] - t) > 1e-9 or t == 0:
        continue
    p = hf["fluid/p"][()]
    scale = np.abs(p).max()
    ref = [interp(p, x) for x in probes]
    got = [rows["p_probe%d_Pa" % j][k] for j in range(3)]
    worst = max([worst] + [abs(a - b) / scale for a, b in zip(got, ref)] + [abs(rows["dp0_Pa"][k] - (ref[0] - ref[1])) / scale])
    n += 1
print(n, "%.1e" % worst, int(n > 0 and worst <= 1e-12))
PY
chmod +x "$W/wet.py"
for np in 1 2; do
  d=$W/wet$np
  mkdir -p "$d"
  (cd "$d" && mpiexec -n $np "$S" $WET -io_dir out >log 2>&1)
  set -- $("$W/wet.py" "$d/out" "$ROOT/tools" 2>&1)
  if [ "$#" -eq 3 ] && [ "$3" -eq 1 ] && [ "$1" -ge 3 ]; then echo "PASS monitor probes vs frames, coupled np=$np: $1 frames, 3 probes (one at a wall, one at a corner) and dp0 within $2 of the pressure scale (bound 1e-12)"
  else echo "FAIL monitor probes vs frames, coupled np=$np: $*; $(grep 'sable:' "$d/log" | head -n 1)"; fi
done
# (c) a restarted run's monitor file
d=$W/rest
mkdir -p "$d"
(cd "$d" && "$S" $DRY -io_interval 0 -io_dir full >log 2>&1 && "$S" $DRY -io_interval 0 -dem_t_end 0.025 -io_checkpoint_interval 0.025 -io_dir part >log1 2>&1)
ck=$(sed -n 's/^checkpoint: //p' "$d/log1" | tail -n 1)
[ -n "$ck" ] && (cd "$d" && "$S" $DRY -io_interval 0 -io_dir part -restart "$ck" >log2 2>&1)
cut -d, -f1-12 "$d/full/sable_monitor.csv" >"$d/a"
cut -d, -f1-12 "$d/part/sable_monitor.csv" >"$d/b" 2>/dev/null
if [ -n "$ck" ] && cmp -s "$d/a" "$d/b" && [ "$(wc -l <"$d/a")" -ge 6 ]; then echo "PASS monitor across a restart: $(($(wc -l <"$d/a") - 1)) rows equal to the uninterrupted run's (12 columns, as text), continued from $ck"
else echo "FAIL monitor across a restart: $(diff "$d/a" "$d/b" 2>&1 | head -n 3 | tr '\n' ' ')"; fi
# (d) the plot tool's spectrum
/usr/bin/python3 -c "
import numpy as np
t = np.arange(0, 10, 0.01)
with open('$W/sine.csv', 'w') as f:
    f.write('time [s],dp0 [Pa]\n')
    for a in t: f.write('%r,%r\n' % (a, 100 + 5 * np.sin(2 * np.pi * 3 * a)))
"
out=$(tools/plot_monitor "$W/sine.csv" --spectrum dp0 --png "$W/sine.png" 2>&1)
f=$(printf '%s\n' "$out" | sed -n 's/.*dominant frequency \([0-9.e+-]*\) Hz (resolution \([0-9.e+-]*\) Hz.*/\1 \2/p')
if [ -s "$W/sine.png" ] && [ -n "$f" ] && /usr/bin/python3 -c "import sys; f, r = map(float, '$f'.split()); sys.exit(abs(f - 3) > r)"; then echo "PASS plot_monitor spectrum: a 3 Hz sine gives $(echo $f | cut -d' ' -f1) Hz (resolution $(echo $f | cut -d' ' -f2) Hz), PNG written"
else echo "FAIL plot_monitor spectrum: $out"; fi
# (e) bad input
for c in "probe in a dry run|-mon_probe_0: a probe of the fluid pressure; this run is dry|-mon_probe_0 0.01,0.01,0.01" "empty box|-mon_box_1 .*: need lo < hi on every axis|-mon_box_1 0.05,0,0,0.05,1,1"; do
  name=${c%%|*}; rest=${c#*|}; pat=${rest%%|*}; opt=${rest#*|}
  out=$("$S" -options_file cases/settle/quick.opts -dem_t_end 0.001 -io_interval 0 -mon_interval 0.001 $opt 2>&1); rc=$?
  if [ "$rc" -ne 0 ] && [ "$(printf '%s\n' "$out" | grep -c 'sable: error')" -eq 1 ] && printf '%s' "$out" | grep -q -- "$pat"; then echo "PASS monitor bad input, $name: exit $rc, \"$(printf '%s' "$out" | grep 'sable: error')\""
  else echo "FAIL monitor bad input, $name: exit $rc; got: $out"; fi
done
# (f) the analytic heights of a lattice
for lat in "12 0" "15 0.002"; do
  set -- $lat
  out=$("$S" -options_file cases/settle/quick.opts -dem_lattice 10,10,$1 -dem_lattice_origin 0,0,$2 -dem_t_end 0 -io_interval 0 -mon_interval 0.01 -io_dir "$W/lat$1" 2>&1)
  res=$(/usr/bin/python3 -c "
import math, numpy as np
r = np.genfromtxt('$W/lat$1/sable_monitor.csv', delimiter=',', names=True)
nz, z0, a = $1, $2, 0.01449
h = z0 + (math.ceil(0.95 * nz) - 1 + 0.5) * a
m = z0 + nz * a / 2
h1, m1 = float(np.atleast_1d(r['bed_height_95_m'])[0]), float(np.atleast_1d(r['mean_height_m'])[0])
print(int(h1 == h and abs(m1 - m) <= 1e-12 * m), repr(h1), repr(h), '%.1e' % (abs(m1 - m) / m))
" 2>&1)
  set -- $1 $res
  if [ "$2" = 1 ]; then echo "PASS monitor bed height of a lattice, nz=$1: 95% height $3 m = the analytic $4 m exactly, centre of mass within $5 relative (bound 1e-12)"
  else echo "FAIL monitor bed height of a lattice, nz=$1: $*; $(printf '%s' "$out" | grep 'sable:' | head -n 1)"; fi
done
