#!/bin/sh
# make run: the default case on one rank, a small fluidized bed (cases/fluidized_bed/small.opts:
# 384 spheres, 100 time units, about 2 s on one core); says where the output is.
set -eu
cd "$(dirname "$0")/.."
[ "$(id -u)" -eq 0 ] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
bin/sable -options_file cases/fluidized_bed/small.opts "$@"
