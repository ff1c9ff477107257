#!/bin/sh
# The monitor file (-mon_interval) against the frames written at the same times, recomputed from
# the frame's datasets alone (positions, velocities, spins, radii; density 2500 kg/m^3; the fluid's
# cell-centred p, eps and velocity):
#   (a) dry, 1 and 2 ranks (settle quick.opts, 1,200 spheres): particle count, translational and
#       rotational kinetic energy (sum of m v^2/2, I w^2/2 with I = 2/5 m r^2), the 95% solids
#       mass height (exactly a particle's height), the centre-of-mass height, the mass and count
#       of a box, the bed surface of the domain and of a box (solids volume profile in slabs of
#       2 diameters along gravity, each sphere shared among slabs by its caps' volumes; where the
#       profile read from the top first reaches half its densest slab, linear between slab
#       centres), the highest particle (centre + radius) and the solids mass flow through a whole
#       plane and a rectangle (sum m v_z / w over centres within w/2 of the plane, w = 2
#       diameters), each within 1e-12 relative (of the flow's scale sum |m v_z| / w);
#   (b) coupled (the small fluidized bed), 1 and 2 ranks: each probe's pressure equals the
#       frame's cell-centred pressure interpolated trilinearly at the probe (within half a cell
#       of the outlet extrapolated from the two nearest centre rows; eps and u take the nearest
#       row), dp0 and dp9 differences of probes (probe 11: more than 8); an inlet patch over the
#       whole zlo face: its mass flow equals rho U A, its mean pressure the monitor's plane
#       average on that face (two routes to the face pressure; near a wall or inlet face it
#       carries the drag the particles leave on the face's points, which the frames do not hold:
#       fluid/test_patch checks that part against the momentum balance), the plane's porosity
#       and velocity the frame's nearest row;
#       the line averages (an oblique segment and one along x) of p, eps and the velocity equal
#       the integral of the same interpolant along the segment (3-point Gauss-Legendre on each
#       piece between the planes of cell centres it crosses: exact for the cubic pieces) over its
#       length, and the plane averages (a whole cross-section, a rectangle) the integral over the
#       rectangle (2 x 2-point Gauss on each bilinear piece), within 1e-12 of each field's scale;
#       the bed surface and highest particle as in (a);
#   (c) a run continued from a checkpoint leaves the same monitor file as the uninterrupted run
#       (every column but the wall-clock ones, as text);
#   (d) tools/plot_monitor finds the frequency of a 3 Hz sine within the spectrum's resolution;
#   (e) a probe, a line or a plane in a dry run, an empty box, a plane flat along two axes, and in
#       a coupled run on 2 ranks a line leaving the domain and a pressure drop of a probe not
#       given are refused in one line naming the option;
#   (f) a lattice bed at rest: the 95% height is the centre of the lattice's layer k = ceil(0.95 nz)
#       - 1, z0 + (k + 1/2) a, exactly, and the centre-of-mass height z0 + nz a / 2 (1e-12); with
#       slabs one lattice spacing a thick (from z = 0 = z0), the bed surface is the lattice's top
#       nz a and the highest particle (nz - 1/2) a + r (1e-12).
cd "$(dirname "$0")/../.." || exit 1
ROOT=$(pwd)
case ${BIN:-bin} in /*) S=$BIN/sable ;; *) S=$ROOT/${BIN:-bin}/sable ;; esac
[ "$(id -u)" -eq 0 ] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1
W=$(mktemp -d)
trap 'rm -rf "$W"' EXIT
DRY="-options_file $ROOT/cases/settle/quick.opts -dem_t_end 0.05 -io_interval 0.01 -mon_interval 0.01 -mon_box_0 0,0,0,0.0725,0.0725,0.05 -mon_surface_3 0,0,0,0.0725,0.1449,0.24633 -mon_flux_0 z=0.1 -mon_flux_12 0.01,0.02,0.12,0.1,0.13,0.12"
cat >"$W/monref.py" <<'PY'
# The monitor's particle and fluid figures recomputed from a frame's datasets (doc/output.md),
# the head of dry.py and wet.py.
import math, numpy as np

def below(c, r, s):  # the fraction of a sphere (centre height c, radius r) below height s
    h = np.clip(s - (c - r), 0, 2 * r)
    return h * h * (3 * r - h) / (4 * r**3)

def surface(z, r, s0, s1, dz, frac=0.5):
    """Bed surface of spheres at heights z (gravity along -z) between s0 and s1, slabs dz."""
    n = max(int(math.ceil((s1 - s0) / dz - 1e-9)), 1)
    prof = np.zeros(n)
    for c, rr in zip(z, r):
        if not (s0 <= c < s1):
            continue
        v = 4 / 3 * math.pi * rr**3
        for k in range(n):
            lo = below(c, rr, s0 + k * dz) if k else 0.0
            hi = below(c, rr, s0 + (k + 1) * dz) if k < n - 1 else 1.0
            prof[k] += v * (hi - lo)
    t = frac * prof.max()
    top = max(k for k in range(n) if prof[k] >= t)
    above = prof[top + 1] if top < n - 1 else 0.0
    return s0 + (top + 0.5) * dz + dz * (prof[top] - t) / (prof[top] - above)

def flow(x, v, m, c, w, lo=(-1e300, -1e300), hi=(1e300, 1e300)):
    """Mass flow along +z through the plane z = c (rectangle lo..hi in x, y), and its scale."""
    sel = (np.abs(x[:, 2] - c) < w / 2) & (x[:, 0] >= lo[0]) & (x[:, 0] < hi[0]) & (x[:, 1] >= lo[1]) & (x[:, 1] < hi[1])
    return (m[sel] * v[sel, 2]).sum() / w, max((m[sel] * np.abs(v[sel, 2])).sum() / w, 1e-300)

class Interp:
    """The trilinear interpolant of cell-centred fields f[z, y, x(, c)]: along a periodic axis the
    centres wrap; along another, within half a cell of the boundary, clamped to the end centres,
    or (extrapolate: the pressure) the line through the two last centres."""
    def __init__(self, f, lo, h, periodic=(False, False, False), extrapolate=False):
        self.f, self.lo, self.h, self.n, self.per, self.ex = f, lo, h, f.shape[:3][::-1], periodic, extrapolate
    def __call__(self, x):
        idx, wt = [], []
        for a in range(3):
            s = (x[a] - self.lo[a]) / self.h[a] - 0.5
            i = int(np.floor(s))
            if self.per[a]: w = s - i
            elif self.ex and i < 0: i, w = 0, s
            elif self.ex and i >= self.n[a] - 1: i, w = self.n[a] - 2, s - (self.n[a] - 2)
            elif i < 0: i, w = 0, 0.0
            elif i >= self.n[a] - 1: i, w = self.n[a] - 1, 0.0
            else: w = s - i
            idx.append(i); wt.append(w)
        v = 0.0
        for c in range(8):
            b = [(c >> a) & 1 for a in range(3)]
            ww = np.prod([wt[a] if b[a] else 1 - wt[a] for a in range(3)])
            j = [(idx[a] + b[a]) % self.n[a] for a in range(3)]
            if ww: v = v + ww * self.f[j[2], j[1], j[0]]
        return v
    def breaks(self, a, s0, s1):  # the centre planes of axis a crossed between coordinates s0 < s1
        c = self.lo[a] + (np.arange(self.n[a]) + 0.5) * self.h[a]
        return sorted(set([s0, s1] + [float(x) for x in c if s0 < x < s1]))

def line_average(F, x0, x1):
    x0, x1 = np.array(x0, float), np.array(x1, float)
    ts = {0.0, 1.0}
    for a in range(3):
        if x1[a] != x0[a]:
            for b in F.breaks(a, min(x0[a], x1[a]), max(x0[a], x1[a])):
                ts.add((b - x0[a]) / (x1[a] - x0[a]))
    ts = sorted(t for t in ts if 0 <= t <= 1)
    g, gw = np.polynomial.legendre.leggauss(3)
    tot = 0.0
    for t0, t1 in zip(ts[:-1], ts[1:]):
        for p, w in zip(g, gw):
            t = 0.5 * (t0 + t1) + 0.5 * (t1 - t0) * p
            tot = tot + 0.5 * w * (t1 - t0) * F(x0 + t * (x1 - x0))
    return tot

def plane_average(F, axis, c, lo, hi):
    """Over the rectangle lo..hi (the two other axes, in order) of the plane x[axis] = c."""
    a, b = [d for d in range(3) if d != axis]
    g, gw = np.polynomial.legendre.leggauss(2)
    pa, pb = F.breaks(a, lo[0], hi[0]), F.breaks(b, lo[1], hi[1])
    tot = 0.0
    for u0, u1 in zip(pa[:-1], pa[1:]):
        for v0, v1 in zip(pb[:-1], pb[1:]):
            for p, wp in zip(g, gw):
                for q, wq in zip(g, gw):
                    x = [0.0] * 3
                    x[axis], x[a], x[b] = c, 0.5 * (u0 + u1) + 0.5 * (u1 - u0) * p, 0.5 * (v0 + v1) + 0.5 * (v1 - v0) * q
                    tot = tot + 0.25 * wp * wq * (u1 - u0) * (v1 - v0) * F(x)
    return tot / ((hi[0] - lo[0]) * (hi[1] - lo[1]))
PY
{ echo '#!/usr/bin/python3'; cat "$W/monref.py" - ; } >"$W/dry.py" <<'PY'
import sys, os, glob, h5py, numpy as np
d = sys.argv[1]
if not os.path.exists(os.path.join(d, "sable_monitor.csv")): sys.exit(print("0 0 no_monitor_file"))
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
    dz = 4 * r.max()  # the defaults of -mon_surface_dz and -mon_flux_width: two diameters
    ins = x[:, 0] < 0.0725
    f0, f12 = flow(x, v, m, 0.1, dz), flow(x, v, m, 0.12, dz, (0.01, 0.02), (0.1, 0.13))
    ref = {"particles_": len(r), "kinetic_energy_J": 0.5 * (m * (v**2).sum(1)).sum(),
           "rotational_energy_J": 0.5 * (0.4 * m * r**2 * (w**2).sum(1)).sum(),
           "bed_height_95_m": h95, "mean_height_m": (m * z).sum() / m.sum(),
           "box0_mass_kg": m[inb].sum(), "box0_count_": inb.sum(),
           "bed_surface_m": surface(z, r, 0, 0.24633, dz), "highest_particle_m": (z + r).max(),
           "surface3_m": surface(z[ins], r[ins], 0, 0.24633, dz), "flux0_kgs": f0, "flux12_kgs": f12}
    for name, val in ref.items():
        val, scale = val if isinstance(val, tuple) else (val, max(abs(val), 1e-300))
        got = rows[name][k]
        worst[name] = max(worst.get(name, 0), abs(got - val) / scale)
    n += 1
print(n, int(n > 0 and max(worst.values()) <= 1e-12), ",".join("%s=%.1e" % (k.rstrip("_"), v) for k, v in worst.items()))
PY
chmod +x "$W/dry.py"
for np in 1 2; do
  d=$W/dry$np
  mkdir -p "$d"
  (cd "$d" && mpiexec -n $np "$S" $DRY -io_dir out >log 2>&1)
  set -- $("$W/dry.py" "$d/out" 2>&1)
  if [ "$#" -eq 3 ] && [ "$2" = 1 ] && [ "$1" -ge 5 ]; then echo "PASS monitor vs frames, dry np=$np: $1 frames, largest relative differences $3 (bound 1e-12)"
  else echo "FAIL monitor vs frames, dry np=$np: $*; $(grep 'sable:' "$d/log" | head -n 1)"; fi
done
# (b) probes, line and plane averages (the small bed is periodic in x and y)
WET="-options_file $ROOT/cases/fluidized_bed/small.opts -cpl_t_end 2 -io_interval 0.5 -mon_interval 0.5 -mon_probe_0 4,2,1.3 -mon_probe_1 3.1,1.2,20.7 -mon_probe_2 8,4,48 -mon_probe_11 0.4,3.7,9.3 -mon_dp_0 0,1 -mon_dp_9 11,2 -mon_line_0 0.3,1.1,5.5,7.7,2.9,30.2 -mon_line_4 0,2,10,8,2,10 -mon_plane_0 z=10 -mon_plane_2 1,0.5,3,6,4,3 -mon_plane_5 z=0 -fluid_patch_0_type inlet -fluid_patch_0_rect 0,0,0,8,0,0,0,4,0 -fluid_patch_0_velocity 0.3054"
{ echo '#!/usr/bin/python3'; cat "$W/monref.py" - ; } >"$W/wet.py" <<'PY'
import sys, os, glob, h5py, numpy as np
sys.path.insert(0, sys.argv[2])
from sable_frames import fluid_mesh
d = sys.argv[1]
if not os.path.exists(os.path.join(d, "sable_monitor.csv")): sys.exit(print("0 0 no_monitor_file"))
(lo, h) = fluid_mesh(d)
rows = np.genfromtxt(os.path.join(d, "sable_monitor.csv"), delimiter=",", names=True)
probes = {0: (4, 2, 1.3), 1: (3.1, 1.2, 20.7), 2: (8, 4, 48), 11: (0.4, 3.7, 9.3)}
lines = {0: ((0.3, 1.1, 5.5), (7.7, 2.9, 30.2)), 4: ((0, 2, 10), (8, 2, 10))}
planes = {0: (2, 10, (0, 0), (8, 4)), 2: (2, 3, (1, 0.5), (6, 4))}
worst, n = {}, 0
def check(name, got, ref, scale):
    worst[name] = max(worst.get(name, 0), abs(got - ref) / scale)
for f in sorted(glob.glob(os.path.join(d, "sable_[0-9]*.h5"))):
    hf = h5py.File(f, "r")
    t = float(hf.attrs["time"])
    k = np.argmin(np.abs(rows["time_s"] - t))
    if abs(rows["time_s"][k] - t) > 1e-9:
        continue
    check("eps_min", rows["eps_min_"][k], hf["fluid/eps"][()].min(), 1)  # the first row's too
    if t == 0:
        continue
    fields = {"p": hf["fluid/p"][()], "eps": hf["fluid/eps"][()], "u": hf["fluid/velocity"][()]}
    F = {q: Interp(v, lo, h, (True, True, False), q == "p") for q, v in fields.items()}
    scale = {q: np.abs(v).max() for q, v in fields.items()}
    p = {j: F["p"](x) for j, x in probes.items()}
    for j in probes:
        check("probes", rows["p_probe%d_Pa" % j][k], p[j], scale["p"])
    check("dp", rows["dp0_Pa"][k], p[0] - p[1], scale["p"])
    check("dp", rows["dp9_Pa"][k], p[11] - p[2], scale["p"])
    for kind, spans in (("line", lines), ("plane", planes)):
        for j, sp in spans.items():
            for q in ("p", "eps", "u"):
                ref = line_average(F[q], *sp) if kind == "line" else plane_average(F[q], *sp)
                names = ["%s%d_%s_%s" % (kind, j, q, "Pa" if q == "p" else "")] if q != "u" else ["%s%d_u%s_ms" % (kind, j, c) for c in "xyz"]
                for c, name in enumerate(names):
                    check(kind + "s_" + q, rows[name][k], ref if q != "u" else ref[c], scale[q])
    check("patch", rows["patch0_p_Pa"][k], rows["plane5_p_Pa"][k], scale["p"])
    for q in ("eps", "u"):
        ref = plane_average(F[q], 2, 0, (0, 0), (8, 4))
        names = ["plane5_eps_"] if q == "eps" else ["plane5_u%s_ms" % c for c in "xyz"]
        for c, name in enumerate(names):
            check("planes_" + q, rows[name][k], ref if q == "eps" else ref[c], scale[q])
    check("patch", rows["patch0_mdot_kgs"][k], 1 * 0.3054 * 32, 1 * 0.3054 * 32)
    x, r = hf["particles/position"][()], hf["particles/radius"][()].ravel()
    check("bed_surface", rows["bed_surface_m"][k], surface(x[:, 2], r, 0, 48, 4 * r.max()), 48)
    check("highest_particle", rows["highest_particle_m"][k], (x[:, 2] + r).max(), 48)
    n += 1
print(n, int(n > 0 and max(worst.values()) <= 1e-12), ",".join("%s=%.1e" % kv for kv in worst.items()))
PY
chmod +x "$W/wet.py"
for np in 1 2; do
  d=$W/wet$np
  mkdir -p "$d"
  (cd "$d" && mpiexec -n $np "$S" $WET -io_dir out >log 2>&1)
  set -- $("$W/wet.py" "$d/out" "$ROOT/tools" 2>&1)
  if [ "$#" -eq 3 ] && [ "$2" = 1 ] && [ "$1" -ge 3 ]; then echo "PASS monitor fluid columns vs frames, coupled np=$np: $1 frames, 4 probes (at a wall, a corner; index 11; the pressure extrapolated to the outlet within half a cell of it), dp0 and dp9, 2 lines and 2 planes (p, eps, u), the inlet face's plane (eps, u; its p = the inlet patch's mean pressure), the patch's mass flow, bed surface and highest particle, eps_min (from the first row on), largest differences over each field's scale $3 (bound 1e-12)"
  else echo "FAIL monitor fluid columns vs frames, coupled np=$np: $*; $(grep 'sable:' "$d/log" | head -n 1)"; fi
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
for c in "probe in a dry run|-mon_probe_0: a probe of the fluid pressure; this run is dry|-mon_probe_0 0.01,0.01,0.01" "line in a dry run|-mon_line_3: an average of the fluid's fields; this run is dry|-mon_line_3 0,0,0.1,0.1,0.1,0.1" "plane in a dry run|-mon_plane_20: an average of the fluid's fields; this run is dry|-mon_plane_20 z=0.1" "empty box|-mon_box_1 .*: need lo < hi on every axis|-mon_box_1 0.05,0,0,0.05,1,1" "plane flat along two axes|-mon_flux_2 0,0,0.1,0,1,0.1: flat along 2 axes|-mon_flux_2 0,0,0.1,0,1,0.1"; do
  name=${c%%|*}; rest=${c#*|}; pat=${rest%%|*}; opt=${rest#*|}
  out=$("$S" -options_file cases/settle/quick.opts -dem_t_end 0.001 -io_interval 0 -mon_interval 0.001 $opt 2>&1); rc=$?
  if [ "$rc" -ne 0 ] && [ "$(printf '%s\n' "$out" | grep -c 'sable: error')" -eq 1 ] && printf '%s' "$out" | grep -q -- "$pat"; then echo "PASS monitor bad input, $name: exit $rc, \"$(printf '%s' "$out" | grep 'sable: error')\""
  else echo "FAIL monitor bad input, $name: exit $rc; got: $out"; fi
done
for c in "line leaving the domain|-mon_line_2: (0., 0., 0.) to (9., 4., 48.) leaves the domain|-mon_line_2 0,0,0,9,4,48" "dp of a probe not given|-mon_dp_5 0,3: both must be probes given by -mon_probe_<k>|-mon_probe_0 1,1,1 -mon_dp_5 0,3" "dp of three probes|-mon_dp_5 takes 2 comma-separated values, got 3|-mon_probe_0 1,1,1 -mon_probe_1 1,1,2 -mon_dp_5 0,1,1"; do
  name=${c%%|*}; rest=${c#*|}; pat=${rest%%|*}; opt=${rest#*|}
  out=$(cd "$W" && mpiexec -n 2 "$S" -options_file "$ROOT/cases/fluidized_bed/small.opts" -cpl_t_end 1 -io_interval 0 -mon_interval 0.5 -io_dir bad $opt 2>&1); rc=$?
  if [ "$rc" -ne 0 ] && [ "$(printf '%s\n' "$out" | grep -c 'sable: error')" -eq 1 ] && printf '%s' "$out" | grep -qF -- "$pat"; then echo "PASS monitor bad input, $name (coupled, 2 ranks): exit $rc, \"$(printf '%s' "$out" | grep 'sable: error')\""
  else echo "FAIL monitor bad input, $name (coupled, 2 ranks): exit $rc; got: $out"; fi
done
# (f) the analytic heights of a lattice
for lat in "12 0" "15 0.002"; do
  set -- $lat
  out=$("$S" -options_file cases/settle/quick.opts -dem_lattice 10,10,$1 -dem_lattice_origin 0,0,$2 -dem_t_end 0 -io_interval 0 -mon_interval 0.01 -mon_surface_dz 0.01449 -io_dir "$W/lat$1" 2>&1)
  res=$(/usr/bin/python3 -c "
import math, numpy as np
r = np.genfromtxt('$W/lat$1/sable_monitor.csv', delimiter=',', names=True)
nz, z0, a = $1, $2, 0.01449
h = z0 + (math.ceil(0.95 * nz) - 1 + 0.5) * a
m = z0 + nz * a / 2
h1, m1 = float(np.atleast_1d(r['bed_height_95_m'])[0]), float(np.atleast_1d(r['mean_height_m'])[0])
s1, t1 = float(np.atleast_1d(r['bed_surface_m'])[0]), float(np.atleast_1d(r['highest_particle_m'])[0])
es, et = abs(s1 - nz * a) / (nz * a), abs(t1 - (z0 + (nz - 0.5) * a + 0.0069)) / t1
ok = h1 == h and abs(m1 - m) <= 1e-12 * m and et <= 1e-12 and (z0 != 0 or es <= 1e-12)
print(int(ok), repr(h1), repr(h), '%.1e' % (abs(m1 - m) / m), repr(s1), '%.1e' % es, '%.1e' % et)
" 2>&1)
  set -- $1 $res
  if [ "$2" = 1 ] && [ "$1" = 12 ]; then echo "PASS monitor bed height of a lattice, nz=$1: 95% height $3 m = the analytic $4 m exactly, centre of mass within $5 relative; bed surface $6 m, the lattice's top nz a within $7, highest particle within $8 (bound 1e-12)"
  elif [ "$2" = 1 ]; then echo "PASS monitor bed height of a lattice, nz=$1: 95% height $3 m = the analytic $4 m exactly, centre of mass within $5 relative, highest particle within $8 (bound 1e-12)"
  else echo "FAIL monitor bed height of a lattice, nz=$1: $*; $(printf '%s' "$out" | grep 'sable:' | head -n 1)"; fi
done
