#!/bin/sh
# cases/dam_break: fill the reservoir (fill.opts), remove the gate and let the column collapse
# (collapse.opts), then measure the aspect ratio and the run-out (tools/column_runout.c).
# One process; about 10-20 minutes on one core. Output and logs in out/dam_break/.
set -eu
cd "$(dirname "$0")/.."
. tools/run_logged.sh
[ "$(id -u)" -eq 0 ] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
make -s bin/sable build/tools/column_runout
mkdir -p out/dam_break
run_logged out/dam_break/fill.log bin/sable -options_file cases/dam_break/fill.opts
run_logged out/dam_break/collapse.log bin/sable -options_file cases/dam_break/collapse.opts
last=$(/usr/bin/python3 -c 'import sys; sys.path.insert(0, "tools"); from sable_frames import run_frames; print(run_frames("out/dam_break", "collapse")[-1])') # this run's last frame, from its index
build/tools/column_runout -runout_initial out/dam_break/fill_000001.h5 -runout_final "$last" \
  -runout_gate 0.015 -runout_width 0.015 -runout_d 0.003
