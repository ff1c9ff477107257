#!/bin/sh
# Signals during output, and the end of a failed parallel run.
# A run writing a frame every 50 steps is sent SIGTERM or SIGINT at staggered times: it must stop
# at a step boundary with one 'sable: stopped:' line and the status 128 + signal, leave no
# temporary (*.tmp), and every frame its index lists must open and hold finite positions. The same
# on 2 ranks through mpiexec. On 2 ranks, an error every rank sees ends with one 'sable: error:'
# line and without MPI_ABORT's banner (under mpiexec -q, stderr is that line alone); an error of
# one rank prints one line naming its rank and ends every rank (through MPI_Abort, the one prompt
# way: Open MPI's notice follows, and in about half the runs its own ORTE_ERROR_LOG line, a race
# inside Open MPI 4.1's MPI_Abort that a ten-line program calling it shows too; the run's whole
# time is reported against the same run ending without the error).
cd "$(dirname "$0")/../.." || exit 1
[ "$(id -u)" -eq 0 ] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
S=${BIN:-bin}/sable
D=$(mktemp -d); trap 'rm -rf "$D"' EXIT
RUN="-options_file cases/settle/quick.opts -dem_t_end 5 -io_interval 0.0005 -dem_progress_interval 0"

# frames listed in the index open and hold finite positions; prints "nframes bad"
check_frames() {
  /usr/bin/python3 - "$1" <<'PY'
import sys, os, re, h5py, numpy as np
d = sys.argv[1]
idx = os.path.join(d, "sable.xmf")
if not os.path.exists(idx):
    print(0, 0); sys.exit()
import xml.dom.minidom
xml.dom.minidom.parse(idx)
files = sorted(set(re.findall(r"(sable_\d+\.h5):/particles/position", open(idx).read())))
bad = 0
for f in files:
    try:
        with h5py.File(os.path.join(d, f), "r") as h:
            bad += not np.isfinite(h["particles/position"][...]).all()
    except Exception:
        bad += 1
print(len(files), bad)
PY
}

# waits (at most 60 s) until the run in $1 has written its second frame: the handlers are in place
wait_frame() {
  i=0
  while [ ! -f "$1/sable_000001.h5" ] && [ $i -lt 600 ]; do sleep 0.1; i=$((i + 1)); done
}

trial() { # label, launcher prefix ('' or mpiexec ...), signal, delay (s)
  label=$1; launch=$2; sig=$3; delay=$4; out="$D/$label"
  $launch $S $RUN -io_dir "$out" >"$D/$label.log" 2>&1 &
  pid=$!
  wait_frame "$out"; sleep "$delay"; kill -"$sig" "$pid"; wait "$pid"; rc=$?
  tmp=$(find "$out" -name '*.tmp' 2>/dev/null | wc -l)
  set -- $(check_frames "$out"); nfr=$1; nbad=$2
  nstop=$(grep -c '^sable: stopped:' "$D/$label.log")
  echo "$rc $tmp $nfr $nbad $nstop"
}

n=0; bad=0; frames=0; detail=""
for k in 1 2 3 4 5 6 7 8; do
  sig=TERM; want=143; [ $((k % 2)) -eq 0 ] && sig=INT && want=130
  set -- $(trial "serial$k" "" $sig "0.$k")
  n=$((n + 1)); frames=$((frames + $3))
  if [ "$1" -ne "$want" ] || [ "$2" -ne 0 ] || [ "$3" -eq 0 ] || [ "$4" -ne 0 ] || [ "$5" -ne 1 ]; then bad=$((bad + 1)); detail="$detail [SIG$sig: exit $1 (want $want), $2 tmp, $3 frames, $4 bad, $5 stop lines]"; fi
done
[ "$bad" -eq 0 ] && echo "PASS signals, 1 rank: $n runs sent SIGTERM/SIGINT while writing a frame every 50 steps: exit 143/130, one 'sable: stopped:' line, 0 temporaries, $frames indexed frames all valid (bound: 0 failures)" \
  || echo "FAIL signals, 1 rank: $bad of $n runs failed:$detail"

n=0; bad=0; frames=0; detail=""
for k in 1 2 3 4; do
  sig=TERM; [ $((k % 2)) -eq 0 ] && sig=INT
  set -- $(trial "par$k" "mpiexec --oversubscribe -n 2" $sig "0.$k")
  n=$((n + 1)); frames=$((frames + $3))
  if [ "$1" -eq 0 ] || [ "$2" -ne 0 ] || [ "$3" -eq 0 ] || [ "$4" -ne 0 ] || [ "$5" -ne 1 ]; then bad=$((bad + 1)); detail="$detail [SIG$sig: exit $1, $2 tmp, $3 frames, $4 bad, $5 stop lines: $(tail -2 "$D/par$k.log" | tr '\n' ' ')]"; fi
