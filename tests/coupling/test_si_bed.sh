#!/bin/sh
# The SI quick-start bed (cases/bubbling_bed/bubbling.opts) shortened: the same beads (d = 1 mm,
# 2500 kg/m^3), air, contact and inlet (3 U_mf of Wen and Yu), in a 20 x 4 mm slice 60 mm tall with 800 beads (a
# 20 x 4 x 10 lattice, 10 mm) for 0.6 s (about 18 s of CPU). Physics references:
#   (a) the run's Wen and Yu figures equal the correlation (Ar = rho_f (rho_p - rho_f) g d^3 /
#       mu^2, Re_mf = sqrt(33.7^2 + 0.0408 Ar) - 33.7) computed here from the case's values (1e-3:
#       the line prints 4 digits);
#   (b) the drag law's U_mf at the lattice's porosity 1 - pi/6 (-cpl_umf_porosity: the line takes
#       a lattice's U_mf at 0.40 by default) equals Ergun's equation's at the same porosity (5%;
#       Beetstra and Ergun cross near Re_p 50, measured 0.05%);
#   (c) hydrostatics: the monitor's probe pressure drop across the bed (probe 0 in the inlet cell
#       below the distributor, probe 1 above the bed), averaged over the second half, over the
#       bed's buoyant weight per area lies in [0.93, 1.02]: the fluid carries the bed but for the
#       distributor's share (the beads resting on it, whose drag is low because the face below the
#       bottom layer sees the particle-free cell's porosity): from the momentum balance of the
#       monitor's centre-of-mass height, 4% in this 10-layer bed at the case's 3 U_mf (8% at 2.5
#       U_mf; measured dp/W 0.953); the bed's momentum change over the window is below 1%;
#   (d) the fluidized bed expands: its mean 95% solids-mass height over the second half is at
#       least 15% above the packed lattice's (measured +72%).
cd "$(dirname "$0")/../.." || exit 1
. tests/common/coupled.sh
"$S" -options_file "$ROOT/cases/bubbling_bed/bubbling.opts" -io_dir "$W/out" -io_interval 0 \
  -domain_hi 0.02,0.004,0.06 -da_grid_x 10 -da_grid_z 30 -dem_plane_1 0,0,0.06,0,0,-1 \
  -dem_lattice 20,4,10 -mon_probe_0 0.01,0.002,0.001 -mon_probe_1 0.01,0.002,0.05 \
  -cpl_umf_porosity 0.476401 -cpl_t_end 0.6 -cpl_progress_interval 0.05 >"$W/log" 2>&1 || { echo "FAIL si bed: the run stopped:"; tail -3 "$W/log"; exit 1; }
# (a), (b): the start's bed line
awk '/^bed: 95%.*between the 5%/ {
  for (i = 1; i <= NF; i++) { if ($i == "U_mf" && umf == "" && $(i + 1) ~ /^[0-9]/) umf = $(i + 1); if ($i == "Wen-Yu") wy = $(i + 1); if ($i == "(Ar") ar = $(i + 1); if ($i == "porosity") eps = $(i + 1) }
  sub(/,/, "", ar)
  rf = 1.2; mu = 1.8e-5; d = 1e-3; rp = 2500; g = 9.81
  Ar = rf * (rp - rf) * g * d^3 / mu^2; re = sqrt(33.7^2 + 0.0408 * Ar) - 33.7; uw = re * mu / (rf * d)
  e1 = (ar - Ar) / Ar; e2 = (wy - uw) / uw; e1 = e1 < 0 ? -e1 : e1; e2 = e2 < 0 ? -e2 : e2
  printf "%s Wen-Yu figures vs the correlation: Ar %s (%.5g), U_mf %s m/s (%.5g), relative errors %.1e %.1e (bound 1e-3)\n", (e1 < 1e-3 && e2 < 1e-3) ? "PASS" : "FAIL", ar, Ar, wy, uw, e1, e2
  # Ergun: 150 (1-e)^2/e^3 mu U/d^2 + 1.75 (1-e)/e^3 rho U^2/d = (1-e)(rho_p - rho_f) g
  a = 1.75 * (1 - eps) / eps^3 * rf / d; b = 150 * (1 - eps)^2 / eps^3 * mu / d^2; c = (1 - eps) * (rp - rf) * g
  ue = (-b + sqrt(b * b + 4 * a * c)) / (2 * a); e3 = (umf - ue) / ue; e3 = e3 < 0 ? -e3 : e3
  printf "%s drag law U_mf at porosity %s vs Ergun: %s m/s (Ergun %.4g), relative error %.1e (bound 0.05)\n", (e3 < 0.05) ? "PASS" : "FAIL", eps, umf, ue, e3
  found = 1 }
  END { if (!found) print "FAIL si bed: no bed line in the log" }' "$W/log"
# (c), (d): the monitor over the second half; W from the column line
w=$(sed -n 's/.*weight per area \([0-9.e+-]*\) Pa.*/\1/p' "$W/log")
awk -F, -v w="$w" 'NR == 1 { for (i = 1; i <= NF; i++) { if ($i == "dp0 [Pa]") cd = i; if ($i == "bed_height_95 [m]") ch = i; if ($i == "time [s]") ct = i } next }
  NR == 2 { h0 = $ch }
  $ct > 0.3 + 1e-9 { s += $cd; h += $ch; n++ }
  END { if (!n || w == "") { print "FAIL si bed: no monitor rows or no weight"; exit }
    r = s / n / w; x = h / n / h0 - 1
    printf "%s probe pressure drop across the bed / buoyant weight per area, mean over t > 0.3 s: %.4f (%d rows, W %s Pa; bounds [0.93, 1.02], the distributor carries the rest)\n", (r >= 0.93 && r <= 1.02) ? "PASS" : "FAIL", r, n, w
    printf "%s fluidized bed expansion: mean 95%% solids-mass height over t > 0.3 s %.4f m, %.0f%% above the packed lattice'"'"'s %.4f m (bound >= 15%%)\n", (x >= 0.15) ? "PASS" : "FAIL", h / n, 100 * x, h0 }' "$W/out/sable_monitor.csv"
