#!/bin/sh
# A study branched from a checkpoint, the checkpoint at the end, and what a restart's log says.
# References: the uninterrupted run's frames and monitor rows at the same times, the files'
# checksums before the restart, and the step counts of the checkpoint and of the uninterrupted run.
# (a) Branch: a dry run (cases/settle/quick.opts, 1 and 2 ranks) and a coupled one
#     (cases/fluidized_bed/small.opts) stopped halfway with a checkpoint, continued with -restart
#     into a new -io_dir, exit 0 and say "restart: new output series in DIR from t = T"; the new
#     monitor starts with the header and a row at the checkpoint's time, and its rows are the
#     uninterrupted run's from there on (every column but the wall times and, in the first row
#     before any step, the last fluid step's eps_min and Poisson iterations); the new index lists
#     only the new frames, from the checkpoint's time on, each bitwise the uninterrupted run's
#     frame at its time (tests/common/frames_equal.py); the old folder is unchanged (checksums).
#     ParaView (pvpython) reads the coupled branch's index. Another -io_prefix in the same -io_dir
#     is a new series too. A restart in the same -io_dir with a new -mon_file continues the frames
#     and starts a new monitor series in that file, the old monitor unchanged.
# (b) -io_checkpoint_interval 0 given explicitly writes no checkpoint at the end (dry and
#     coupled); a SIGTERM still writes its checkpoint.
# (c) A restart's log: an inlet table's row reached before the checkpoint is not announced as
#     reached at t = 0 (the line names the row's time and the restart's); "done:" counts this
#     run's steps (the uninterrupted run's minus the checkpoint's) and names the step reached.
cd "$(dirname "$0")/../.." || exit 1
R=$(pwd)
S=$R/${BIN:-bin}/sable
[ "$(id -u)" -eq 0 ] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1
W=$(mktemp -d)
trap 'rm -rf "$W"' EXIT
DRY="-options_file $R/cases/settle/quick.opts -dem_progress_interval 0 -io_interval 0.01 -mon_interval 0.005"
WET="-options_file $R/cases/fluidized_bed/small.opts -cpl_progress_interval 0 -io_interval 0.5 -mon_interval 0.25 -fluid_bc_zlo_velocity_table 0,0,0,0.2036,3,0,0,0.3054"
# the new series in $2 against the uninterrupted run in $1 from time $3 on; monitor file names
# $4 (in $1) and $5; prints "header rows rows_equal first_time index_frames index_from_t0
# frames_equal frames_compared"
cat >"$W/branch.py" <<'PY'
#!/usr/bin/python3
import sys, os, re, subprocess
full, new, t0, mfull, mnew = sys.argv[1], sys.argv[2], float(sys.argv[3]), sys.argv[4], sys.argv[5]
def rows(p):
    lines = open(p).read().splitlines()
    return lines[0], [l.split(",") for l in lines[1:]]
hf, rf = rows(mfull)
hn, rn = rows(mnew)
cols = hn.split(",")
skip = {i for i, c in enumerate(cols) if c.startswith("wall_time")}
first = {i for i, c in enumerate(cols) if c.startswith("eps_min") or c.startswith("poisson_iterations")}
ref = [r for r in rf if float(r[0]) >= t0 * (1 - 1e-9)]
eq = len(ref) == len(rn) and all(all(a[i] == b[i] for i in range(len(cols)) if i not in skip and not (k == 0 and i in first)) for k, (a, b) in enumerate(zip(ref, rn)))
def index(d):
    x = open(os.path.join(d, "sable.xmf")).read()
    return [(float(t), f) for t, f in re.findall(r'<Grid Name="particles" GridType="Uniform">\s*<Time Value="([^"]+)"/>.*?>([^<>]+\.h5):/particles/vertex<', x, re.S)]
fi, ni = dict((t, f) for t, f in index(full)), index(new)
ok = n = 0
for t, f in ni:
    if t not in fi:
        continue
    out = subprocess.run([sys.executable, "tests/common/frames_equal.py", os.path.join(full, fi[t]), os.path.join(new, f)], capture_output=True, text=True).stdout.split()
    n += 1
    ok += len(out) >= 2 and int(out[0]) > 0 and int(out[1]) == 0
