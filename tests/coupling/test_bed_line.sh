#!/bin/sh
# The coupled start-up lines against figures recomputed here, glass beads (2500 kg/m^3) in air
# (1.2 kg/m^3, 1.8e-5 Pa s), -cpl_drag gidaspow (Ergun below porosity 0.8, so the drag law's
# U_mf has a closed form), one coupling step:
# - a bed of spheres of their own sizes on a loose lattice (tools/poly_bed.py: lognormal, d50
#   1 mm, sigma_g 1.25, cut 0.6-1.6 mm; -dem_radius 0.5 mm), porosity about 0.7: the bed: line's
#   d32 is sum d^3 / sum d^2 of the initial frame's spheres (1e-3: 4 digits printed); a lattice is
#   not the bed that fluidizes, so U_mf is taken at the packed porosity -cpl_umf_porosity (0.40
#   by default) and equals Ergun's root there at d32,
#     150 (1-e)^2 mu U / (e^3 d^2) + 1.75 (1-e) rho U^2 / (e^3 d) = (1-e)(rho_p - rho) g,
#   Wen and Yu's U_mf at d32 their correlation (Ar = rho (rho_p - rho) g d^3 / mu^2,
#   Re_mf = sqrt(33.7^2 + 0.0408 Ar) - 33.7) (both 2e-3), and the inlet's multiple of U_mf is
#   inlet / U_mf (5e-3: 3 digits printed);
# - a packed bed of its own sizes (an fcc lattice, periodic sides, diameters uniform in 0.9-1
#   mm): the porosity the line takes U_mf at is the bed's own (at most 0.445) and U_mf Ergun's
#   root there at d32;
# - a lattice of cubes of 1 mm: d32 is the volume-equivalent diameter (6/pi)^(1/3) mm;
# - a restart: a pour into still air (pour_coupled.opts) from an empty start, checkpointed at
#   0.01 s and continued: the pre-flight's relaxation time is taken at the smallest cell porosity
#   of the checkpoint's bed, the minimum of the porosity field of the frame written at the
#   checkpoint's time (5e-4: 3 decimals printed), not at the empty start's 1.
cd "$(dirname "$0")/../.." || exit 1
ROOT=$(pwd)
case ${BIN:-bin} in /*) S=$BIN/sable ;; *) S=$ROOT/${BIN:-bin}/sable ;; esac
[ "$(id -u)" -eq 0 ] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
W=$(mktemp -d)
trap 'rm -rf "$W"' EXIT
AIR="-dem_density 2500 -dem_gravity 0,0,-9.81 -dem_contact_law linear -dem_kn 500 -dem_restitution 0.9 -dem_friction 0.3 -dem_dt 5e-6 -fluid_density 1.2 -fluid_viscosity 1.8e-5 -fluid_bc_zlo inlet -fluid_bc_zlo_velocity 0,0,0.8 -fluid_bc_zhi outlet -cpl_drag gidaspow -cpl_substeps 10 -cpl_t_end 5e-5 -cpl_progress_interval 0 -io_interval 0"

# the beds: the loose lattice of poly_bed.py, and an fcc lattice written here
"$ROOT/tools/poly_bed.py" "$W/loose.h5" 200 0.001 1.25 0.008 0.008 0 --cut 0.6,1.6 >/dev/null || echo "FAIL bed line: tools/poly_bed.py failed"
/usr/bin/python3 - "$W/packed.h5" <<'EOF' || echo "FAIL bed line: the fcc bed was not written"
import sys
import h5py
import numpy as np
a, n, nz = 1e-3 * np.sqrt(2), 5, 8  # cube side for a nearest-neighbour distance of 1 mm
basis = np.array([[0, 0, 0], [0.5, 0.5, 0], [0.5, 0, 0.5], [0, 0.5, 0.5]])
pos = np.array([(np.array([i, j, k]) + b + 0.25) * a for k in range(nz) for j in range(n) for i in range(n) for b in basis])
pos[:, 2] += 0.5e-3 - 0.25 * a  # the lowest layer's spheres just above the floor
m = len(pos)
rng = np.random.RandomState(3)
with h5py.File(sys.argv[1], "w") as f:
    f["particles/position"] = pos
    f["particles/velocity"] = np.zeros((m, 3))
    f["particles/angular_velocity"] = np.zeros((m, 3))
    q = np.zeros((m, 4)); q[:, 0] = 1
    f["particles/quaternion"] = q
    f["particles/id"] = np.arange(m, dtype=np.float64)
    f["particles/radius"] = 0.5e-3 * rng.uniform(0.9, 1.0, m)
EOF
"$S" $AIR -domain_lo 0,0,0 -domain_hi 0.008,0.008,0.04 -da_grid_x 4 -da_grid_y 4 -da_grid_z 20 -dem_box 0,0,0,0.008,0.008,0.04 -dem_radius 0.0005 -dem_init_file "$W/loose.h5" -dem_init_file_radii own -io_dir "$W/loose" >"$W/loose.log" 2>&1 || echo "FAIL bed line: the loose bed's run stopped: $(grep error "$W/loose.log" | head -n 1)"
"$S" $AIR -domain_lo 0,0,0 -domain_hi 0.008,0.008,0.04 -da_grid_x 4 -da_grid_y 4 -da_grid_z 20 -dem_box 0,0,0,0.008,0.008,0.04 -dem_shape cube -dem_shape_size 0.001 -dem_lattice 4,4,6 -dem_lattice_spacing 0.0019 -io_dir "$W/cubes" >"$W/cubes.log" 2>&1 || echo "FAIL bed line: the cubes' run stopped: $(grep error "$W/cubes.log" | head -n 1)"
L=$(awk 'BEGIN { printf "%.17g", 5 * sqrt(2) * 1e-3 }')
"$S" $AIR -domain_lo 0,0,0 -domain_hi "$L,$L,0.02" -domain_periodic_x -domain_periodic_y -da_grid_x 4 -da_grid_y 4 -da_grid_z 10 -dem_plane_0 0,0,0,0,0,1 -dem_plane_1 0,0,0.02,0,0,-1 -dem_radius 0.0005 -dem_init_file "$W/packed.h5" -dem_init_file_radii own -io_dir "$W/packed" >"$W/packed.log" 2>&1 || echo "FAIL bed line: the packed bed's run stopped: $(grep error "$W/packed.log" | head -n 1)"

# d32 of a frame: sum d^3 / sum d^2
d32() { /usr/bin/python3 -c "import h5py, sys; d = 2 * h5py.File(sys.argv[1], 'r')['particles/radius'][()].ravel(); print('%.17g' % ((d ** 3).sum() / (d ** 2).sum()))" "$1"; }
check() { # name, log, reference d32 (m), expected porosity ("bed": the bed's own, else a value)
  grep '^bed: 95%.*between the 5%' "$2" | head -n 1 | awk -v name="$1" -v ref="$3" -v want="$4" '{
    for (i = 1; i <= NF; i++) {
      if ($i == "porosity" && bed == "") bed = $(i + 1)
      if ($i == "U_mf" && umf == "" && $(i + 1) ~ /^[0-9]/) umf = $(i + 1)
      if ($i == "at" && $(i + 1) == "porosity") eps = $(i + 2)
      if ($i == "d32" && d == "") d = $(i + 1)
      if ($i == "Wen-Yu" && wy == "") wy = $(i + 1)
      if ($i == "velocity" && $(i + 2) == "m/s") { u = $(i + 1); x = $(i + 4) }
    }
    rf = 1.2; mu = 1.8e-5; rp = 2500; g = 9.81
    ed = (d - ref) / ref; ed = ed < 0 ? -ed : ed
    printf "%s bed line, %s: d32 %s m against %.6g m, relative error %.1e (bound 1e-3)\n", (d != "" && ed < 1e-3) ? "PASS" : "FAIL", name, d, ref, ed
    e = want == "bed" ? bed : want; ee = eps - e; ee = ee < 0 ? -ee : ee
    printf "%s bed line, %s: U_mf taken at porosity %s (expected %s, %s)\n", (eps != "" && ee < 1e-4) ? "PASS" : "FAIL", name, eps, e, want == "bed" ? "the packed bed'"'"'s own" : "-cpl_umf_porosity, the bed being looser than a random packing"
    a = 1.75 * (1 - e) / e^3 * rf / ref; b = 150 * (1 - e)^2 / e^3 * mu / ref^2; c = (1 - e) * (rp - rf) * g
    ue = (-b + sqrt(b * b + 4 * a * c)) / (2 * a); eu = (umf - ue) / ue; eu = eu < 0 ? -eu : eu
    printf "%s bed line, %s: U_mf %s m/s against Ergun at porosity %s and d32 %.6g m: %.6g m/s, relative error %.1e (bound 2e-3)\n", (umf != "" && eu < 2e-3) ? "PASS" : "FAIL", name, umf, e, ref, ue, eu
    Ar = rf * (rp - rf) * g * ref^3 / mu^2; uw = (sqrt(33.7^2 + 0.0408 * Ar) - 33.7) * mu / (rf * ref); ew = (wy - uw) / uw; ew = ew < 0 ? -ew : ew
    printf "%s bed line, %s: Wen-Yu U_mf %s m/s against the correlation at d32: %.6g m/s (Ar %.5g), relative error %.1e (bound 2e-3)\n", (wy != "" && ew < 2e-3) ? "PASS" : "FAIL", name, wy, uw, Ar, ew
    if (u != "") { r = u / umf; er = (x - r) / r; er = er < 0 ? -er : er
      printf "%s bed line, %s: inlet %s U_mf, against %s m/s / %s m/s = %.4g (bound 5e-3: 3 digits printed)\n", (er < 5e-3) ? "PASS" : "FAIL", name, x, u, umf, r }
    found = 1 }
    END { if (!found) print "FAIL bed line, " name ": no bed line" }'
}
check "a loose lattice of lognormal sizes (d32: the frame's sum d^3 / sum d^2)" "$W/loose.log" "$(d32 "$W/loose.h5")" 0.40
check "a packed fcc bed of sizes 0.9-1 mm (d32: the frame's)" "$W/packed.log" "$(d32 "$W/packed.h5")" bed
check "a lattice of cubes of 1 mm (d32: the volume-equivalent (6/pi)^(1/3) mm)" "$W/cubes.log" "$(awk 'BEGIN { printf "%.17g", 1e-3 * (6 / atan2(0, -1))^(1 / 3) }')" 0.40

# the restart's pre-flight
P="-options_file $ROOT/tests/coupling/pour_coupled.opts -cpl_progress_interval 0 -io_dir $W/pour -io_interval 0.01"
"$S" $P -cpl_t_end 0.01 -io_checkpoint_interval 0.01 >"$W/pour.log" 2>&1 || echo "FAIL bed line: the pour stopped: $(grep error "$W/pour.log" | head -n 1)"
ck=$(sed -n 's/^checkpoint: //p' "$W/pour.log" | tail -n 1)
"$S" $P -cpl_t_end 0.0105 -restart "$ck" >"$W/rest.log" 2>&1 || echo "FAIL bed line: the restart stopped: $(grep error "$W/rest.log" | head -n 1)"
ref=$(/usr/bin/python3 -c "import h5py, sys; f = h5py.File(sys.argv[1], 'r'); print('%.6f %.9g' % (f['fluid/eps'][()].min(), f.attrs['time']))" "$W/pour/sable_000001.h5" 2>/dev/null)
got=$(sed -n 's/^pre-flight: coupling step .* at porosity \([0-9.]*\).*/\1/p' "$W/rest.log")
start=$(sed -n 's/^pre-flight: coupling step .* at porosity \([0-9.]*\).*/\1/p' "$W/pour.log")
set -- $ref
if [ -n "$got" ] && [ $# -eq 2 ] && awk -v a="$got" -v b="$1" 'BEGIN { e = a - b; exit !(e < 5e-4 && e > -5e-4) }'; then
  echo "PASS bed line, restart pre-flight: relaxation time at porosity $got, the smallest of the checkpoint's bed (the frame at t = $2 s: $1; bound 5e-4; the empty start's $start)"
else echo "FAIL bed line, restart pre-flight: relaxation time at porosity '$got', expected the smallest of the checkpoint's bed, '$1' at t = '$2' s (the start's: $start)"; fi
