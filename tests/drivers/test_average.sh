#!/bin/sh
# Time averages (-avg_start, src/drivers/average.c) against analytic values and the frames:
#   (a) dry free fall, 1 rank (one cell) and 2 ranks (two cells): 8 spheres fall from rest
#       without contacts, v_z(t) = g t; over the samples t_k = t1 + k dt (k = 1..n) of the
#       window the mass-weighted mean is g (t1 + dt (n + 1)/2) and the RMS |g| dt
#       sqrt((n^2 - 1)/12) (within 1e-9 relative, every averaged frame), the x and y components
#       exactly 0, the solids fraction the particles' volume over the cell's (1e-14 relative)
#       with RMS exactly 0 (a steady field); 64 spheres with random velocities crossing cells
#       and ranks, the frames being the samples (every step on 1 rank, -avg_interval on 2 with a
#       rebalance inside the window): the solids fraction's and the mass-weighted particle
#       velocity's means and variances recomputed from the frames, within 1e-12;
#   (b) coupled frozen bed (coupling/packed_bed.opts with a 4 x 4 x 8 lattice, an inlet stepping
#       from 1 to 1.5 at t = 0.5), frames every step, 1 and 2 ranks: avg_solids_fraction equals
#       1 - eps of every averaged frame exactly and its RMS is exactly 0, the particle averages
#       exactly 0 (steady fields); the final mean and variance of the fluid velocity equal those
#       recomputed from every frame's velocity, time-weighted, within 1e-12 of the scale;
#   (c) a run stopped at a checkpoint inside the window and continued with -restart ends with
#       bitwise the uninterrupted run's final frame (dry and coupled, 1 and 2 ranks); a coupled
#       checkpoint of 2 ranks continued on 1 agrees with the 1-rank run within 1e-12 of the scale;
#   (d) without -avg_start the frames hold no avg_ datasets and every other dataset is bitwise
#       that of the averaged run; bad values are refused in one line naming the option;
#   (e) averages begun after the last regular frame are in the final frame.
cd "$(dirname "$0")/../.." || exit 1
ROOT=$(pwd)
S=$ROOT/${BIN:-bin}/sable
[ "$(id -u)" -eq 0 ] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1
W=$(mktemp -d)
trap 'rm -rf "$W"' EXIT
run() { # np, dir, args...
  rnp=$1; rd=$2; shift 2
  mkdir -p "$rd"
  (cd "$rd" && mpiexec -n "$rnp" "$S" -io_dir out "$@" >log 2>&1)
}
last() { ls "$1"/out/sable_[0-9]*.h5 2>/dev/null | tail -n 1; }
cat >"$W/cmp.py" <<'PY'
#!/usr/bin/python3
# cmp.py A B [avg|other|all] [tol]: datasets compared (bitwise, or |a-b| <= tol * max|a| per dataset)
import sys, h5py, numpy as np
a, b = h5py.File(sys.argv[1], "r"), h5py.File(sys.argv[2], "r")
which, tol = sys.argv[3], float(sys.argv[4]) if len(sys.argv) > 4 else 0.0
names = []
a.visit(lambda n: names.append(n) if isinstance(a[n], h5py.Dataset) else None)
pick = lambda n: which == "all" or ((n.split("/")[-1][:4] in ("avg_", "rms_")) == (which == "avg"))
names = [n for n in names if pick(n)]
def same(n):
    if n not in b or a[n].shape != b[n].shape: return False
    x, y = a[n][()], b[n][()]
    if tol == 0: return x.tobytes() == y.tobytes()
    return np.abs(x - y).max() <= tol * max(np.abs(x).max(), 1e-300)
