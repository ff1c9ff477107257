#!/bin/sh
# Every option that a case (cases/**/*.opts) or a tool's script (tools/*.sh: the names under
# Sable's and PETSc's -da_ prefixes) gives is written out in src/, so that grep finds where it is
# read. The rule, one of three:
#   Sable's: the name appears as a whole string literal, "-dem_wall_kn"; or it is a member of an
#     indexed family written once with %d in one literal, "-dem_plane_%d" for -dem_plane_0 (the
#     index a run of digits);
#   PETSc's: the name is a prefix that src/ gives a solver (KSPSetOptionsPrefix(ksp,
#     "fluid_poisson_"), empty for the global ones), then optionally PETSc's own level prefix
#     (mg_levels_, mg_coarse_, sub_), then an option name that PETSc's library holds as a
#     literal ("-pc_type", "-da_grid_x"): -fluid_poisson_mg_levels_ksp_type is PETSc's.
# One line per source of names, naming any option that fits none of the rules.
cd "$(dirname "$0")/../.." || exit 1
T=$(mktemp -d); trap 'rm -rf "$T"' EXIT
S=${BIN:-bin}/sable
lib=$(ldd "$S" | awk '/libpetsc/ {print $3; exit}')
[ -f "$lib" ] || { echo "FAIL options literal: PETSc's library not found from $S"; exit 1; }
strings -n 4 "$lib" | grep -E '^-[a-z][a-z0-9_]*$' | sort -u > "$T/petsc"
grep -rhoE '"-[a-z][a-z0-9_]*"' src | tr -d '"' | sort -u > "$T/literal"
grep -rhoE '"-[a-z][a-z0-9_]*%d[a-z0-9_]*"' src | tr -d '"' | sed 's/%d/[0-9]+/; s/^/^/; s/$/$/' | sort -u > "$T/indexed"
grep -rhoE 'OptionsPrefix\([^,]*, "[a-z0-9_]*"\)' src | sed 's/.*"\(.*\)")/\1/' | sort -u > "$T/prefixes"
echo "" >> "$T/prefixes" # the global options
np=$(grep -c . "$T/prefixes")

check() { # label, file of names
  label=$1; names=$2; missing=""; ns=0; ni=0; npet=0; n=0
  for o in $(sort -u "$names"); do
    n=$((n + 1))
    if grep -qxF -- "$o" "$T/literal"; then ns=$((ns + 1)); continue; fi
    if printf '%s\n' "$o" | grep -qE -f "$T/indexed"; then ni=$((ni + 1)); continue; fi
    found=0
    while read -r p; do
      rest=${o#-"$p"}
      [ "$rest" = "$o" ] && [ -n "$p" ] && continue
      for sub in "" mg_levels_ mg_coarse_ sub_; do
        r=${rest#"$sub"}
        [ "$r" = "$rest" ] && [ -n "$sub" ] && continue
        grep -qxF -- "-$r" "$T/petsc" && found=1 && break
      done
      [ $found -eq 1 ] && break
    done < "$T/prefixes"
    if [ $found -eq 1 ]; then npet=$((npet + 1)); else missing="$missing $o"; fi
  done
}
report() { # label
  if [ -z "$missing" ] && [ "$n" -gt 0 ]; then echo "PASS options literal $1: $n options: $ns written out in src/, $ni members of an indexed family (%d), $npet PETSc's (global or under one of $np solver prefixes)"
  else echo "FAIL options literal $1: of $n options, not written out in src/ nor PETSc's:$missing"; fi
}
find cases -name '*.opts' -exec sed -n 's/^[ \t]*\(-[a-zA-Z][a-zA-Z0-9_]*\).*/\1/p' {} + > "$T/cases"
check "cases/**/*.opts" "$T/cases"; report "cases/**/*.opts"
grep -ohE -- '-(dem|fluid|cpl|domain|io|lb|sable|da)_[a-z0-9_]+' tools/*.sh > "$T/tools"
check "tools/*.sh" "$T/tools"; report "tools/*.sh"
# the rule itself refuses names that are not written out: an index that is not a number, an
# option of Sable's not in src/, a PETSc prefix with a name PETSc does not have
printf '%s\n' -dem_plane_x -dem_frobnicate -fluid_poisson_frobnicate -dem_plane_1 > "$T/control"
check control "$T/control"
if [ "$missing" = " -dem_frobnicate -dem_plane_x -fluid_poisson_frobnicate" ]; then echo "PASS options literal control: 3 of 4 made-up names refused:$missing"
else echo "FAIL options literal control: expected -dem_frobnicate -dem_plane_x -fluid_poisson_frobnicate refused, got:${missing:- none}"; fi
