#!/bin/sh
# Output and input under faults. A disk that fills during a run (cases/settle/quick.opts on a
# 1 MB tmpfs with 564 kB taken: room for two frames of 160 kB; root only) ends it with one line
# naming the frame file and "No space left on device", exit status 1, no temporary left, the
# earlier frames readable and listed in a well-formed index (also on 2 ranks). A disk too full
# for even a frame's metadata (200 kB tmpfs, 30 kB taken) never crashes the run at exit (5 runs:
# the failed frame's HDF5 file, left open, used to crash HDF5 inside MPI_Finalize). An index that cannot be written names its
# file. Hostile init files (-dem_init_file) each end with one line naming the file and the
# dataset, promptly, on 1 and 2 ranks: datasets declared with 800,000,000 rows and no data
# (rows x columns overflows 32-bit counts), a string-typed position, position with 2 columns.
cd "$(dirname "$0")/../.." || exit 1
S=${BIN:-bin}/sable
D=$(mktemp -d)
M="$D/m"
T="$D/t"
trap 'umount "$M" 2>/dev/null; umount "$T" 2>/dev/null; rm -rf "$D"' EXIT
trap 'exit 1' HUP INT TERM
[ "$(id -u)" -eq 0 ] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
SCENE="-domain_lo 0,0,0 -domain_hi 0.0725,0.0725,0.1 -dem_box 0,0,0,0.0725,0.0725,0.1 -dem_radius 0.0069 -dem_kn 7.2e5"
RUN="-options_file cases/settle/quick.opts -dem_t_end 0.03 -io_interval 0.01 -dem_progress_interval 1"
TWO="-da_processors_x 2 -da_processors_y 1 -da_processors_z 1 -domain_cell 0.03"

# one error line matching a pattern, and the exit status: name, expected status, pattern, log
one_line() {
  nl=$(grep -c 'sable: error' "$4"); msg=$(grep 'sable: error' "$4" | head -n 1)
  if [ "$rc" -eq "$2" ] && [ "$nl" -eq 1 ] && printf '%s\n' "$msg" | grep -q -- "$3"; then echo "PASS $1: exit $rc, \"$msg\""
  else echo "FAIL $1: exit $rc (expected $2), $nl error lines, expected /$3/; got: $(tail -n 2 "$4" | tr '\n' ' ')"; fi
}

# (a) a full disk
mkdir "$M"
why=""
if [ "$(id -u)" -ne 0 ]; then why="not running as root (mount needs it)"
elif ! mount -t tmpfs -o size=1m tmpfs "$M" 2>"$D/mount.err"; then why="mount -t tmpfs failed: $(head -n 1 "$D/mount.err")"
else dd if=/dev/zero of="$M/fill" bs=1k count=564 2>/dev/null || why="cannot fill the tmpfs"; fi
if [ -n "$why" ]; then
  echo "NOTE io_faults: disk-full check skipped: $why"
else
  timeout 60 "$S" $RUN -io_dir "$M" > "$D/full.log" 2>&1; rc=$?
  one_line "disk full, 1 rank" 1 "cannot write $M/sable_[0-9]*\.h5: No space left on device" "$D/full.log"
  tmp=$(ls -a "$M" | grep -c -e '\.tmp$' -e reserve)
  [ "$tmp" -eq 0 ] && echo "PASS disk full: no temporary or reserve file left" || echo "FAIL disk full: $tmp temporary files left: $(ls -a "$M" | tr '\n' ' ')"
  /usr/bin/python3 - "$M" <<'PY' || echo "FAIL disk full: the checking script exited with status $?"
import sys, os, glob, xml.dom.minidom, h5py, numpy as np
d = sys.argv[1]
frames = sorted(glob.glob(d + "/sable_*.h5"))
good = 0
for f in frames:
    with h5py.File(f, "r") as h:
        p = h["particles/position"][:]
        good += p.shape == (1200, 3) and np.isfinite(p).all()
