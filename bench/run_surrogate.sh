#!/bin/sh
# SPDX-License-Identifier: MIT
# Kriging / propagation benchmark beside OpenTURNS and scikit-learn; writes bench/results/surrogate.md.
# usage: bench/run_surrogate.sh [build-dir] [max peer N]
set -e
ROOT=$(cd "$(dirname "$0")/.." && pwd)
BUILD=${1:-$ROOT/build}
MAXN=${2:-1000}
cmake --build "$BUILD" --target bench_surrogate
DATA=$(mktemp -d)
/usr/bin/time -v "$BUILD/bench/bench_surrogate" "$DATA" 2> "$DATA/time.txt" || { cat "$DATA/time.txt"; exit 1; }
grep -v '^\s' "$DATA/time.txt" || true
RSS=$(sed -n 's/.*Maximum resident set size (kbytes): //p' "$DATA/time.txt")
/usr/bin/python3 - "$DATA/ours.json" "$RSS" <<'PY'
import json, sys
p = sys.argv[1]; d = json.load(open(p)); d["maxrss_kb"] = int(sys.argv[2]); json.dump(d, open(p, "w"))
PY
/usr/bin/python3 "$ROOT/bench/surrogate_peers.py" "$DATA" "$ROOT/bench/results/surrogate.md" "$MAXN"
rm -rf "$DATA"
