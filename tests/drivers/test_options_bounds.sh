#!/bin/sh
# Bounds of a run's options, each an error of one line (exit 1, exactly one "sable: error:" line
# naming the option and the value as given), never a run that does not end or floods the log:
#   - a step count beyond the step counter (PetscInt) from the end time and the time step, dry
#     and coupled; a progress or output interval shorter than one step;
#   - a run without an end time (-dem_t_end, -cpl_t_end); an end equal to the start runs 0 steps
#     and the log says so in one line;
#   - an integer option whose item is not an integer or does not fit in PetscInt, for every
#     option that src/ reads with PetscOptions*Int* or SableOptionsInt under a literal name and
#     every PETSc -da_ option that the cases and tests give;
#   - an options file holding a NUL byte, a control byte or a byte-order mark;
#   - two options of which one would silently override the other;
#   - an unknown option near a known one gets "did you mean -<known>?".
cd "$(dirname "$0")/../.." || exit 1
T=$(mktemp -d); trap 'rm -rf "$T"' EXIT
S=${BIN:-bin}/sable
DRY="-options_file cases/settle/quick.opts -dem_t_end 0.001 -io_interval 0"
WET="-options_file cases/fluidized_bed/small.opts -cpl_t_end 0.5 -io_interval 0"
expect() { # name, fixed text the error must hold, arguments...
  name=$1; pat=$2; shift 2
  out=$($S "$@" 2>&1); rc=$?
  err=$(printf '%s\n' "$out" | grep 'sable: error')
  n=$(printf '%s\n' "$out" | grep -c 'sable: error')
  if [ "$rc" -eq 1 ] && [ "$n" -eq 1 ] && printf '%s\n' "$err" | grep -qF -- "$pat"; then echo "PASS bounds $name: exit 1, \"$err\""
  else echo "FAIL bounds $name: exit $rc, $n error lines, expected \"$pat\"; got: $(printf '%s\n' "$out" | tail -n 2)"; fi
}
# 1. step count and cadences
expect "tiny DEM step" "-dem_t_end 0.001 s at a time step of 1e-30 s (-dem_dt) takes 1e+27 steps, more than the step counter holds (2147483647)" $DRY -dem_dt 1e-30
expect "huge DEM end" "-dem_t_end 1e+30 s at a time step of 1e-05 s (-dem_dt) takes 1e+35 steps" $DRY -dem_t_end 1e30
expect "progress below the step" "-dem_progress_interval 1e-30 s is shorter than the time step 1e-05 s" $DRY -dem_progress_interval 1e-30
expect "output below the step" "-io_interval 1e-09 s is shorter than the time step 1e-05 s" $DRY -io_interval 1e-9 -io_dir "$T/o"
expect "huge coupled end" "-cpl_t_end 1e+30 s at a coupling step of 0.025 s (-cpl_substeps 5 x -dem_dt 0.005 s) takes 2e+32 DEM steps" $WET -cpl_t_end 1e30
expect "coupled progress below the step" "-cpl_progress_interval 0.001 s is shorter than the coupling step 0.025 s" $WET -cpl_progress_interval 0.001
expect "coupled output below the step" "-io_interval 0.001 s is shorter than the coupling step 0.025 s" $WET -io_interval 0.001 -io_dir "$T/o"
# 2. an end is needed; an end at the start says it runs 0 steps
grep -v '_t_end' cases/settle/quick.opts > "$T/dry.opts"; grep -v '_t_end' cases/fluidized_bed/small.opts > "$T/wet.opts"
expect "dry run without an end" "the run has no end: give -dem_t_end, the simulated time to reach (s)" -options_file "$T/dry.opts" -io_interval 0
expect "coupled run without an end" "the run has no end: give -cpl_t_end, the simulated time to reach (s)" -options_file "$T/wet.opts" -io_interval 0
for c in "dem:$DRY" "cpl:$WET"; do
  out=$($S ${c#*:} -${c%%:*}_t_end 0 2>&1); rc=$?
  n=$(printf '%s\n' "$out" | grep -c "^run: -${c%%:*}_t_end 0. s is not after the start time 0. s: 0 steps")
  if [ "$rc" -eq 0 ] && [ "$n" -eq 1 ]; then echo "PASS bounds -${c%%:*}_t_end 0: exit 0, \"$(printf '%s\n' "$out" | grep '^run:')\""
  else echo "FAIL bounds -${c%%:*}_t_end 0: exit $rc, $n lines saying 0 steps; got: $(printf '%s\n' "$out" | tail -n 2)"; fi
done
# 3. integer options
R="(an integer in [-2147483648, 2147483647])"
expect "grid count beyond PetscInt" "option -da_grid_x 2147483648: '2147483648' does not fit in PetscInt $R" $DRY -da_grid_x 2147483648
expect "lattice count beyond PetscInt" "option -dem_lattice 2147483648,1,1: '2147483648' does not fit in PetscInt $R" $DRY -dem_lattice 2147483648,1,1
expect "fraction for an integer" "option -dem_seed 1.5: '1.5' is not an integer $R" $DRY -dem_seed 1.5
ints=$( (grep -rhE '(PetscOptions|SableOptions)[A-Za-z]*Int[A-Za-z]*\(' src | grep -oE '"-[a-z][a-z0-9_]*"' | tr -d '"'; grep -rhoE -- '-da_[a-z_]+' cases tests) | sort -u)
bad=""; n=0
for o in $ints; do
  n=$((n + 1))
  $S $DRY "$o" 99999999999 2>&1 | grep -qF "sable: error: option $o 99999999999: '99999999999' does not fit in PetscInt" || bad="$bad $o"
done
[ -z "$bad" ] && [ "$n" -ge 15 ] && echo "PASS bounds: each of the $n integer options (src/ and the -da_ ones of cases and tests) refuses 99999999999 naming itself" || echo "FAIL bounds: integer options of $n that take 99999999999 without naming themselves:$bad"
# 4. bytes of an options file that is not text
printf -- '-dem_t_end 0.001\n-dem_kn 1\0000e5\n' > "$T/nul.opts"
printf -- '-dem_t_end 0.001\n-dem_kn 1\001e5\n' > "$T/ctl.opts"
printf -- '\357\273\277-dem_t_end 0.001\n' > "$T/bom.opts"
expect "NUL byte in an options file" "-options_file $T/nul.opts, line 2: contains a NUL byte (not a text file?)" -options_file "$T/nul.opts"
expect "control byte in an options file" "-options_file $T/ctl.opts, line 2: contains the control byte 0x01 at column 10 (not a text file?)" -options_file "$T/ctl.opts"
expect "byte-order mark in an options file" "-options_file $T/bom.opts, line 1: starts with a UTF-8 byte-order mark" -options_file "$T/bom.opts"
# 5. options that would silently override one another
expect "kn beside the Young's modulus" "-dem_kn and -dem_youngs_modulus both set the contact stiffness of -dem_contact_law linear; -dem_kn wins" $DRY -dem_youngs_modulus 1e9
expect "kn beside the Poisson ratio" "-dem_kn and -dem_poisson_ratio both set the contact stiffness" $DRY -dem_poisson_ratio 0.2
expect "kn beside the wall's Young's modulus" "-dem_kn and -dem_wall_youngs_modulus both set the wall stiffness" $DRY -dem_wall_youngs_modulus 1e9
expect "wall kn beside the wall's Young's modulus" "-dem_wall_kn and -dem_wall_youngs_modulus both set the wall stiffness" $DRY -dem_wall_kn 1e6 -dem_wall_youngs_modulus 1e9
expect "kn under hertz" "-dem_kn is ignored by -dem_contact_law hertz" $DRY -dem_contact_law hertz -dem_youngs_modulus 1e9
expect "kt without history" "-dem_kt is ignored by -dem_contact_law linear_nohist" $DRY -dem_contact_law linear_nohist -dem_kt 1e5
expect "balance interval in steps and in time" "-lb_interval and -lb_interval_time are both given" $DRY -lb_scheme frequent -lb_interval 10 -lb_interval_time 0.1
expect "balance step and time" "-lb_step and -lb_time are both given" $DRY -lb_scheme once -lb_step 10 -lb_time 0.1
expect "cell size beside three grid counts" "-domain_cell 0.05 and -da_grid_x, -da_grid_y, -da_grid_z are all given" $DRY -domain_cell 0.05 -da_grid_x 2 -da_grid_y 2 -da_grid_z 2
# 6. did you mean
expect "words swapped" "option -dem_kn_wall 1e5 was given but nothing reads it (did you mean -dem_wall_kn?" $DRY -dem_kn_wall 1e5
expect "underscore missing" "option -demfriction 0.3 was given but nothing reads it (did you mean -dem_friction?" $DRY -demfriction 0.3
expect "indexed wall option" "(did you mean -dem_plane_0_velocity?" $DRY -dem_plane_0 0,0,0,0,0,1 -dem_plane_0_velocty 0,0,1
expect "nothing close" "option -zzz_qqq 1 was given but nothing reads it (a typo?" $DRY -zzz_qqq 1
