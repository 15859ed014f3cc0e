#!/bin/sh
# SPDX-License-Identifier: MIT
# Runs bench_stats beside SciPy / numpy / OpenTURNS and writes bench/results/stats.md.
# usage: bench/run_stats.sh [build dir]   (default: build)
set -eu
here=$(cd "$(dirname "$0")" && pwd)
build=${1:-$here/../build}
cmake --build "$build" --target bench_stats >/dev/null
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$build/bench/bench_stats" "$tmp" > "$tmp/ours.txt"
cat "$tmp/ours.txt"
/usr/bin/python3 "$here/stats_peers.py" "$tmp" "$tmp/ours.txt" "$here/results/stats.md"
