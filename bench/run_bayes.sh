#!/bin/sh
# SPDX-License-Identifier: MIT
# Times smi.calibrate_bayes (bench/bayes.lua) and a NumPy TMCMC peer (bench/bayes_peer.py) on the
# same 10-parameter Gaussian problem, and writes bench/results/bayes.md.
# usage: bench/run_bayes.sh [build dir] [samples] [n]   (defaults: build, 1000, 2000)
# Run it with `nice -n 5` on a shared machine; the results file records the load average.
set -eu
here=$(cd "$(dirname "$0")" && pwd)
build=${1:-$here/../build}
samples=${2:-1000}
n=${3:-2000}
cmake --build "$build" --target smi-lua >/dev/null
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
echo "load_before $(cut -d' ' -f1-3 /proc/loadavg)" > "$tmp/ours.txt"
for case in kriging lua gauss; do
  t0=$(date +%s.%N)
  "$build/smi-lua" --quiet --out "$tmp/out" "$here/bayes.lua" "$samples" "$n" 2 "$case" >> "$tmp/ours.txt"
  t1=$(date +%s.%N)
  echo "${case}_seconds_wall $(echo "$t1 - $t0" | bc)" >> "$tmp/ours.txt"
done
echo "load_after $(cut -d' ' -f1-3 /proc/loadavg)" >> "$tmp/ours.txt"
cat "$tmp/ours.txt"
/usr/bin/python3 "$here/bayes_peer.py" "$samples" "$tmp/ours.txt" "$here/results/bayes.md"
