#!/bin/sh
# make run: the default case on one rank; says where the output is.
set -eu
cd "$(dirname "$0")/.."
[ "$(id -u)" -eq 0 ] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
bin/sable -options_file cases/settle/quick.opts "$@"
