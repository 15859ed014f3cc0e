#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The kernel bootstrap through smi.calibrate: its cost against the calibration alone, one thread
# against two, and the intervals' Monte Carlo errors (bench/bootstrap.lua). Writes
# bench/results/bootstrap.md.
# usage: bash bench/run_bootstrap.sh [BUILD_DIR] [--replicates 50,200]
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
shift || true
cmake --build "$build" --target smi-lua > /dev/null
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p bench/results
nice -n 5 "$build/smi-lua" --quiet --out "$work" bench/bootstrap.lua "$@"
cp "$work/bootstrap.md" bench/results/bootstrap.md
echo "wrote bench/results/bootstrap.md"
