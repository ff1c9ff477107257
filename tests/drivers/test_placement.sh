#!/bin/sh
# Placement at start-up. Particles that insertion puts inside a wall or inside each other stop the
# run before the first step with one line that names what overlaps what and the option that
# placed it (never the time-step advice of a diverging run); a lattice behind the distributor
# plane, a lattice added on an init file's particles, on 1 and 2 ranks, and a pair split across
# two ranks. A clean case and the restart of its own settling frame (contacts, well below the
# limit) run; a frame's sphere past a periodic side is wrapped back. A coupled run warns once per fluid wall or inlet face that has no DEM wall, names
# both options, and the shipped coupled cases print no such warning; a periodic axis is one
# option for both, and the ways to make it differ are errors.
cd "$(dirname "$0")/../.." || exit 1
[ "$(id -u)" -eq 0 ] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
S=${BIN:-bin}/sable
T=$(mktemp -d); trap 'rm -rf "$T"' EXIT
Q="-options_file cases/settle/quick.opts -dem_progress_interval 0"
B="-options_file cases/fluidized_bed/small.opts -cpl_t_end 0.025 -cpl_progress_interval 0 -io_interval 0"

stops() { # name, ranks, patterns the line must hold (|-separated), arguments...
  name=$1; np=$2; pats=$3; shift 3
  if [ "$np" -eq 1 ]; then out=$($S -io_dir "$T/x" "$@" 2>&1); rc=$?
  else out=$(mpiexec --oversubscribe -n "$np" $S -io_dir "$T/x" "$@" 2>&1); rc=$?; fi
  line=$(printf '%s\n' "$out" | grep 'sable: error'); n=$(printf '%s\n' "$out" | grep -c 'sable: error')
  ok=1; [ "$rc" -ne 0 ] && [ "$n" -eq 1 ] || ok=0
  printf '%s' "$line" | grep -q -- '-dem_dt' && ok=0
  old=$IFS; IFS='|'; for p in $pats; do printf '%s' "$line" | grep -q -- "$p" || ok=0; done; IFS=$old
  if [ "$ok" -eq 1 ]; then echo "PASS placement $name on $np rank(s): exit $rc, $n line, names $pats, no -dem_dt: \"$line\""
  else echo "FAIL placement $name on $np rank(s): exit $rc, $n error lines, expected $pats and no -dem_dt; got: $(printf '%s' "$out" | tail -n 3)"; fi
  LAST=$line
}
runs() { # name, arguments...: exit 0 and no error line
  name=$1; shift
  out=$($S "$@" 2>&1); rc=$?
  if [ "$rc" -eq 0 ] && ! printf '%s' "$out" | grep -q 'sable: error'; then echo "PASS placement $name: exit 0, no error"
  else echo "FAIL placement $name: exit $rc: $(printf '%s' "$out" | tail -n 2)"; fi
}

# clean: the quick case settles for 0.2 s (the spheres land: contacts) and restarts from that frame
runs "clean quick case (0.2 s, frame written)" $Q -dem_t_end 0.2 -io_interval 0.2 -io_dir "$T/q"
F=$T/q/sable_000001.h5
runs "restart from its own frame with -dem_lattice 0,0,0" $Q -dem_init_file "$F" -dem_lattice 0,0,0 -dem_t_end 1e-4 -io_interval 0 -io_dir "$T/r"

for np in 1 2; do
  stops "lattice behind the distributor" $np '-dem_plane_0|-dem_lattice_origin 0,0,0|lies wholly on the wrong side' $B -dem_lattice_origin 0,0,0
  stops "lattice added on the init file's particles" $np '-dem_init_file|-dem_lattice 10,10,12|overlaps particle id' $Q -dem_init_file "$F" -dem_t_end 1e-4 -io_interval 0
