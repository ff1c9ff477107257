#!/bin/sh
# A fresh Debian 12 has what the suite and the tools call: every external program that tests/**/*.sh,
# tools/* (shell and Python), the Makefile's recipes, .ci/run and cases/**/*.sh call, every Python
# module their Python code imports and every shebang interpreter comes from a package that
# tools/install-deps.sh installs (its PKGS, or their Depends and Pre-Depends, recursively, the
# first alternative of each or-group: what apt-get picks on a fresh machine) or from the base
# system every Debian 12 has (Essential: yes or Priority: required). A program is found by its
# path on Debian's default PATH (not this shell's: pyenv's python3 is no Debian package) and
# dpkg -S of that path, of each link on its way (alternatives such as mpiexec) and of its
# /usr-merged twin. Nothing calls a bare `python3` (the first on PATH may lack numpy and h5py).
# Also tools/install-deps.sh itself: POSIX sh, apt-get update before apt-get install, a failed
# install is a non-zero exit, nothing done when every package is present (both run against
# stand-in apt-get, dpkg-query and id commands: nothing is installed).
# Words in command position are found by a small shell lexer (quotes, $( ), heredocs, case
# patterns, functions); dash's builtins are recognised by `command -v` printing no path.
cd "$(dirname "$0")/../.." || exit 1
T=$(mktemp -d); trap 'rm -rf "$T"' EXIT
DPATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin # Debian's default PATH
PY=/usr/bin/python3
# Called only in a setting that brings its own copy, never by the suite or `make`:
#   srun: tools/scaling --launcher srun, inside a cluster's Slurm job.
OPTIONAL="srun"

# ---- the scripts
SH_FILES=$(ls tests/*.sh tests/*/*.sh .ci/run 2>/dev/null; find cases -name '*.sh' 2>/dev/null | sort)
PY_FILES=""
for f in tools/*; do
  [ -f "$f" ] || continue
  case "$f" in *.c) continue ;; *.py) PY_FILES="$PY_FILES $f"; continue ;; *.sh) SH_FILES="$SH_FILES $f"; continue ;; esac
  case "$(head -n 1 "$f")" in
    '#!'*python*) PY_FILES="$PY_FILES $f" ;;
    '#!'*sh*) SH_FILES="$SH_FILES $f" ;;
    *) echo "FAIL deps: $f is neither shell nor Python (no shebang): add one" ;;
  esac
done
# Makefile recipes (tab-led lines) as shell, $(CC) and $(MAKE) spelled out, other make
# expansions turned into a shell variable; same line numbers.
cc=$(sed -n 's/^CC *[:?]*= *\([^ ]*\).*/\1/p' Makefile | head -n 1)
awk -v cc="$cc" '/^\t/ { sub(/^\t[@+-]*/, ""); gsub(/\$\(CC\)/, cc); gsub(/\$\(MAKE\)/, "make"); gsub(/\$\([^()]*\)/, "$MK"); print; next } { print "" }' Makefile > "$T/Makefile.recipes"

