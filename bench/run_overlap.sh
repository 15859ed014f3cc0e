#!/bin/sh
# SPDX-License-Identifier: MIT
# Runs bench_overlap beside SciPy's quad and writes bench/results/overlap.md.
# usage: bench/run_overlap.sh [build dir]   (default: build)
set -eu
here=$(cd "$(dirname "$0")" && pwd)
build=${1:-$here/../build}
cmake --build "$build" --target bench_overlap >/dev/null
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$build/bench/bench_overlap" > "$tmp/ours.txt"
cat "$tmp/ours.txt"
/usr/bin/python3 "$here/overlap_peers.py" "$tmp/ours.txt" "$here/results/overlap.md"
