#!/bin/sh
# Coverage of the 90 % profile intervals over 100 seeds; writes bench/results/calibration_coverage.md.
# usage: bench/run_coverage.sh [build dir] [seeds]
set -eu
here=$(cd "$(dirname "$0")" && pwd)
build=${1:-$here/../build}
"$build/smi-lua" --quiet "$here/calibration_coverage.lua" "${2:-100}" | tee "$here/results/calibration_coverage.md"
