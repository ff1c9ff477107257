#!/bin/sh
# The layout of src/ shows the design (DESIGN.md, "One picture"), checked by tools/check-layout:
#   (a) no circle of references among the .c files of any folder of src/, and every #include
#       points down the layers (geom and io know nothing of the rest; dem uses geom; dem and
#       fluid never see each other; coupling joins them; balance moves them; drivers run them);
#   (b) src/geom includes nothing from src/dem (said on its own: the geometry is a library);
#   (c) the checker can fail: on a copy of src/ with a circle planted in src/io (two files that
#       call each other) and an include of the DEM in src/geom, it reports both and exits 1;
#   (d) the C sources are formatted as .clang-format says (clang-format --dry-run finds nothing);
#   (e) no DEM file includes a private header of a concern it does not use, and every .c and .h
#       file of a folder of src/ is named in its README.md (its file map): the checker fails on a
#       copy of src/ with an unused dem_sources.h planted in src/dem/springs.c and a file
#       unnamed in src/geom/README.md.
cd "$(dirname "$0")/../.." || exit 1
T=$(mktemp -d); trap 'rm -rf "$T"' EXIT

out=$(tools/check-layout src 2>&1); rc=$?
summary=$(echo "$out" | tail -n 1)
if [ $rc -eq 0 ]; then echo "PASS layout src/: $summary"
else echo "FAIL layout src/: exit $rc; $(echo "$out" | head -n 8 | tr '\n' ';')"; fi

n=$(grep -rln '#include "dem/' src/geom | wc -l)
[ "$n" -eq 0 ] && echo "PASS layout src/geom includes nothing from src/dem (0 files)" \
  || echo "FAIL layout src/geom includes src/dem in $n files: $(grep -rln '#include "dem/' src/geom | tr '\n' ' ')"

cp -r src "$T/src"
printf '#include "io/io.h"\nint IoPlantedB(int);\nint IoPlantedA(int k) { return k ? IoPlantedB(k - 1) : 0; }\n' > "$T/src/io/planted_a.c"
printf '#include "io/io.h"\nint IoPlantedA(int);\nint IoPlantedB(int k) { return k ? IoPlantedA(k - 1) : 1; }\n' > "$T/src/io/planted_b.c"
echo '#include "dem/dem.h"' >> "$T/src/geom/hull.c"
bad=$(tools/check-layout "$T/src" 2>&1); rc=$?
if [ $rc -ne 0 ] && echo "$bad" | grep -q 'planted_a.c -> planted_b.c' && echo "$bad" | grep -q 'geom/hull.c:.*may not use dem/'; then
  echo "PASS layout checker fails on a planted circle and a planted include: exit $rc, $(echo "$bad" | tail -n 1)"
else echo "FAIL layout checker missed a planted fault: exit $rc; $(echo "$bad" | tail -n 3 | tr '\n' ';')"; fi

rm -rf "$T/src"; cp -r src "$T/src"
sed -i 's|^#include "dem/dem_core.h"$|&\n#include "dem/dem_sources.h"|' "$T/src/dem/springs.c"
printf '/* planted */\nint GeomPlanted(void);\n' > "$T/src/geom/planted.h"
bad=$(tools/check-layout "$T/src" 2>&1); rc=$?
if [ $rc -ne 0 ] && echo "$bad" | grep -q 'dem/springs.c:[0-9]*: includes "dem_sources.h" and uses none' \
  && echo "$bad" | grep -q 'geom/README.md: does not name planted.h' && echo "$bad" | tail -n 1 | grep -q ' 1 unused private headers, 1 files missing'; then
  echo "PASS layout checker fails on a planted unused DEM header and a file missing from a README: exit $rc, $(echo "$bad" | tail -n 1)"
else echo "FAIL layout checker missed a planted unused header or README omission: exit $rc; $(echo "$bad" | tail -n 3 | tr '\n' ';')"; fi

files=$(find src tests tools -name '*.[ch]' | sort)
nf=$(echo "$files" | wc -l)
if ! command -v clang-format > /dev/null; then echo "FAIL layout format: clang-format not found (tools/install-deps.sh installs it)"
else
  unformatted=$(for f in $files; do clang-format --dry-run "$f" 2>&1 | grep -q warning && echo "$f"; done)
  nu=$(echo "$unformatted" | grep -c .)
  [ "$nu" -eq 0 ] && echo "PASS layout format: $nf C files as .clang-format says (0 to reformat)" \
    || echo "FAIL layout format: $nu of $nf C files differ from .clang-format (clang-format -i fixes them): $(echo "$unformatted" | head -n 5 | tr '\n' ' ')"
fi
