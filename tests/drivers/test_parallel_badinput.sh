#!/bin/sh
# Parallel bad input: a process grid that does not match the rank count, a grid with fewer cells
# than ranks, a rank box thinner than the halo. Each stops with one line naming the option, and a non-zero exit.
cd "$(dirname "$0")/../.." || exit 1
[ "$(id -u)" -eq 0 ] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
Q="-options_file cases/settle/quick.opts -dem_t_end 0.001 -dem_progress_interval 0 -io_interval 0"
expect() { # name, ranks, pattern, arguments...
  name=$1; np=$2; pat=$3; shift 3
  out=$(mpiexec --oversubscribe -n "$np" ${BIN:-bin}/sable "$@" 2>&1); rc=$?
  lines=$(printf '%s\n' "$out" | grep -c 'sable: error')
  if [ "$rc" -ne 0 ] && [ "$lines" -eq 1 ] && printf '%s' "$out" | grep -q -- "$pat"; then
    echo "PASS bad input, $name: exit $rc, \"$(printf '%s' "$out" | grep 'sable: error')\""
  else
    echo "FAIL bad input, $name: exit $rc, $lines error lines, expected /$pat/; got: $(printf '%s' "$out" | head -5)"
  fi
}
expect "process grid 3 x 1 x 1 on 2 ranks" 2 "does not fit the 2 MPI ranks" $Q -da_processors_x 3 -da_processors_y 1 -da_processors_z 1
expect "process grid 4 along x on 2 ranks" 2 "must divide 2" $Q -da_processors_x 4
expect "rank box thinner than the halo" 4 "thinner than the halo" $Q -da_processors_x 4 -da_processors_y 1 -da_processors_z 1 -domain_cell 0.01 -dem_skin 0.03
expect "more ranks than cells along x" 2 "-da_processors_x 2 must be in \[1, 1\]" $Q -da_processors_x 2 -domain_cell 0.2
expect "one cell, 2 ranks, free process grid" 2 "the grid of 1 x 1 x 1 cells cannot be split over 2 ranks" $Q -domain_cell 0.3
if mpiexec --oversubscribe -n 2 ${BIN:-bin}/sable $Q -dem_check_every 1 >/dev/null 2>&1; then echo "PASS good input on 2 ranks with -dem_check_every 1: exit 0"; else echo "FAIL good input on 2 ranks: exit $?"; fi
