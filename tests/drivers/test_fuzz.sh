#!/bin/sh
# Fuzz test of the input handling: 150 mutated copies of the shipped option files
# (cases/**/*.opts; with today's 29 files two rounds: every whole case 6 times, every preset
# twice), each run briefly, one in five on 2 ranks; no crash, no hang, no NaN or inf in a frame,
# no temporary file left, and every error exactly one "sable: error:" line
# (tests/drivers/fuzz_options.py says how the files are mutated and the runs sorted). FUZZ_SEED,
# FUZZ_RUNS, FUZZ_TIMEOUT change the seed, the count and the per-run timeout.
cd "$(dirname "$0")/../.." || exit 1
[ "$(id -u)" -eq 0 ] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
exec /usr/bin/python3 tests/drivers/fuzz_options.py
