#!/bin/sh
# SPDX-License-Identifier: MIT
# Coverage of the 90 % profile intervals (plain and small-sample delta) over many seeds, with the
# exact coverage of both deltas beside it; writes bench/results/calibration_coverage.md.
# usage: bench/run_coverage.sh [build dir] [seeds]   (default 1000 seeds, about a minute)
set -eu
here=$(cd "$(dirname "$0")" && pwd)
build=${1:-$here/../build}
out=$here/results/calibration_coverage.md
"$build/smi-lua" --quiet "$here/calibration_coverage.lua" "${2:-1000}" > "$out"
{
  echo
  echo "Exact coverage of the same intervals (bench/coverage_exact.py: t and χ² distributions of the normal linear model, no sampling):"
  echo
  /usr/bin/python3 "$here/coverage_exact.py"
} >> "$out"
cat "$out"
