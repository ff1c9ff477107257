#!/bin/sh
# A run that continues: signals, output and options across a restart (dry runs of 384 spheres
# settling in a box, on 1 and 2 ranks).
# (a) SIGTERM, sent once the run has written its second frame, leaves a checkpoint (named by the stop
#     line) and no .tmp; the run continued from it with -restart ends with bitwise the same
#     frames (every dataset of every frame, the final one included) as the uninterrupted run.
# (b) The continued run's frames go on numbering in the same -io_dir: its XDMF index lists the
#     frames of both parts, the same files and times as the uninterrupted run's index (times
#     increasing), and every frame and the index carry one run_id.
# (c) A restart into a directory holding another run's frames (the uninterrupted run's) is
#     refused before running, in one line naming the file and -io_dir; those frames are untouched.
# (d) A restart with a physics option changed prints one warning naming it, old and new value;
#     one with only -dem_t_end extended prints none.
cd "$(dirname "$0")/../.." || exit 1
S=$(pwd)/${BIN:-bin}/sable
[ "$(id -u)" -eq 0 ] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1
W=$(mktemp -d)
trap 'rm -rf "$W"' EXIT
SCENE="-domain_lo 0,0,0 -domain_hi 0.1449,0.1449,0.24633 -dem_box 0,0,0,0.1449,0.1449,0.24633 -dem_radius 0.0069 -dem_density 2500 -dem_restitution 0.75 -dem_friction 0.3 -dem_dt 1e-5 -dem_lattice 8,8,6 -dem_lattice_spacing 0.01449 -dem_lattice_speed 0.05 -dem_contact_law linear -dem_kn 7.2e5"
RUN="-dem_t_end 0.3 -io_interval 0.03 -dem_progress_interval 0.03"
# every frame of the index in $1 against the same file in $2 (every dataset, bytes), the two
# indexes' (file, time) lists, increasing times, one run_id across $2's frames and index. Prints
# "frames datasets differing sametimes increasing runids".
cat >"$W/cmp.py" <<'PY'
#!/usr/bin/python3
import sys, os, re, h5py
def index(d):
    x = open(os.path.join(d, "sable.xmf")).read()
    grids = re.findall(r'<Grid Name="particles" GridType="Uniform">\s*<Time Value="([^"]+)"/>.*?>([^<>]+\.h5):/particles/vertex<', x, re.S)
    return [(os.path.basename(f), float(t)) for t, f in grids], re.findall(r'Name="run_id" Value="(\d+)"', x)
ref, _ = index(sys.argv[1])
got, ids = index(sys.argv[2])
ndata = ndiff = 0
for f, _ in ref:
    a, b = h5py.File(os.path.join(sys.argv[1], f), "r"), h5py.File(os.path.join(sys.argv[2], f), "r")
    names = []
    a.visit(lambda n: names.append(n) if isinstance(a[n], h5py.Dataset) else None)
    ndata += len(names)
    ndiff += sum(n not in b or a[n].dtype != b[n].dtype or a[n][()].tobytes() != b[n][()].tobytes() for n in names)
    ids.append(str(b.attrs.get("run_id", "none")))
