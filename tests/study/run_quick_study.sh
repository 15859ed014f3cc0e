#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Runs the steering-column study with --quick in a fresh output folder, then the checks.
# usage: run_quick_study.sh SMI_LUA COLUMN_FE SOURCE_DIR WORK_DIR
set -euo pipefail
smi=$1 fe=$2 src=$3 work=$4
rm -rf "$work"
mkdir -p "$work"
cd "$src"
# A fresh store each time: the test exercises the solver runs, not only the cache.
"$smi" --quiet --allow-exec "$fe" --out "$work" scripts/steering_column.lua --quick --solver "$fe"
"$smi" --quiet --allow-read "$work" --out "$work/check" tests/study/check_study.lua "$work/results.json" "$work/report.html"
