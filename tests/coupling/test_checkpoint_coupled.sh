#!/bin/sh
# Exact checkpoints of a coupled run: a small fluidized bed (the make-run case, 384 spheres,
# 4 x 2 x 24 cells) whose inlet table switches from 2 U_mf to 3 U_mf at t = 3, after the restart
# point. On 1 and 2 ranks, a run to T = 4 without checkpoints and a run to T/2 = 2 that writes a
# checkpoint, continued with -restart to T, end with bitwise the same final frame (every dataset,
# particles and fluid, compared with h5py) and the same "column:" summary line (means over the
# second half of the run); the restarted run must be the one that switches the inlet; the same
# with -cpl_porosity_width 2 (1 and 2 ranks) and in the pressure-gradient form -cpl_form A (2). A
# checkpoint continued on another rank count (2 -> 1, 1 -> 2) ends within round-off of the
# writer's uninterrupted run. SIGTERM during a run leaves a checkpoint (exit 143, no .tmp) that
# continues bitwise to the same final frame. A checkpoint given to a run whose fluid grid
# differs is refused: exit non-zero, one error line naming the file and the dataset.
cd "$(dirname "$0")/../.." || exit 1
S=$(pwd)/${BIN:-bin}/sable
[ "$(id -u)" -eq 0 ] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1
W=$(mktemp -d)
trap 'rm -rf "$W"' EXIT
SCENE="-options_file $(pwd)/cases/fluidized_bed/small.opts -fluid_bc_zlo_velocity 0,0,0.2036 -fluid_bc_zlo_velocity_table 3,0,0,0.3054 -cpl_progress_interval 0"
T=4
H=2
run() { # np, dir, args...
  rnp=$1; rd=$2; shift 2
  mkdir -p "$rd"
  (cd "$rd" && mpiexec -n "$rnp" "$S" $SCENE -io_dir out "$@" >log 2>&1)
}
for np in 1 2; do
  d=$W/bed.$np
  run "$np" "$d/full" -cpl_t_end $T -io_interval $T
  run "$np" "$d/half" -cpl_t_end $H -io_interval 0 -io_checkpoint_interval $H
  ck=$(sed -n 's/^checkpoint: //p' "$d/half/log" | tail -n 1)
  run "$np" "$d/rest" -cpl_t_end $T -io_interval $T -restart "../half/$ck"
  a=$(ls "$d/full/out/"sable_*.h5 2>/dev/null | grep -v checkpoint | tail -n 1); b=$(ls "$d/rest/out/"sable_*.h5 2>/dev/null | grep -v checkpoint | tail -n 1)
  if [ -z "$ck" ] || [ -z "$a" ] || [ -z "$b" ]; then
    echo "FAIL coupled checkpoint np=$np: a run failed; $(cat "$d"/*/log | grep 'error' | head -n 2)"
    continue
  fi
  set -- $(tests/common/frames_equal.py "$a" "$b")
  if [ "$1" -gt 0 ] && [ "$2" -eq 0 ]; then
    echo "PASS coupled checkpoint np=$np: final frames at t=$T bitwise equal, $1 datasets compared (particles and fluid), 0 differing (restart from $ck at t=$H)"
  else
    echo "FAIL coupled checkpoint np=$np: $1 datasets compared, $2 differing: $3 $4 $5 $6"
  fi
  cf=$(grep '^column:' "$d/full/log"); cr=$(grep '^column:' "$d/rest/log")
  if [ -n "$cf" ] && [ "$cf" = "$cr" ]; then
    echo "PASS coupled checkpoint summary np=$np: the restarted run's \"column:\" line is the uninterrupted run's (${cf#column: pressure drop / bed buoyant weight per area })"
  else
    echo "FAIL coupled checkpoint summary np=$np: uninterrupted \"$cf\", restarted \"$cr\""
  fi
  if grep -q 'inlet zlo reaches row 1' "$d/rest/log" && ! grep -q 'inlet zlo reaches row' "$d/half/log"; then
    echo "PASS coupled checkpoint inlet np=$np: the inlet table switches in the restarted run ($(grep -o 'reaches row 1 .* s:' "$d/rest/log")), not before the checkpoint"
  else
    echo "FAIL coupled checkpoint inlet np=$np: the inlet switch is not after the restart point"
  fi