done
stops "lattice through the box side" 1 '-dem_box xhi|-dem_lattice_origin 0.003,0,0|by 0.385 radii' $Q -dem_lattice_origin 0.003,0,0 -dem_t_end 1e-4 -io_interval 0
# a 7-site row of spacing 1.2 d from x = 0.1 to 7.3 in the 8 d periodic column: 0.8 d from the
# first site's image, 0.4 radii deep; seen only through the periodic ghosts
stops "lattice longer than the periodic domain" 1 'lattice particles id 0 at (0.1, 0.6, 2.6) and id 6 at (7.3, 0.6, 2.6) overlap|overlap by 0.4 radii|-dem_lattice_spacing 1.2' $B -dem_lattice 7,3,10 -dem_lattice_spacing 1.2 -dem_lattice_origin -0.5,0,2
stops "init file cut by a plane" 1 "-dem_init_file $F|lies wholly on the wrong side of -dem_plane_0 (z = 0.05), more than a contact reaches (limit 0.05 radii, -dem_init_file_overlap_max: by default twice the contact design's overlap at -dem_impact_velocity, at least 0.05)" $Q -dem_init_file "$F" -dem_lattice 0,0,0 -dem_plane_0 0,0,0.05,0,0,1 -dem_t_end 1e-4 -io_interval 0
grep -v '^-dem_box' cases/settle/quick.opts > "$T/nobox.opts"
stops "init file's contacts above a forced limit" 1 "-dem_init_file $F|overlap by|limit 1e-06 radii, -dem_init_file_overlap_max" -options_file "$T/nobox.opts" -dem_init_file "$F" -dem_lattice 0,0,0 -dem_init_file_overlap_max 1e-6 -dem_t_end 1e-4 -io_interval 0

# a frame holds positions up to skin/2 past a periodic side (written between list builds): a
# sphere moved by whole periods along the periodic x and y is wrapped back; along z it is outside
runs "small bed frame" $B -cpl_t_end 0 -io_interval 1 -io_dir "$T/s"
/usr/bin/python3 - "$T/s/sable_000000.h5" "$T" <<'PY' || echo "FAIL placement: the frame-editing script exited with status $?"
import sys, shutil, h5py
for name, shift in (("xy", (8.0, -4.0, 0.0)), ("z", (0.0, 0.0, 48.0))):
    shutil.copy(sys.argv[1], sys.argv[2] + "/shifted_" + name + ".h5")
    with h5py.File(sys.argv[2] + "/shifted_" + name + ".h5", "r+") as f:
        p = f["particles/position"]
        p[0] = p[0] + shift
PY
runs "restart with a sphere one period past the periodic x and y sides" $B -dem_lattice 0,0,0 -dem_init_file "$T/shifted_xy.h5" -io_dir "$T/x"
stops "init file sphere above the domain" 1 "-dem_init_file $T/shifted_z.h5: 1 of its 384 particles lie outside the domain box" $B -dem_lattice 0,0,0 -dem_init_file "$T/shifted_z.h5"

# a pair split across two ranks: the file's sphere at z = 0.1135 below the rank boundary at
# z = 0.123165 (two cells along z), the lattice's at z = 0.1234 above it, 0.0099 m apart (d = 0.0138)
P="$Q -da_grid_z 2 -dem_lattice 1,1,1 -dem_t_end 1e-4 -io_interval 0"
runs "single sphere frame" $Q -dem_lattice 1,1,1 -dem_lattice_origin 0.05,0.05,0.106255 -dem_t_end 0 -io_interval 1 -io_dir "$T/one"
stops "pair across the rank boundary" 1 'lattice particle id 1 at (0.057245, 0.057245, 0.1234) overlaps particle id 0 at (0.057245, 0.057245, 0.1135)|by 0.565 radii' $P -dem_init_file "$T/one/sable_000000.h5" -dem_lattice_origin 0.05,0.05,0.116155
one=$LAST
stops "pair across the rank boundary" 2 'lattice particle id 1 at (0.057245, 0.057245, 0.1234) overlaps particle id 0 at (0.057245, 0.057245, 0.1135)|by 0.565 radii' $P -dem_init_file "$T/one/sable_000000.h5" -dem_lattice_origin 0.05,0.05,0.116155 -da_processors_x 1 -da_processors_y 1 -da_processors_z 2
[ "$one" = "$LAST" ] && echo "PASS placement pair across the rank boundary: the same line on 1 and 2 ranks" || echo "FAIL placement pair across the rank boundary: 1 rank \"$one\", 2 ranks \"$LAST\""

