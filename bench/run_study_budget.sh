#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The steering-column study at the real solver's cost: the whole study run both ways in
# one run, each in a fresh output folder (a fresh evaluation store: no run reused):
#   economical  the default (surrogate screening of 300 runs, 20 Kriging test points, a 40-point
#               stratified solver check)
#   full        --screening full --test-points 50 --solver-check 300 (the study before the surrogate screening:
#               eq.-3 screening on smi-column-fe itself, (46 + 1) x 200 runs)
# then bench/study_budget.lua writes solver runs per step, wall time and the conclusions side by
# side to bench/results/study_budget.md.
# usage: bash bench/run_study_budget.sh [BUILD_DIR] [EXTRA STUDY OPTIONS...]   (e.g. --quick)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
shift || true
cmake --build "$build" --target smi-lua smi-column-fe
fe=$(realpath "$build/smi-column-fe")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p bench/results
run() {  # name, options...
  local name=$1; shift
  local t0=$(date +%s)
  nice -n 5 "$build/smi-lua" --quiet --allow-exec "$fe" --out "$work/$name" scripts/steering_column.lua --solver "$fe" "$@" \
    > "$work/$name.log" 2>&1 || { echo "the $name study failed:"; tail -20 "$work/$name.log"; exit 1; }
  echo $(( $(date +%s) - t0 )) > "$work/$name.wall"
  echo "$name: $(tail -1 "$work/$name.log") [$(cat "$work/$name.wall") s]"
}
run economical --design fixed "$@"
run full --screening full --design fixed --test-points 50 --solver-check 300 "$@"
"$build/smi-lua" --quiet --allow-read "$work" --out "$work/cmp" bench/study_budget.lua \
  "$work/economical/results.json" "$(cat "$work/economical.wall")" "$work/full/results.json" "$(cat "$work/full.wall")" "$*"
cp "$work/cmp/study_budget.md" bench/results/study_budget.md
echo "wrote bench/results/study_budget.md"
