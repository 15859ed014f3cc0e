#!/bin/sh
# Runs bench_calibrate beside SciPy's SLSQP (finite differences) and writes bench/results/calibrate.md.
# usage: bench/run_calibrate.sh [build dir] [quick]   (default: build; quick: the 4-parameter problem only)
set -eu
here=$(cd "$(dirname "$0")" && pwd)
build=${1:-$here/../build}
cmake --build "$build" --target bench_calibrate >/dev/null
tmp=$(mktemp -d)
mkdir -p "$tmp/profile"
trap 'rm -rf "$tmp"' EXIT
"$build/bench/bench_calibrate" "$tmp" ${2:-} > "$tmp/ours.txt"
[ "${2:-}" = quick ] || "$build/bench/bench_calibrate" "$tmp/profile" profile | grep '^profile_' >> "$tmp/ours.txt"
cat "$tmp/ours.txt"
/usr/bin/python3 "$here/calibrate_peers.py" "$tmp" "$tmp/ours.txt" "$here/results/calibrate.md"
