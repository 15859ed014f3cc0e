#!/bin/sh
# SPDX-License-Identifier: MIT
# Kriging fit speed against the fastest peer configuration reaching test Q2 >= 0.99 (OpenTURNS with
# scaled inputs and multistart, scikit-learn with restarts) at N = 200 and 1,000; writes
# bench/results/kriging_fit.md. Needs python3-openturns and python3-sklearn (/usr/bin/python3).
# usage: bench/run_kriging_fit.sh [build-dir]
set -e
ROOT=$(cd "$(dirname "$0")/.." && pwd)
BUILD=${1:-$ROOT/build}
cmake --build "$BUILD" --target bench_surrogate
DATA=$(mktemp -d)
trap 'rm -rf "$DATA"' EXIT
nice -n 5 "$BUILD/bench/bench_surrogate" "$DATA" 200 1000
nice -n 5 /usr/bin/python3 "$ROOT/bench/kriging_fit_peers.py" "$DATA" "$ROOT/bench/results/kriging_fit.md"
