#!/bin/sh
# cases/silo_cubes: fill the silo with the orifice closed (fill.opts), open it and discharge
# (discharge.opts), then count the cubes above the orifice per frame (tools/silo_discharge.c).
# One process; long (~2.6 s of simulated time with 2,560 cubes). Output in out/silo_cubes/.
set -eu
cd "$(dirname "$0")/.."
. tools/run_logged.sh
[ "$(id -u)" -eq 0 ] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
make -s bin/sable build/tools/silo_discharge
mkdir -p out/silo_cubes
run_logged out/silo_cubes/fill.log bin/sable -options_file cases/silo_cubes/fill.opts "$@"
run_logged out/silo_cubes/discharge.log bin/sable -options_file cases/silo_cubes/discharge.opts "$@"
build/tools/silo_discharge -silo_dir out/silo_cubes -silo_prefix discharge -silo_interval 0.05 -silo_z0 0 -silo_mass 5.4e-4
