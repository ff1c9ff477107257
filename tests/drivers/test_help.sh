#!/bin/sh
# What -help shows (src/options.c), with no case, with cases/fluidized_bed/bed.opts and with
# cases/settle/settle.opts:
#   (a) no uninitialised value: the same options give the same text under two environments of
#       different sizes (the stack a reader leaves uninitialised holds other bytes), and every
#       number shown between <> is sane: finite, |x| <= 1e30, and 0 or |x| >= 1e-200;
#   (b) Sable's options come first, grouped by prefix (-domain_, -dem_, -fluid_, -cpl_, -lb_,
#       -io_, -mon_, -avg_, -sable_), all before the first of PETSc's;
#   (c) no line ends with PETSc's "(None)" (no manual page);
#   (d) with bed.opts each face shows its own inlet velocity and table: the values the case
#       gives that face, the default (0,0,0; none) for the others;
#   (e) every shipped case (cases/*/*.opts), dry or coupled: exit 0, no "sable: error" line, every
#       option group listed (-domain_, -dem_, -fluid_, -cpl_, -lb_, -io_, -mon_, -avg_, -sable_,
#       -restart), each of Sable's options once: an indexed family (-dem_plane_<k>_velocity) on
#       one line with its index range and no member on a line of its own, except the members
#       the case gives, each shown under its family with the case's value;
#   (f) the text starts with a header naming Sable, how to run a case and doc/options.md;
#   (g) a source left incomplete (-dem_insert_0_region box alone, a lognormal without its mean)
#       is no error under -help, nor an option given without the one it completes (a source's rate,
#       an outlet's start, a plane's velocity, a drum's speed, a mesh's rotation), and the
#       size-distribution options (-dem_insert_<k>_psd...) are listed;
#   (h) -help opens no file a case names (an init frame, a mesh that do not exist: exit 0), and
#       with no case lists the families of walls, meshes, sources and monitors not given.
cd "$(dirname "$0")/../.." || exit 1
T=$(mktemp -d); trap 'rm -rf "$T"' EXIT
S=${BIN:-bin}/sable
PAD=$(awk 'BEGIN {for (i = 0; i < 4000; i++) printf "x"}')
for c in none bed settle; do
  case $c in none) o="" ;; bed) o="-options_file cases/fluidized_bed/bed.opts" ;; settle) o="-options_file cases/settle/settle.opts" ;; esac
  $S -help $o > "$T/$c.1" 2>&1; echo $? > "$T/$c.rc"
  env SABLE_TEST_PAD="$PAD" $S -help $o > "$T/$c.2" 2>&1
done

# (a) the same text twice; sane numbers
for c in none bed settle; do
  d=$(diff "$T/$c.1" "$T/$c.2" | grep -c '^<')
  n=$(wc -l < "$T/$c.1")
  if [ "$(cat "$T/$c.rc")" -eq 0 ] && [ "$d" -eq 0 ]; then echo "PASS help $c: exit 0, $n lines, the same under two environments (0 lines differ)"
  else echo "FAIL help $c: exit $(cat "$T/$c.rc"), $d of $n lines differ between two environments: $(diff "$T/$c.1" "$T/$c.2" | grep '^<' | head -n 2)"; fi
  awk '/^ *-[a-zA-Z]/ && /</ {
      line = $0; sub(/^[^<]*</, "", line); sub(/>.*/, "", line)
      gsub(/now |formerly |default |[():]/, " ", line); gsub(/,/, " ", line)
      n = split(line, t, / +/)
      for (i = 1; i <= n; i++) {
        x = t[i]; if (x == "") continue
        if (tolower(x) ~ /^[-+]?(nan|inf)/) { print "BAD", x, $1; continue }
        if (x !~ /^[-+]?[0-9]+\.?[0-9]*([eE][-+]?[0-9]+)?$/) continue
        v = x + 0; a = v < 0 ? -v : v; cnt++
        if (a > 1e30 || (a > 0 && a < 1e-200)) print "BAD", x, $1
      }
    } END { print "COUNT", cnt + 0 }' "$T/$c.1" > "$T/$c.nums"
  bad=$(grep -c '^BAD' "$T/$c.nums"); cnt=$(sed -n 's/^COUNT //p' "$T/$c.nums")
  if [ "$bad" -eq 0 ] && [ "$cnt" -gt 100 ]; then echo "PASS help $c: $cnt numbers shown between <>, 0 insane (|x| > 1e30, 0 < |x| < 1e-200, nan, inf)"
  else echo "FAIL help $c: $bad of $cnt numbers shown between <> are insane: $(grep '^BAD' "$T/$c.nums" | head -n 3 | tr '\n' ' ')"; fi
