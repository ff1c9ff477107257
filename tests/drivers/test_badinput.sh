#!/bin/sh
# Bad input stops with one clear line naming the option, the value and the valid range, and a
# non-zero exit status; nothing is run.
cd "$(dirname "$0")/../.." || exit 1
S=${BIN:-bin}/sable
OK="-domain_lo 0,0,0 -domain_hi 0.1,0.1,0.1 -dem_box 0,0,0,0.1,0.1,0.1 -dem_kn 1e4 -dem_lattice 2,2,2 -dem_radius 0.005 -dem_t_end 0.001"
expect() { # name, pattern the message must match, arguments...
  name=$1; pat=$2; shift 2
  out=$($S "$@" 2>&1 >/dev/null); rc=$?
  lines=$(printf '%s\n' "$out" | grep -c 'sable: error')
  if [ "$rc" -ne 0 ] && [ "$lines" -eq 1 ] && printf '%s' "$out" | grep -q -- "$pat"; then
    echo "PASS bad input, $name: exit $rc, \"$(printf '%s' "$out" | grep 'sable: error')\""
  else
    echo "FAIL bad input, $name: exit $rc, $lines error lines, expected /$pat/; got: $out"
  fi
}
expect "negative radius" "-dem_radius -0.005 must be > 0" $OK -dem_radius -0.005
expect "missing options file" "-options_file cases/none.opts: cannot open" -options_file cases/none.opts
expect "unknown option" "option -dem_resitution 0.5 was given but nothing reads it" $OK -dem_resitution 0.5
expect "restitution above 1" "-dem_restitution 1.5 must be in (0,1]" $OK -dem_restitution 1.5
expect "restitution zero" "-dem_restitution 0. must be in (0,1]" $OK -dem_restitution 0
expect "cell count beyond PetscInt" "-domain_cell 1e-30 m (by default 4 particle diameters) gives 1e+29 cells along x, more than 2147483647" $OK -domain_cell 1e-30
expect "zero cells along y" "-da_grid_y 0 must be >= 1" $OK -da_grid_y 0
expect "time step above Tc/10" "-dem_dt 0.0001 s exceeds -dem_dt_max_fraction 0.1 x the contact time" $OK -dem_dt 1e-4
expect "lattice outside the domain" "lie outside the domain box" $OK -dem_lattice 20,2,2
expect "hertz without modulus" "-dem_contact_law hertz needs -dem_youngs_modulus" $(printf '%s\n' "$OK" | sed 's/ -dem_kn 1e4//') -dem_contact_law hertz
expect "wrong vector length" "-dem_gravity takes 3 comma-separated values, got 2" $OK -dem_gravity 0,1
# walls (src/dem/walls_polygon.c, walls_cylinder.c)
expect "non-planar quad" "-dem_quad_0: the vertices are not planar: vertex 0 is" $OK -dem_quad_0 0.01,0.01,0.01,0.09,0.01,0.01,0.09,0.09,0.03,0.01,0.09,0.01
expect "non-convex quad" "-dem_quad_0: the polygon is not convex, or its vertices are not in order around it (turn at vertex 2 is the wrong way)" $OK -dem_quad_0 0.01,0.01,0.01,0.09,0.01,0.01,0.03,0.03,0.01,0.01,0.09,0.01
expect "crossed quad" "-dem_quad_0: the polygon has zero area (repeated or collinear vertices, or crossing edges)" $OK -dem_quad_0 0.01,0.01,0.01,0.09,0.09,0.01,0.09,0.01,0.01,0.01,0.09,0.01
expect "degenerate quad" "-dem_quad_0: the polygon has zero area" $OK -dem_quad_0 0.01,0.01,0.01,0.01,0.01,0.01,0.01,0.01,0.01,0.01,0.01,0.01
expect "quad with 11 values" "-dem_quad_0 takes 12 comma-separated values, got 11" $OK -dem_quad_0 0,0,0,1,0,0,1,1,0,0,1
expect "hopper wider at the bottom" "-dem_hopper: half-widths top 0.01 and bottom 0.03 must satisfy top > bottom > 0" $OK -dem_hopper 0.05,0.05,0.08,0.01,0.02,0.03
expect "hopper upside down" "-dem_hopper: top z 0.02 must exceed bottom z 0.08" $OK -dem_hopper 0.05,0.05,0.02,0.04,0.08,0.01
expect "cylinder of zero radius" "-dem_cylinder: radius 0. must be > 0" $OK -dem_cylinder 0.05,0.05,0.05,1,0,0,0
expect "cylinder with zero axis" "-dem_cylinder: the axis direction 0.,0.,0. must be non-zero" $OK -dem_cylinder 0.05,0.05,0.05,0,0,0,0.04
expect "drum speed without a drum" "-dem_cylinder_omega given without -dem_cylinder" $OK -dem_cylinder_omega 2
expect "plate removal without a plate" "-dem_plane_3_remove_time given without -dem_plane_3" $OK -dem_plane_3_remove_time 1
expect "negative plate removal time" "-dem_plane_0_remove_time -1.* must be >= 0 (s)" $OK -dem_plane_0 0,0,0,0,0,1 -dem_plane_0_remove_time -1
expect "caps in the wrong order" "-dem_cylinder_caps: s1 -0.04 must exceed s0 0.04" $OK -dem_cylinder 0.05,0.05,0.05,1,0,0,0.04 -dem_cylinder_caps 0.04,-0.04
# a good run for contrast: exit 0
if $S $OK >/dev/null 2>&1; then echo "PASS good input runs: exit 0"; else echo "FAIL good input runs: exit $?"; fi
# -help lists every module's options (it once crashed printing uninitialised shape arrays)
out=$($S -help 2>&1); rc=$?
n=$(printf '%s\n' "$out" | grep -c -e '-dem_shape <' -e '-lb_scheme <' -e '-fluid_density <' -e '-cpl_drag <' -e '-domain_lo <')
if [ "$rc" -eq 0 ] && [ "$n" -eq 5 ]; then echo "PASS -help: exit 0, lists -domain_, -dem_, -fluid_, -cpl_, -lb_ options ($n of 5 probes)"; else echo "FAIL -help: exit $rc, $n of 5 probes found"; fi
# not an option but a scene: particles falling through a side with no wall stop the run at the
# next list build, naming the particle and the side (no particle silently drifts away)
expect "particle leaves the domain" "particle [0-9]* left the domain across its lower z side .*close that side with walls" -domain_lo 0,0,0 -domain_hi 0.1,0.1,0.1 -dem_kn 1e4 -dem_lattice 2,2,2 -dem_radius 0.005 -dem_t_end 0.3
# an init file that is missing, or not HDF5: one line each (no HDF5 error stack)
expect "missing init file" "-dem_init_file none.h5: cannot open (No such file or directory)" $OK -dem_init_file none.h5
expect "init file not HDF5" "-dem_init_file tests/run.sh: not an HDF5 file" $OK -dem_init_file tests/run.sh
expect "plane with zero normal" "-dem_plane_0 0.,0.,0.,0.,0.,0.: the normal (the last 3 values) must be non-zero" $OK -dem_plane_0 0,0,0,0,0,0
expect "prefix with a directory" "-io_prefix a/b: a file name prefix, without '/'" $OK -io_prefix a/b
expect "prefix too long" "-io_prefix x*: at most 63 characters" $OK -io_prefix xxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxx
expect "box across a periodic axis" "-dem_box puts walls across the x axis, which is periodic" $OK -domain_periodic_x
# the solver mode (-sable_solver auto|dry|coupled; src/drivers/coupled.c, DriverIsCoupled): a
# typo of a -fluid_ or -cpl_ option is named before it can make a dry case coupled; an explicit
# mode refuses the other mode's options, saying why the run is what it is
Q="-options_file cases/settle/quick.opts"
expect "fluid typo in a dry case" "option -fluid_viscocity 1.8e-5 was given but nothing reads it (did you mean -fluid_viscosity?" $Q -fluid_viscocity 1.8e-5
expect "coupling typo in a dry case" "option -cpl_t_ned 1 was given but nothing reads it (did you mean -cpl_t_end?" $Q -cpl_t_ned 1
expect "a fluid option makes a dry case coupled" "-dem_t_end applies to dry runs; this run is coupled (it has -fluid_viscosity: remove it for a dry run): use -cpl_t_end" $Q -fluid_viscosity 1.8e-5
expect "-sable_solver dry with a fluid option" "-sable_solver dry: -fluid_viscosity is an option of coupled runs (remove it, or give -sable_solver coupled)" $Q -sable_solver dry -fluid_viscosity 1.8e-5
expect "-sable_solver dry on a coupled case" "-sable_solver dry: -cpl_drag is an option of coupled runs" -options_file cases/packed_bed/packed_bed.opts -sable_solver dry
expect "-sable_solver coupled on a dry case" "-dem_t_end applies to dry runs; this run is coupled (-sable_solver coupled): use -cpl_t_end" $Q -sable_solver coupled
expect "-sable_solver of another word" "-sable_solver wet is not known; valid values: auto, dry, coupled" $Q -sable_solver wet
for m in "dry|$OK -sable_solver dry|fluid off" "auto|$OK -sable_solver auto|fluid off" "coupled|-options_file cases/packed_bed/packed_bed.opts -sable_solver coupled -cpl_t_end 0|fluid on"; do
  name=${m%%|*}; rest=${m#*|}; args=${rest%|*}; want=${rest##*|}
  out=$($S $args 2>&1); rc=$?
  if [ "$rc" -eq 0 ] && printf '%s\n' "$out" | grep -q "^modules: .*$want"; then echo "PASS -sable_solver $name: exit 0, $(printf '%s\n' "$out" | grep '^modules:' | cut -d';' -f1-2)"
  else echo "FAIL -sable_solver $name: exit $rc, no \"modules: ... $want\" line: $(printf '%s\n' "$out" | tail -n 1)"; fi
done