fromt0 = len(ni) > 0 and ni[0][0] == min(t for t in fi if t >= t0 * (1 - 1e-9)) and all(t >= t0 * (1 - 1e-9) for t, _ in ni) and len(ni) == len([t for t in fi if t >= t0 * (1 - 1e-9)])
print(int(hn == hf), len(rn), int(eq), rn[0][0] if rn else "none", len(ni), int(fromt0), ok, n)
PY
chmod +x "$W/branch.py"
sums() { (cd "$1" && find . -type f | sort | xargs md5sum | md5sum | cut -c1-12); }

# branch kind np run_opts end half: the uninterrupted run, the half run with a checkpoint, the
# branch into a new -io_dir
branch() {
  kind=$1 np=$2 opts=$3 tend=$4 half=$5
  d=$W/$kind.$np
  mkdir -p "$d"
  L="mpiexec -n $np"
  [ "$np" -eq 1 ] && L=""
  endopt=-dem_t_end
  [ "$kind" = coupled ] && endopt=-cpl_t_end
  (cd "$d" && $L "$S" $opts $endopt "$tend" -io_dir full >full.log 2>&1 &&
    $L "$S" $opts $endopt "$half" -io_dir half -io_checkpoint_interval "$half" >half.log 2>&1)
  ck=$(sed -n 's/^checkpoint: //p' "$d/half.log" | tail -n 1)
  before=$(sums "$d/half")
  (cd "$d" && $L "$S" $opts $endopt "$tend" -io_dir out/branch -restart "$ck" >branch.log 2>&1)
  rc=$?
  line=$(grep '^restart: new output series' "$d/branch.log")
  if [ -n "$ck" ] && [ "$rc" -eq 0 ] && printf '%s' "$line" | grep -q "^restart: new output series in out/branch from t = $half"; then
    echo "PASS branch $kind np=$np: -restart $ck -io_dir out/branch: exit 0, \"$line\""
  else
    echo "FAIL branch $kind np=$np: checkpoint '$ck', exit $rc: $(grep -e 'sable:' -e '^restart' "$d/branch.log" | head -n 3)"
    return
  fi
  set -- $(cd "$R" && "$W/branch.py" "$d/full" "$d/out/branch" "$half" "$d/full/sable_monitor.csv" "$d/out/branch/sable_monitor.csv")
  if [ "$#" -eq 8 ] && [ "$1" -eq 1 ] && [ "$2" -gt 2 ] && [ "$3" -eq 1 ] && awk -v t="$4" -v h="$half" 'BEGIN { exit !(t > h - 1e-9 && t < h + 1e-9) }'; then
    echo "PASS branch monitor $kind np=$np: a new file with the uninterrupted run's header, its first row at t = $4 (the checkpoint's), $2 rows equal to the uninterrupted run's from there on"
  else
    echo "FAIL branch monitor $kind np=$np: same header $1, rows $2, equal $3, first time $4"
  fi
  if [ "$#" -eq 8 ] && [ "$5" -gt 1 ] && [ "$6" -eq 1 ] && [ "$7" -eq "$5" ] && [ "$8" -eq "$5" ]; then
    echo "PASS branch frames $kind np=$np: the new index lists $5 frames, from the checkpoint's time to the end, each bitwise the uninterrupted run's at its time"
  else
    echo "FAIL branch frames $kind np=$np: the new index lists $5 frames (from the checkpoint's time on, as many as the uninterrupted run's there: $6); $7 of $8 equal to the uninterrupted run's"
  fi
  after=$(sums "$d/half")
  if [ "$before" = "$after" ]; then
    echo "PASS branch old folder $kind np=$np: the checkpoint's run's folder unchanged ($(ls "$d/half" | wc -l) files, checksum $after)"
  else
    echo "FAIL branch old folder $kind np=$np: checksum $before before the branch, $after after"
  fi
}
branch dry 1 "$DRY" 0.04 0.02
branch dry 2 "$DRY" 0.04 0.02
branch coupled 1 "$WET" 4 2
# ParaView (pvpython's XDMF reader) reads the coupled branch's index: its times are the new frames'
if command -v pvpython >/dev/null; then
  cat >"$W/pv.py" <<'PY'
import sys
from paraview.simple import XDMFReader, servermanager
r = XDMFReader(FileNames=[sys.argv[1]])
r.UpdatePipelineInformation()
t = list(r.TimestepValues)
ok = 0
for tt in t:
    r.UpdatePipeline(tt)
    d = servermanager.Fetch(r)
    ok += d.GetBlock(0).GetNumberOfPoints() == 384 and d.GetBlock(1).GetNumberOfCells() == 192
