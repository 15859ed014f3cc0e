#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Screening of the 46 steering-column inputs at the real solver's cost: the full
# eq.-3 screening ((46 + 1) x N_FULL smi-column-fe runs) against the surrogate screening (RUNS
# runs), in one run with a fresh output folder and so a fresh evaluation store (no run reused); writes
# bench/results/screening_budget.md.
# usage: bash bench/run_screening_budget.sh [BUILD_DIR] [N_FULL] [RUNS]   (defaults: build, 200, 300)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
n_full=${2:-200}
runs=${3:-300}
cmake --build "$build" --target smi-lua smi-column-fe
solver=$(realpath "$build/smi-column-fe")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p bench/results
"$build/smi-lua" --quiet --lib scripts --allow-exec "$solver" --out "$work/out" \
  bench/screening_budget.lua "$solver" "$n_full" "$runs"
cp "$work/out/screening_budget.md" bench/results/screening_budget.md
echo "wrote bench/results/screening_budget.md"
