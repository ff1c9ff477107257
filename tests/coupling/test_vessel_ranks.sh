#!/bin/sh
# The bed in a cylinder that bounds particles and gas (vessel_cylinder.opts: 196 beads, a cylinder
# of radius 8 mm on cells of 2 mm) run by bin/sable on 1 and 2 ranks (the cut at z = 20 mm runs
# through the bed; -dem_deterministic: the particles' forces in the same order on both):
#  - the start-up lines say what bounds the gas: the cylinder particles and gas, the floor plane
#    the particles only;
#  - the bed: line takes the porosity over the open volume and the superficial velocity over the
#    vessel's cross-section: the inlet's 0.5 m/s (the flux through the open inlet faces over their
#    area, 1e-9 relative), not the box's;
#  - the same answers on 2 ranks as on 1: the column's dp/W and drag/W means to 1e-7 relative
#    (the Poisson tolerance is 1e-8), the particles of the last frame to 1e-8 m;
#  - a checkpoint of the bed (two-way, and one-way, whose beta never changes, so the Poisson
#    matrix of beta plus the wall slivers' film friction stays current across the checkpoint)
#    at t = 0.005 continued with -restart ends with bitwise the final frame of the uninterrupted
#    run;
#  - an open mesh asked to bound the gas is refused in one line;
#  - a closed STL cylinder with its caps on the inlet and outlet faces bounds the gas as well.
cd "$(dirname "$0")/../.."
[ "$(id -u)" -eq 0 ] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1
out=$(mktemp)
trap 'rm -rf "$out" "$out.d"' EXIT
opts="-options_file tests/coupling/vessel_cylinder.opts -dem_deterministic -cpl_t_end 0.01 -cpl_progress_interval 0 -io_interval 0.01 -da_processors_x 1 -da_processors_y 1"
ref=""
for n in 1 2; do
  if [ "$n" -eq 1 ]; then ${BIN:-bin}/sable $opts -io_dir "$out.d/$n" >"$out" 2>&1; else mpiexec -n $n ${BIN:-bin}/sable $opts -io_dir "$out.d/$n" -da_processors_z 2 >"$out" 2>&1; fi
  rc=$?
  if [ "$rc" -ne 0 ]; then echo "FAIL cpl_vessel_np$n: exit $rc"; tail -n 3 "$out" | sed 's/^/    /'; continue; fi
  if [ "$n" -eq 1 ]; then
    for l in "vessel: -dem_cylinder bounds particles and gas" "vessel: -dem_plane_0 bounds the particles only"; do
      if grep -q "^$l" "$out"; then echo "PASS cpl_vessel_line: \"$l\""; else echo "FAIL cpl_vessel_line: \"$l\" missing"; grep '^vessel' "$out" | sed 's/^/    /'; fi
    done
    u=$(sed -n 's/^bed: .*inlet superficial velocity \([0-9.e+-]*\) m\/s.*/\1/p' "$out")
    echo "$u" | awk '{ e = ($1 - 0.5) / 0.5; if (e < 0) e = -e; printf "%s cpl_vessel_bed_line: inlet superficial velocity over the vessel'"'"'s cross-section %s m/s (reference 0.5, rel. %.1e < 1e-9)\n", (NF == 1 && e < 1e-9) ? "PASS" : "FAIL", $1, e }'
  fi
  v=$(sed -n 's/^column: pressure drop \/ bed buoyant weight per area \([0-9.]*\), drag on the particles \/ buoyant weight \([0-9.]*\).*/\1 \2/p' "$out")
  if [ -z "$v" ]; then echo "FAIL cpl_vessel_np$n: no column: line"; tail -n 3 "$out" | sed 's/^/    /'; continue; fi
  if [ -z "$ref" ]; then ref=$v; continue; fi
  echo "$ref $v" | awk -v b=1e-7 '{ e1 = ($1 - $3) / $1; if (e1 < 0) e1 = -e1; e2 = ($2 - $4) / $2; if (e2 < 0) e2 = -e2;
    ok = (e1 < b && e2 < b); printf "%s cpl_vessel_ranks: dp/W %s, drag/W %s; rel. diff %.2e, %.2e (< %g) on 2 ranks vs 1\n", ok ? "PASS" : "FAIL", $1, $2, e1, e2, b }'
  /usr/bin/python3 - "$out.d/1/sable_000001.h5" "$out.d/2/sable_000001.h5" <<'PY'
import sys
import h5py
import numpy as np
a, b = h5py.File(sys.argv[1], "r"), h5py.File(sys.argv[2], "r")
ia, ib = np.argsort(a["particles/id"][()]), np.argsort(b["particles/id"][()])
dx = np.abs(a["particles/position"][()][ia] - b["particles/position"][()][ib]).max()
ok = len(ia) == 196 and len(ib) == 196 and dx < 1e-8
print("%s cpl_vessel_ranks_frame: %d particles, largest position difference %.2e m (< 1e-8) on 2 ranks vs 1" % ("PASS" if ok else "FAIL", len(ib), dx))
PY
done