done
# the same with the drag's porosity smoothed over 2 d (-cpl_porosity_width: its mean diameter is in
# the checkpoint, the smoothed field is recomputed from the particles at every step) and in the
# pressure-gradient form (-cpl_form A: its force on the particles and the reaction are recomputed
# from the checkpoint's pressure and positions at every step)
same_restart() { # label, np, dir, options...
  lbl=$1; snp=$2; sd=$3; shift 3
  run "$snp" "$sd/full" -cpl_t_end $T -io_interval $T "$@"
  run "$snp" "$sd/half" -cpl_t_end $H -io_interval 0 -io_checkpoint_interval $H "$@"
  ck=$(sed -n 's/^checkpoint: //p' "$sd/half/log" | tail -n 1)
  run "$snp" "$sd/rest" -cpl_t_end $T -io_interval $T -restart "../half/$ck" "$@"
  a=$(ls "$sd/full/out/"sable_*.h5 2>/dev/null | grep -v checkpoint | tail -n 1); b=$(ls "$sd/rest/out/"sable_*.h5 2>/dev/null | grep -v checkpoint | tail -n 1)
  set -- $([ -n "$ck" ] && [ -n "$a" ] && [ -n "$b" ] && tests/common/frames_equal.py "$a" "$b")
  if [ "$#" -ge 2 ] && [ "$1" -gt 0 ] && [ "$2" -eq 0 ]; then
    echo "PASS coupled checkpoint $lbl np=$snp: final frames at t=$T bitwise equal, $1 datasets compared, 0 differing"
  else
    echo "FAIL coupled checkpoint $lbl np=$snp: compared: $*; $(cat "$sd"/*/log | grep 'error' | head -n 2)"
  fi
}
for np in 1 2; do same_restart "-cpl_porosity_width 2" "$np" "$W/pw.$np" -cpl_porosity_width 2; done
same_restart "-cpl_form A" 2 "$W/formA" -cpl_form A
out=$(cd "$W/pw.1" && "$S" $SCENE -cpl_t_end $T -io_interval 0 -io_dir plain -restart "half/$(sed -n 's/^checkpoint: //p' "$W/pw.1/half/log" | tail -n 1)" 2>&1 >/dev/null); rc=$?
out2=$(cd "$W/bed.1" && "$S" $SCENE -cpl_t_end $T -io_interval 0 -io_dir pw -cpl_porosity_width 2 -restart "half/$(sed -n 's/^checkpoint: //p' "$W/bed.1/half/log" | tail -n 1)" 2>&1 >/dev/null); rc2=$?
if [ "$rc" -eq 0 ] && [ "$rc2" -ne 0 ] && printf '%s' "$out2" | grep -q -- "-cpl_porosity_width 2.: the checkpoint was written without it; restart without -cpl_porosity_width"; then
  echo "PASS coupled checkpoint -cpl_porosity_width: a smoothed run's checkpoint continues without it (exit 0); a plain checkpoint with it is refused: \"$(printf '%s' "$out2" | grep 'sable: error')\""
else
  echo "FAIL coupled checkpoint -cpl_porosity_width: continued without it: exit $rc; plain checkpoint with it: exit $rc2, $(printf '%s' "$out2" | grep 'error' | head -n 1)"
