#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Fuzzes the Slurm executor's sbatch argument parser (glibc's getopt_long as the oracle) for a
# stated time and writes bench/results/fuzz_sbatch_args.md (bench/fuzz_run.sh does the work).
# Needs Debian's clang and libclang-rt-14-dev (not part of the CI build: run on demand).
# usage: bash bench/run_fuzz_sbatch_args.sh [SECONDS]   (default 120)
exec bash "$(dirname "$0")/fuzz_run.sh" sbatch_args "${1:-120}" 256 \
  "-I /usr/include bench/fuzz_sbatch_args.cpp host/platform/eval/sbatch_args.cpp -lfmt" "bench/run_fuzz_sbatch_args.sh"
