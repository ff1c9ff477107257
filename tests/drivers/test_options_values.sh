#!/bin/sh
# Values given to Sable's own options (src/sable.c, SableCheckOptionValues): a word where a number
# is expected, a NaN or infinite number, an option that needs a value given none, and a list with
# a surplus item are each an error naming the option and the value (exit 1), never a run with a
# default or a dropped item; a negative first item is a value, not an option; the unused-option
# check lets through PETSc's run-time options by whole name only (-log_vieww is a typo); a bad
# options file is one line naming the file and line, not PETSc's traceback. Also: the lists of
# flags (given alone, they mean true) and of options that take words (no number check), which the
# build derives from the sources, agree with what -help shows.
cd "$(dirname "$0")/../.." || exit 1
T=$(mktemp -d); trap 'rm -rf "$T"' EXIT
Q="${BIN:-bin}/sable -options_file cases/settle/quick.opts -dem_t_end 0.001 -io_interval 0"
expect() { # name, pattern, options...
  name=$1; pat=$2; shift 2
  out=$($Q "$@" 2>&1); rc=$?
  if [ "$rc" -eq 1 ] && printf '%s\n' "$out" | grep -q -- "$pat"; then echo "PASS options $name: exit 1, \"$(printf '%s\n' "$out" | grep 'sable: error' | head -n 1)\""
  else echo "FAIL options $name: exit $rc, expected \"$pat\"; got: $(printf '%s\n' "$out" | tail -n 1)"; fi
}
expect "NaN item" "option -dem_gravity 0,nan,-9.81: 'nan' is not a finite number" -dem_gravity 0,nan,-9.81
expect "infinite end time" "option -dem_t_end inf: 'inf' is not a finite number" -dem_t_end inf
expect "infinite inlet" "option -fluid_bc_zlo_velocity 0,0,-inf: '-inf' is not a finite number" -fluid_bc_zlo_velocity 0,0,-inf
expect "word for a number" "option -dem_kn abc: 'abc' is not a number" -dem_kn abc
expect "missing value" "option -dem_box needs a value" -dem_box
expect "missing value last" "option -dem_kn needs a value" -dem_kn
expect "surplus item" "-domain_hi takes 3 comma-separated values, got 4" -domain_hi 0.1449,0.1449,0.24633,7
expect "Sable option under a solver prefix, no value" "option -fluid_viscous_number_max needs a value" -fluid_viscous_number_max
expect "Sable option under a solver prefix, inf" "option -fluid_poisson_pc_lag_growth inf: 'inf' is not a finite number" -fluid_poisson_pc_lag_growth inf
expect "negative skin" "-dem_skin -1. must be > 0 (m)" -dem_skin -1
expect "negative progress interval" "-dem_progress_interval -1. must be >= 0" -dem_progress_interval -1
expect "more radii than shapes" "-dem_radius takes at most 32 comma-separated values, got 34" -dem_radius "$(awk 'BEGIN {for (i = 0; i < 34; i++) printf "%s0.0069", i ? "," : ""}')"
Q="${BIN:-bin}/sable -options_file cases/fluidized_bed/small.opts -cpl_t_end 0.5 -io_interval 0"
expect "probe heights equal" "-cpl_probe_z 10.,10.: need lo <= z1 < z2 <= hi with the domain's z range \[0., 48.\]" -cpl_probe_z 10,10
expect "probe above the domain" "-cpl_probe_z 100.,200.: need lo <= z1 < z2 <= hi" -cpl_probe_z 100,200
expect "surplus inlet component" "-fluid_bc_zlo_velocity takes 3 comma-separated values, got 4" -fluid_bc_zlo_velocity 0,0,0.3,4
Q="${BIN:-bin}/sable -options_file cases/settle/quick.opts -dem_t_end 0.001 -io_interval 0"
expect "second value on the command line" "-dem_restitution has more than one value ('0.9' follows '0.5'" -dem_restitution 0.5 0.9
expect "typo of a PETSc option" "option -log_vieww was given but nothing reads it" -log_vieww
expect "multigrid-like name outside the solvers" "option -dem_mg_levels_foo 1 was given but nothing reads it" -dem_mg_levels_foo 1
out=$($Q -dem_plane_0 -1,0,0,0,0,1 -dem_frozen -io_prefix inf -io_dir "$T/inf" -io_interval 0.001 2>&1); rc=$?
if [ "$rc" -eq 0 ] && [ -f "$T/inf/inf.xmf" ]; then echo "PASS options negative first item, a flag alone, a file prefix named inf: exit 0"; else echo "FAIL options negative first item, a flag alone, a file prefix named inf: exit $rc: $(printf '%s\n' "$out" | tail -n 1)"; fi
printf -- '-io_prefix "my run"\n-dem_t_end 0.001\n-io_dir %s/q\n-io_interval 0.001\n' "$T" > "$T/q.opts"
out=$($Q -options_file "$T/q.opts" 2>&1); rc=$?
if [ "$rc" -eq 0 ] && [ -f "$T/q/my run.xmf" ]; then echo "PASS options file with a quoted value holding a blank: exit 0"; else echo "FAIL options file with a quoted value holding a blank: exit $rc: $(printf '%s\n' "$out" | tail -n 1)"; fi
# options files: a line that is not an option, a second value, a second option, a directory, no file name
printf -- '-dem_t_end 0.001\nthis is not an option\n' > "$T/a.opts"; printf -- '-dem_t_end 0.001 0.002\n' > "$T/b.opts"
printf -- '-dem_contact_law -linear\n' > "$T/c.opts" # PETSc's reader: "two options per line", a traceback
for c in "a.opts:line 2: 'this' is not an option" "b.opts:line 1: -dem_t_end has more than one value" "c.opts:line 1: -dem_contact_law is followed by another option, -linear" ":is a directory"; do
  f="$T/${c%%:*}"; pat=${c#*:}
  out=$(${BIN:-bin}/sable -options_file "$f" 2>&1); rc=$?
  if [ "$rc" -eq 1 ] && [ "$(printf '%s\n' "$out" | wc -l)" -eq 1 ] && printf '%s' "$out" | grep -q -- "$pat"; then echo "PASS options file ${c%%:*}: exit 1, one line: $out"
  else echo "FAIL options file ${c%%:*}: exit $rc, expected one line /$pat/; got: $(printf '%s\n' "$out" | head -n 3)"; fi
done
out=$(${BIN:-bin}/sable -options_file 2>&1); rc=$?
if [ "$rc" -eq 1 ] && [ "$out" = "sable: error: -options_file needs a file name" ]; then echo "PASS options file missing name: exit 1, $out"; else echo "FAIL options file missing name: exit $rc, $out"; fi
# The flag and word lists of the value check are generated from the sources at build time
# (tools/gen-options.sh -> $BUILD/gen/sable_options.h). They are checked here against -help, which
# shows each option as the call that reads it at run time prints it: every option of Sable's
# shown as a flag ("-name: <TRUE : TRUE>", SableOptionsBool's "<true>") must be in
# SableFlagOptions, every one whose value is a word (an enum's "choose one of" or "(one of ...)",
# a string, SableOptionsString's "(text)", a list of names) in SableWordOptions, and every name
# in those lists must be shown by -help as such. A flag or word option that the generator cannot
# see (read under a name it does not find) fails here.
genlist() { sed -n "/$1\[\] = {/,/NULL};/p" "${BUILD:-build}/gen/sable_options.h" | grep -o '"[a-z0-9_%]*"' | tr -d '"'; }
${BIN:-bin}/sable -help > "$T/help" 2>&1
awk '/^  -(dem|fluid|cpl|domain|io|lb)_[a-z0-9_<>]*[ :]/ {
    raw = substr($1, 2); sub(/:$/, "", raw); name = raw; gsub(/<k>/, "%d", name) # a family: its pattern
    if (match(name, /_[0-9]+_/)) name = substr(name, 1, RSTART) "%d" substr(name, RSTART + RLENGTH - 1) # a member: its family
    else if (match(name, /_[0-9]+$/)) name = substr(name, 1, RSTART) "%d"
    if (name ~ /^fluid_(poisson|viscous)_/ && name !~ /^fluid_(poisson_pc_lag|poisson_pc_lag_growth|viscous_number_max)$/) next # PETSc solvers
    v = $0; sub(/^ *[^ ]*/, "", v); sub(/^[^<]*</, "", v)
    if ($0 ~ "^  -" raw ": <(TRUE|FALSE) : " || v ~ /^(true|false)( \(default (true|false)\))?>/) { print "flag", name; next }
    now = (v ~ /^now /); sub(/^now /, "", v); split(v, t, /[ ,>]/); x = t[1]
    num = (x ~ /^[-+]?[0-9.]+([eE][-+]?[0-9]+)?$/)
    if ($0 ~ /\(choose (one of|from)\)/ || $0 ~ /\(one of [^()]*\)$/ || $0 ~ / \(text\)( \(k = [^()]*\))?$/ || (now && !num) || (!now && !num && x != "none")) print "word", name
    else print "number", name
  }' "$T/help" > "$T/kinds"
