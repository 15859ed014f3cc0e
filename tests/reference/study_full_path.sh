#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Regenerates tests/reference/study_full_path.json: runs the steering-column study's full path on
# the committed data (scripts/steering_column.lua --screening full --design fixed --test-points 50
# --solver-check 300; 9,400 screening runs, about 5 minutes on 2 cores) in a fresh folder, then
# study_full_path.lua keeps its conclusions. usage: bash tests/reference/study_full_path.sh [BUILD_DIR]
set -euo pipefail
cd "$(dirname "$0")/../.."
build=${1:-build}
fe=$(realpath "$build/smi-column-fe")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$build/smi-lua" --quiet --allow-exec "$fe" --out "$work/full" scripts/steering_column.lua --solver "$fe" \
  --screening full --design fixed --test-points 50 --solver-check 300
"$build/smi-lua" --quiet --allow-read "$work" --allow-write tests/reference --out "$work/ref" \
  tests/reference/study_full_path.lua "$work/full/results.json" tests/reference/study_full_path.json
