#!/bin/sh
# cases/silo (Grains3D Part II §4.1.1): fill the silo with the orifice closed (fill.opts, 1.5 s),
# open it and discharge (discharge.opts, 32 s), then count the beads above the orifice per frame
# and print the discharge rate and the discharge time (tools/silo_discharge.c); measured 29.27 s
# (González-Montellano et al. 2011), Grains3D 29.36 s. Extra arguments go to the discharge run
# (a short check: tools/silo.sh -dem_t_end 0.6); SILO_FILL_ARGS to the fill; SILO_SKIP_FILL=1
# reuses out/silo/fill_000001.h5; RANKS=2 runs both on two ranks split along z. One rank, this
# 2-core VM: fill 4.7 min; discharge 0.15-0.18 us per particle-step, about 2 h for the full 32 s.
set -eu
cd "$(dirname "$0")/.."
. tools/run_logged.sh
[ "$(id -u)" -eq 0 ] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
RANKS=${RANKS:-1}
RUN="bin/sable"
[ "$RANKS" -gt 1 ] && RUN="mpiexec -n $RANKS bin/sable -da_processors_x 1 -da_processors_y 1 -da_processors_z $RANKS"
make -s bin/sable build/tools/silo_discharge
mkdir -p out/silo
[ -n "${SILO_SKIP_FILL:-}" ] || run_logged out/silo/fill.log $RUN -options_file cases/silo/fill.opts ${SILO_FILL_ARGS:-}
run_logged out/silo/discharge.log $RUN -options_file cases/silo/discharge.opts "$@"
build/tools/silo_discharge -silo_dir out/silo -silo_prefix discharge -silo_interval 0.05 -silo_z0 0 -silo_mass 3.44e-3
