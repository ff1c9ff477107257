#!/bin/sh
# How a run ends on a bad STL file: build/tests/geom/test_stl FILE reads FILE with the reader
# (collective on all ranks) and is run on 1 and 2 ranks as a program. A truncated binary file and
# an ASCII file with a NaN vertex must end the program with a non-zero status within 60 s (no
# rank left waiting in a broadcast) and print the message naming the file and the triangle
# exactly once; a good file reads to the same summary (count, area, volume) on 2 ranks as on 1.
cd "$(dirname "$0")/../.." || exit 1
BUILD=${BUILD:-build}
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
[ "$(id -u)" -eq 0 ] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
READ="$BUILD/tests/geom/test_stl"
tools/make_stl vblender --binary -o "$OUT/good.stl" >/dev/null || echo "FAIL make_stl vblender: exit status $?"
head -c 1000 "$OUT/good.stl" >"$OUT/trunc.stl" # 84 + 50 x 18 + 16: triangle 19 is cut
printf 'solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 nan 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid s\n' >"$OUT/nan.stl"
run() { # ranks, file: the program's output in $OUT/log, its status in rc
  if [ "$1" -eq 1 ]; then timeout -k 5 60 "$READ" "$2" >"$OUT/log" 2>&1; else timeout -k 5 60 mpiexec --oversubscribe -n "$1" "$READ" "$2" >"$OUT/log" 2>&1; fi
  rc=$?
}
for n in 1 2; do
  for c in "trunc:triangle 19 is incomplete" "nan:triangle 1 (line 5) vertex 2 has a non-finite coordinate"; do
    f=${c%%:*}; frag=${c#*:}
    run "$n" "$OUT/$f.stl"
    if [ "$rc" -ne 0 ] && [ "$rc" -ne 124 ] && [ "$rc" -ne 137 ]; then echo "PASS bad STL ($f) on $n ranks: exit status $rc (non-zero, no time-out)"
    else echo "FAIL bad STL ($f) on $n ranks: exit status $rc (want non-zero; 124/137: timed out)"; fi
    lines=$(grep -cF "STL file $OUT/$f.stl: " "$OUT/log")
    if [ "$lines" -eq 1 ] && grep -qF "$frag" "$OUT/log"; then echo "PASS bad STL ($f) on $n ranks: one line naming the file and '$frag'"
    else echo "FAIL bad STL ($f) on $n ranks: $lines lines naming the file (want 1 with '$frag'):"; tail -n 5 "$OUT/log" | sed 's/^/    /'; fi
  done
done
run 1 "$OUT/good.stl"; one=$(grep '^mesh ' "$OUT/log")
run 2 "$OUT/good.stl"; two=$(grep '^mesh ' "$OUT/log")
if [ -n "$one" ] && [ "$one" = "$two" ]; then echo "PASS good STL on 2 ranks: the same summary as on 1 ($one)"
else echo "FAIL good STL on 2 ranks: '$two', on 1 rank '$one'"; fi