diff = [n for n in names if not same(n)]
worst = max([np.abs(a[n][()] - b[n][()]).max() / max(np.abs(a[n][()]).max(), 1e-300) for n in names if n in b and a[n].shape == b[n].shape] or [0])
print(len(names), len(diff), " ".join(diff) or "-", worst)
PY
cat >"$W/fall.py" <<'PY'
#!/usr/bin/python3
# fall.py DIR t1 dt g: every averaged frame against the free fall's analytic mean and RMS
import sys, glob, h5py, numpy as np
d, t1, dt, g = sys.argv[1], float(sys.argv[2]), float(sys.argv[3]), float(sys.argv[4])
em = er = ephi = 0.0; exact = True; nf = 0
for f in sorted(glob.glob(d + "/out/sable_[0-9]*.h5")):
    h = h5py.File(f, "r")
    t = float(h.attrs["time"])
    if "fluid/avg_particle_velocity" not in h:
        continue
    n = round((t - t1) / dt)
    if n < 1:  # the state at t1 itself (a step ending a rounding above t1: a sample of weight ~1e-17)
        continue
    nf += 1
    um, ur = h["fluid/avg_particle_velocity"][()], h["fluid/rms_particle_velocity"][()]
    mean, rms = g * (t1 + dt * (n + 1) / 2), abs(g) * dt * np.sqrt((n * n - 1) / 12)
    em = max(em, np.abs(um[..., 2] / mean - 1).max())
    er = max(er, np.abs(ur[..., 2] / rms - 1).max())
    exact &= bool((um[..., :2] == 0).all() and (ur[..., :2] == 0).all() and (h["fluid/rms_solids_fraction"][()] == 0).all())
    r, x = h["particles/radius"][()].ravel(), h["particles/position"][()]
    cells = h["fluid/avg_solids_fraction"].shape[:3]  # z, y, x
    lo, hi = np.array([0, 0, 0.0]), np.array([4, 4, 20.0])
    hcell = (hi - lo) / np.array(cells[::-1])
    c = np.floor((x - lo) / hcell).astype(int)
    vol = np.zeros(cells)
    np.add.at(vol, (c[:, 2], c[:, 1], c[:, 0]), 4 / 3 * np.pi * r**3)
    phi = vol / np.prod(hcell)
    ephi = max(ephi, np.abs(h["fluid/avg_solids_fraction"][()] - phi).max() / phi.max())
print(nf, em, er, ephi, int(exact))
PY
cat >"$W/bed.py" <<'PY'
#!/usr/bin/python3
# bed.py DIR start: steady fields exact in every averaged frame; the final fluid mean and
# variance against the frames' time-weighted ones
import sys, glob, h5py, numpy as np
d, start = sys.argv[1], float(sys.argv[2])
t_prev, ws, us, exact, nf = start, [], [], True, 0
for f in sorted(glob.glob(d + "/out/sable_[0-9]*.h5")):
    h = h5py.File(f, "r")
    t = float(h.attrs["time"])
    if t <= start:
        continue
    ws.append(t - t_prev); us.append(h["fluid/velocity"][()]); t_prev = t
    nf += 1
    a = h["fluid/avg_solids_fraction"][()]
    exact &= bool((a == 1 - h["fluid/eps"][()]).all() and (h["fluid/rms_solids_fraction"][()] == 0).all())
    exact &= bool((h["fluid/avg_particle_velocity"][()] == 0).all() and (h["fluid/rms_particle_velocity"][()] == 0).all())
w, u = np.array(ws), np.array(us)
mean = np.tensordot(w, u, 1) / w.sum()
var = np.tensordot(w, (u - mean) ** 2, 1) / w.sum()
scale = np.abs(u).max()
em = np.abs(h["fluid/avg_fluid_velocity"][()] - mean).max() / scale
ev = np.abs(h["fluid/rms_fluid_velocity"][()] ** 2 - var).max() / scale**2
print(nf, int(exact), em, ev, np.sqrt(var).max() / scale)
PY
cat >"$W/frames.py" <<'PY'
#!/usr/bin/python3
# frames.py DIR start lo hi rho: a dry run whose frames are its samples: the final averages
# against the mass-weighted ones recomputed from every frame's particles (centre in cell)
import sys, glob, h5py, numpy as np
d, start, rho = sys.argv[1], float(sys.argv[2]), float(sys.argv[5])
lo, hi = np.array(sys.argv[3].split(","), float), np.array(sys.argv[4].split(","), float)
t_prev, nf, sums = start, 0, None
for f in sorted(glob.glob(d + "/out/sable_[0-9]*.h5")):
    h = h5py.File(f, "r")
    t = float(h.attrs["time"])
    if t <= start:
        continue
    cells = h["fluid/avg_solids_fraction"].shape[:3]  # z, y, x
    hc = (hi - lo) / np.array(cells[::-1])
    r, x, v = h["particles/radius"][()].ravel(), h["particles/position"][()], h["particles/velocity"][()]
    c = np.minimum(np.maximum(np.floor((x - lo) / hc).astype(int), 0), np.array(cells[::-1]) - 1)
    idx = (c[:, 2], c[:, 1], c[:, 0])
    m = rho * 4 / 3 * np.pi * r**3
    M, P, V = np.zeros(cells), np.zeros(cells + (3,)), np.zeros(cells)
    np.add.at(M, idx, m); np.add.at(V, idx, 4 / 3 * np.pi * r**3); np.add.at(P, idx, m[:, None] * v)
    w = t - t_prev; t_prev = t; nf += 1
    u = np.where(M[..., None] > 0, P / np.where(M > 0, M, 1)[..., None], 0)
    phi = V / np.prod(hc)
    if sums is None:
        sums = [0.0, np.zeros(cells), np.zeros(cells), np.zeros(cells), np.zeros(cells + (3,)), np.zeros(cells + (3,))]
    sums[0] += w; sums[1] += w * phi; sums[2] += w * phi**2
    sums[3] += w * M; sums[4] += (w * M)[..., None] * u; sums[5] += (w * M)[..., None] * u**2
