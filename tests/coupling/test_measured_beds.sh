#!/bin/sh
# The measured beds of `make validate` (cases/wachem_bed, cases/muller_bed), short, and the tool
# that sets a run against its record (tools/bed_record).
#   (a) the tool on a synthetic monitor and record (sines): the rms of a sine of amplitude A is
#       A/sqrt(2) (1e-3), its Welch peak is its frequency (within a tenth of the spectrum's bin),
#       the mean of a constant-plus-sine height its constant (1e-3); a record of the same sines
#       PASSes;
#   (b) each case briefly (wachem 0.03 s, muller_u09 0.02 s with its averages from 0.01 s; 2
#       ranks): the run ends, tools/bed_record reads its monitor or last frame and prints a finite
#       figure on every row of the case's record description; wachem: the gas carries the bed,
#       the column line's dp/W within 5% of 1 (1.8 U_mf); muller: the time-averaged solids
#       fraction over the cells, times their volume, is the seeds' volume 9240 pi/6 d^3 (1e-10:
#       each sample of the kernel's porosity holds the particles' volume exactly).
cd "$(dirname "$0")/../.." || exit 1
. tests/common/coupled.sh
# (a) synthetic
mkdir -p "$W/syn/run" "$W/syn/rec"
/usr/bin/python3 - "$W/syn" <<'PY'
import math, sys
d = sys.argv[1]
with open(d + "/run/sable_monitor.csv", "w") as f:
    f.write("time [s],p_probe0 [Pa],bed_surface [m]\n")
    for k in range(4001):
        t = 2 + k * 0.002
        f.write("%.6f,%.9g,%.9g\n" % (t, 100 * math.sin(2 * math.pi * 2.5 * t), 0.12 + 0.01 * math.sin(2 * math.pi * 3.0 * t)))
with open(d + "/rec/pressure.csv", "w") as f:
    f.write("# synthetic\nt,p\n")
    for k in range(3001):
        t = 3 + k * 0.001
        f.write("%.6f,%.9g\n" % (t, 100 * math.sin(2 * math.pi * 2.5 * t)))
with open(d + "/rec/height.csv", "w") as f:
    f.write("t,h\n")
    for k in range(4001):
        t = 2 + k * 0.001
        f.write("%.6f,%.9g\n" % (t, 0.12 + 0.01 * math.sin(2 * math.pi * 3.0 * t)))
with open(d + "/rec/spec.txt", "w") as f:
    f.write("window 2 10\npressure pressure.csv - p_probe0 [Pa]\nheight height.csv bed_surface [m]\nband frequency 0.15\nband rms 0.25\nband height 0.08\n")
PY
out=$(tools/bed_record "$W/syn/rec/spec.txt" "$W/syn/run" 2>&1); rc=$?
printf '%s\n' "$out" | awk -v rc="$rc" '
  /^pressure fluctuation rms/ { run = $4 }
  /^pressure dominant frequency/ { f = $7 + 0; bin = $5 + 0; fv = $NF }
  /^mean bed height/ { h = $4 + 0; hv = $NF }
  /^bed height dominant frequency/ { hf = $5 + 0 }
  END {
    e1 = (run / (100 * sqrt(0.5 * 4000 / 4001)) - 1); e1 = e1 < 0 ? -e1 : e1
    e2 = f - 2.5; e2 = e2 < 0 ? -e2 : e2; e3 = hf - 3.0; e3 = e3 < 0 ? -e3 : e3
    e4 = h / 0.12 - 1; e4 = e4 < 0 ? -e4 : e4
    ok = (rc == 0 && bin > 0 && e1 < 1e-3 && e2 < 0.1 * bin && e3 < 0.1 * bin && e4 < 1e-3 && fv == "PASS" && hv == "PASS")
    printf "%s bed_record on sines: rms %.6g (of the 4001 samples of a sine of amplitude 100 over 20 periods: 70.7018; relative error %.1e, bound 1e-3), Welch peaks %.4f and %.4f Hz (2.5 and 3, bound a tenth of the %.3g Hz bin), mean height %.6g (0.12, bound 1e-3), a record like the run PASSes (%s, %s), exit %d\n", ok ? "PASS" : "FAIL", run, e1, f, hf, bin, h, fv, hv, rc }'
# (b) the cases, short
check_case() { # name, spec, run dir, end time, args...
  n=$1; spec=$2; d=$3; te=$4; shift 4
  mpiexec -n 2 "$S" "$@" -cpl_t_end "$te" -io_dir "$d" >"$d.log" 2>&1 || { echo "FAIL measured bed $n: the run stopped: $(grep error "$d.log" | head -n 1)"; return 1; }
  out=$(tools/bed_record "$spec" "$d" --from 0.002 --to "$te" 2>&1); rc=$?
  want=$(grep -c '^\(pressure\|height\|voidage\|velocity\)' "$spec")
  set -- $(printf '%s\n' "$out" | awk '/^(pressure|mean bed|bed height|voidage|velocity)/ { n++; for (i = 2; i <= NF; i++) if ($i ~ /^-?(nan|inf)$/) bad++ } END { print n + 0, bad + 0 }')
  if [ "$rc" -eq 0 ] && [ "$1" -ge "$want" ] && [ "$2" -eq 0 ]; then
    echo "PASS measured bed $n: $te s on 2 ranks, bed_record printed $1 finite rows for the $want items of $(basename "$spec")"
  else
    echo "FAIL measured bed $n: bed_record exit $rc, $1 rows ($2 not finite) for $want items: $(printf '%s' "$out" | tail -n 2)"
  fi
}
check_case wachem cases/wachem_bed/record/wachem.txt "$W/wachem" 0.03 -options_file cases/wachem_bed/wachem.opts -mon_interval 0.0002 -io_interval 0 -cpl_progress_interval 0 &&
  dpw=$(sed -n 's/^column: pressure drop \/ bed buoyant weight per area \([0-9.e+-]*\),.*/\1/p' "$W/wachem.log") &&
  if [ -n "$dpw" ] && awk -v x="$dpw" 'BEGIN { exit !(x > 0.95 && x < 1.05) }'; then
    echo "PASS measured bed wachem: the gas carries the bed: column dp/W $dpw (bound within 5% of 1)"
  else
    echo "FAIL measured bed wachem: column dp/W '$dpw' (bound within 5% of 1)"
  fi
check_case muller_u09 cases/muller_bed/record/muller_u09.txt "$W/muller" 0.02 -options_file cases/muller_bed/muller_u09.opts -avg_start 0.01 -io_interval 0.02 -cpl_progress_interval 0 &&
  /usr/bin/python3 - "$W/muller" <<'PY'
import math, sys
sys.path.insert(0, "tools")
import h5py, numpy as np
import sable_frames
run = sys.argv[1]
(o, h) = sable_frames.fluid_mesh(run)
with h5py.File(sable_frames.run_frames(run, kind="fluid")[-1], "r") as f:
    phi = np.array(f["fluid/avg_solids_fraction"])
vs = phi.sum() * h[0] * h[1] * h[2]
vp = 9240 * math.pi / 6 * 0.0012 ** 3
e = abs(vs / vp - 1)
print("%s measured bed muller_u09: time-averaged solids volume on the grid %.10g m^3 vs the seeds' %.10g (relative error %.1e, bound 1e-10)" % ("PASS" if e < 1e-10 else "FAIL", vs, vp, e))
PY