# shlex: prints "C file line word" for a word in command position, "F file line name" for a
# function definition, "P file line text" for Python source (heredoc bodies fed to python3 or
# pvpython or ended by PY, python -c strings).
cat > "$T/shlex.awk" <<'AWK'
function push(t) { sp++; typ[sp] = t; if (t != "dq") { cpos[sp] = 1; wd[sp] = ""; inw[sp] = 0; wvar[sp] = 0; skp[sp] = ""; rd[sp] = 0; prev[sp] = ""; last[sp] = ""; csd[sp] = 0; pat[sp] = 0 } }
function cf(i) { for (i = sp; i > 1 && typ[i] == "dq"; i--); return i }
function app(s, f) { f = cf(); wd[f] = wd[f] s; inw[f] = 1 }
function endword(f, w, v) {
  f = cf(); if (!inw[f]) return
  w = wd[f]; v = wvar[f]; wd[f] = ""; inw[f] = 0; wvar[f] = 0
  if (pat[f]) { if (w == "esac") { pat[f] = 0; csd[f]--; cpos[f] = 0 } return } # a case pattern
  if (rd[f]) { rd[f] = 0; return }                       # a redirection's file
  if (skp[f] == "for") return                            # for NAME in WORDS
  if (skp[f] == "case") { if (w == "in") { skp[f] = ""; csd[f]++; pat[f] = 1 } return }
  if (!cpos[f]) { prev[f] = w; return }
  if (cpos[f] == 2 && (w ~ /^-/ || w ~ /^[0-9.]+[smhd]?$/)) return # options of a prefix command
  if (w ~ /[*?]/) { cpos[f] = 0; return }                # a glob: no program name
  if (w ~ /^[A-Za-z_][A-Za-z0-9_]*=/) return             # an assignment: the command follows
  if (v) { cpos[f] = (w ~ /^\$\{?SUDO\}?$/) ? 2 : 0; return } # a variable: the project's programs
  if (w ~ /^(if|then|else|elif|do|while|until|!|\{|\}|time)$/) { cpos[f] = 1; return }
  if (w ~ /^(fi|done|esac)$/) { cpos[f] = 0; if (w == "esac" && csd[f] > 0) csd[f]--; return }
  if (w == "for" || w == "case") { skp[f] = w; cpos[f] = 0; return }
  print "C", FILENAME, FNR, w; last[f] = w; prev[f] = w
  cpos[f] = (w ~ /^(exec|command|timeout|xvfb-run|nice|nohup|env|mpiexec|mpirun|srun|sudo|xargs)$/) ? 2 : 0
}
function sep(f) { endword(); f = cf(); cpos[f] = 1; last[f] = ""; prev[f] = ""; if (skp[f] == "for") skp[f] = "" }
FNR == 1 { sp = 0; push("top"); sq = 0; nhd = 0; hd = 0 }
hd { t = $0; if (hdtab[1]) sub(/^\t+/, "", t)
     if (t == hddelim[1]) { for (k = 1; k < nhd; k++) { hddelim[k] = hddelim[k + 1]; hdpy[k] = hdpy[k + 1]; hdtab[k] = hdtab[k + 1] } nhd--; hd = nhd > 0 }
     else if (hdpy[1]) print "P", FILENAME, FNR, $0
     next }
{
  line = $0; n = length(line); cont = 0
  for (i = 1; i <= n; i++) {
    c = substr(line, i, 1); c2 = substr(line, i, 2)
    if (sq) { if (c == "'") { sq = 0; if (pyc) { print "P", FILENAME, FNR, pybuf; pyc = 0 } } else if (pyc) pybuf = pybuf c; continue }
    if (typ[sp] == "dq") {
      if (c == "\"") sp--
      else if (c == "\\") { if (i == n) cont = 1; app(substr(line, i + 1, 1)); i++ }
      else if (c2 == "$(" && substr(line, i + 2, 1) != "(") { wvar[cf()] = 1; push("sub"); i++ }
      else if (c == "`") { wvar[cf()] = 1; push("bt") }
      else { if (c == "$") wvar[cf()] = 1; app(c) }
      continue
    }
    f = sp
    if (pat[f] && c == ")") { wd[f] = ""; inw[f] = 0; wvar[f] = 0; pat[f] = 0; cpos[f] = 1; continue } # end of a case pattern
    if (pat[f] && (c == "|" || c == "(")) { wd[f] = ""; inw[f] = 0; wvar[f] = 0; continue }
    if (c == " " || c == "\t") endword()
    else if (c == "#" && !inw[f]) break
    else if (c == "'") { sq = 1; inw[f] = 1; if (last[f] ~ /python/ && prev[f] == "-c") { pyc = 1; pybuf = "" } }
    else if (c == "\"") { inw[f] = 1; push("dq") }
    else if (c == "\\") { if (i == n) cont = 1; else app(substr(line, i + 1, 1)); i++ }
    else if (c2 == "$(" && substr(line, i + 2, 1) == "(") { j = index(substr(line, i), "))"); app("$"); wvar[f] = 1; i += (j ? j : n) }
    else if (c2 == "$(") { inw[f] = 1; wvar[f] = 1; push("sub"); i++ }
    else if (c == "`") { if (typ[f] == "bt") { endword(); sp-- } else { inw[f] = 1; wvar[f] = 1; push("bt") } }
    else if (c2 == "${") { dp = 1; for (j = i + 2; j <= n && dp > 0; j++) { x = substr(line, j, 1); dp += (x == "{") - (x == "}") }
                           app(substr(line, i, j - i)); wvar[f] = 1; i = j - 1 } # ${x:-a b} is one word
    else if (c == "$") { app(c); wvar[f] = 1 }
    else if (c == ")") { if (typ[f] == "sub") { endword(); sp-- } else { wd[f] = ""; inw[f] = 0; wvar[f] = 0; cpos[f] = 1 } } # else: a case pattern
    else if (c == "(") { if (inw[f] && substr(line, i + 1, 1) == ")") { print "F", FILENAME, FNR, wd[f]; wd[f] = ""; inw[f] = 0; cpos[f] = 1; i++ } else { endword(); push("sub") } }
    else if (c2 == ";;") { sep(); i++; if (csd[f] > 0) pat[f] = 1 }
    else if (c == ";" || c == "&" || c == "|") sep()
    else if (c2 == "<<") {
      endword(); i += 2; tab = 0; if (substr(line, i, 1) == "-") { tab = 1; i++ }
      while (substr(line, i, 1) == " ") i++
      d = ""; while (i <= n && substr(line, i, 1) !~ /[ ;|&)<>]/) { d = d substr(line, i, 1); i++ }
      i--; gsub(/['"\\]/, "", d)
      nhd++; hddelim[nhd] = d; hdtab[nhd] = tab; hdpy[nhd] = (last[f] ~ /python/ || d ~ /^PY/)
    }
    else if (c == "<" || c == ">") {
      if (inw[f] && wd[f] ~ /^[0-9]+$/) { wd[f] = ""; inw[f] = 0 } else endword()
      while (substr(line, i + 1, 1) ~ /[<>&|]/) i++
      rd[f] = 1
    }
    else app(c)
  }
  if (!sq && !cont && typ[sp] != "dq") sep()
  if (nhd) hd = 1
}
AWK
# pyscan: prints "M file line module" per import and "C file line program" per program that a
# subprocess call or a command list (a name ending in cmd, assigned a list) starts with.
cat > "$T/pyscan.awk" <<'AWK'
function scan(file, ln, s, k, a, m, parts, p, x) {
  k = split(s, parts, ";")
  for (p = 1; p <= k; p++) {
    x = parts[p]
    if (match(x, /^[ \t]*import[ \t]+/)) {
      m = split(substr(x, RLENGTH + 1), a, ",")
      for (j = 1; j <= m; j++) { sub(/^[ \t]+/, "", a[j]); sub(/[ \t].*/, "", a[j]); if (a[j] != "") print "M", file, ln, a[j] }
    } else if (match(x, /^[ \t]*from[ \t]+[A-Za-z_][A-Za-z0-9_.]*[ \t]+import/)) {
      split(x, a, /[ \t]+/); for (j = 1; a[j] != "from"; j++); print "M", file, ln, a[j + 1]
    }
    if (match(x, /(subprocess\.[a-z_]+|Popen|os\.system|os\.exec[a-z]*|[A-Za-z_]*cmd[A-Za-z_]*[ \t]*=)[ \t]*\(?[ \t]*\[?[ \t]*["'][^"' ]+/)) {
      m = substr(x, RSTART, RLENGTH); sub(/.*["']/, "", m); print "C", file, ln, m
    }
  }
}
$1 == "P" { f = $2; l = $3; $1 = $2 = $3 = ""; scan(f, l, substr($0, 4)); next }
{ scan(FILENAME, FNR, $0) }
AWK
awk -f "$T/shlex.awk" $SH_FILES "$T/Makefile.recipes" > "$T/lex" 2> "$T/lex.err" || { echo "FAIL deps: the shell lexer failed: $(head -n 3 "$T/lex.err")"; exit 1; }
sed -i "s|$T/Makefile.recipes|Makefile|" "$T/lex"
grep '^P ' "$T/lex" > "$T/pysrc"
awk -f "$T/pyscan.awk" "$T/pysrc" $PY_FILES > "$T/pyscan"
grep -no '\$(shell [A-Za-z0-9_.+-]*' Makefile | sed 's/^\([0-9]*\):.* /C Makefile \1 /' >> "$T/lex"
echo "C Makefile 0 make" >> "$T/lex" # `make test`, `make run`: the README's commands
grep '^C ' "$T/pyscan" >> "$T/lex"
funcs=" $(awk '$1 == "F" { print $4 }' "$T/lex" | sort -u | tr '\n' ' ')"

# ---- what the script installs: the closure of PKGS, and the base system
PKGS=$(sed -n 's/^PKGS="\(.*\)"/\1/p' tools/install-deps.sh)
[ -n "$PKGS" ] || echo "FAIL deps: no PKGS=\"...\" line in tools/install-deps.sh"
apt-cache depends --recurse --important $PKGS 2>/dev/null | awk -v roots="$PKGS" '
  /^[^ ]/ { cur = $1; grp = 0; pick = 0; next }
  /^ [ |](Pre)?Depends: / { alt = ($0 ~ /^ \|/); t = $2; pick = !grp; grp = alt; virt = (t ~ /^</)
    if (pick && !virt) { sub(/:any$/, "", t); e[cur] = e[cur] " " t }; next }
  /^    / { if (pick && virt) { t = $1; sub(/:any$/, "", t); e[cur] = e[cur] " " t }; next }
  END { n = split(roots, q, " "); for (i = 1; i <= n; i++) seen[q[i]] = 1
        for (h = 1; h <= n; h++) { m = split(e[q[h]], d, " "); for (j = 1; j <= m; j++) if (!seen[d[j]]) { seen[d[j]] = 1; q[++n] = d[j] } }
        for (p in seen) print p }' | sort -u > "$T/closure"
dpkg-query -W -f '${Package} ${Essential} ${Priority}\n' | awk '$2 == "yes" || $3 == "required" { print $1 }' | sort -u > "$T/base"
cat "$T/closure" "$T/base" | sort -u > "$T/covered"
[ "$(wc -l < "$T/closure")" -gt "$(echo $PKGS | wc -w)" ] || echo "FAIL deps: apt-cache depends gave no dependency closure for PKGS ($(wc -l < "$T/closure") packages)"

# owners: reads "key path..." lines, prints "key pkg" per owning package of any path (dpkg -S once)
owners() {
  awk '{ for (i = 2; i <= NF; i++) print $i }' "$1" | sort -u > "$T/paths"
  xargs dpkg -S < "$T/paths" 2>/dev/null | grep -v '^diversion by' | sed 's/: \(\/.*\)$/\t\1/' > "$T/dpkg"
  awk -F'\t' 'NR == FNR { n = split($1, p, ", "); for (i = 1; i <= n; i++) { sub(/:[a-z0-9]+$/, "", p[i]); own[$2] = own[$2] " " p[i] }; next }
    { split($0, w, " "); for (i = 2; i in w; i++) { m = split(own[w[i]], o, " "); for (j = 1; j <= m; j++) if (!seen[w[1] " " o[j]]++) print w[1], o[j] } }' "$T/dpkg" "$1"
}
# paths: a path, each link it passes through, its target, each with its /usr-merged twin
paths() {
  p=$1; out=""; k=0
  while [ -n "$p" ] && [ $k -lt 10 ]; do
    out="$out $p"; case "$p" in /usr/bin/* | /usr/sbin/*) out="$out ${p#/usr}" ;; /bin/* | /sbin/*) out="$out /usr$p" ;; esac
    nx=$(readlink "$p") || break
    case "$nx" in /*) p=$nx ;; *) p=$(dirname "$p")/$nx ;; esac; k=$((k + 1))
  done
  r=$(readlink -f "$1"); echo "$out $r"; case "$r" in /usr/bin/* | /usr/sbin/*) echo " ${r#/usr}" ;; esac
}
covered() { grep -qx "$1" "$T/covered"; }

# ---- programs
progs=$(awk '$1 == "C" { print $4 }' "$T/lex" | sort -u)
: > "$T/prog.paths"; nprog=0; skipped=""; bad=0
where() { awk -v w="$1" '$1 == "C" && $4 == w { print $2 ":" $3; exit }' "$T/lex"; }
for w in $progs; do
  case "$funcs" in *" $w "*) continue ;; esac
  case " $OPTIONAL " in *" $w "*) skipped="$skipped $w"; continue ;; esac
  case "$w" in */*) case "$w" in /*) ;; *) continue ;; esac ;; esac # the project's own programs
  if [ "$w" = python3 ] || [ "$w" = python ]; then continue; fi # below: bare python3
  p=$(PATH=$DPATH; command -v "$w")
  case "$p" in
    /*) echo "$w $(paths "$p" | tr '\n' ' ')" >> "$T/prog.paths"; nprog=$((nprog + 1)) ;;
    "") echo "FAIL deps programs: $w (called in $(where "$w")) is not on this machine: add its package to PKGS in tools/install-deps.sh"; bad=$((bad + 1)) ;;
    *) ;; # a builtin or keyword of sh
  esac
done
owners "$T/prog.paths" > "$T/prog.own"
pk=""
while read -r w rest; do
  o=$(awk -v w="$w" '$1 == w { print $2 }' "$T/prog.own")
  if [ -z "$o" ]; then echo "FAIL deps programs: $w (called in $(where "$w")) is $rest, which no Debian package owns: use a Debian package's program and add the package to PKGS"; bad=$((bad + 1)); continue; fi
  ok=""; for x in $o; do covered "$x" && ok=$x && break; done
  if [ -n "$ok" ]; then pk="$pk $ok"; else echo "FAIL deps programs: $w (called in $(where "$w")) comes from package $(echo $o | tr ' ' ','), which tools/install-deps.sh does not install: add it to PKGS"; bad=$((bad + 1)); fi
done < "$T/prog.paths"
[ "$bad" -eq 0 ] && echo "PASS deps programs: $nprog programs called, all from installed or base packages ($(echo $pk | tr ' ' '\n' | sort -u | tr '\n' ' ' | sed 's/ $//'))${skipped:+; not checked:$skipped (cluster only)} (bound: every program covered)"

# ---- Python modules, imported by /usr/bin/python3 -I (no user site, no PYTHON* variables)
mods=$(awk '$1 == "M" { print $4 }' "$T/pyscan" | sort -u)
local_mods=$(for f in tools/*.py; do [ -f "$f" ] && basename "$f" .py; done)
: > "$T/mods"
for m in $mods; do case " $(echo $local_mods) " in *" ${m%%.*} "*) ;; *) echo "$m" >> "$T/mods" ;; esac; done
$PY -I - "$T/mods" > "$T/mod.paths" 2> "$T/mod.err" <<'PYEOF' || echo "FAIL deps python modules: $PY could not run the import probe: $(tail -n 2 "$T/mod.err")"
import importlib, os, sys
for m in open(sys.argv[1]).read().split():
    try:
        mod = importlib.import_module(m)
        print(m, os.path.realpath(getattr(mod, "__file__", None) or sys.executable))
    except Exception as e:
        print(m, "MISSING", type(e).__name__ + ":" + str(e).replace(" ", "_"))
PYEOF
mwhere() { awk -v w="$1" '$1 == "M" && $4 == w { print $2 ":" $3; exit }' "$T/pyscan"; }
grep -v ' MISSING ' "$T/mod.paths" > "$T/mod.ok"
owners "$T/mod.ok" > "$T/mod.own"
pk=""; bad=0
while read -r m a b; do
  if [ "$a" = MISSING ]; then echo "FAIL deps python modules: $PY cannot import $m (imported in $(mwhere "$m")): $b: add python3-${m%%.*} or the package providing it to PKGS"; bad=$((bad + 1)); continue; fi
  o=$(awk -v w="$m" '$1 == w { print $2 }' "$T/mod.own")
  ok=""; for x in $o; do covered "$x" && ok=$x && break; done
  if [ -n "$ok" ]; then pk="$pk $ok"
  elif [ -z "$o" ]; then echo "FAIL deps python modules: $m (imported in $(mwhere "$m")) is $a, which no Debian package owns (pip?): add its python3-* package to PKGS"; bad=$((bad + 1))
  else echo "FAIL deps python modules: $m (imported in $(mwhere "$m")) comes from package $(echo $o | tr ' ' ','), which tools/install-deps.sh does not install: add it to PKGS"; bad=$((bad + 1)); fi
done < "$T/mod.paths"
nm=$(wc -l < "$T/mods")
[ "$bad" -eq 0 ] && echo "PASS deps python modules: $nm modules imported by $PY, all from installed or base packages ($(echo $pk | tr ' ' '\n' | sort -u | tr '\n' ' ' | sed 's/ $//')) (bound: every module covered)"

# ---- shebang interpreters; bare python3
: > "$T/sheb"; bad=0; n=0
for f in $SH_FILES $PY_FILES; do
  l=$(head -n 1 "$f")
  case "$l" in
    '#!'*) i=$(echo "${l#\#!}" | awk '{ print $1 }'); a=$(echo "${l#\#!}" | awk '{ print $2 }')
      if [ "$i" = /usr/bin/env ]; then echo "FAIL deps shebang: $f:1 runs '$a' through /usr/bin/env (the first on PATH): name Debian's interpreter, e.g. #!/usr/bin/python3"; bad=$((bad + 1)); continue; fi
      echo "$i $(paths "$i" | tr '\n' ' ')" >> "$T/sheb"; n=$((n + 1)) ;;
    *) [ -x "$f" ] && { echo "FAIL deps shebang: $f is executable but has no #! line"; bad=$((bad + 1)); } ;;
  esac
done
sort -u "$T/sheb" -o "$T/sheb"
owners "$T/sheb" > "$T/sheb.own"
desc=""
while read -r i rest; do
  o=$(awk -v w="$i" '$1 == w { print $2 }' "$T/sheb.own"); ok=""; for x in $o; do covered "$x" && ok=$x && break; done
  if [ -n "$ok" ]; then desc="$desc, $i ($ok)"; else echo "FAIL deps shebang: interpreter $i (in $(grep -l "^#!$i" $SH_FILES $PY_FILES | head -n 1)) comes from ${o:-no package}, not installed by tools/install-deps.sh"; bad=$((bad + 1)); fi
done < "$T/sheb"
[ "$bad" -eq 0 ] && echo "PASS deps shebang interpreters: $n scripts with #!, interpreters ${desc#, } (bound: every interpreter covered, none through /usr/bin/env)"
bare=$(awk '$1 == "C" && ($4 == "python3" || $4 == "python") { print $2 ":" $3 }' "$T/lex" | sort -u | tr '\n' ' ' | sed 's/ $//')
if [ -z "$bare" ]; then echo "PASS deps no bare python3: 0 calls of python3 or python by name in $(echo $SH_FILES $PY_FILES | wc -w) scripts and the Makefile (bound 0; $PY has numpy and h5py)"
else echo "FAIL deps bare python3: called by name (the first python3 on PATH, maybe without numpy/h5py) at $bare: use $PY"; fi

# ---- tools/install-deps.sh
I=tools/install-deps.sh
bashisms=$(grep -nE '\[\[|(^|[ ;])function |(^|[ ;])source |\$'"'"'|^[^#]*[A-Za-z_]+=\(|\$\{[A-Za-z_]+//|(^|[ ;])local |&>|<<<|==' "$I" | head -n 3)
if [ "$(head -n 1 "$I")" = "#!/bin/sh" ] && dash -n "$I" 2>/dev/null && [ -z "$bashisms" ]; then echo "PASS deps install-deps.sh is POSIX sh: #!/bin/sh, dash -n parses it, 0 bashisms ([[, function, source, \$'', arrays, \${x//}, local, &>, <<<, ==) (bound 0)"
else echo "FAIL deps install-deps.sh is POSIX sh: shebang '$(head -n 1 "$I")', dash -n status $(dash -n "$I" >/dev/null 2>&1; echo $?), bashisms: $bashisms"; fi
# stand-ins: id says root (no sudo), dpkg-query says xauth is missing, apt-get logs its calls
# and fails to install; sudo must never be reached. They work only when the script calls these
# by name: a path would reach the real apt-get, so then the runs are skipped (a FAIL).
if grep -vE '^[[:space:]]*#' "$I" | grep -qE '/(apt-get|apt|sudo|id|dpkg-query)([[:space:]]|$)'; then
  echo "FAIL deps install-deps.sh: calls apt-get, sudo, id or dpkg-query by path; the stand-in runs need names looked up on PATH"; exit 1
fi
mkdir -p "$T/fake"
printf '#!/bin/sh\necho 0\n' > "$T/fake/id"
printf '#!/bin/sh\necho "sudo $*" >> %s/calls; exit 97\n' "$T" > "$T/fake/sudo"
printf '#!/bin/sh\ncase "$*" in *xauth*) echo "unknown ok not-installed" ;; *) echo "install ok installed" ;; esac\n' > "$T/fake/dpkg-query"
printf '#!/bin/sh\necho "apt-get $*" >> %s/calls\ncase "$1" in install) echo "E: Unable to locate package xauth" >&2; exit 100 ;; esac\n' "$T" > "$T/fake/apt-get"
chmod +x "$T/fake/id" "$T/fake/sudo" "$T/fake/dpkg-query" "$T/fake/apt-get"
: > "$T/calls"
PATH="$T/fake:$PATH" sh "$I" > "$T/inst.out" 2> "$T/inst.err"; rc=$?
calls=$(awk '{ print $2 }' "$T/calls" | tr '\n' ' ' | sed 's/ $//')
if [ "$rc" -ne 0 ] && [ "$calls" = "update install" ] && grep -q 'Unable to locate' "$T/inst.err" && grep -q 'xauth' "$T/calls"; then
  echo "PASS deps install-deps.sh with a package missing: apt-get calls '$calls' (update first), a failed install exits $rc with apt's message on stderr (bound: non-zero, update before install)"
else echo "FAIL deps install-deps.sh with a package missing: exit $rc, apt-get calls '$calls', stderr: $(head -n 2 "$T/inst.err")"; fi
rm "$T/fake/dpkg-query"; : > "$T/calls" # the real dpkg-query: this machine has everything
PATH="$T/fake:$PATH" sh "$I" > "$T/inst.out" 2>&1; rc=$?
if [ "$rc" -eq 0 ] && [ ! -s "$T/calls" ] && [ ! -s "$T/inst.out" ]; then echo "PASS deps install-deps.sh with every package present: exit 0, 0 apt-get calls, 0 lines printed (bound 0)"
else echo "FAIL deps install-deps.sh with every package present: exit $rc, calls: $(cat "$T/calls"), output: $(head -n 2 "$T/inst.out")"; fi
