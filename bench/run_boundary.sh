#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Measures the C++/Lua boundary and writes bench/results/boundary.md:
#   bench_boundary (sum over 1e7 numbers: smi.vec vs plain Lua; start-up of smi-lua -e '')
#   and the same sums in Python (NumPy and a plain loop) as peers, in the same run.
# usage: bash bench/run_boundary.sh [BUILD_DIR]   (default: build)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
cmake --build "$build" --target smi-lua bench_boundary
py=/usr/bin/python3
out=bench/results/boundary.md
tmp=$(mktemp)
"$build/bench/bench_boundary" "$build/smi-lua" "$py" -c "" > "$tmp"

peer=$("$py" - <<'PY'
import time, statistics
import numpy as np
n = 10_000_000
t = [i * 0.5 for i in range(1, n + 1)]
a = np.array(t)
def med(f, k=5):
    ts = []
    for _ in range(k):
        s = time.perf_counter(); f(); ts.append(time.perf_counter() - s)
    return statistics.median(ts)
def loop():
    s = 0.0
    for x in t:
        s += x
    return s
print(f"| NumPy `a.sum()` {np.__version__} | {med(a.sum) * 1e3:.2f} |")
print(f"| Python `for x in list: s += x` | {med(loop, 3) * 1e3:.2f} |")
PY
)

{
  echo "# Boundary benchmark"
  echo
  echo "Run $(date -u +%Y-%m-%d) on $(nproc) cores ($(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs)),"
  echo "Release build, \`bash bench/run_boundary.sh\`. Ratios are taken within this one run"
  echo "(load average at the end: $(cut -d' ' -f1-3 /proc/loadavg); absolute times vary with it)."
  echo
  cat "$tmp"
  echo
  echo "## Peers: the same sum in Python (same run)"
  echo
  echo "| what | time (ms) |"
  echo "|---|---:|"
  echo "$peer"
} > "$out"
rm -f "$tmp"
cat "$out"
