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
long=$(printf '%04096d' 0) # one character more than a path holds: refused, not cut short
out=$($S $OK -dem_mesh_0_file "$long" 2>&1 >/dev/null); rc=$?
if [ "$rc" -ne 0 ] && [ "$(printf '%s\n' "$out" | grep -c 'sable: error')" -eq 1 ] && printf '%s' "$out" | grep -q -- "-dem_mesh_0_file 0\{200\}\.\.\.: at most 4095 characters"; then
  echo "PASS bad input, file name too long: exit $rc, \"$(printf '%s' "$out" | grep 'sable: error' | sed 's/0\{200\}/<200 zeros>/')\""
else
  echo "FAIL bad input, file name too long: exit $rc, expected one error line /at most 4095 characters/; got: $(printf '%s' "$out" | cut -c1-200)"
fi
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

# malformed STL through the program, on 1 and 2 ranks: one error line naming the file and the
# triangle, a non-zero status, no rank left waiting (time-out 60 s)
[ "$(id -u)" -eq 0 ] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
/usr/bin/python3 - "$W" <<'PY'
import math, struct, sys
w = sys.argv[1]
tris = []  # the box of box.stl as 12 binary triangles
for line in open(w + "/box.stl"):
    if line.split()[:1] == ["vertex"]:
        tris.append([float(x) for x in line.split()[1:]])
def binary(path, tri, count, cut=None):
    b = b"binary box".ljust(80, b" ") + struct.pack("<I", count)
    for t in range(len(tri) // 3):
        b += struct.pack("<3f", 0, 0, 0) + b"".join(struct.pack("<3f", *tri[3 * t + j]) for j in range(3)) + b"\0\0"
    open(path, "wb").write(b[:cut] if cut else b)
n = len(tris) // 3
binary(w + "/trunc.stl", tris, n, 84 + 50 * 5 + 20)
binary(w + "/count.stl", tris, n - 1)
nan = [list(v) for v in tris]; nan[3 * 6 + 1][2] = math.nan
binary(w + "/nanbin.stl", nan, n)
PY
printf 'solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 nan 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid s\n' >"$W/nan.stl"
for np in 1 2; do
  for c in "trunc:triangle 6 is incomplete" "count:the count disagrees with the size after triangle 11" "nanbin:triangle 7 (binary) vertex 2 has a non-finite coordinate" "nan:triangle 1 (line 5) vertex 2 has a non-finite coordinate" "text:not STL"; do
    f=${c%%:*}; frag=${c#*:}
    if [ "$np" -eq 1 ]; then out=$(timeout -k 5 60 $S $OK -dem_mesh_0_file "$W/$f.stl" 2>&1 >/dev/null); rc=$?
    else out=$(timeout -k 5 60 mpiexec --oversubscribe -n 2 $S $OK -dem_mesh_0_file "$W/$f.stl" 2>&1 >/dev/null); rc=$?; fi
    lines=$(printf '%s\n' "$out" | grep -c 'sable: error')
    if [ "$rc" -ne 0 ] && [ "$rc" -ne 124 ] && [ "$rc" -ne 137 ] && [ "$lines" -eq 1 ] && printf '%s' "$out" | grep 'sable: error' | grep -qF "STL file $W/$f.stl: " && printf '%s' "$out" | grep -qF "$frag"; then
      echo "PASS malformed STL ($f) on $np ranks: exit $rc, \"$(printf '%s' "$out" | grep 'sable: error')\""
    else
      echo "FAIL malformed STL ($f) on $np ranks: exit $rc (124/137: timed out), $lines error lines, expected 'STL file $W/$f.stl: ...$frag'; got: $out"
    fi
  done
done
out=$(timeout -k 5 60 mpiexec --oversubscribe -n 2 $S $OK -domain_cell 0.05 -dem_mesh_0_file "$W/extra.stl" 2>&1); rc=$?
n=$(printf '%s\n' "$out" | grep -c "warning: mesh -dem_mesh_0: .*skipped 1 zero-area and 1 duplicate")
if [ "$rc" -eq 0 ] && [ "$n" -eq 1 ]; then echo "PASS degenerate and duplicate triangles on 2 ranks: exit 0, the counted warning once"
else echo "FAIL degenerate and duplicate triangles on 2 ranks: exit $rc, $n warnings (want 1): $(printf '%s' "$out" | grep -i 'warning\|error')"; fi