flags=$(genlist SableFlagOptions); words=$(genlist SableWordOptions)
bad=""
# an indexed name is listed by the generator either by its pattern (dem_insert_%d_psd) or member
# by member (dem_insert_0_region, from a table of names); -help shows each indexed family once, by
# its pattern (-dem_insert_<k>_psd): names are compared as patterns
for kind in flag word; do
  list=$(for f in $flags; do printf '%s\n' "$f"; done); [ $kind = word ] && list=$(for f in $words; do printf '%s\n' "$f"; done)
  pats=$(printf '%s\n' "$list" | sed -E 's/_[0-9]+(_|$)/_%d\1/' | sort -u)
  for f in $(awk -v k=$kind '$1 == k {print $2}' "$T/kinds"); do
    printf '%s\n' "$pats" | grep -qxF -e "$f" || bad="$bad $f(-help: $kind, not in the generated list)"
  done
  for f in $pats; do
    case $f in dem_*|fluid_*|cpl_*|domain_*|io_*|lb_*) ;; *) continue ;; esac
    case $f in
    *%d*) other=$(awk -v n="$f" -v k=$kind '$2 == n && $1 != k {print $1; exit}' "$T/kinds")
      [ -z "$other" ] || bad="$bad $f(listed as a $kind, -help: $other)" ;;
    *) grep -qx "$kind $f" "$T/kinds" || bad="$bad $f(listed as a $kind, -help: $(awk -v n="$f" '$2 == n {print $1}' "$T/kinds" | head -n 1))" ;;
    esac
  done
done
nf=$(grep -c '^flag ' "$T/kinds"); nw=$(grep -c '^word ' "$T/kinds"); nn=$(grep -c '^number ' "$T/kinds")
if [ -z "$bad" ] && [ "$nf" -gt 0 ] && [ "$nw" -gt 0 ]; then echo "PASS options: the generated flag and word lists match -help ($nf flags, $nw word options, $nn numeric options of Sable's)"
else echo "FAIL options: the generated flag and word lists do not match -help ($nf flags, $nw words):$bad"; fi