print(len(t), ok, t[0] if t else -1, t[-1] if t else -1)
PY
  set -- $(timeout 120 pvpython "$W/pv.py" "$W/coupled.1/out/branch/sable.xmf" 2>/dev/null | tail -n 1)
  if [ "$#" -eq 4 ] && [ "$1" -eq 5 ] && [ "$2" -eq 5 ] && awk -v a="$3" -v b="$4" 'BEGIN { exit !(a > 2 - 1e-9 && a < 2 + 1e-9 && b > 4 - 1e-9 && b < 4 + 1e-9) }'; then
    echo "PASS branch paraview: pvpython reads the branch's index: $1 times from $3 to $4 (the checkpoint's to the end, every 0.5), each with 384 particles and 192 fluid cells"
  else
    echo "FAIL branch paraview: pvpython read: $* (want 5 times from 2 to 4, each with 384 particles and 192 cells)"
  fi
else
  echo "NOTE branch paraview: pvpython not found, the branch's index not opened in ParaView"
fi

# another -io_prefix in the same -io_dir: a new series beside the old one, which is untouched
d=$W/dry.1
ck=$(sed -n 's/^checkpoint: //p' "$d/half.log" | tail -n 1)
s0=$(cd "$d/half" && md5sum sable* | md5sum | cut -c1-12)
(cd "$d" && "$S" $DRY -dem_t_end 0.04 -io_dir half -io_prefix b -restart "$ck" >prefix.log 2>&1)
rc=$?
nb=$(grep -c 'Name="particles" GridType="Uniform"' "$d/half/b.xmf" 2>/dev/null)
tb=$(grep -o 'Time Value="[^"]*"' "$d/half/b.xmf" 2>/dev/null | head -n 1 | cut -d'"' -f2)
mb=$(sed -n 2p "$d/half/b_monitor.csv" 2>/dev/null | cut -d, -f1)
s1=$(cd "$d/half" && md5sum sable* | md5sum | cut -c1-12)
if [ "$rc" -eq 0 ] && [ "${nb:-0}" -eq 3 ] && [ -f "$d/half/b_000000.h5" ] && [ "$tb" = "$mb" ] && [ -n "$tb" ] && [ "$s0" = "$s1" ]; then
  echo "PASS new -io_prefix: exit 0, b.xmf lists 3 frames from t = $tb, b_monitor.csv starts there, the sable_* files unchanged (checksum $s1)"
else
  echo "FAIL new -io_prefix: exit $rc, b.xmf lists ${nb:-no} frames from t = '$tb', b_monitor.csv's first row at '$mb', sable_* checksum $s0 -> $s1: $(grep 'sable:' "$d/prefix.log")"
fi

# a new -mon_file in the same -io_dir: the frames go on, the monitor starts a new series
m0=$(md5sum <"$d/half/sable_monitor.csv")
(cd "$d" && "$S" $DRY -dem_t_end 0.04 -io_dir half -mon_file half/other.csv -restart "$ck" >mon.log 2>&1)
rc=$?
set -- $(cd "$R" && "$W/branch.py" "$d/full" "$d/half" 0 "$d/full/sable_monitor.csv" "$d/full/sable_monitor.csv")
nidx=$5
set -- $([ -f "$d/half/other.csv" ] && cd "$R" && "$W/branch.py" "$d/full" "$d/full" 0.02 "$d/full/sable_monitor.csv" "$d/half/other.csv")
if [ "$rc" -eq 0 ] && [ "$#" -eq 8 ] && [ "$1" -eq 1 ] && [ "$3" -eq 1 ] && [ "$m0" = "$(md5sum <"$d/half/sable_monitor.csv")" ] && [ "$nidx" -eq "$(grep -c 'Name="particles" GridType="Uniform"' "$d/full/sable.xmf")" ]; then
  echo "PASS new -mon_file: exit 0; the frames continue in -io_dir ($nidx in the index, as the uninterrupted run's), a new monitor series of $2 rows from t = $4, the old monitor unchanged"
else
  echo "FAIL new -mon_file: exit $rc: $(grep 'sable:' "$d/mon.log"); monitor: $*; index frames $nidx"
fi

# (b) -io_checkpoint_interval 0: none at the end; a stop signal still writes one
d=$W/zero
mkdir -p "$d"
(cd "$d" && "$S" $DRY -dem_t_end 0.005 -io_interval 0 -mon_interval 0 -io_checkpoint_interval 0 -io_dir dry >dry.log 2>&1 &&
  "$S" $WET -cpl_t_end 0.5 -io_interval 0 -mon_interval 0 -io_checkpoint_interval 0 -io_dir wet >wet.log 2>&1)