# Checkpoint and restart in the vessel, 1 rank, to t = 0.01 with the checkpoint at 0.005 (the
# two-way run without checkpoints is the 1-rank run above).
for mode in twoway oneway; do
  full=$out.d/1
  [ "$mode" = oneway ] && full=$out.d/oneway-full && ${BIN:-bin}/sable $opts -cpl_mode oneway -io_dir "$full" >"$out" 2>&1
  ${BIN:-bin}/sable $opts -cpl_mode $mode -io_checkpoint_interval 0.005 -cpl_t_end 0.005 -io_dir "$out.d/$mode-half" >"$out" 2>&1
  ck=$(sed -n 's/^checkpoint: \([^ ]*\).*/\1/p' "$out" | tail -n 1)
  if [ -z "$ck" ] || [ ! -f "$full/sable_000001.h5" ] || ! ${BIN:-bin}/sable $opts -cpl_mode $mode -restart "$ck" -io_dir "$out.d/$mode-rest" >"$out" 2>&1; then
    echo "FAIL cpl_vessel_restart_$mode: the runs stopped"; tail -n 3 "$out" | sed 's/^/    /'; continue
  fi
  /usr/bin/python3 - "$full/sable_000001.h5" "$out.d/$mode-rest/sable_000001.h5" "$mode" <<'PY'
import sys
import h5py
import numpy as np
a, b = h5py.File(sys.argv[1], "r"), h5py.File(sys.argv[2], "r")
names = []
a.visititems(lambda n, o: names.append(n) if isinstance(o, h5py.Dataset) else None)
diff = [n for n in names if n not in b or a[n].shape != b[n].shape or not np.array_equal(a[n][()], b[n][()])]
print("%s cpl_vessel_restart_%s: the final frame of the run continued from its checkpoint at t = 0.005 and of the uninterrupted run, %d datasets, %d differ%s" % ("PASS" if names and not diff else "FAIL", sys.argv[3], len(names), len(diff), (": " + ", ".join(diff[:4])) if diff else " (bitwise)"))
PY
done

# An open mesh asked to bound the gas (a tube without caps, tools/make_stl, 64 open edges at its
# two rims) is refused in one line naming the option, the file and the open edges.
/usr/bin/python3 tools/make_stl cylinder --point 0.01,0.01,-0.002 --axis 0,0,1 --radius 0.0085 --s0 0 --s1 0.044 --n 32 --nlen 2 -o "$out.tube.stl" >/dev/null 2>&1
${BIN:-bin}/sable -options_file tests/coupling/vessel_cylinder.opts -dem_mesh_0_file "$out.tube.stl" -cpl_t_end 0.001 -io_interval 0 -io_dir "$out.d/tube" >"$out" 2>&1
rc=$?
msg=$(grep 'error' "$out" | head -n 1)
if [ "$rc" -ne 0 ] && [ "$(grep -c 'error' "$out")" -eq 1 ] && echo "$msg" | grep -q -- "-dem_mesh_0_fluid inside: -dem_mesh_0 ($out.tube.stl) is not closed: 64 edges"; then
  echo "PASS cpl_vessel_open_mesh: exit $rc, \"$msg\""
else
  echo "FAIL cpl_vessel_open_mesh: exit $rc, $(grep -c 'error' "$out") error lines: \"$msg\""
fi
rm -f "$out.tube.stl"

# The same bed in a closed STL cylinder (tools/make_stl, 32 facets, its caps on the inlet and
# outlet faces: those triangles are the box's faces, the gas passes) in place of -dem_cylinder:
# the run goes through and its bed: line sees the inlet's 0.5 m/s over the mesh's cross-section.
/usr/bin/python3 tools/make_stl cylinder --point 0.01,0.01,0 --axis 0,0,1 --radius 0.008 --s0 0 --s1 0.04 --n 32 --nlen 4 --caps -o "$out.cyl.stl" >/dev/null 2>&1
${BIN:-bin}/sable -options_file tests/coupling/vessel_cylinder.opts -dem_cylinder_fluid no -dem_mesh_0_file "$out.cyl.stl" -cpl_t_end 0.002 -cpl_progress_interval 0 -io_interval 0 -io_dir "$out.d/cyl" >"$out" 2>&1
rc=$?
u=$(sed -n 's/^bed: .*inlet superficial velocity \([0-9.e+-]*\) m\/s.*/\1/p' "$out")
if [ "$rc" -eq 0 ] && grep -q "^vessel: -dem_mesh_0 .* bounds particles and gas (the gas inside it: closed, 320 triangles; 64 of them lie in the box's faces" "$out" && echo "$u" | awk '{ e = ($1 - 0.5) / 0.5; exit !(NF == 1 && e < 1e-9 && e > -1e-9) }'; then
  echo "PASS cpl_vessel_stl_cylinder: exit 0, caps on the box's faces, inlet superficial velocity $u m/s (reference 0.5, 1e-9)"
else
  echo "FAIL cpl_vessel_stl_cylinder: exit $rc, inlet superficial velocity \"$u\" (reference 0.5)"; grep -E '^vessel: -dem_mesh|error' "$out" | sed 's/^/    /'
fi
rm -f "$out.cyl.stl"
