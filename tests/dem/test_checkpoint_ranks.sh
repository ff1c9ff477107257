#!/bin/sh
# Restart on another rank count: a checkpoint written on 2 ranks continued on 1, and one written
# on 1 continued on 2, against the uninterrupted run of the rank count that wrote it.
# - With -dem_deterministic (full rows summed in id order) the result does not depend on the rank
#   count: first the uninterrupted 1- and 2-rank runs are checked bitwise equal to each other,
#   then both remapped runs bitwise equal to them at 0.3 s, every dataset compared by id.
# - Without it, the summation order changes with the ranks and the runs part at round-off, which
#   the settling bed amplifies (measured here: 1e-13 d 10 ms after the restart, 6e-2 d after
#   50 ms, linear law). So the comparison is 10 ms (1,000 steps) after the restart, bound 1e-9 d:
#   a defect (a spring lost, the last step's forces dropped, a particle misplaced) changes an
#   acceleration by at least ~g (the bed's contact forces are of the order of the weight and
#   more), that is g dt^2 = 1e-9 m = 7e-8 d within one step (measured: a lost pair or wall spring
#   2e-3 d, dropped forces 1e-3 d, springs of pairs cut by the new rank boundary 4e-3 d).
# - The same rank count on another process grid (boxes cut along z instead of x) is remapped too
#   (reading it as the writer's own boxes would be wrong), within the same bound.
# - Every id is present once after the remap (-dem_check_every, and the final frame's ids).
# - A checkpoint that cannot be mapped (a position outside the domain, an id repeated) stops
#   with one error line naming the file and the dataset.
# The 2-rank runs cut the box along x (-da_processors_x 2): the cut goes through the bed, so pairs
# and springs cross it in the writer and in the reader.
cd "$(dirname "$0")/../.." || exit 1
S=$(pwd)/${BIN:-bin}/sable
[ "$(id -u)" -eq 0 ] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1
W=$(mktemp -d)
trap 'rm -rf "$W"' EXIT
SCENE="-domain_lo 0,0,0 -domain_hi 0.1449,0.1449,0.24633 -dem_box 0,0,0,0.1449,0.1449,0.24633 -dem_radius 0.0069 -dem_density 2500 -dem_restitution 0.75 -dem_friction 0.3 -dem_dt 1e-5 -dem_lattice 8,8,6 -dem_lattice_spacing 0.01449 -dem_lattice_speed 0.05 -dem_progress_interval 0 -dem_check_every 100"
H=0.15
BOUND=1e-9
# The final frames a and b compared by particle id: prints the particle count, whether the ids
# are the same set with each once, the largest position difference over the diameter, and the
# count and names of the datasets not bitwise equal (per-particle ones in id order; vertex, the
# frame's connectivity 0..N-1, as it is).
cat >"$W/cmp.py" <<'PY'
#!/usr/bin/python3
import sys, h5py, numpy as np
a, b = h5py.File(sys.argv[1], "r"), h5py.File(sys.argv[2], "r")
ia, ib = a["particles/id"][()], b["particles/id"][()]
n = len(ia)
ok = len(ib) == n and len(np.unique(ib)) == n and np.array_equal(np.sort(ia), np.sort(ib))
if not ok:
    print(n, 0, "nan", 1, "particles/id"); sys.exit()
oa, ob = np.argsort(ia), np.argsort(ib)
names = []
a.visit(lambda k: names.append(k) if isinstance(a[k], h5py.Dataset) else None)
diff = []
for k in names:
    x, y = a[k][()], b[k][()] if k in b else None
    if y is None or x.shape != y.shape or x.dtype != y.dtype: diff.append(k); continue
    if x.ndim and x.shape[0] == n and k != "particles/vertex": x, y = x[oa], y[ob]  # vertex: row numbers
    if x.tobytes() != y.tobytes(): diff.append(k)
