#!/bin/sh
# Bad fluid input must stop the run with a clear message and a non-zero exit status. Drives
# tests/fluid/test_cli.c (a fluid-only driver) with one bad setting at a time and checks that
# the exit status is non-zero and that the message names the option or the limit.
cd "$(dirname "$0")/../.."
BUILD=${BUILD:-build}
[ "$(id -u)" -eq 0 ] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1
exe="$BUILD/tests/fluid/test_cli"
out=$(mktemp)
trap 'rm -f "$out"' EXIT

check() { # name, expected message (grep -E), ranks, options...
  name=$1; msg=$2; np=$3; shift 3
  if [ "$np" -eq 1 ]; then "$exe" -io_dir "${out}.d" "$@" >"$out" 2>&1; rc=$?
  else mpiexec -n "$np" "$exe" -io_dir "${out}.d" "$@" >"$out" 2>&1; rc=$?; fi
  rm -rf "${out}.d"
  if [ "$rc" -ne 0 ] && grep -Eq -- "$msg" "$out"; then
    echo "PASS badinput_$name: exit $rc, message found ($msg)"
  else
    echo "FAIL badinput_$name: exit $rc, message '$msg' not found; output:"
    grep -E 'ERROR|PASS|FAIL' "$out" | head -n 5 | sed 's/^/    /'
  fi
}

check negative_viscosity '-fluid_viscosity -0.001 must be > 0' 1 -fluid_viscosity -0.001
check zero_density '-fluid_density 0\.? must be > 0' 1 -fluid_density 0
check dt_above_cfl 'dt = 0.5 s gives CFL number .* above the limit -fluid_cfl_max' 1 -fluid_dt 0.5
check dt_above_viscous_limit 'explicit viscous number .* above the limit -fluid_viscous_number_max' 1 -fluid_viscosity 10 -fluid_density 1
check undecomposable_grid 'cannot be split over 2 ranks: every rank needs >= 2 cells' 2 -da_grid_x 2 -da_processors_x 2 -da_processors_y 1 -da_processors_z 1
check periodic_axis_bc '-fluid_bc_zlo inlet: the z axis is periodic' 1 -fluid_bc_zlo inlet
check misspelled_option 'option -fluid_viscosty .* nothing reads it' 1 -fluid_viscosty 1
check inlet_table_not_inlet '-fluid_bc_xhi_velocity_table is given but -fluid_bc_xhi is outlet, not inlet' 1 -fluid_bc_xhi_velocity_table 1,0,0,1
check inlet_table_row_count '-fluid_bc_xlo_velocity_table takes rows of 4 values t,u,v,w, 1 to 32 rows; got 3 values' 1 -fluid_bc_xlo_velocity_table 1,0.5,0
check inlet_table_times_decrease '-fluid_bc_xlo_velocity_table: times must increase strictly, row 2 has 0.5 after 1' 1 -fluid_bc_xlo_velocity_table 1,1,0,0,0.5,2,0,0
check inlet_table_negative_time '-fluid_bc_xlo_velocity_table: time -1\.? of row 1 must be >= 0' 1 -fluid_bc_xlo_velocity_table -1,1,0,0
check inlet_table_too_many_rows '-fluid_bc_xlo_velocity_table takes rows of 4 values t,u,v,w, 1 to 32 rows; got more than 128 values' 1 -fluid_bc_xlo_velocity_table "$(awk 'BEGIN {for (i = 0; i < 33; i++) printf "%s%d,1,0,0", i ? "," : "", i}')"
check inlet_interpolation_name '-fluid_inlet_interpolation cubic is not known; valid values: step, linear' 1 -fluid_inlet_interpolation cubic
check mg_levels_too_many '-fluid_poisson_pc_mg_levels 2: the fluid grid \(-da_grid_x 16\) has 16 cells along the bounded x axis after 0 coarsenings and cannot be coarsened again' 1 -fluid_poisson_pc_type mg -fluid_poisson_pc_mg_levels 2
check mg_levels_zero '-fluid_poisson_pc_mg_levels 0: the number of multigrid levels must be an integer in \[1,30\]' 1 -fluid_poisson_pc_type mg -fluid_poisson_pc_mg_levels 0
check negative_pc_lag '-fluid_poisson_pc_lag -1 must be >= 0' 1 -fluid_poisson_pc_lag -1
check pc_lag_growth_below_1 '-fluid_poisson_pc_lag_growth 0.5 must be >= 1' 1 -fluid_poisson_pc_lag_growth 0.5
check bad_advection_name '-fluid_advection upwind3 is not known; valid values: central, tvd, none' 1 -fluid_advection upwind3
# patches (src/fluid/patch.c), on 1 and 2 ranks; the box is 1 x 0.5 x 0.125 m, periodic in z
P="-fluid_patch_0_type inlet"
for np in 1 2; do
  check patch_not_on_named_face_np$np '-fluid_patch_0_face xhi: the shape of patch 0 does not lie on that face' $np $P -fluid_patch_0_disc 0,0.25,0.06,1,0,0,0.05 -fluid_patch_0_face xhi -fluid_patch_0_velocity 1
  check patch_source_off_grid_np$np '-fluid_patch_0 lies on no box face and crosses no open cell' $np $P -fluid_patch_0_disc 5,5,5,1,0,0,0.1 -fluid_patch_0_velocity 1
  check patch_velocity_and_mass_flow_np$np '-fluid_patch_0: give a velocity \(-fluid_patch_0_velocity\) or a mass flow \(-fluid_patch_0_mass_flow\), not both' $np $P -fluid_patch_0_disc 0,0.25,0.06,1,0,0,0.05 -fluid_patch_0_velocity 1 -fluid_patch_0_mass_flow 0.1
  check patch_outlet_inside_np$np '-fluid_patch_0: an outlet must lie on a box face' $np -fluid_patch_0_type outlet -fluid_patch_0_disc 0.5,0.25,0.06,1,0,0,0.05
