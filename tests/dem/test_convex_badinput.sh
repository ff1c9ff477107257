#!/bin/sh
# Bad input for convex shapes and shaped walls: one clear line naming the option, the value and the
# valid range, a non-zero exit status, nothing run.
cd "$(dirname "$0")/../.." || exit 1
S=${BIN:-bin}/sable
OK="-domain_lo 0,0,0 -domain_hi 0.1,0.1,0.1 -dem_box 0,0,0,0.1,0.1,0.1 -dem_kn 1e4 -dem_lattice 2,2,2 -dem_t_end 0.001"
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
expect "unknown shape" "-dem_shape: unknown shape 'dodecahedron'; valid: sphere, cube, tetrahedron, octahedron, icosahedron, cylinder, polyhedron" $OK -dem_shape dodecahedron -dem_shape_size 0.01
expect "shape without size" "-dem_shape cube needs -dem_shape_size or -dem_shape_deq" $OK -dem_shape cube
expect "negative size" "-dem_shape_size -0.01 must be > 0" $OK -dem_shape cube -dem_shape_size -0.01
expect "size count" "-dem_shape_size has 1 values for 2 shapes" $OK -dem_shape cube,icosahedron -dem_shape_size 0.01
expect "radius and shape" "give either -dem_radius (spheres) or -dem_shape" $OK -dem_radius 0.005 -dem_shape cube -dem_shape_size 0.01
expect "spheres with polyhedra" "spheres and convex shapes in one scene are not supported" $OK -dem_shape sphere,cube -dem_shape_size 0.01,0.01
expect "polyhedron without file" "needs a vertex file" $OK -dem_shape polyhedron
expect "missing vertex file" "none.txt" $OK -dem_shape polyhedron -dem_shape_file none.txt
expect "cylinder aspect" "-dem_cylinder_aspect -1.* must be > 0" $OK -dem_shape cylinder -dem_shape_size 0.01 -dem_cylinder_aspect -1
expect "skewed rectangle" "-dem_rect_0: the edges p1 - p0 = 1.,0.,0. and p2 - p0 = 1.,1.,0. must be non-zero and perpendicular" $OK -dem_shape cube -dem_shape_size 0.01 -dem_rect_0 0,0,0,1,0,0,1,1,0
expect "negative wall friction" "-dem_box_friction -0.5 must be >= 0" $OK -dem_shape cube -dem_shape_size 0.01 -dem_box_friction 0.5,0.5,-0.5,0.5,0.5,0.5
expect "wall friction count" "-dem_plane_0_friction takes 1 comma-separated values, got 2" $OK -dem_shape cube -dem_shape_size 0.01 -dem_plane_0 0,0,0,0,0,1 -dem_plane_0_friction 0.1,0.2
expect "contact point model" "-dem_convex_contact_point foo is not known; valid values: patch, support" $OK -dem_shape cube -dem_shape_size 0.01 -dem_convex_contact_point foo
expect "separating-axis limit" "-dem_convex_sat_axes -2 must be >= 0" $OK -dem_shape cube -dem_shape_size 0.01 -dem_convex_sat_axes -2
if $S $OK -dem_shape cube,icosahedron -dem_shape_deq 0.01,0.01 -dem_lattice_random_orientation >/dev/null 2>&1; then echo "PASS good convex input runs: exit 0"; else echo "FAIL good convex input runs: exit $?"; fi