done

# (b) Sable's first, grouped by prefix
for c in none bed settle; do
  awk 'function own(n) { return n == "-restart" || n ~ /^-(domain|dem|fluid|cpl|lb|io|mon|avg|sable)_/ && (n !~ /^-fluid_(poisson|viscous)_/ || n ~ /^-fluid_(poisson_pc_lag|poisson_pc_lag_growth|viscous_number_max)$/) }
    /^ *-[a-zA-Z]/ {
      n = $1; sub(/[:<].*/, "", n)
      if (own(n)) {
        last = NR; split("domain dem fluid cpl lb io mon avg sable", p, " ")
        for (k = 1; k <= 9; k++) if (index(n, "-" p[k] "_") == 1) g = k
        if (n == "-restart") g = 6
        if (g < prev) back++
        prev = g; nown++
      } else if (!first) first = NR
    } END { printf "%d %d %d %d\n", nown, last, first, back }' "$T/$c.1" > "$T/$c.order"
  read nown last first back < "$T/$c.order"
  if [ "$nown" -gt 100 ] && [ "$first" -gt "$last" ] && [ "$back" -eq 0 ]; then echo "PASS help $c: Sable's $nown options on lines up to $last, grouped by prefix (0 steps back), PETSc's first option on line $first"
  else echo "FAIL help $c: Sable's $nown options end on line $last, PETSc's first option is on line $first, $back steps back in the prefix order"; fi
done

# (c) no "(None)"
for c in none bed settle; do
  k=$(grep -c '(None)$' "$T/$c.1")
  if [ "$k" -eq 0 ]; then echo "PASS help $c: 0 lines end with (None)"; else echo "FAIL help $c: $k lines end with (None), e.g. $(grep '(None)$' "$T/$c.1" | head -n 1)"; fi
done

# (d) each face its own values (bed.opts)
bad=""; nf=0
for f in xlo xhi ylo yhi zlo zhi; do
  for o in velocity velocity_table; do
    given=$(sed -n "s/^-fluid_bc_${f}_${o} *\([^ ]*\).*/\1/p" cases/fluidized_bed/bed.opts)
    shown=$(sed -n "s/^  -fluid_bc_${f}_${o} <\([^>]*\)>.*/\1/p" "$T/bed.1")
    case "$shown" in *" (default "*) val=${shown%% (default*} ;; *) val=$shown ;; esac
    if [ -n "$given" ]; then want=$given; else case $o in velocity) want=0,0,0 ;; *) want=none ;; esac; fi
    same=$(awk -v a="$val" -v b="$want" 'BEGIN { na = split(a, x, ","); nb = split(b, y, ","); s = na == nb; for (i = 1; i <= na && s; i++) s = (x[i] == y[i]) || (x[i] + 0 == y[i] + 0 && x[i] ~ /^[-+.0-9]/); print s }')
    nf=$((nf + 1))
    [ "$same" -eq 1 ] || bad="$bad -fluid_bc_${f}_${o} shows <$shown>, the case gives ${given:-nothing} (want $want);"
  done
done
if [ -z "$bad" ]; then echo "PASS help bed: each of the 6 faces shows its own inlet velocity and table ($nf lines as the case gives them)"
else echo "FAIL help bed: faces show another face's value:$bad"; fi

