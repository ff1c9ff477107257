#!/bin/sh
# A fluidized bed in a cylinder that bounds the gas: 9,000 spheres (d = 1, rho_p = 2) poured into a
# vertical cylinder of D = 30 d (test_cylinder_bed_pour.opts, dry; a random packing about 12 d
# deep), then fluidized with the inlet ramped from 0 to 2.5 U_mf over t = 0-8 and held there to
# t = 28 (test_cylinder_bed.opts: rho_f = 1, mu = 0.01, Ar = 1e4; dimensionless). Grids and
# ranks: CYL_RUNS, words <h>:<n> (cells of h d on n ranks; default "3:2": the suite's, whose 1 vs 2 ranks check is coupling/test_vessel_ranks.sh; the
# grid study of doc/validation.md ran "2:2 3:1 3:2 4:2"). Physics references, on every run:
#   (a) the plateau: dp/W, the pressure drop from the inlet face to the top cell over the bed's
#       buoyant weight per area of the cylinder, W = N (pi d^3/6)(rho_p - rho_f) g / (pi R^2),
#       mean over t = 18-28 (U = 2.5 U_mf, 10 time units after the ramp's end), within 3% of 1 (the fluid carries the bed); the inlet
#       face's pressure from a monitor probe on the face, on the axis (the centres' linear
#       extrapolation plus the drag the beads leave on the inlet's face points: the half cell's
#       momentum balance, src/fluid/faceshift.c); printed beside it: the same over the run's
#       own open cross-section (the column line's weight per area), the centres' extrapolation
#       alone and the first cell centre alone;
#   (b) U_mf from the ramp (the packed branch, U in 0.3-0.7 of Wen and Yu's U_mf, fitted by
#       dp = a U + b U^2 and met with W) within 10% of Wen and Yu's correlation
#       (Re_mf = sqrt(33.7^2 + 0.0408 Ar) - 33.7; made for beds near eps_mf 0.40, as poured here);
#   (c) no gas outside the cylinder at the end: u = 0 exactly in every cell wholly outside it (the
#       cells centred outside but open in part carry a little flux: a NOTE line gives its fraction);
# and across runs: (d) the same grid on 1 and 2 ranks gives U_mf and the plateau within 1%.
# 18 s of wall in the suite (2026-12-03, the 2-core VM idle; about 3 min at load 6-12 with two
# runs).
cd "$(dirname "$0")/../.." || exit 1
ROOT=$(pwd)
S=$ROOT/${BIN:-bin}/sable
T="/usr/bin/python3 $ROOT/tools/cylinder_bed"
[ "$(id -u)" -eq 0 ] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
W=$(mktemp -d)
[ -n "$CYL_KEEP" ] && echo "NOTE cylinder bed: runs kept in $W" || trap 'rm -rf "$W"' EXIT
D=tests/coupling
"$S" -options_file $D/test_cylinder_bed_pour.opts -io_dir "$W/pour" >"$W/pour.log" 2>&1 ||
  { echo "FAIL cylinder bed: the pour stopped:"; tail -3 "$W/pour.log"; exit 1; }
