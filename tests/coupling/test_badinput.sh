#!/bin/sh
# Coupled runs that cross a hard limit or carry a mistake must stop with a clear message and a
# non-zero exit status. Drives ${BIN:-bin}/sable on the small fluidized bed (cases/fluidized_bed/small.opts)
# with one bad setting at a time; also checks that the start-up log lists the modules and the
# pre-flight ratios, and that a frozen bed says it integrates nothing.
cd "$(dirname "$0")/../.."
[ "$(id -u)" -eq 0 ] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
case=cases/fluidized_bed/small.opts
out=$(mktemp)
trap 'rm -rf "$out" "$out.d"' EXIT

check() { # name, expected message (grep -E), options...
  name=$1; msg=$2; shift 2
  ${BIN:-bin}/sable -options_file ${CASE:-$case} -io_dir "$out.d" -cpl_t_end 0.1 "$@" >"$out" 2>&1; rc=$?
  if [ "$rc" -ne 0 ] && grep -Eq -- "$msg" "$out"; then
    echo "PASS cpl_badinput_$name: exit $rc, message found ($msg)"
  else
    echo "FAIL cpl_badinput_$name: exit $rc, message '$msg' not found; output:"
    tail -n 3 "$out" | sed 's/^/    /'
  fi
}

CASE=cases/packed_bed/packed_bed.opts; check kernel_too_wide 'cube kernel side .* above the limit of 2: coarsen the grid .* or lower -cpl_kernel_scale' -cpl_kernel_scale 2.6
CASE=
check relaxation_time 'coupling step .* particle relaxation times .* above -cpl_relaxation_ratio_max 1' -dem_density 1.01 -cpl_substeps 400
check inconsistent_dt '-fluid_dt 0.1 differs from -cpl_substeps 5 x -dem_dt' -fluid_dt 0.1
check porosity_floor '-cpl_porosity_floor 1.5 must be in \(0,1\)' -cpl_porosity_floor 1.5
check substeps '-cpl_substeps 0 must be >= 1' -cpl_substeps 0
check filter_sweeps '-cpl_filter_width 200. .* takes 5411 diffusion sweeps .* the limit is 100' -cpl_filter_width 200
check form_unknown '-cpl_form C is not known; valid values: B, A' -cpl_form C
check form_filter '-cpl_filter_width 2. with -cpl_form A: the filter would move' -cpl_form A -cpl_filter_width 2
check form_self '-cpl_self_velocity with -cpl_form A: ' -cpl_form A -cpl_self_velocity
check self_porosity_filter '-cpl_self_porosity removes the particle.s unfiltered kernel dip, which -cpl_filter_width 2. changes' -cpl_self_porosity -cpl_filter_width 2
check porosity_width_filter '-cpl_porosity_width 3.5 with -cpl_filter_width 2.: both smooth over a width in diameters' -cpl_porosity_width 3.5 -cpl_filter_width 2
check porosity_width_oneway '-cpl_porosity_width 3.5 with -cpl_mode oneway: a one-way run.s drag sees porosity 1' -cpl_porosity_width 3.5 -cpl_mode oneway
check porosity_width_negative '-cpl_porosity_width -1.? must be >= 0' -cpl_porosity_width -1
check porosity_width_too_wide '-cpl_porosity_width 40.? .* reaches .* beyond the domain.s length' -cpl_porosity_width 40
check bad_drag_name '-cpl_drag stokes is not known; valid values: beetstra, difelice, gidaspow, schiller' -cpl_drag stokes
check fluid_gravity '-fluid_gravity .* must be 0,0,0 in a coupled run' -fluid_gravity 0,0,-1
check misspelled_option 'option -cpl_substep 3 was given but nothing reads it' -cpl_substep 3
check bad_mode '-cpl_mode both is not known; valid values: twoway, oneway' -cpl_mode both
check self_porosity_word '^sable: error: -cpl_self_porosity maybe is not a flag; valid values: true, false' -cpl_self_porosity maybe
# a word another option also takes: the line names this option, not the first one given the word
check self_porosity_number '^sable: error: -cpl_self_porosity 2 is not a flag' -cpl_substeps 2 -cpl_self_porosity 2
CASE=cases/packed_bed/packed_bed.opts; check oneway_frozen '-cpl_mode oneway with -dem_frozen: .*nothing would be coupled' -cpl_mode oneway
CASE=
CASE=tests/coupling/test_conserve.opts; check init_uniform_no_inlet '-cpl_init_fluid uniform: the fluid has no inlet face' -cpl_init_fluid uniform
CASE=
check init_steady_unconverged '-cpl_init_fluid steady: a pseudo step still changed the velocity by .* after -cpl_init_fluid_max_steps 2' -cpl_init_fluid steady -cpl_init_fluid_max_steps 2
check init_rtol '-cpl_init_fluid_rtol 0\.? must be in \(0,1\)' -cpl_init_fluid_rtol 0

${BIN:-bin}/sable -options_file $case -io_dir "$out.d" -cpl_t_end 0.5 >"$out" 2>&1; rc=$?
if [ "$rc" -eq 0 ] && grep -q '^modules: DEM on; fluid on; coupling on' "$out" && grep -q '^pre-flight: coupling step / particle relaxation time' "$out" && grep -q '^pre-flight: cell / diameter' "$out"; then
  echo "PASS cpl_startup_log: modules line and pre-flight ratios printed"
else echo "FAIL cpl_startup_log: exit $rc"; head -n 12 "$out" | sed 's/^/    /'; fi
${BIN:-bin}/sable -options_file cases/packed_bed/packed_bed.opts -io_dir "$out.d" -cpl_t_end 0.5 >"$out" 2>&1; rc=$?
if [ "$rc" -eq 0 ] && grep -q 'DEM on (frozen: no particle integration)' "$out"; then
  echo "PASS cpl_frozen_log: the frozen bed says it integrates no particles"
else echo "FAIL cpl_frozen_log: exit $rc"; head -n 4 "$out" | sed 's/^/    /'; fi
CASE=; check dry_end_time_in_coupled_run '-dem_t_end applies to dry runs; this run is coupled .*use -cpl_t_end' -dem_t_end 5
# multigrid without Galerkin coarse operators (PETSc's own message asked for DMKSPSetComputeOperators)
CASE=cases/fluidized_bed/bed.opts; check mg_without_galerkin '-fluid_poisson_pc_type mg with 2 levels needs -fluid_poisson_pc_mg_galerkin pmat' -cpl_t_end 0.05 -fluid_poisson_pc_mg_galerkin none
CASE=
