#!/usr/bin/env bash
# Fuzzes the sandbox's path resolver for a stated time and writes bench/results/fuzz_path_walk.md.
# Needs Debian's clang and libclang-rt-14-dev (not part of the CI build: run on demand).
# usage: bash bench/run_fuzz_path_walk.sh [SECONDS]   (default 120)
set -euo pipefail
cd "$(dirname "$0")/.."
secs=${1:-120}
out_dir=${TMPDIR:-/tmp}/fuzz_path_walk.build
mkdir -p "$out_dir"
clang++ -std=c++20 -O1 -g -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined \
  -I host bench/fuzz_path_walk.cpp host/kernels/core/path_walk.cpp -o "$out_dir/fuzz_path_walk"
corpus=bench/fuzz_corpus/path_walk
work=$(mktemp -d)
cp "$corpus"/* "$work"/ 2>/dev/null || true
log=$(mktemp)
set +e
"$out_dir/fuzz_path_walk" -max_total_time="$secs" -max_len=512 -timeout=10 -rss_limit_mb=1024 \
  -dict=bench/fuzz_corpus/path_walk.dict -artifact_prefix="$out_dir/" "$work" 2> "$log"
rc=$?
set -e
tail -5 "$log"
[ $rc = 0 ] || echo "crash input and log: $out_dir/ (crash-*), $log" >&2
# Keep the committed corpus small: merge what was found into a minimal set.
mkdir -p "$work.min"
"$out_dir/fuzz_path_walk" -merge=1 "$work.min" "$work" 2> /dev/null > /dev/null || true
rm -f "$corpus"/*
cp "$work.min"/* "$corpus"/
runs=$(grep -o 'Done [0-9]* runs' "$log" | tail -1 || true)
cov=$(grep -o 'cov: [0-9]*' "$log" | tail -1 || true)
{
  echo "# fuzz_path_walk"
  echo
  echo "bench/run_fuzz_path_walk.sh $secs on $(date -u +%Y-%m-%d) ($(nproc) cores, clang $(clang++ -dumpversion))."
  echo
  echo "- exit status: $rc ($( [ $rc = 0 ] && echo 'no crash, no oracle mismatch' || echo 'FAILED: see the log' ))"
  echo "- ${runs:-runs: see log}; ${cov:-}"
  echo "- corpus after merge: $(ls "$corpus" | wc -l) inputs, $(cat "$corpus"/* | wc -c) bytes (bench/fuzz_corpus/path_walk)"
} > bench/results/fuzz_path_walk.md
cat bench/results/fuzz_path_walk.md
rm -rf "$work" "$work.min"
[ $rc != 0 ] || rm -f "$log"
exit $rc