done
[ "$bad" -eq 0 ] && echo "PASS signals, 2 ranks: $n mpiexec runs sent SIGTERM/SIGINT: non-zero exit, one 'sable: stopped:' line, 0 temporaries, $frames indexed frames all valid (bound: 0 failures)" \
  || echo "FAIL signals, 2 ranks: $bad of $n runs failed:$detail"

# two signals in a row (the kernel may merge them into one): either way one line and no temporary
$S $RUN -io_dir "$D/twice" >"$D/twice.log" 2>&1 &
pid=$!; wait_frame "$D/twice"; kill -TERM $pid; kill -TERM $pid; wait $pid; rc=$?
tmp=$(find "$D/twice" -name '*.tmp' | wc -l)
if [ "$rc" -eq 143 ] && [ "$tmp" -eq 0 ] && [ "$(grep -c '^sable: stopped:' "$D/twice.log")" -eq 1 ]; then echo "PASS signals, SIGTERM twice in a row: exit $rc, one 'sable: stopped:' line, 0 temporaries"
else echo "FAIL signals, SIGTERM twice: exit $rc, $tmp temporaries: $(tail -2 "$D/twice.log")"; fi

# 2 ranks, an error every rank sees (an option nothing reads)
mpiexec --oversubscribe -n 2 $S -options_file cases/settle/quick.opts -demfriction 0.3 >"$D/all.out" 2>"$D/all.err"; rc=$?
nerr=$(grep -c 'sable: error' "$D/all.err"); noise=$(grep -c -E 'MPI_ABORT|ORTE_ERROR_LOG' "$D/all.err")
if [ "$rc" -ne 0 ] && [ "$nerr" -eq 1 ] && [ "$noise" -eq 0 ]; then echo "PASS parallel error seen by every rank: exit $rc, one 'sable: error:' line, no MPI_ABORT banner: \"$(grep 'sable: error' "$D/all.err")\""
else echo "FAIL parallel error seen by every rank: exit $rc, $nerr error lines, $noise MPI_ABORT/ORTE lines: $(head -3 "$D/all.err" | tr '\n' ' ')"; fi
mpiexec -q --oversubscribe -n 2 $S -options_file cases/settle/quick.opts -demfriction 0.3 >/dev/null 2>"$D/q.err"; rc=$?
if [ "$rc" -ne 0 ] && [ "$(wc -l <"$D/q.err")" -eq 1 ]; then echo "PASS parallel error under mpiexec -q: exit $rc, stderr is one line"
else echo "FAIL parallel error under mpiexec -q: exit $rc, stderr has $(wc -l <"$D/q.err") lines: $(head -3 "$D/q.err" | tr '\n' ' ')"; fi

# 2 ranks, an error of rank 1 alone: a particle leaves the domain in rank 1's box while rank 0 steps on
LOCAL="-domain_lo 0,0,0 -domain_hi 0.2,0.1,0.1 -da_processors_x 2 -da_processors_y 1 -da_processors_z 1 -dem_radius 0.005 -dem_density 2500 -dem_kn 1e4 -dem_dt 5e-5 -dem_lattice 1,1,1 -dem_lattice_origin 0.18,0.05,0.05 -dem_gravity 50,0,0 -dem_t_end 1 -io_interval 0"
start=$(date +%s.%N)
timeout 60 mpiexec --oversubscribe -n 2 $S $LOCAL >"$D/one.out" 2>"$D/one.err"; rc=$?
el=$(echo "$(date +%s.%N) - $start" | bc)
nerr=$(grep -c 'sable: error' "$D/one.err")
if [ "$rc" -ne 0 ] && [ "$rc" -ne 124 ] && [ "$nerr" -eq 1 ] && grep -q 'sable: error (rank 1): .*left the domain across its upper x side' "$D/one.err" && [ "$(grep -c 'sable: stopped' "$D/one.err")" -eq 0 ]; then
  echo "PASS parallel error of one rank: exit $rc, one line naming the rank, none from the rank it leaves waiting, every rank ended (no hang): \"$(grep 'sable: error' "$D/one.err")\""
else echo "FAIL parallel error of one rank: exit $rc (124 = hung), $nerr error lines: $(head -3 "$D/one.err" | tr '\n' ' ')"; fi
start=$(date +%s.%N)
mpiexec --oversubscribe -n 2 $S $LOCAL -dem_t_end 0.028 >/dev/null 2>&1
ok=$(echo "$(date +%s.%N) - $start" | bc)
echo "NOTE parallel error of one rank: the whole mpiexec run took $el s; the same run ending without the error at that time, $ok s"