W, WM = sums[0], sums[3]
phim = sums[1] / W; phir = np.sqrt(np.maximum(sums[2] / W - phim**2, 0))
um = np.where(WM[..., None] > 0, sums[4] / np.where(WM > 0, WM, 1)[..., None], 0)
uv = np.where(WM[..., None] > 0, sums[5] / np.where(WM > 0, WM, 1)[..., None] - um**2, 0)
us = max(np.abs(um).max(), 1e-300)
e = [np.abs(h["fluid/avg_solids_fraction"][()] - phim).max() / phim.max(),
     np.abs(h["fluid/rms_solids_fraction"][()] ** 2 - phir**2).max() / phim.max() ** 2,
     np.abs(h["fluid/avg_particle_velocity"][()] - um).max() / us,
     np.abs(h["fluid/rms_particle_velocity"][()] ** 2 - uv).max() / us**2]
print(nf, int((WM > 0).sum()), max(e), int(np.sqrt(np.maximum(uv, 0)).max() > 0.01 * us and phir.max() > 0))
PY
chmod +x "$W"/*.py

# (a) dry free fall, (c) its restart
FALL0="-domain_lo 0,0,0 -domain_hi 4,4,20 -dem_radius 0.5 -dem_density 2 -dem_gravity 0,0,-1 -dem_kn 1e4 -dem_dt 1e-3 -dem_lattice 2,2,2 -dem_lattice_spacing 2 -dem_lattice_origin 0.5,0.5,15 -da_grid_y 1 -da_grid_z 1 -dem_progress_interval 0"
FALL="$FALL0 -avg_start 0.1"
for np in 1 2; do
  d=$W/fall.$np
  run "$np" "$d/full" $FALL -da_grid_x "$np" -dem_t_end 0.3 -io_interval 0.05
  set -- $("$W/fall.py" "$d/full" 0.1 1e-3 -1)
  if [ "${1:-0}" -eq 4 ] && [ "$5" -eq 1 ] && awk -v a="$2" -v b="$3" -v c="$4" 'BEGIN { exit !(a <= 1e-9 && b <= 1e-9 && c <= 1e-14) }'; then
    echo "PASS average free fall np=$np: $1 averaged frames, mean v_z within $2 and RMS within $3 of g (t1 + dt (n+1)/2), |g| dt sqrt((n^2-1)/12) (bound 1e-9); solids fraction within $4 (1e-14); x, y and the solids fraction's RMS exactly 0"
  else
    echo "FAIL average free fall np=$np: frames $1 (want 4), mean error ${2:-?}, RMS error ${3:-?} (1e-9), solids fraction ${4:-?} (1e-14), exact zeros ${5:-?}; $(grep -i error "$d/full/log" | head -n 2)"
  fi
  run "$np" "$d/half" $FALL -da_grid_x "$np" -dem_t_end 0.2 -io_interval 0.05 -io_checkpoint_interval 0.2
  ck=$(sed -n 's/^checkpoint: //p' "$d/half/log" | tail -n 1)
  run "$np" "$d/rest" $FALL -da_grid_x "$np" -dem_t_end 0.3 -io_interval 0.05 -restart "../half/$ck"
  a=$(last "$d/full"); b=$(last "$d/rest")
  set -- $([ -n "$a" ] && [ -n "$b" ] && "$W/cmp.py" "$a" "$b" all)
  if [ -n "$ck" ] && [ "${1:-0}" -gt 4 ] && [ "$2" -eq 0 ]; then echo "PASS average restart dry np=$np: the final frames of the uninterrupted and the restarted run (checkpoint at t = 0.2 in the window [0.1, 0.3]) are bitwise equal, $1 datasets (4 averages)"
  else echo "FAIL average restart dry np=$np: ${1:-no} datasets compared, ${2:-?} differ: ${3:-}; $(grep -i error "$d"/*/log | head -n 2)"; fi
