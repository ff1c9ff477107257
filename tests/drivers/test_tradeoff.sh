#!/bin/sh
# The trade-off tool (tools/tradeoff) and the stability limits it maps.
#  1. tools/tradeoff --quick on the normal impact (linear law, e = 0.75): 2 points, dt/Tc = 1/10
#     and 1/40; the restitution and contact-time errors must shrink at least as fast as dt
#     (order p = ln(err1/err2) / ln(dt1/dt2) >= 1: first order or better).
#  2. a 3 x 3 stability map (dt/Tc 0.02, 0.1, 0.5 x density ratio 1.2, 100, 3000, the small
#     fluidized bed): every cell stable (finite, dp/W within 5%) or stopped with one
#     "sable: error:" line; never NaN (printed or in an output frame) or a crash.
#  3. a DEM run past its stability limit (settle at dt/Tc 0.65 with the guard -dem_dt_max_fraction
#     raised to 1) stays finite but diverges: it must stop with the overlap message or the
#     particle-through-a-wall one (both say the run is diverging), not finish.
cd "$(dirname "$0")/../.." || exit 1
BUILD=${BUILD:-build}
export BUILD
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT

if tools/tradeoff impact --quick --out "$OUT" >"$OUT/log" 2>&1; then
  /usr/bin/python3 - "$OUT/impact.csv" <<'PY' || echo "FAIL tradeoff impact --quick: the checking script exited with status $?"
import csv, math, sys
rows = [r for r in csv.DictReader(open(sys.argv[1]))]
ok = len(rows) == 2 and all(r["status"] == "ok" for r in rows)
if not ok:
    print(f"FAIL tradeoff impact --quick: {len(rows)} rows, statuses {[r['status'] for r in rows]}")
    sys.exit(0)
rows.sort(key=lambda r: -float(r["dt_tc"]))
dts = [float(r["dt_tc"]) for r in rows]
for key, what in (("err_e", "restitution"), ("err_tc", "contact time")):
    e1, e2 = (float(r[key]) for r in rows)
    p = math.log(e1 / e2) / math.log(dts[0] / dts[1]) if e1 > 0 and e2 > 0 else float("nan")
    print(f"{'PASS' if p >= 1 else 'FAIL'} tradeoff impact --quick {what}: error {e1:.3e} at dt/Tc {dts[0]:.3g}, {e2:.3e} at {dts[1]:.3g}, order {p:.2f} (>= 1)")
PY
else
  echo "FAIL tradeoff impact --quick: exit status $?"; tail -n 5 "$OUT/log"
fi

tools/tradeoff stability --plane dem --quick --out "$OUT" >"$OUT/log" 2>&1
rc=$?
/usr/bin/python3 - "$OUT/stability_dem.csv" "$rc" <<'PY' || echo "FAIL stability map 3x3: the checking script exited with status $?"
import csv, sys
rows = [r for r in csv.DictReader(open(sys.argv[1]))] if sys.argv[2] in ("0", "1") else []
bad = [r for r in rows if not (r["status"] == "stable" or (r["status"] == "stopped" and r["message"].startswith("sable: error:")))]
nan = [r for r in rows if "nan" in ",".join(r.values()).lower()]
n = {s: sum(r["status"] == s for r in rows) for s in ("stable", "stopped")}
ok = len(rows) == 9 and not bad and not nan
print(f"{'PASS' if ok else 'FAIL'} stability map 3x3 (dt/Tc x density ratio): {len(rows)} cells, {n['stable']} stable, {n['stopped']} stopped with a message, {len(bad)} other, {len(nan)} with NaN (bound: 9 cells, 0 other, 0 NaN)")
for r in bad:
    print(f"    cell dt_tc={r['dt_tc']} density_ratio={r['density_ratio']}: {r['status']} {r.get('message', '')}")
PY

out=$(${BIN:-bin}/sable -options_file cases/settle/quick.opts -io_interval 0.05 -io_dir "$OUT/div" -dem_dt 1e-4 -dem_dt_max_fraction 1 -dem_t_end 0.3 -dem_progress_interval 0.02 2>&1)
rc=$?
msg=$(printf '%s\n' "$out" | grep 'sable: error')
if [ "$rc" -eq 1 ] && printf '%s' "$msg" | grep -q "above -dem_overlap_max\|went through wall" && ! printf '%s' "$out" | grep -qi '\bnan\b'; then
  echo "PASS diverging DEM (dt/Tc 0.65) stops: exit $rc, \"$msg\""
else
  echo "FAIL diverging DEM (dt/Tc 0.65) stops: exit $rc, got: $(printf '%s' "$out" | tail -n 2)"
fi

# -dem_dt_tc (the presets' way to set dt): dt is that fraction of the shortest contact time
out=$(${BIN:-bin}/sable -options_file cases/settle/quick.opts -io_interval 0 -io_dir "$OUT/dttc" -dem_dt_tc 0.05 -dem_t_end 0.002 2>&1)
got=$(printf '%s\n' "$out" | sed -n 's/.*with particle: .*dt\/Tc = \([0-9.]*\) .*/\1/p')
if [ "$got" = "0.05" ]; then echo "PASS -dem_dt_tc 0.05: the log's particle-particle dt/Tc $got (0.05)"; else echo "FAIL -dem_dt_tc 0.05: dt/Tc '$got'; $(printf '%s' "$out" | tail -n 1)"; fi