done
check patch_no_type '-fluid_patch_3_\* options are given without -fluid_patch_3_type inlet\|outlet' 1 -fluid_patch_3_disc 0,0.25,0.06,1,0,0,0.05
check patch_two_shapes '-fluid_patch_0_\*: give exactly one shape' 1 $P -fluid_patch_0_disc 0,0.25,0.06,1,0,0,0.05 -fluid_patch_0_rect 0,0,0,0,0.5,0,0,0,0.125 -fluid_patch_0_velocity 1
check patch_periodic_face '-fluid_patch_0 lies on the zlo face, but the z axis is periodic' 1 $P -fluid_patch_0_disc 0.5,0.25,0,0,0,1,0.05 -fluid_patch_0_velocity 1
check patch_outlet_with_velocity '-fluid_patch_0_velocity: patch 0 is an outlet; it takes a pressure' 1 -fluid_patch_0_type outlet -fluid_patch_0_disc 1,0.25,0.06,1,0,0,0.05 -fluid_patch_0_velocity 1
check patch_not_convex '-fluid_patch_0_polygon: the vertices must make a convex polygon in one plane' 1 $P -fluid_patch_0_polygon 0,0.1,0.02,0,0.4,0.02,0,0.2,0.05,0,0.4,0.1 -fluid_patch_0_velocity 1
check distributor_open_area '-fluid_distributor: open-area fraction 1.5 must be in \(0,1\]' 1 -domain_periodic_z 0 -fluid_distributor 0.06,1.5
check distributor_outside '-fluid_distributor: height 0.5 m must lie inside the domain' 1 -domain_periodic_z 0 -fluid_distributor 0.5,0.3
# the same too-large dt with adaptive stepping: the step is cut to 0.9 of the CFL limit
"$exe" -io_dir "${out}.d" -fluid_dt 0.5 -fluid_adaptive_dt >"$out" 2>&1; rc=$?
rm -rf "${out}.d"
cfl=$(sed -n 's/.*last CFL \([0-9.]*\),.*/\1/p' "$out")
if [ "$rc" -eq 0 ] && [ "$cfl" = "0.450" ]; then echo "PASS adaptive_dt_cuts_to_0.9_cfl_max: CFL $cfl (0.9 x 0.5)"
else echo "FAIL adaptive_dt_cuts_to_0.9_cfl_max: exit $rc, CFL '$cfl'"; fi
check vessel_wall_name '-fluid_vessel_wall glue is not known; valid values: noslip, slip' 1 -fluid_vessel_wall glue
check vessel_theta_min_range '-fluid_vessel_theta_min 0\.? must be in \(0,1\]' 2 -fluid_vessel_theta_min 0