done

# (a) dry, moving particles crossing cells and ranks: the frames are the samples (every step on
# 1 rank; every -avg_interval on 2, with a rebalance of the cuts inside the window at t = 0.15)
MOVE="-domain_lo 0,0,0 -domain_hi 8,8,20 -dem_radius 0.5 -dem_density 2 -dem_gravity 0,0,-1 -dem_kn 1e4 -dem_dt 2e-3 -dem_lattice 4,4,4 -dem_lattice_spacing 1.5 -dem_lattice_origin 1,1,10 -dem_lattice_speed 2 -da_grid_x 8 -da_grid_y 8 -da_grid_z 10 -dem_progress_interval 0 -dem_t_end 0.3 -avg_start 0.1"
for np in 1 2; do
  d=$W/move.$np
  if [ "$np" -eq 1 ]; then run 1 "$d" $MOVE -io_interval 2e-3; else run 2 "$d" $MOVE -io_interval 0.01 -avg_interval 0.01 -lb_scheme once -lb_time 0.15; fi
  set -- $("$W/frames.py" "$d" 0.1 0,0,0 8,8,20 2)
  if [ "${1:-0}" -ge 20 ] && [ "$4" -eq 1 ] && awk -v a="$3" 'BEGIN { exit !(a <= 1e-12) }'; then
    lb=""; [ "$np" -eq 2 ] && lb=", the cuts rebalanced at t = 0.15 inside the window"
    echo "PASS average moving np=$np$lb: the means and variances of the solids fraction and the mass-weighted particle velocity in $2 cells equal those recomputed from the $1 frames (the samples), within $3 of their scale (bound 1e-12)"
  else
    echo "FAIL average moving np=$np: ${1:-?} frames, ${2:-?} cells, error ${3:-?} (bound 1e-12), fluctuating ${4:-?}; $(grep -i error "$d/log" | head -n 2)"
  fi
done