# (e) every shipped case
own='function own(n) { return n == "-restart" || n ~ /^-(domain|dem|fluid|cpl|lb|io|mon|avg|sable)_/ && (n !~ /^-fluid_(poisson|viscous)_/ || n ~ /^-fluid_(poisson_pc_lag|poisson_pc_lag_growth|viscous_number_max)$/) }'
for f in cases/*/*.opts; do
  timeout 60 $S -help -options_file "$f" > "$T/case" 2>&1; rc=$?
  err=$(grep -c 'sable: error' "$T/case")
  miss=""; for g in domain dem fluid cpl lb io mon avg sable; do grep -q "^  -${g}_" "$T/case" || miss="$miss -${g}_"; done
  grep -q '^  -restart ' "$T/case" || miss="$miss -restart"
  # top-level lines (2 blanks): Sable's names once, none indexed; members (6 blanks) under a family
  awk "$own"'
    /^  -[a-zA-Z]/ { n = $1; sub(/:$/, "", n); if (!own(n)) next
      if (seen[n]++) dup = dup " " n
      if (n ~ /_[0-9]+(_|$)/) idx = idx " " n
      if (n ~ /<k>/) { fam++; cur = n } else cur = "" }
    /^      -[a-zA-Z]/ { n = $1; sub(/:$/, "", n); p = n; sub(/_[0-9]+/, "_<k>", p)
      if (p != cur) bad = bad " " n
      v = $0; sub(/^[^<]*</, "", v); sub(/>.*/, "", v); sub(/ \(default .*/, "", v); sub(/^now /, "", v); sub(/ : formerly.*/, "", v)
      gsub(/ : /, "|", v); print "MEMBER", n, v }
    END { printf "SUM %d %s|%s|%s\n", fam, dup, idx, bad }' "$T/case" > "$T/case.sum"
  line=$(grep '^SUM' "$T/case.sum"); fam=$(echo "$line" | cut -d' ' -f2)
  few() { awk '{ for (i = 1; i <= NF && i <= 4; i++) printf " %s", $i; if (NF > 4) printf " ... (%d in all)", NF }'; } # a list, cut short
  dup=$(echo "$line" | cut -d' ' -f3- | cut -d'|' -f1 | few); idx=$(echo "$line" | cut -d'|' -f2 | few); bad=$(echo "$line" | cut -d'|' -f3 | few)
  # the indexed options the case gives: each a member line with the case's value
  given=0; lost=""
  for o in $(sed -n 's/^\(-[a-z0-9_]*_[0-9][0-9]*\(_[a-z0-9_]*\)\{0,1\}\)[ \t].*/\1/p' "$f"); do
    case $o in *_[0-9]|*_[0-9]_*|*_[0-9][0-9]|*_[0-9][0-9]_*) ;; *) continue ;; esac
    given=$((given + 1))
    want=$(sed -n "s/^$o[ \t][ \t]*\([^ \t#]*\).*/\1/p" "$f" | tail -n 1)
    shown=$(awk -v o="$o" '$1 == "MEMBER" && $2 == o { print $3 }' "$T/case.sum")
    # the value as the case wrote it, numbers to the 6 digits shown; of PETSc's "a : b", either
    same=$(awk -v all="$shown" -v b="$want" 'BEGIN { nv = split(all, alt, "|"); ok = 0
      for (k = 1; k <= nv && !ok; k++) { a = alt[k]; na = split(a, x, ","); nb = split(b, y, ","); s = na == nb && a != ""
        for (i = 1; i <= na && s; i++) { d = x[i] - y[i]; if (d < 0) d = -d; m = y[i] < 0 ? -y[i] : y[i]; s = (x[i] == y[i]) || (x[i] ~ /^[-+.0-9]/ && d <= 1e-5 * m) }
        ok = s }
      print ok }')
    [ "$same" -eq 1 ] || lost="$lost $o (case $want, shown '${shown}')"
  done
  if [ "$rc" -eq 0 ] && [ "$err" -eq 0 ] && [ -z "$miss" ] && [ -z "$dup$idx$bad$lost" ] && [ "$fam" -gt 20 ]; then
    echo "PASS help $f: exit 0, no error line, 10 of 10 groups, each option once ($fam indexed families on one line each), $given indexed options of the case shown with its values"
  else
    echo "FAIL help $f: exit $rc, $err error lines ($(grep 'sable: error' "$T/case" | head -n 1)), groups missing:${miss:- none}; listed twice:${dup:- none}; members on lines of their own:${idx:- none}; members outside their family:${bad:- none}; case values not shown:${lost:- none}; $fam indexed families"
  fi
