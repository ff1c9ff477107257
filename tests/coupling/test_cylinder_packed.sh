#!/bin/sh
# A packed bed in a cylinder that bounds the gas: 1,440 spheres (d = 1) poured into a vertical
# cylinder of D = 10 d (test_cylinder_packed_pour.opts, dry), then frozen, and gas (rho_f = 1,
# mu = 1, U = 1: Re_p = 1) passed upward through them (test_cylinder_packed.opts) on cells of 1 d
# and of 2 d, 2 ranks; dimensionless. Physics references:
#   (a) dp/L between the axis probes at z = 3 and 13 (inside the bed, top near 17.5) against
#       Eisfeld & Schnitzlein (2001, Chem. Eng. Sci. 56:4321: Ergun with the wall terms
#       A_w = 1 + 2 / (3 (D/d) (1 - eps)), B_w = (1.15 (d/D)^2 + 0.87)^2 and K1 = 154;
#       tools/cylinder_bed ergun_ws) at the porosity measured between the same planes from the
#       particles themselves (exact spherical caps over pi R^2 dz): within 10%;
#   (b) no gas outside the cylinder: every cell wholly outside it has u = 0 exactly (the cells
#       centred outside but open in part carry a little flux: a NOTE line gives its fraction);
#   (c) the poured spheres lie inside the cylinder (centre distance + r - R below 2% of d:
#       the wall contacts' overlap).
# The drag is Beetstra's (its low-Re limit 180 (1-eps)^2/eps^3 against the correlation's
# 154 A_w^2 = 191 at D/d = 10, eps = 0.42). About 6 s of CPU.
cd "$(dirname "$0")/../.." || exit 1
ROOT=$(pwd)
S=$ROOT/${BIN:-bin}/sable
T="/usr/bin/python3 $ROOT/tools/cylinder_bed"
[ "$(id -u)" -eq 0 ] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
W=$(mktemp -d)
trap 'rm -rf "$W"' EXIT
D=tests/coupling
"$S" -options_file $D/test_cylinder_packed_pour.opts -io_dir "$W/pour" >"$W/pour.log" 2>&1 ||
  { echo "FAIL cylinder packed bed: the pour stopped:"; tail -3 "$W/pour.log"; exit 1; }
F=$W/pour/sable_000001.h5
set -- $($T porosity "$F" 5 3 13)
eps=${1#eps=} out=${4#outside=}
awk -v o="$out" 'BEGIN { printf "%s cylinder packed bed: poured spheres inside the cylinder, largest centre distance + r - R: %.4f d (bound < 0.02)\n", o < 0.02 ? "PASS" : "FAIL", o }'
set -- $($T ergun_ws "$eps" 10 1 1 1 1)
es=${1#es=} erg=${2#ergun=}
for cell in 1 2; do
  mpiexec --oversubscribe -n 2 "$S" -options_file $D/test_cylinder_packed.opts -domain_cell $cell \
    -dem_init_file "$F" -io_dir "$W/c$cell" >"$W/c$cell.log" 2>&1 ||
    { echo "FAIL cylinder packed bed: the flow on cells of $cell d stopped:"; tail -3 "$W/c$cell.log"; continue; }
  awk -F, -v es="$es" -v erg="$erg" -v eps="$eps" -v c="$cell" '
    NR == 1 { for (i = 1; i <= NF; i++) if ($i == "dp0 [Pa]") cd = i; next }
    { prev = last; last = $cd }
    END { g = last / 10; r = g / es; s = (last - prev) / last; s = s < 0 ? -s : s
      printf "%s cylinder packed bed, cells of %s d: dp/L %.5g at porosity %.4f vs Eisfeld-Schnitzlein %.5g, ratio %.4f (bound within 10%%; Ergun without the wall %.5g); change over the last 0.5 time units %.1e\n", (r > 0.9 && r < 1.1) ? "PASS" : "FAIL", c, g, eps, es, r, erg, s }' "$W/c$cell/sable_monitor.csv"
  set -- $($T outside "$W/c$cell/sable_000001.h5" 5 -5 -5 5 5)
  awk -v n="${1#closed=}" -v u="${2#umax=}" -v f="${3#outside_flux=}" -v c="$cell" 'BEGIN {
    if (n > 0) printf "%s cylinder packed bed, cells of %s d: gas in the %d cells wholly outside the cylinder, largest |u| %.3g (bound 0: exact)\n", u == 0 ? "PASS" : "FAIL", c, n, u
    printf "NOTE cylinder packed bed, cells of %s d: fraction of the upward flux in the cells centred outside the cylinder (open in part) %.3g\n", c, f }'
done
