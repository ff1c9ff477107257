#!/bin/sh
# make run: the default case on one rank, the SI bubbling bed (cases/bubbling_bed/bubbling.opts:
# 3,200 glass beads of 1 mm in air at 3 U_mf, 1.2 s of bed time, about 2 minutes on one core).
# The run's last lines are its figures ("column:" dp/W, "bed:" heights and U_mf) and where its
# frames are; its start names the monitor file (pressure drop and bed height every 5 ms).
set -eu
cd "$(dirname "$0")/.."
[ "$(id -u)" -eq 0 ] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
bin/sable -options_file cases/bubbling_bed/bubbling.opts "$@"
echo "plot the monitor file (the \"monitor:\" line above): tools/plot_monitor FILE --columns dp0,bed_surface --spectrum dp0"
