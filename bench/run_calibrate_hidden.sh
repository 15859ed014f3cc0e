#!/bin/sh
# SPDX-License-Identifier: MIT
# Runs bench/calibrate_hidden.lua (smi-lua, the Lua function model) beside SciPy's SLSQP on the same
# objective and writes bench/results/calibrate_hidden.md.
# usage: bench/run_calibrate_hidden.sh [build dir]   (run it with `nice -n 5` on a shared machine)
set -eu
here=$(cd "$(dirname "$0")" && pwd)
build=${1:-$here/../build}
cmake --build "$build" --target smi-lua >/dev/null
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
echo "load $(cut -d' ' -f1 /proc/loadavg)" > "$tmp/ours.txt"
"$build/smi-lua" --quiet --allow-read "$here/../tests/lua" --out "$tmp/out" "$here/calibrate_hidden.lua" "$here/../tests/lua/hidden_problem.lua" >> "$tmp/ours.txt"
cat "$tmp/ours.txt"
/usr/bin/python3 "$here/calibrate_hidden_peers.py" "$tmp/out" "$tmp/ours.txt" "$here/results/calibrate_hidden.md"