d = 2 * a["particles/radius"][()].max()
dx = np.abs(a["particles/position"][()][oa] - b["particles/position"][()][ob]).max() / d
print(n, 1, "%.3e" % dx, len(diff), " ".join(diff) if diff else "-")
PY
chmod +x "$W/cmp.py"
CUT2="-da_processors_x 2"
run() { # np, dir, args... (the 2-rank runs with the process grid CUT2)
  rnp=$1; rd=$2; shift 2
  cut=""; [ "$rnp" -eq 2 ] && cut=$CUT2
  mkdir -p "$rd"
  (cd "$rd" && mpiexec -n "$rnp" "$S" $SCENE $cut -io_dir out "$@" >log 2>&1)
}
frame() { ls "$1"/out/sable_[0-9]*.h5 2>/dev/null | tail -n 1; }
# case name, law options, end time; runs to T on 1 and 2 ranks, to H writing a checkpoint, and
# the remaps 2 -> 1, 1 -> 2; sets F1 F2 (final frames), R21 R12 (remapped final frames)
scene() {
  d=$W/$1; M=$2; T=$3
  for np in 1 2; do
    run "$np" "$d/full$np" $M -dem_t_end "$T" -io_interval "$T"
    run "$np" "$d/half$np" $M -dem_t_end $H -io_interval 0 -io_checkpoint_interval $H
  done
  ck1=$(ls "$d"/half1/out/*checkpoint*.h5 2>/dev/null | tail -n 1)
  ck2=$(ls "$d"/half2/out/*checkpoint*.h5 2>/dev/null | tail -n 1)
  run 1 "$d/rest21" $M -dem_t_end "$T" -io_interval "$T" -restart "$ck2"
  run 2 "$d/rest12" $M -dem_t_end "$T" -io_interval "$T" -restart "$ck1"
  F1=$(frame "$d/full1"); F2=$(frame "$d/full2"); R21=$(frame "$d/rest21"); R12=$(frame "$d/rest12")
  if [ -z "$ck1" ] || [ -z "$ck2" ] || [ -z "$F1" ] || [ -z "$F2" ] || [ -z "$R21" ] || [ -z "$R12" ]; then
    echo "FAIL remap $1: a run failed; $(grep -h 'error' "$d"/*/log | head -n 2)"
    return 1
  fi
}
# roundoff: history laws, 10 ms after the restart
for law in linear hertz; do
  case $law in hertz) M="-dem_contact_law hertz -dem_youngs_modulus 5e6" ;; *) M="-dem_contact_law linear -dem_kn 7.2e5" ;; esac
  scene "$law" "$M" 0.16 || continue
  for pair in "2->1 $F2 $R21" "1->2 $F1 $R12"; do
    set -- $pair
    set -- "$1" $("$W/cmp.py" "$2" "$3")
    if [ "$3" -eq 1 ] && awk "BEGIN { exit !($4 < $BOUND) }"; then
      echo "PASS remap $law $1 ranks: largest position difference at t=0.16 s (1,000 steps after the restart) vs the writer's uninterrupted run $4 d (bound $BOUND d); $2 ids, each once"
    else
      echo "FAIL remap $law $1 ranks: largest position difference $4 d (bound $BOUND d), ids each once: $3"
    fi
  done
  [ "$law" = linear ] || continue
  # the same rank count on another process grid: the ranks' boxes differ, the state is remapped
  CUT2="-da_processors_z 2"
  run 2 "$W/$law/rest22" $M -dem_t_end 0.16 -io_interval 0.16 -restart "$ck2"
  CUT2="-da_processors_x 2"
  set -- $("$W/cmp.py" "$F2" "$(frame "$W/$law/rest22")")
  if [ "$2" -eq 1 ] && awk "BEGIN { exit !($3 < $BOUND) }"; then
    echo "PASS remap $law 2 ranks cut along x -> 2 ranks stacked along z: largest position difference at t=0.16 s vs the writer's uninterrupted run $3 d (bound $BOUND d); $1 ids, each once"
  else echo "FAIL remap $law 2 ranks cut along x -> 2 ranks stacked along z: largest position difference $3 d (bound $BOUND d), ids each once: $2; $(grep -h 'error' "$W/$law/rest22/log" | head -n 1)"; fi
done
# bitwise with -dem_deterministic
if scene deterministic "-dem_contact_law linear -dem_kn 7.2e5 -dem_deterministic" 0.3; then
  set -- $("$W/cmp.py" "$F1" "$F2")
  if [ "$2" -eq 1 ] && [ "$4" -eq 0 ]; then
    echo "PASS remap deterministic: uninterrupted runs on 1 and 2 ranks bitwise equal at t=0.3 s (every dataset by id)"
  else echo "FAIL remap deterministic: uninterrupted runs on 1 and 2 ranks differ at t=0.3 s by $3 d in $4 datasets: $5"; fi
  for pair in "2->1 $F2 $R21" "1->2 $F1 $R12"; do
    set -- $pair
    set -- "$1" $("$W/cmp.py" "$2" "$3")
    if [ "$3" -eq 1 ] && [ "$5" -eq 0 ]; then
      echo "PASS remap deterministic $1 ranks: final frame at t=0.3 s bitwise equal to the uninterrupted run, every dataset by id; $2 ids, each once"
    else echo "FAIL remap deterministic $1 ranks: $5 datasets differ ($6), largest position difference $4 d, ids each once: $3"; fi
  done
fi
# unmappable checkpoints, read on 2 ranks from a 1-rank checkpoint
expect() { # name, pattern, checkpoint
  out=$(cd "$W" && mpiexec -n 2 "$S" $SCENE -da_processors_x 2 -dem_contact_law linear -dem_kn 7.2e5 -dem_t_end 0.16 -io_interval 0 -io_dir bad -restart "$3" 2>&1 >/dev/null); rc=$?
  lines=$(printf '%s\n' "$out" | grep -c 'sable: error')
  if [ "$rc" -ne 0 ] && [ "$lines" -eq 1 ] && printf '%s' "$out" | grep -q -- "$2"; then
    echo "PASS bad remap, $1: exit $rc, \"$(printf '%s' "$out" | grep 'sable: error')\""
  else
    echo "FAIL bad remap, $1: exit $rc, $lines error lines, expected /$2/; got: $out"
  fi
}
ck1=$(ls "$W"/linear/half1/out/*checkpoint*.h5 2>/dev/null | tail -n 1)
if [ -n "$ck1" ]; then
  cp "$ck1" "$W/outside.h5" && /usr/bin/python3 -c "import h5py, sys; f = h5py.File(sys.argv[1], 'a'); f['dem/x'][2] = 1.0; f.close()" "$W/outside.h5"
  expect "a position outside the domain" "outside.h5: the dataset dem/x puts particle" "$W/outside.h5"
  cp "$ck1" "$W/twice.h5" && /usr/bin/python3 -c "import h5py, sys; f = h5py.File(sys.argv[1], 'a'); f['dem/id'][1] = f['dem/id'][0]; f.close()" "$W/twice.h5"
  expect "an id repeated" "twice.h5: the dataset dem/id gives" "$W/twice.h5"
fi
