#!/bin/sh
# The load balancer keeps -cpl_porosity_width's ghost layer inside every rank box: a 384-sphere
# bed (cases/fluidized_bed/small.opts widened to 8 x 8 x 48 d, cells of 2 d) on 4 ranks stacked
# along z, all the spheres in the lowest rank, rebalanced once at step 50 with
# -cpl_porosity_width 3.5 (its grid's ghost layer: 9 nodes of 2/3 d, 3 cells). Reference: the
# run rebalances and ends (without the balancer knowing the ghost layer, the cut left a 2-cell box
# and the next step stopped naming the width).
cd "$(dirname "$0")/../.." || exit 1
[ "$(id -u)" -eq 0 ] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
out=$(mpiexec --oversubscribe -n 4 ${BIN:-bin}/sable -options_file cases/fluidized_bed/small.opts -domain_hi 8,8,48 -da_grid_y 4 -dem_lattice 8,8,12 -cpl_porosity_width 3.5 -da_processors_x 1 -da_processors_y 1 -da_processors_z 4 -lb_scheme once -lb_step 50 -cpl_t_end 2 -io_interval 0 2>&1); rc=$?
if [ "$rc" -eq 0 ] && printf '%s\n' "$out" | grep -q -- '-> rebalanced' && printf '%s\n' "$out" | grep -q '^done: t = 2'; then
  echo "PASS smooth_balance: rebalanced with -cpl_porosity_width 3.5 on 4 ranks and ran to the end ($(printf '%s\n' "$out" | grep -o 'predicted Lmax/Lavg [0-9.]*'))"
else
  echo "FAIL smooth_balance: exit $rc; $(printf '%s\n' "$out" | grep -E 'error|lb:' | head -n 2)"
fi
