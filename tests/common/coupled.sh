# Sourced by the shell tests that run bin/sable (". tests/common/coupled.sh" after cd-ing to the
# repository): ROOT, S (the binary of BIN, default bin), Open MPI's permission to run as root, and
# a work directory W removed on exit.
ROOT=$(pwd)
S=$ROOT/${BIN:-bin}/sable
[ "$(id -u)" -eq 0 ] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
W=$(mktemp -d)
trap 'rm -rf "$W"' EXIT