inc = all(t1 < t2 for (_, t1), (_, t2) in zip(got, got[1:]))
print(len(ref), ndata, ndiff, int(ref == got), int(inc), len(set(ids)))
PY
chmod +x "$W/cmp.py"
for np in 1 2; do
  d=$W/np$np
  L="mpiexec -n $np"
  [ $np -eq 1 ] && L="" # one process without the launcher: its lines reach the log at once
  mkdir -p "$d/full" "$d/sig"
  (cd "$d/full" && $L "$S" $SCENE $RUN -io_dir out >log 2>&1)
  # the stopped run would go on far beyond T (a run to T takes under a second here, less than
  # the launcher's start); its continuation ends at T like the uninterrupted one
  (cd "$d/sig" && exec $L "$S" $SCENE $RUN -dem_t_end 30 -io_dir out >log 2>&1) &
  pid=$!
  i=0 # the run is under way once its second frame is in place (mpiexec may hold the log's lines back)
  while [ ! -f "$d/sig/out/sable_000001.h5" ] && [ $i -lt 1200 ] && kill -0 $pid 2>/dev/null; do sleep 0.05; i=$((i + 1)); done
  # every rank gets the signal, as a batch system sends it to every task (mpiexec passes one on
  # late: the run is then past T)
  if [ $np -eq 1 ]; then kill -TERM $pid 2>/dev/null; else pkill -TERM -P $pid 2>/dev/null; fi
  wait $pid
  rc=$?
  ck=$(sed -n 's/^checkpoint: //p' "$d/sig/log" | tail -n 1)
  stop=$(grep '^sable: stopped:' "$d/sig/log")
  tmp=$(find "$d/sig" -name '*.tmp' | wc -l)
  nbefore=$(ls "$d/sig/out/" | grep -c '^sable_[0-9]*\.h5$')
  if [ "$rc" -ne 0 ] && [ -n "$ck" ] && [ -f "$d/sig/$ck" ] && [ "$tmp" -eq 0 ] && printf '%s' "$stop" | grep -q "checkpoint $ck"; then
    echo "PASS signal checkpoint np=$np: SIGTERM after the second frame: exit $rc, $ck written and named by the stop line, 0 .tmp files"
  else
    echo "FAIL signal checkpoint np=$np: exit $rc, checkpoint '$ck', $tmp .tmp files; stop line: '$stop'; $(grep -c '^done:' "$d/sig/log") done lines (1: the run ended before the signal); waited $i x 0.05 s for its second frame"
    continue
  fi
  (cd "$d/sig" && $L "$S" $SCENE $RUN -io_dir out -restart "$ck" >log2 2>&1)
  set -- $("$W/cmp.py" "$d/full/out" "$d/sig/out")
  if [ "$#" -eq 6 ] && [ "$1" -gt 1 ] && [ "$3" -eq 0 ]; then
    echo "PASS signal restart np=$np: continued from $ck, $1 frames ($2 datasets) bitwise equal to the uninterrupted run's, 0 differing"
  else
    echo "FAIL signal restart np=$np: frames, datasets, differing = $1 $2 $3; $(grep 'sable:' "$d/sig/log2")"
  fi
  if [ "$#" -eq 6 ] && [ "$4" -eq 1 ] && [ "$5" -eq 1 ] && [ "$6" -eq 1 ] && [ "$1" -gt "$nbefore" ]; then
    echo "PASS frames continue np=$np: the index lists $1 frames ($nbefore written before the signal, the rest after the restart), the same files and times as the uninterrupted run's, increasing, one run_id"
  else
    echo "FAIL frames continue np=$np: $1 frames (before the signal $nbefore), same (file, time) list $4, increasing $5, run_ids $6"
  fi
done
# (c) another run's frames, from the restart's next frame on, are refused
d=$W/np1
ck=$(sed -n 's/^checkpoint: //p' "$d/sig/log" | tail -n 1)
before=$(cksum "$d"/full/out/sable_*.h5 | cksum)
out=$(cd "$d/sig" && "$S" $SCENE $RUN -io_dir ../full/out -restart "$ck" 2>&1 >/dev/null)
rc=$?
if [ "$rc" -ne 0 ] && [ "$(printf '%s\n' "$out" | grep -c 'sable: error')" -eq 1 ] && printf '%s' "$out" | grep -q -- "-io_dir ../full/out: ../full/out/sable_[0-9]*\.h5 is a frame of another run.*choose another -io_dir" && [ "$before" = "$(cksum "$d"/full/out/sable_*.h5 | cksum)" ]; then
  echo "PASS another run's frames refused: exit $rc, \"$out\", its frames unchanged"
else
  echo "FAIL another run's frames refused: exit $rc; got: $out"
fi
# (d) changed physics options warn, an extended run does not
mkdir -p "$W/opt" && cd "$W/opt" || exit 1
"$S" $SCENE -dem_t_end 0.01 -io_interval 0 -io_checkpoint_interval 0.01 -io_dir out >log 2>&1
ck=$(sed -n 's/^checkpoint: //p' log | tail -n 1)
"$S" $SCENE -dem_t_end 0.012 -io_interval 0 -io_dir out -restart "$ck" >ext.log 2>&1
rc1=$?
"$S" $SCENE -dem_t_end 0.012 -io_interval 0 -io_dir out -restart "$ck" -dem_friction 0.25 -dem_deterministic >chg.log 2>&1
rc2=$?
n1=$(grep -c '^restart: -' ext.log)
n2=$(grep -c '^restart: -' chg.log)
if [ -n "$ck" ] && [ "$rc1" -eq 0 ] && [ "$n1" -eq 0 ]; then
  echo "PASS extended run: -dem_t_end 0.01 -> 0.012 continued from $ck with 0 warnings"
else
  echo "FAIL extended run: exit $rc1, $n1 warnings: $(grep -e '^restart: -' -e 'sable:' ext.log)"
fi
if [ "$rc2" -eq 0 ] && [ "$n2" -eq 2 ] && grep -q "^restart: -dem_friction was 0.3 in the checkpoint's run, now 0.25: the continued run is not the same physics$" chg.log && grep -q "^restart: -dem_deterministic was not given in the checkpoint's run, now given" chg.log; then
  echo "PASS changed physics: one warning each for -dem_friction (changed) and -dem_deterministic (added): \"$(grep '^restart: -dem_friction' chg.log)\""
else
  echo "FAIL changed physics: exit $rc2, $n2 warnings (want 2): $(grep -e '^restart: -' -e 'sable:' chg.log)"
fi
