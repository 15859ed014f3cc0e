#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Builds one libFuzzer target, fuzzes it for a stated time from its committed corpus, merges what
# was found back into a minimal corpus and writes bench/results/fuzz_<NAME>.md. The run_fuzz_*.sh
# scripts call it with their target. Needs Debian's clang and libclang-rt-14-dev (run on demand).
# usage: bash bench/fuzz_run.sh NAME SECONDS MAX_LEN 'SOURCES AND FLAGS' CALLER
set -euo pipefail
cd "$(dirname "$0")/.."
name=$1 secs=$2 max_len=$3 sources=$4 caller=$5
out_dir=${TMPDIR:-/tmp}/fuzz_$name.build
mkdir -p "$out_dir"
# shellcheck disable=SC2086  # the sources and flags are words
clang++ -std=c++20 -O1 -g -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined \
  -I host $sources -o "$out_dir/fuzz_$name"
corpus=bench/fuzz_corpus/$name
work=$(mktemp -d)
cp "$corpus"/* "$work"/ 2>/dev/null || true
log=$(mktemp)
set +e
"$out_dir/fuzz_$name" -max_total_time="$secs" -max_len="$max_len" -timeout=10 -rss_limit_mb=1024 \
  -dict="bench/fuzz_corpus/$name.dict" -artifact_prefix="$out_dir/" "$work" 2> "$log"
rc=$?
set -e
tail -5 "$log"
[ $rc = 0 ] || echo "crash input and log: $out_dir/ (crash-*), $log" >&2
# Keep the committed corpus small: merge what was found into a minimal set.
mkdir -p "$work.min"
"$out_dir/fuzz_$name" -merge=1 "$work.min" "$work" 2> /dev/null > /dev/null || true
rm -f "$corpus"/*
cp "$work.min"/* "$corpus"/
runs=$(grep -o 'Done [0-9]* runs' "$log" | tail -1 || true)
cov=$(grep -o 'cov: [0-9]*' "$log" | tail -1 || true)
{
  echo "# fuzz_$name"
  echo
  echo "$caller $secs on $(date -u +%Y-%m-%d) ($(nproc) cores, clang $(clang++ -dumpversion))."
  echo
  echo "- exit status: $rc ($( [ $rc = 0 ] && echo 'no crash, no oracle mismatch' || echo 'FAILED: see the log' ))"
  echo "- ${runs:-runs: see log}; ${cov:-}"
  echo "- corpus after merge: $(ls "$corpus" | wc -l) inputs, $(cat "$corpus"/* | wc -c) bytes (bench/fuzz_corpus/$name)"
} > "bench/results/fuzz_$name.md"
cat "bench/results/fuzz_$name.md"
rm -rf "$work" "$work.min"
[ $rc != 0 ] || rm -f "$log"
exit $rc