# fluid faces without a DEM wall: one warning line per face, naming both options
warns() { # name, expected count, pattern every warning line holds, arguments...
  name=$1; want=$2; pat=$3; shift 3
  out=$($S -io_dir "$T/x" "$@" 2>&1); rc=$?
  n=$(printf '%s\n' "$out" | grep -c '^warning: -fluid_bc_.* has no DEM wall'); m=$(printf '%s\n' "$out" | grep '^warning: -fluid_bc_' | grep -c -- "$pat")
  if [ "$rc" -eq 0 ] && [ "$n" -eq "$want" ] && [ "$m" -eq "$want" ]; then echo "PASS placement $name: $n face warnings (expected $want)$( [ "$n" -gt 0 ] && printf ', "%s"' "$(printf '%s\n' "$out" | grep '^warning: -fluid_bc_' | head -n 1)")"
  else echo "FAIL placement $name: exit $rc, $n face warnings, $m matching /$pat/ (expected $want): $(printf '%s\n' "$out" | grep -i 'warning\|error' | head -n 3)"; fi
}
warns "inlet below a distributor moved out of the domain" 1 '-fluid_bc_zlo inlet at z = 0 has no DEM wall there (-dem_box or -dem_plane_k)' $B -dem_plane_0 0,0,-1,0,0,1
warns "x faces walls, no DEM walls along x" 2 '-fluid_bc_x\(lo\|hi\) wall at x = [08] has no DEM wall there (-dem_box or -dem_plane_k): particles that reach it leave the domain' $B -domain_periodic_x 0
warns "x faces walls with DEM planes on them" 0 . $B -domain_periodic_x 0 -dem_plane_2 0,0,0,1,0,0 -dem_plane_3 8,0,0,-1,0,0
warns "slip faces inside a -dem_box" 0 . $B -domain_periodic_x 0 -domain_periodic_y 0 -fluid_bc_ylo slip -dem_box 0,0,0,8,4,48
tests/common/box_stl.py "$T/box.stl" 0,0,0,8,4,48 2
warns "x and y faces walls closed by a mesh box" 0 . $B -domain_periodic_x 0 -domain_periodic_y 0 -dem_mesh_0_file "$T/box.stl"
warns "the mesh box moved by 1 along x: its x sides off the x faces, its y sides overhanging theirs" 4 '-fluid_bc_[xy]\(lo\|hi\) wall' $B -domain_periodic_x 0 -domain_periodic_y 0 -dem_mesh_0_file "$T/box.stl" -dem_mesh_0_translate 1,0,0
for f in cases/*/*.opts; do
  grep -q '^-\(cpl\|fluid\)_' "$f" || continue
  grep -q '^-domain_lo' "$f" || continue # a preset: options added to a case
  init=$(sed -n 's/^-dem_init_file //p' "$f")
  set --
  if [ -n "$init" ]; then # a case that starts from its fill stage's frame: that stage first, short
    prefix=$(basename "$init" | sed 's/_[0-9]*\.h5$//')
    fill=$(grep -l "^-io_prefix $prefix\$" "$(dirname "$f")"/*.opts | head -n 1)
    rm -rf "$T/fill"
    [ -n "$fill" ] && $S -options_file "$fill" -dem_t_end 0.01 -io_interval 0.01 -io_dir "$T/fill" >/dev/null 2>&1
    set -- -dem_init_file "$T/fill/$(basename "$init")"
  fi
  warns "shipped case $f" 0 . -options_file "$f" "$@" -cpl_t_end 1e-4 -cpl_progress_interval 0 -io_interval 0
done
# periodicity is one option for both: a fluid wall on a periodic axis, a DEM box across one, are errors
stops "fluid wall on a periodic axis" 1 '-fluid_bc_xlo wall: the x axis is periodic (-domain_periodic_x)' $B -fluid_bc_xlo wall
stops "DEM box across a periodic axis" 1 '-dem_box puts walls across the x axis, which is periodic (-domain_periodic_x)' $B -dem_box 0,0,0,8,4,48
