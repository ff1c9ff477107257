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
#       gives that face, the default (0,0,0; none) for the others.
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
