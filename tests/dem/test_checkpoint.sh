#!/bin/sh
# Exact checkpoints of a dry run: for each contact law (linear_nohist, linear, hertz) on 1 and 2
# ranks, a run to T and a run to T/2 that writes a checkpoint then continued with -restart to T
# end with bitwise the same final frame (every dataset compared with h5py). A bad checkpoint
# (truncated, of another format version, missing, without a dataset) is refused: exit non-zero,
# one error line. Convex shapes, moving walls and periodic boxes: test_checkpoint_scenes.sh;
# another rank count: test_checkpoint_ranks.sh.
cd "$(dirname "$0")/../.." || exit 1
S=$(pwd)/${BIN:-bin}/sable
[ "$(id -u)" -eq 0 ] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1
W=$(mktemp -d)
trap 'rm -rf "$W"' EXIT
# 384 glass spheres falling onto the floor of a box from a jittered lattice: at T/2 the bed is
# forming (wall and pair contacts, rebuilds, migration between the two ranks stacked along z)
SCENE="-domain_lo 0,0,0 -domain_hi 0.1449,0.1449,0.24633 -dem_box 0,0,0,0.1449,0.1449,0.24633 -dem_radius 0.0069 -dem_density 2500 -dem_restitution 0.75 -dem_friction 0.3 -dem_dt 1e-5 -dem_lattice 8,8,6 -dem_lattice_spacing 0.01449 -dem_lattice_speed 0.05 -dem_progress_interval 0"
T=0.3
H=0.15
run() { # np, dir, args...
  rnp=$1; rd=$2; shift 2
  mkdir -p "$rd"
  (cd "$rd" && mpiexec -n "$rnp" "$S" $SCENE -io_dir out "$@" >log 2>&1)
}
for law in linear_nohist linear hertz; do
  case $law in hertz) M="-dem_contact_law hertz -dem_youngs_modulus 5e6" ;; *) M="-dem_contact_law $law -dem_kn 7.2e5" ;; esac
  for np in 1 2; do
    d=$W/$law.$np
    run "$np" "$d/full" $M -dem_t_end $T -io_interval $T
    run "$np" "$d/half" $M -dem_t_end $H -io_interval 0 -io_checkpoint_interval $H
    ck=$(sed -n 's/^checkpoint: //p' "$d/half/log" | tail -n 1)
    run "$np" "$d/rest" $M -dem_t_end $T -io_interval $T -restart "../half/$ck"
    a=$(ls "$d/full/out/"sable_*.h5 2>/dev/null | tail -n 1); b=$(ls "$d/rest/out/"sable_*.h5 2>/dev/null | tail -n 1)
    if [ -z "$ck" ] || [ -z "$a" ] || [ -z "$b" ]; then
      echo "FAIL checkpoint $law np=$np: a run failed; $(cat "$d"/*/log | grep 'error' | head -n 2)"
      continue
    fi
    set -- $(tests/common/frames_equal.py "$a" "$b")
    if [ "$1" -gt 0 ] && [ "$2" -eq 0 ]; then
      echo "PASS checkpoint $law np=$np: final frames at t=$T bitwise equal, $1 datasets compared, 0 differing (restart from $ck)"
    else
      echo "FAIL checkpoint $law np=$np: $1 datasets compared, $2 differing: $3 $4 $5"
    fi
  done
done
expect() { # name, pattern, np, checkpoint (1 rank without mpiexec: it lingers 2 s after a failure)
  L=$([ "$3" -gt 1 ] && echo "mpiexec -n $3")
  out=$(cd "$W/linear.1/rest" && $L "$S" $SCENE -dem_contact_law linear -dem_kn 7.2e5 -dem_t_end $T -io_interval 0 -restart "$4" 2>&1 >/dev/null); rc=$?
  lines=$(printf '%s\n' "$out" | grep -c 'sable: error')
  if [ "$rc" -ne 0 ] && [ "$lines" -eq 1 ] && printf '%s' "$out" | grep -q -- "$2"; then
    echo "PASS bad checkpoint, $1: exit $rc, \"$(printf '%s' "$out" | grep 'sable: error')\""
  else
    echo "FAIL bad checkpoint, $1: exit $rc, $lines error lines, expected /$2/; got: $out"
  fi
}
ck1=$(ls "$W"/linear.1/half/out/*checkpoint*.h5 | tail -n 1)
head -c 20000 "$ck1" >"$W/truncated.h5"
expect "truncated" "truncated" 1 "$W/truncated.h5"
expect "missing file" "not a readable HDF5 file" 1 "$W/none.h5"
cp "$ck1" "$W/missing.h5" && /usr/bin/python3 -c "import h5py, sys; f = h5py.File(sys.argv[1], 'a'); del f['dem/nl_hist']; f.close()" "$W/missing.h5"
expect "missing dataset" "the dataset dem/nl_hist is missing" 1 "$W/missing.h5"
cp "$ck1" "$W/version.h5" && /usr/bin/python3 -c "import h5py, sys, numpy; f = h5py.File(sys.argv[1], 'a'); f.attrs['sable_checkpoint_version'] = numpy.int32(1); f.close()" "$W/version.h5"
expect "another version" "attribute sable_checkpoint_version 1, this Sable reads version 2" 1 "$W/version.h5"
