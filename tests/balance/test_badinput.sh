#!/bin/sh
# Load-balancing bad input: a negative weight, a threshold outside (0, inf), an unknown scheme or
# weight model, a zero interval. Each stops with one line naming the option and the valid range,
# and a non-zero exit; good input with every scheme runs (2 ranks split along z, so the loads
# differ) and its log shows the checks.
cd "$(dirname "$0")/../.." || exit 1
[ "$(id -u)" -eq 0 ] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
Q="-options_file cases/settle/quick.opts -dem_t_end 0.02 -dem_progress_interval 0 -io_interval 0 -domain_cell 0.02 -da_processors_x 1 -da_processors_y 1"
expect() { # name, pattern, arguments...
  name=$1; pat=$2; shift 2
  out=$(mpiexec --oversubscribe -n 2 ${BIN:-bin}/sable "$@" 2>&1); rc=$?
  lines=$(printf '%s\n' "$out" | grep -c 'sable: error')
  if [ "$rc" -ne 0 ] && [ "$lines" -eq 1 ] && printf '%s' "$out" | grep -q -- "$pat"; then
    echo "PASS bad input, $name: exit $rc, \"$(printf '%s' "$out" | grep 'sable: error')\""
  else
    echo "FAIL bad input, $name: exit $rc, $lines error lines, expected /$pat/; got: $(printf '%s' "$out" | head -5)"
  fi
}
expect "negative particle weight" "-lb_alpha -1.* must be >= 0" $Q -lb_scheme once -lb_alpha -1
expect "negative cell weight" "-lb_beta -0.5 must be >= 0" $Q -lb_scheme once -lb_beta -0.5
expect "zero threshold" "-lb_threshold 0.* must be > 0" $Q -lb_scheme dynamic -lb_threshold 0
expect "infinite threshold" "option -lb_threshold inf: 'inf' is not a finite number" $Q -lb_scheme dynamic -lb_threshold inf
expect "unknown scheme" "-lb_scheme sometimes is not known; valid values: none, once, frequent, dynamic" $Q -lb_scheme sometimes
expect "unknown weight model" "-lb_weight cubic is not known; valid values: linear, quadratic, measured" $Q -lb_scheme once -lb_weight cubic
expect "zero interval" "-lb_interval 0 must be >= 1" $Q -lb_scheme frequent -lb_interval 0
for s in none once frequent dynamic; do
  out=$(mpiexec --oversubscribe -n 2 ${BIN:-bin}/sable $Q -lb_scheme $s -lb_interval 500 -lb_threshold 0.1 -dem_check_every 100 2>&1); rc=$?
  checks=$(printf '%s\n' "$out" | grep -c '^lb: step')
  # 2000 steps: once (-lb_step 0) checks after step 1; frequent and dynamic after step 1, then at 501, 1001, 1501
  case $s in none) want=0; first=0 ;; once) want=1; first=1 ;; *) want=4; first=1 ;; esac
  one=$(printf '%s\n' "$out" | grep -c '^lb: step 1 ')
  if [ "$rc" -eq 0 ] && [ "$checks" -eq "$want" ] && [ "$one" -eq "$first" ]; then echo "PASS good input -lb_scheme $s on 2 ranks: exit 0, $checks check lines (expected $want), a check after step 1: $one (expected $first)"
  else echo "FAIL good input -lb_scheme $s: exit $rc, $checks check lines (expected $want), after step 1: $one (expected $first): $(printf '%s' "$out" | tail -3)"; fi
done