F=$W/pour/sable_000001.h5
set -- $($T porosity "$F" 15 1 9)
eps=${1#eps=} n=${2#n=}
set -- $($T wenyu 1 2 1 0.01 1)
uwy=${1#umf=}
w=$(awk -v n="$n" 'BEGIN { printf "%.10g", n * (3.141592653589793 / 6) * 1 * 1 / (3.141592653589793 * 225) }')
echo "NOTE cylinder bed: $n spheres poured, porosity $eps between z = 1 and 9; W = $w; Wen-Yu U_mf $uwy"
lo=$(awk -v u="$uwy" 'BEGIN { print 0.3 * u }')
hi=$(awk -v u="$uwy" 'BEGIN { print 0.7 * u }')
for run in ${CYL_RUNS:-3:2}; do
  h=${run%:*} np=${run#*:}
  half=$(awk -v h="$h" 'BEGIN { print 15 - (15 % h) + (15 % h ? h : 0) }')
  top=$(awk -v h="$h" -v b="$half" 'BEGIN { print 2 * b - h / 2 }')
  mpiexec --oversubscribe -n "$np" "$S" -options_file $D/test_cylinder_bed.opts -dem_init_file "$F" \
    -domain_lo "-$half,-$half,0" -domain_hi "$half,$half,$((2 * half))" -domain_cell "$h" \
    -mon_probe_0 "0,0,$(awk -v h="$h" 'BEGIN { print h / 2 }')" -mon_probe_1 "0,0,$(awk -v h="$h" 'BEGIN { print 1.5 * h }')" \
    -mon_probe_2 "0,0,$top" -mon_probe_3 0,0,0 -io_dir "$W/r$h-$np" >"$W/r$h-$np.log" 2>&1 ||
    { echo "FAIL cylinder bed, cells of $h d, $np ranks: the run stopped:"; tail -3 "$W/r$h-$np.log"; continue; }
  set -- $($T ramp "$W/r$h-$np/sable_monitor.csv" "$w" 0,0,8,0.14 "$lo" "$hi" 18 28 0 1 2 "$h" 3)
  umf=${1#umf=} pl=${5#plateau=} plc=${6#plateau_centre=} ple=${8#plateau_extrap=}
  wo=$(sed -n 's/.*weight per area \([0-9.e+-]*\) Pa.*/\1/p' "$W/r$h-$np.log")
  echo "$h $np $umf $pl" >>"$W/results"
  awk -v u="$umf" -v r="$uwy" -v p="$pl" -v pc="$plc" -v pe="$ple" -v h="$h" -v np="$np" -v w="$w" -v wo="$wo" 'BEGIN {
    e = p - 1; e = e < 0 ? -e : e
    printf "%s cylinder bed, cells of %s d, %s ranks: plateau dp/W at 2.5 U_mf (the inlet face'"'"'s pressure) %.4f (bound within 3%% of 1; over the open cross-section %.4f; the centres extrapolated alone %.4f; the first cell centre alone %.4f)\n", e < 0.03 ? "PASS" : "FAIL", h, np, p, (wo > 0 ? p * w / wo : 0), pe, pc
    x = u / r - 1; ax = x < 0 ? -x : x
    printf "%s cylinder bed, cells of %s d, %s ranks: U_mf from the ramp %.5g vs Wen-Yu %.5g, %+.1f%% (bound within 10%%)\n", ax < 0.1 ? "PASS" : "FAIL", h, np, u, r, 100 * x }'
  last=$(ls "$W/r$h-$np"/sable_0*.h5 | tail -1)
  set -- $($T outside "$last" 15 "-$half" "-$half" "$half" "$half")
  awk -v n="${1#closed=}" -v u="${2#umax=}" -v f="${3#outside_flux=}" -v h="$h" -v np="$np" 'BEGIN {
    printf "%s cylinder bed, cells of %s d, %s ranks: gas in the %d cells wholly outside the cylinder, largest |u| %.3g (bound 0: exact)\n", (n > 0 && u == 0) ? "PASS" : "FAIL", h, np, n, u
    printf "NOTE cylinder bed, cells of %s d, %s ranks: fraction of the upward flux in the cells centred outside the cylinder (open in part) %.3g\n", h, np, f }'
done
[ -f "$W/results" ] && awk '{ u[$1 ":" $2] = $3; p[$1 ":" $2] = $4; g[$1] = 1 }
  END { for (h in g) if ((h ":1") in u && (h ":2") in u) {
    du = u[h ":2"] / u[h ":1"] - 1; dp = p[h ":2"] - p[h ":1"]; du = du < 0 ? -du : du; dp = dp < 0 ? -dp : dp
    printf "%s cylinder bed, cells of %s d: 1 vs 2 ranks, U_mf %.5g / %.5g, plateau dp/W %.4f / %.4f (bounds within 1%%)\n", (du < 0.01 && dp < 0.01) ? "PASS" : "FAIL", h, u[h ":1"], u[h ":2"], p[h ":1"], p[h ":2"] } }' "$W/results"
