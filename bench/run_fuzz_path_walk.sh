#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Fuzzes the sandbox's path resolver for a stated time and writes bench/results/fuzz_path_walk.md
# (bench/fuzz_run.sh does the work). Needs Debian's clang and libclang-rt-14-dev (not part of the
# CI build: run on demand).
# usage: bash bench/run_fuzz_path_walk.sh [SECONDS]   (default 120)
exec bash "$(dirname "$0")/fuzz_run.sh" path_walk "${1:-120}" 512 \
  "bench/fuzz_path_walk.cpp host/platform/core/path_walk.cpp" "bench/run_fuzz_path_walk.sh"
