# Sourced by the case scripts: run_logged LOG command... runs the command with its output shown
# and copied to LOG, and stops the script with the command's exit status when it fails (a plain
# `command | tee LOG` reports tee's status and lets the script go on after a failed stage).
run_logged() {
  log=$1; shift
  { if "$@"; then echo 0 > "$log.rc"; else echo $? > "$log.rc"; fi; } | tee "$log" # if: immune to set -e
  rc=$(cat "$log.rc"); rm -f "$log.rc"
  [ "$rc" -eq 0 ] || { echo "$(basename "$0"): stopped: '$*' failed with exit status $rc (log: $log)" >&2; exit "$rc"; }
}