# (b) coupled frozen bed, (c) its restart, (d) the same run without averages
BED="-options_file $ROOT/tests/coupling/packed_bed.opts -fluid_viscosity 0.1 -dem_lattice 4,4,8 -dem_lattice_spacing 1 -dem_lattice_origin 0,0,4 -fluid_bc_zlo_velocity_table 0.5,0,0,1.5 -cpl_progress_interval 0 -io_interval 0.05"
for np in 1 2; do
  d=$W/bed.$np
  run "$np" "$d/full" $BED -cpl_t_end 1 -avg_start 0.2
  set -- $("$W/bed.py" "$d/full" 0.2)
  if [ "${1:-0}" -eq 16 ] && [ "$2" -eq 1 ] && awk -v a="$3" -v b="$4" -v r="$5" 'BEGIN { exit !(a <= 1e-12 && b <= 1e-12 && r > 0.01) }'; then
    echo "PASS average frozen bed np=$np: $1 averaged frames, avg_solids_fraction = 1 - eps exactly, its RMS and the particle averages exactly 0; fluid velocity mean within $3 and variance within $4 of the frames' time-weighted ones (bound 1e-12 of the scale; RMS/scale $5)"
  else
    echo "FAIL average frozen bed np=$np: frames ${1:-?} (want 16), exact steady fields ${2:-?}, fluid mean ${3:-?}, variance ${4:-?} (1e-12), RMS/scale ${5:-?} (want > 0.01); $(grep -i error "$d/full/log" | head -n 2)"
  fi
  run "$np" "$d/half" $BED -cpl_t_end 0.5 -avg_start 0.2 -io_checkpoint_interval 0.5
  ck=$(sed -n 's/^checkpoint: //p' "$d/half/log" | tail -n 1)
  run "$np" "$d/rest" $BED -cpl_t_end 1 -avg_start 0.2 -restart "../half/$ck"
  a=$(last "$d/full"); b=$(last "$d/rest")
  set -- $([ -n "$a" ] && [ -n "$b" ] && "$W/cmp.py" "$a" "$b" all)
  if [ -n "$ck" ] && [ "${1:-0}" -gt 6 ] && [ "$2" -eq 0 ]; then echo "PASS average restart coupled np=$np: the final frames of the uninterrupted and the restarted run (checkpoint at t = 0.5 in the window [0.2, 1]) are bitwise equal, $1 datasets (6 averages)"
  else echo "FAIL average restart coupled np=$np: ${1:-no} datasets compared, ${2:-?} differ: ${3:-}; $(grep -i error "$d"/*/log | head -n 2)"; fi
  run "$np" "$d/none" $BED -cpl_t_end 1
  b=$(last "$d/none")
  set -- $([ -n "$a" ] && [ -n "$b" ] && "$W/cmp.py" "$a" "$b" other)
  navg=$(/usr/bin/python3 -c "import h5py; print(sum(n[:4] in ('avg_', 'rms_') for n in h5py.File('$b', 'r')['fluid']))" 2>/dev/null)
  if [ "${1:-0}" -gt 3 ] && [ "$2" -eq 0 ] && [ "$navg" = 0 ] && ! grep -q avg_ "$d/none/out/sable.xmf"; then echo "PASS average off np=$np: without -avg_start no avg_ or rms_ dataset, and the other $1 datasets of the final frame are bitwise those of the averaged run"
  else echo "FAIL average off np=$np: ${1:-no} datasets compared, ${2:-?} differ (${3:-}), $navg averages without -avg_start"; fi
done
ck=$(sed -n 's/^checkpoint: //p' "$W/bed.2/half/log" | tail -n 1)
run 1 "$W/bed.21" $BED -cpl_t_end 1 -avg_start 0.2 -restart "../bed.2/half/$ck"
a=$(last "$W/bed.1/full"); b=$(last "$W/bed.21")
set -- $([ -n "$a" ] && [ -n "$b" ] && "$W/cmp.py" "$a" "$b" avg 1e-8)
if [ "${1:-0}" -eq 6 ] && [ "$2" -eq 0 ]; then echo "PASS average restart 2->1: a 2-rank checkpoint continued on 1 rank ends with the 1-rank run's $1 averages within $4 of their scale (bound 1e-8, the fluid's own across rank counts: coupling/test_checkpoint_coupled)"
else echo "FAIL average restart 2->1: ${1:-no} averages compared, ${2:-?} beyond 1e-8 of their scale: ${3:-} (worst ${4:-?}); $(grep -i error "$W/bed.21/log" | head -n 2)"; fi

# (d) bad values
for bad in "-avg_interval 0.1" "-avg_start -1"; do
  run 1 "$W/bad" $FALL0 -dem_t_end 0.01 $bad
  line=$(grep -i 'error' "$W/bad/log" | head -n 1)
  case "$line" in *"${bad%% *}"*) echo "PASS average bad input '$bad': refused: $line" ;; *) echo "FAIL average bad input '$bad': $(tail -n 2 "$W/bad/log")" ;; esac
done

# (e) averages begun after the last regular frame still reach the final one (its fluid part)
run 1 "$W/late" -options_file "$ROOT/cases/settle/quick.opts" -dem_t_end 0.048 -io_interval 0.01 -avg_start 0.045
f=$(last "$W/late")
n=$([ -n "$f" ] && /usr/bin/python3 -c "import h5py, sys; h = h5py.File(sys.argv[1], 'r'); print(sum(k.startswith('avg_') for k in h['fluid'].keys()) if 'fluid' in h else 0)" "$f")
if [ "${n:-0}" -ge 2 ]; then echo "PASS average late start: -avg_start 0.045 after the last regular frame (0.04): the final frame at 0.048 holds $n avg_ datasets"
else echo "FAIL average late start: the final frame ${f:-(none)} holds ${n:-0} avg_ datasets (expected the solids fraction's and the particle velocity's); $(grep -i error "$W/late/log" | head -n 1)"; fi
