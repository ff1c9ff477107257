#!/bin/sh
# The decomposition chosen from the particles, on 2 ranks. Scene: 330 glass spheres on a lattice
# 22 x 5 x 3 at the floor of a tall box 0.4416 x 0.07245 x 0.6 m whose grid is 8 x 1 x 10 cells;
# the bed covers the first 0.32 m of x and settles a few millimetres. PETSc's default cuts z
# (the longest axis) at 0.3 m, above the bed: one rank holds every particle. The rule predicts:
# z (gravity) stays whole, y has one cell, so x is cut, at the cell face that best halves the
# particles (the test finds it from the frame's positions, not from the code: 3 + 5 cells).
# Checks: (1) the log line says 2 x 1 x 1 with that cut; (2) the particles on each side of the
# logged cut, counted from the final frame, are within 10% of N/2 (PETSc's default: 0 and N);
# (3) -da_processors_z 2 and -da_processors_x 2 win unchanged (logged as given; uniform cuts);
# (4) physics is the same up to decomposition: with -dem_deterministic the final frame equals the
# one-rank run's bit for bit; (5) a restart from a checkpoint keeps the checkpoint's process grid
# and cuts (logged) and ends bit for bit on the uninterrupted run's frame.
cd "$(dirname "$0")/../.." || exit 1
S=$(pwd)/${BIN:-bin}/sable
[ "$(id -u)" -eq 0 ] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
W=$(mktemp -d)
trap 'rm -rf "$W"' EXIT
SCENE="-domain_lo 0,0,0 -domain_hi 0.4416,0.07245,0.6 -dem_box 0,0,0,0.4416,0.07245,0.6 -domain_cell 0.0552 -dem_radius 0.0069 -dem_density 2500 -dem_restitution 0.75 -dem_friction 0.3 -dem_dt 1e-5 -dem_lattice 22,5,3 -dem_lattice_spacing 0.01449 -dem_lattice_speed 0.05 -dem_progress_interval 0 -dem_contact_law linear -dem_kn 7.2e5"
T=0.01
run() { # np, dir, args...
  rnp=$1; rd=$2; shift 2
  mkdir -p "$rd"
  (cd "$rd" && mpiexec -n "$rnp" "$S" $SCENE -io_dir out "$@" >log 2>&1)
}
last() { ls "$1"/out/sable_*.h5 2>/dev/null | tail -n 1; }
cat >"$W/side.py" <<'PY'
#!/usr/bin/python3
# side.py FRAME CELLS_LEFT H: particles left/right of x = CELLS_LEFT * H, and the cell face
# (in cells) that best halves them
import sys, h5py, numpy as np
x = h5py.File(sys.argv[1], "r")["particles/position"][()][:, 0]
c, h = int(sys.argv[2]), float(sys.argv[3])
faces = np.arange(1, 8)
best = faces[np.argmin([abs((x < f * h).sum() - len(x) / 2) for f in faces])]
print(len(x), (x < c * h).sum(), (x >= c * h).sum(), best)
PY
cat >"$W/same.py" <<'PY'
#!/usr/bin/python3
# same.py A B: 1 when every particle dataset of frame B equals A's bit for bit (rows by id;
# "vertex", the file's own point numbering for ParaView, left out)
import sys, h5py, numpy as np
a, b = h5py.File(sys.argv[1], "r")["particles"], h5py.File(sys.argv[2], "r")["particles"]
oa, ob = np.argsort(a["id"][()]), np.argsort(b["id"][()])
print(int(all(k in b and a[k][()][oa].tobytes() == b[k][()][ob].tobytes() for k in a if k != "vertex")))
PY
chmod +x "$W/side.py" "$W/same.py"

# (1), (2): the default
run 2 "$W/def" -dem_t_end $T -io_interval $T
line=$(grep '^decomposition:' "$W/def/log")
f=$(last "$W/def")
cuts=$(echo "$line" | sed -n 's/^decomposition: 2 x 1 x 1 ranks, cut along x, balanced cuts (cells per rank) x \([0-9]*\),\([0-9]*\):.*/\1 \2/p')
if [ -z "$f" ] || [ -z "$cuts" ]; then
  echo "FAIL decomposition default: expected '2 x 1 x 1 ranks, cut along x, balanced cuts', got: ${line:-$(grep error "$W/def/log" | head -n 1)}"
else
  set -- $cuts
  set -- $("$W/side.py" "$f" "$1" 0.0552) "$1"
  if [ "$4" -eq "$5" ]; then echo "PASS decomposition default: 2 x 1 x 1, x cut after $5 cells, the face that best halves the bed (from the frame: $4)"
  else echo "FAIL decomposition default: x cut after $5 cells, the frame's best face is $4"; fi
  awk -v n="$1" -v a="$2" -v b="$3" 'BEGIN { m = (a > b ? a : b) / (n / 2) - 1
    printf "%s decomposition balance: particles per rank %d, %d of %d: largest %.3f above N/2 (bound 0.1; PETSc default: all on one rank)\n", (m <= 0.1 ? "PASS" : "FAIL"), a, b, n, m }'
fi

# (3): the user's process grid wins
for opt in "-da_processors_z 2" "-da_processors_x 2"; do
  d=$W/given_$(echo "$opt" | cut -c16)
  run 2 "$d" -dem_t_end 0.001 -io_interval 0 $opt
  want="2 x 1 x 1"; [ "$opt" = "-da_processors_z 2" ] && want="1 x 1 x 2"
  if grep -q "^decomposition: $want ranks, as given by -da_processors_x/y/z" "$d/log" && grep -q '^done:' "$d/log"; then
    echo "PASS decomposition given: $opt runs on $want, as given"
  else echo "FAIL decomposition given: $opt: $(grep -E '^decomposition|error' "$d/log" | head -n 1)"; fi
done

# (4): the same physics up to decomposition
run 1 "$W/one" -dem_t_end $T -io_interval $T -dem_deterministic
run 2 "$W/two" -dem_t_end $T -io_interval $T -dem_deterministic
a=$(last "$W/one"); b=$(last "$W/two")
if [ -n "$a" ] && [ -n "$b" ] && [ "$("$W/same.py" "$a" "$b")" = 1 ] && grep -q '^decomposition: 2 x 1 x 1' "$W/two/log"; then
  echo "PASS decomposition physics: -dem_deterministic, 2 ranks on the chosen 2 x 1 x 1 = 1 rank, bit for bit (bound: bitwise)"
else echo "FAIL decomposition physics: the 2-rank deterministic frame differs from the 1-rank one (or a run failed)"; fi

# (5): a restart keeps the checkpoint's decomposition
run 2 "$W/half" -dem_t_end 0.005 -io_interval 0 -io_checkpoint_interval 0.005
ck=$(sed -n 's/^checkpoint: //p' "$W/half/log" | tail -n 1)
run 2 "$W/rest" -dem_t_end $T -io_interval $T -restart "../half/$ck"
a=$(last "$W/def"); b=$(last "$W/rest")
if [ -n "$ck" ] && [ -n "$b" ] && grep -q "^decomposition: 2 x 1 x 1 ranks, the checkpoint's process grid and cuts" "$W/rest/log" && [ "$("$W/same.py" "$a" "$b")" = 1 ]; then
  echo "PASS decomposition restart: the checkpoint's 2 x 1 x 1 and cuts kept, final frame bit for bit the uninterrupted run's"
else echo "FAIL decomposition restart: $(grep -E '^decomposition|^lb:|error' "$W/rest/log" | head -n 2)"; fi