doc = xml.dom.minidom.parse(d + "/sable.xmf")
items = [i.firstChild.data.split(":")[0] for i in doc.getElementsByTagName("DataItem") if i.getAttribute("Format") == "HDF"]
listed = sorted(set(items))
ok = len(frames) >= 2 and good == len(frames) and listed == [os.path.basename(f) for f in frames]
print(("PASS" if ok else "FAIL") + " disk full: %d earlier frames, %d readable with 1200 finite positions; the index parses and lists %d files (expected the same %d)" % (len(frames), good, len(listed), len(frames)))
PY
  mkdir "$T"
  if mount -t tmpfs -o size=200k tmpfs "$T" && dd if=/dev/zero of="$T/fill" bs=1k count=30 2>/dev/null; then
    crash=0; clean=0
    for i in 1 2 3 4 5; do
      rm -f "$T"/sable*
      timeout 60 "$S" -options_file cases/settle/quick.opts -dem_t_end 0.05 -io_interval 0.01 -io_dir "$T" > "$D/rep.log" 2>&1; r=$?
      [ "$r" -gt 128 ] && crash=$((crash + 1))
      [ "$r" -eq 1 ] && [ "$(grep -c 'sable: error: cannot write .*: No space left on device' "$D/rep.log")" -eq 1 ] && clean=$((clean + 1))
    done
    [ "$crash" -eq 0 ] && [ "$clean" -eq 5 ] && echo "PASS disk full at once: 5 runs, $crash ended by a signal (bound 0), $clean ended with exit 1 and one line (expected 5)" || echo "FAIL disk full at once: $crash of 5 runs ended by a signal, $clean of 5 with exit 1 and one line"
  else echo "FAIL disk full at once: the second tmpfs could not be mounted and filled"; fi
  rm -f "$M"/sable*
  timeout 60 mpiexec --oversubscribe -n 2 "$S" $RUN -io_dir "$M" > "$D/full2.log" 2>&1; rc=$?
  one_line "disk full, 2 ranks" 1 "cannot write $M/sable_[0-9]*\.h5: No space left on device" "$D/full2.log"
  tmp=$(ls -a "$M" | grep -c -e '\.tmp$' -e reserve)
  [ "$tmp" -eq 0 ] && echo "PASS disk full, 2 ranks: no temporary left" || echo "FAIL disk full, 2 ranks: $tmp temporary files left"
fi

# an index that cannot be written (its temporary's name is taken by a directory)
mkdir -p "$D/x/sable.xmf.tmp"
timeout 60 "$S" $SCENE -dem_lattice 2,2,2 -dem_t_end 0 -io_interval 1 -io_dir "$D/x" > "$D/x.log" 2>&1; rc=$?
one_line "index not writable" 1 "cannot write $D/x/sable.xmf.tmp: Is a directory" "$D/x.log"

# an output directory whose parents do not exist yet is made with them (as mkdir -p); one under a
# regular file is refused in one line
timeout 60 "$S" $SCENE -dem_lattice 2,2,2 -dem_t_end 0 -io_interval 1 -io_dir "$D/new/a/b" > "$D/p.log" 2>&1; rc=$?
if [ $rc -eq 0 ] && [ -f "$D/new/a/b/sable.xmf" ]; then echo "PASS io_dir parents: $D/new/a/b made with its parents, exit 0"
else echo "FAIL io_dir parents: exit $rc, $(grep -c sable.xmf "$D/p.log") index lines; $(grep 'sable: error' "$D/p.log" | head -n 1)"; fi
: > "$D/afile"
timeout 60 "$S" $SCENE -dem_lattice 2,2,2 -dem_t_end 0 -io_interval 1 -io_dir "$D/afile/out" > "$D/pf.log" 2>&1; rc=$?
one_line "io_dir under a file" 1 "-io_dir $D/afile/out: cannot create the directory (Not a directory)" "$D/pf.log"

# (b), (c) hostile init files
/usr/bin/python3 - "$D" <<'PY' || echo "FAIL init files: the script making them exited with status $?"
import sys, h5py, numpy as np
d = sys.argv[1]
cols = {"position": 3, "velocity": 3, "angular_velocity": 3, "quaternion": 4, "id": 1, "radius": 1}
with h5py.File(d + "/huge.h5", "w") as f:
    for k, c in cols.items():
        f.create_dataset("particles/" + k, shape=(800000000, c) if c > 1 else (800000000,), dtype="f8", chunks=True)
with h5py.File(d + "/str.h5", "w") as f:
    f["particles/position"] = np.array([b"a", b"b"])
with h5py.File(d + "/str3.h5", "w") as f:
    f["particles/position"] = np.array([[b"a", b"b", b"c"]] * 4)
with h5py.File(d + "/cols.h5", "w") as f:
    f["particles/position"] = np.zeros((10, 2))
PY
B="$SCENE -dem_t_end 0 -io_interval 0"
for n in 1 2; do # (1 rank without mpiexec: mpiexec lingers 2 s after any non-zero exit)
  dec=""; L=""; [ "$n" -eq 2 ] && dec=$TWO && L="mpiexec --oversubscribe -n 2"
  for c in "huge.h5:dataset /particles/position declares 800000000 x 3 values, more than Sable can index" \
           "str.h5:dataset /particles/position holds strings, expected numbers" \
           "str3.h5:dataset /particles/position holds strings, expected numbers" \
           "cols.h5:dataset /particles/position has 2 columns, expected 3"; do
    f=${c%%:*}; pat=${c#*:}
    timeout 60 $L "$S" $B $dec -dem_init_file "$D/$f" > "$D/in.log" 2>&1; rc=$?
    one_line "init file $f, $n rank(s)" 1 "$D/$f: $pat" "$D/in.log"
  done
done
