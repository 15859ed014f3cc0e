#!/bin/sh
# SPDX-License-Identifier: MIT
# Runs bench_calibrate beside SciPy's SLSQP (finite differences) and writes bench/results/calibrate.md.
# usage: bench/run_calibrate.sh [build dir] [quick]   (default: build; quick: the analytic problems only)
# Run it with `nice -n 5` on a shared machine; the results file records the load average.
set -eu
here=$(cd "$(dirname "$0")" && pwd)
build=${1:-$here/../build}
cmake --build "$build" --target bench_calibrate >/dev/null
tmp=$(mktemp -d)
mkdir -p "$tmp/profile"
trap 'rm -rf "$tmp"' EXIT
echo "load_before $(cut -d' ' -f1-3 /proc/loadavg)" > "$tmp/ours.txt"
"$build/bench/bench_calibrate" "$tmp" ${2:-} >> "$tmp/ours.txt"
echo "load_after_main $(cut -d' ' -f1-3 /proc/loadavg)" >> "$tmp/ours.txt"
if [ "${2:-}" != quick ]; then
  "$build/bench/bench_calibrate" "$tmp/profile" profile | grep '^profile_' >> "$tmp/ours.txt"
  # Section 2's variants: CRN kind and size, bandwidth rule, CRN seed, data size, metric, method, basin hopping (one at a time).
  for v in quantiles random2000seed robust random8000 quantiles8000 data1000 loglik lbfgs hops2_0.4 hops4_0.4; do
    "$build/bench/bench_calibrate" "$tmp/profile" variants $v >> "$tmp/ours.txt"
  done
fi
cat "$tmp/ours.txt"
/usr/bin/python3 "$here/calibrate_peers.py" "$tmp" "$tmp/ours.txt" "$here/results/calibrate.md"
