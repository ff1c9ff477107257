#!/bin/sh
# Bad input for mesh walls (-dem_mesh_<k>_*): one clear line naming the option (or the file), the
# value and the valid range, a non-zero exit status, nothing run. The good input runs and
# announces each mesh in one line (file, triangles, box), with a warning counting the skipped
# zero-area and duplicate triangles. (Malformed STL files in detail: tests/geom, the reader's.)
cd "$(dirname "$0")/../.." || exit 1
S=${BIN:-bin}/sable
W=$(mktemp -d)
trap 'rm -rf "$W"' EXIT
tests/common/box_stl.py "$W/box.stl" 0,0,0,0.1,0.1,0.1
OK="-domain_lo 0,0,0 -domain_hi 0.1,0.1,0.1 -dem_kn 1e4 -dem_lattice 2,2,2 -dem_t_end 0.001"
M="$OK -dem_mesh_0_file $W/box.stl"
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
expect "missing file" "-dem_mesh_0_file $W/none.stl: no such readable file" $OK -dem_mesh_0_file "$W/none.stl"
printf 'this is not a mesh\n' >"$W/text.stl"
expect "not STL at all" "$W/text.stl: not STL" $OK -dem_mesh_0_file "$W/text.stl"
expect "zero scale" "-dem_mesh_0_scale 0. must be > 0" $M -dem_mesh_0_scale 0
expect "rotation of 2 values" "-dem_mesh_0_rotate takes 3 comma-separated values, got 2" $M -dem_mesh_0_rotate 1,2
expect "option without its file" "-dem_mesh_0_velocity given without -dem_mesh_0_file" $OK -dem_mesh_0_velocity 1,0,0
expect "omega and a table" "-dem_mesh_0_omega and -dem_mesh_0_omega_table both set the rotation" $M -dem_mesh_0_omega 1 -dem_mesh_0_omega_table 0,1
expect "odd table" "-dem_mesh_0_omega_table has 3 values: it takes pairs t,w" $M -dem_mesh_0_omega_table 0,1,2
expect "table times decreasing" "-dem_mesh_0_omega_table: time 0.5 must exceed the previous one 1." $M -dem_mesh_0_omega_table 1,1,0.5,2
expect "zero axis" "-dem_mesh_0_axis 0.,0.,0. must be non-zero" $M -dem_mesh_0_omega 1 -dem_mesh_0_axis 0,0,0
expect "axis point without rotation" "-dem_mesh_0_axis_point given without -dem_mesh_0_omega or -dem_mesh_0_omega_table" $M -dem_mesh_0_axis_point 1,1,1
expect "negative friction" "-dem_mesh_0_friction -1. must be >= 0" $M -dem_mesh_0_friction -1
expect "restitution above 1" "-dem_mesh_0_restitution 1.5 must be in (0,1]" $M -dem_mesh_0_restitution 1.5
expect "negative stiffness" "-dem_mesh_0_kn -3. must be > 0" $M -dem_mesh_0_kn -3
expect "kn under hertz" "-dem_mesh_0_kn is ignored by -dem_contact_law hertz" -domain_lo 0,0,0 -domain_hi 0.1,0.1,0.1 -dem_lattice 2,2,2 -dem_t_end 0.001 -dem_contact_law hertz -dem_youngs_modulus 1e7 -dem_mesh_0_file "$W/box.stl" -dem_mesh_0_kn 1e4
expect "Young's modulus under kn" "-dem_mesh_0_youngs_modulus is ignored: the wall stiffness is given by" $M -dem_mesh_0_youngs_modulus 1e7
expect "rolling friction without a model" "-dem_mesh_0_rolling_friction is ignored by -dem_rolling_model none" $M -dem_mesh_0_rolling_friction 0.1
tests/common/box_stl.py "$W/small.stl" 0.02,0.02,0.02,0.08,0.08,0.08
# a lattice across the sides of a mesh box (0.02..0.08): site (1,1,1) at 1.5 x 0.01449 = 0.021735, r = 0.0069,
# overlaps the face x = 0.02 by (0.0069 - 0.001735)/0.0069 = 0.749 radii; a cube of side 0.01 at
# x = 0.015 + 0.5 x 0.0181865 reaches 0.00091 past x = 0.02, over d_eq/2 = 0.0062035: 0.146
expect "lattice of spheres across a mesh side" "lattice particle id 7 at (0.021735, 0.021735, 0.021735) overlaps a triangle of mesh -dem_mesh_0 by 0.749 radii" $OK -dem_mesh_0_file "$W/small.stl"
expect "lattice of cubes across a mesh side" "lattice particle id 0 at (0.0240933, 0.0290933, 0.0390933) overlaps a triangle of mesh -dem_mesh_0 by 0.146 radii" $OK -dem_mesh_0_file "$W/small.stl" -dem_shape cube -dem_shape_size 0.01 -dem_lattice_origin 0.015,0.02,0.03
expect "mesh too stiff for dt" "-dem_dt 1e-05 s exceeds -dem_dt_max_fraction 0.1 x the contact time .* with mesh -dem_mesh_0" $M -dem_mesh_0_kn 1e8
# good input: a duplicate and a zero-area triangle are skipped with a counted warning
{ sed '$d' "$W/box.stl"; sed -n '2,8p' "$W/box.stl"; printf 'facet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 0.1 0 0\nvertex 0.05 0 0\nendloop\nendfacet\nendsolid box\n'; } >"$W/extra.stl"
out=$($S $OK -dem_mesh_0_file "$W/extra.stl" -dem_mesh_0_omega 0.5 -dem_mesh_0_axis_point 0.05,0.05,0 -dem_mesh_0_friction 0.2 2>&1); rc=$?
if [ "$rc" -eq 0 ] && printf '%s' "$out" | grep -q "mesh -dem_mesh_0: $W/extra.stl, 12 triangles, box" && printf '%s' "$out" | grep -q "warning: mesh -dem_mesh_0: .*skipped 1 zero-area and 1 duplicate"; then
  echo "PASS good mesh input runs: exit 0, \"$(printf '%s\n' "$out" | grep 'mesh -dem_mesh_0' | tr '\n' ' ')\""
else
  echo "FAIL good mesh input runs: exit $rc; got: $(printf '%s' "$out" | grep -i 'mesh\|error')"
fi