rc=$?
n1=$(ls "$d/dry" "$d/wet" 2>/dev/null | grep -c checkpoint)
if [ "$rc" -eq 0 ] && [ "$n1" -eq 0 ]; then
  echo "PASS checkpoint interval 0: a dry and a coupled run with -io_checkpoint_interval 0 end without a checkpoint (0 files)"
else
  echo "FAIL checkpoint interval 0: exit $rc, $n1 checkpoint files: $(cat "$d"/*.log | grep -e '^checkpoint:' -e 'sable:')"
fi
(cd "$d" && exec "$S" $DRY -dem_t_end 30 -io_interval 0.001 -mon_interval 0 -io_checkpoint_interval 0 -io_dir sig >sig.log 2>&1) &
pid=$!
i=0
while [ ! -f "$d/sig/sable_000001.h5" ] && [ $i -lt 600 ] && kill -0 $pid 2>/dev/null; do sleep 0.05; i=$((i + 1)); done
kill -TERM $pid 2>/dev/null
wait $pid
rc=$?
ck=$(sed -n 's/^checkpoint: //p' "$d/sig.log" | tail -n 1)
if [ "$rc" -eq 143 ] && [ -n "$ck" ] && [ -f "$d/$ck" ] && grep -q "^sable: stopped: SIGTERM.*checkpoint $ck" "$d/sig.log"; then
  echo "PASS checkpoint interval 0, SIGTERM: exit 143, $ck written and named by the stop line"
else
  echo "FAIL checkpoint interval 0, SIGTERM: exit $rc, checkpoint '$ck': $(grep 'sable:' "$d/sig.log")"
fi

# (c) the log of a restart in the same place (works on any version): inlet rows and "done:"
d=$W/coupled.1
ck=$(sed -n 's/^checkpoint: //p' "$d/half.log" | tail -n 1)
(cd "$d" && "$S" $WET -cpl_t_end 4 -io_dir half -restart "$ck" >rest.log 2>&1)
rc=$?
inl=$(grep '^fluid: inlet zlo' "$d/rest.log" | head -n 1)
if [ "$rc" -eq 0 ] && ! grep -q 'reaches row 1 ' "$d/rest.log" && printf '%s' "$inl" | grep -q "is at row 1 of its table (reached at t = 0\.* s, before this run's start at t = 2\.* s)" && grep -q 'reaches row 2 of its table at t = 3\.* s' "$d/rest.log"; then
  echo "PASS restart inlet line: \"$inl\"; row 2 announced when reached"
else
  echo "FAIL restart inlet line: exit $rc; inlet lines: $(grep '^fluid: inlet' "$d/rest.log" | tr '\n' '|')"
fi
# the done: line of the restart in $1 from checkpoint $2: this run's steps (the uninterrupted run's
# less the checkpoint's) and the step reached; $3 the label, $4 what the counter counts, $5 the
# restart time as printed
done_line() {
  tot=$(sed -n "s/^done: t = [^,]*, \([0-9]*\) $4.*/\1/p" "$1/full.log")
  cks=$(printf '%s' "$2" | sed 's/.*_0*\([0-9][0-9]*\)\.h5$/\1/')
  done=$(grep '^done:' "$1/rest.log")
  got=$(printf '%s' "$done" | sed -n "s/^done: t = [^,]*, \([0-9]*\) $4.*/\1/p")
  if [ -n "$tot" ] && [ "$got" = "$((tot - cks))" ] && printf '%s' "$done" | grep -q "from the restart at t = $5, step $cks, to step $tot"; then
    echo "PASS restart done line $3: \"$done\" ($tot - $cks steps: the uninterrupted run's less the checkpoint's)"
  else
    echo "FAIL restart done line $3: \"$done\" (want $tot - $cks steps of this run, and the step reached)"
  fi
}
done_line "$d" "$ck" coupled "fluid steps" '2\.*'
d=$W/dry.1
ck=$(sed -n 's/^checkpoint: //p' "$d/half.log" | tail -n 1)
(cd "$d" && "$S" $DRY -dem_t_end 0.04 -io_dir half2 -mon_interval 0 -io_interval 0 -restart "$ck" >rest.log 2>&1)
done_line "$d" "$ck" dry steps '0.02 s'