fi
# another rank count: each half run's checkpoint continued on the other rank count, against the
# writer's uninterrupted run (particles matched by id). Other summation orders (the DEM's pair
# sums, the Poisson solve's reductions) differ at round-off; a lost field or spring would differ
# at the size of a step's change (>= 1e-6 here).
cat >"$W/near.py" <<'PY'
#!/usr/bin/python3
import sys, h5py, numpy as np
a, b = h5py.File(sys.argv[1], "r"), h5py.File(sys.argv[2], "r")
ia, ib = np.argsort(a["particles/id"][()]), np.argsort(b["particles/id"][()])
same = np.array_equal(a["particles/id"][()][ia], b["particles/id"][()][ib])
d = 2 * float(sys.argv[3])
dx = np.abs(a["particles/position"][()][ia] - b["particles/position"][()][ib]).max() / d
df = max(np.abs(a["fluid"][k][()] - b["fluid"][k][()]).max() / max(np.abs(a["fluid"][k][()]).max(), 1e-300) for k in a["fluid"])
print(int(same), "%.2g" % dx, "%.2g" % df)
PY
chmod +x "$W/near.py"
R=$(sed -n 's/^-dem_radius  *//p' cases/fluidized_bed/small.opts)
for pair in "2 1" "1 2"; do
  set -- $pair
  ck=$(sed -n 's/^checkpoint: //p' "$W/bed.$1/half/log" | tail -n 1)
  run "$2" "$W/x$1$2" -cpl_t_end $T -io_interval $T -restart "$W/bed.$1/half/$ck"
  a=$(ls "$W/bed.$1/full/out/"sable_*.h5 | grep -v checkpoint | tail -n 1); b=$(ls "$W/x$1$2/out/"sable_*.h5 2>/dev/null | grep -v checkpoint | tail -n 1)
  set -- $1 $2 $([ -n "$b" ] && "$W/near.py" "$a" "$b" "$R")
  if [ "$#" -eq 5 ] && [ "$3" -eq 1 ] && /usr/bin/python3 -c "import sys; sys.exit(not (float('$4') < 1e-9 and float('$5') < 1e-8))"; then
    echo "PASS coupled checkpoint $1 -> $2 ranks: final frame at t=$T vs the uninterrupted $1-rank run: every id, positions within $4 d (bound 1e-9), fluid fields within $5 of their largest value (bound 1e-8)"
  else
    echo "FAIL coupled checkpoint $1 -> $2 ranks: ids/positions/fields: $3 $4 $5; $(grep 'error' "$W/x$1$2/log" | head -n 1)"
  fi
done
# a stop signal: the checkpoint it leaves continues to the same final frame, bitwise
d=$W/sig
mkdir -p "$d"
(cd "$d" && exec "$S" $SCENE -cpl_t_end 400 -io_interval 1 -io_dir out >log 2>&1) &
pid=$!
i=0
while [ ! -f "$d/out/sable_000001.h5" ] && [ $i -lt 1200 ] && kill -0 $pid 2>/dev/null; do sleep 0.05; i=$((i + 1)); done
kill -TERM $pid 2>/dev/null
wait $pid
rc=$?
ck=$(sed -n 's/^checkpoint: //p' "$d/log" | tail -n 1)
[ -n "$ck" ] && (cd "$d" && "$S" $SCENE -cpl_t_end $T -io_interval $T -io_dir out2 -restart "$ck" >log2 2>&1)
b=$(ls "$d/out2/"sable_*.h5 2>/dev/null | grep -v checkpoint | tail -n 1)
a=$(ls "$W/bed.1/full/out/"sable_*.h5 | grep -v checkpoint | tail -n 1) # the final frames, both at T
set -- $([ -n "$b" ] && tests/common/frames_equal.py "$a" "$b")
tmp=$(find "$d" -name '*.tmp' | wc -l)
if [ "$rc" -eq 143 ] && [ "$tmp" -eq 0 ] && [ "$#" -ge 2 ] && [ "$1" -gt 0 ] && [ "$2" -eq 0 ]; then
  echo "PASS coupled signal: SIGTERM at $(grep -o 't = [0-9.]* s' "$d/log" | head -n 1) left $ck (0 .tmp); continued to t=$T, $1 datasets bitwise equal to the uninterrupted run's"
else
  echo "FAIL coupled signal: exit $rc, checkpoint '$ck', $tmp .tmp, compared: $*; $(grep 'sable:' "$d/log" "$d/log2" 2>/dev/null | head -n 2)"
fi
ck=$(ls "$W"/bed.1/half/out/*checkpoint*.h5 | tail -n 1)
out=$(cd "$W" && "$S" $SCENE -da_grid_z 20 -cpl_t_end $T -io_interval 0 -io_dir grid -restart "$ck" 2>&1 >/dev/null); rc=$?
lines=$(printf '%s\n' "$out" | grep -c 'sable: error')
if [ "$rc" -ne 0 ] && [ "$lines" -eq 1 ] && printf '%s' "$out" | grep -q -- "-restart $ck: the dataset fluid/p has 192 values, this grid needs 160 (the fluid grid differs)"; then
  echo "PASS bad coupled checkpoint, other fluid grid: exit $rc, \"$(printf '%s' "$out" | grep 'sable: error')\""
else
  echo "FAIL bad coupled checkpoint, other fluid grid: exit $rc, $lines error lines; got: $out"
fi