done

# (f) the header
head -n 12 "$T/none.1" > "$T/head"
if head -n 1 "$T/head" | grep -q '^Sable [0-9.]*: parallel CFD-DEM' && grep -q 'bin/sable -options_file cases/' "$T/head" && grep -q 'doc/options.md' "$T/head"; then echo "PASS help none: starts with a header: $(head -n 1 "$T/head" | cut -c1-60)..., how to run a case, doc/options.md"
else echo "FAIL help none: no header (Sable, how to run a case, doc/options.md) in the first 12 lines: $(head -n 1 "$T/head")"; fi

# (g) an incomplete source under -help
$S -help -dem_insert_0_region box > "$T/src" 2>&1; rc=$?
n=$(grep -c '^  -dem_insert_<k>_psd' "$T/src")
if [ "$rc" -eq 0 ] && ! grep -q 'sable: error' "$T/src" && [ "$n" -ge 8 ]; then echo "PASS help -dem_insert_0_region box (no -dem_insert_0_box): exit 0, no error, $n size-distribution options listed (-dem_insert_<k>_psd*)"
else echo "FAIL help -dem_insert_0_region box: exit $rc, $(grep 'sable: error' "$T/src" | head -n 1), $n lines -dem_insert_<k>_psd* (want >= 8)"; fi
part="-dem_insert_0_region cylinder -dem_insert_0_psd lognormal -dem_insert_1_rate 5 -dem_outlet_0_start 1 -dem_plane_3_velocity 1,0,0 -dem_cylinder_omega 2 -dem_mesh_2_omega 1"
$S -help $part > "$T/part" 2>&1; rc=$?
if [ "$rc" -eq 0 ] && ! grep -q 'sable: error' "$T/part"; then echo "PASS help $part: exit 0, no error"
else echo "FAIL help $part: exit $rc, $(grep 'sable: error' "$T/part" | head -n 1)"; fi

# (h) no file opened; the families of what no case gives
$S -help -dem_init_file "$T/none.h5" -dem_mesh_0_file "$T/none.stl" > "$T/files" 2>&1; rc=$?
if [ "$rc" -eq 0 ] && ! grep -q 'sable: error' "$T/files"; then echo "PASS help with a missing -dem_init_file and -dem_mesh_0_file: exit 0, no error (no file opened)"
else echo "FAIL help with a missing -dem_init_file and -dem_mesh_0_file: exit $rc, $(grep 'sable: error' "$T/files" | head -n 1)"; fi
miss=""; nfam=0
for o in -dem_box_friction '-dem_plane_<k>_friction' '-dem_rect_<k>_friction' '-dem_quad_<k>_friction' -dem_hopper_friction -dem_cylinder_friction '-dem_mesh_<k>_scale' '-dem_mesh_<k>_omega' '-dem_outlet_<k>_side' '-dem_insert_<k>_cylinder' '-dem_insert_<k>_psd_mean' '-mon_box_<k>' '-mon_probe_<k>' '-mon_dp_<k>' -avg_start; do
  nfam=$((nfam + 1)); grep -q -- "^  $o[ :]" "$T/none.1" || miss="$miss $o"
done
if [ -z "$miss" ]; then echo "PASS help none: the $nfam options and families of walls, meshes, outlets, sources and monitors that no case gives are listed"
else echo "FAIL help none: not listed:$miss"; fi
