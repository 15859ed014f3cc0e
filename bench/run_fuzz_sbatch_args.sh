#!/usr/bin/env bash
# Fuzzes the Slurm executor's sbatch argument parser for a stated time and writes bench/results/fuzz_sbatch_args.md.
# Needs Debian's clang and libclang-rt-14-dev (not part of the CI build: run on demand).
# usage: bash bench/run_fuzz_sbatch_args.sh [SECONDS]   (default 120)
set -euo pipefail
cd "$(dirname "$0")/.."
secs=${1:-120}
out_dir=${TMPDIR:-/tmp}/fuzz_sbatch_args.build
mkdir -p "$out_dir"
clang++ -std=c++20 -O1 -g -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined \
  -I host -I /usr/include bench/fuzz_sbatch_args.cpp host/kernels/eval/sbatch_args.cpp -lfmt -o "$out_dir/fuzz_sbatch_args"
corpus=bench/fuzz_corpus/sbatch_args
work=$(mktemp -d)
cp "$corpus"/* "$work"/ 2>/dev/null || true
log=$(mktemp)
set +e
"$out_dir/fuzz_sbatch_args" -max_total_time="$secs" -max_len=256 -timeout=10 -rss_limit_mb=1024 \
  -dict=bench/fuzz_corpus/sbatch_args.dict -artifact_prefix="$out_dir/" "$work" 2> "$log"
rc=$?
set -e
tail -5 "$log"
[ $rc = 0 ] || echo "crash input and log: $out_dir/ (crash-*), $log" >&2
# Keep the committed corpus small: merge what was found into a minimal set.
mkdir -p "$work.min"
"$out_dir/fuzz_sbatch_args" -merge=1 "$work.min" "$work" 2> /dev/null > /dev/null || true
rm -f "$corpus"/*
cp "$work.min"/* "$corpus"/
runs=$(grep -o 'Done [0-9]* runs' "$log" | tail -1 || true)
cov=$(grep -o 'cov: [0-9]*' "$log" | tail -1 || true)
{
  echo "# fuzz_sbatch_args"
  echo
  echo "bench/run_fuzz_sbatch_args.sh $secs on $(date -u +%Y-%m-%d) ($(nproc) cores, clang $(clang++ -dumpversion))."
  echo
  echo "- exit status: $rc ($( [ $rc = 0 ] && echo 'no crash, no oracle mismatch' || echo 'FAILED: see the log' ))"
  echo "- ${runs:-runs: see log}; ${cov:-}"
  echo "- corpus after merge: $(ls "$corpus" | wc -l) inputs, $(cat "$corpus"/* | wc -c) bytes (bench/fuzz_corpus/sbatch_args)"
} > bench/results/fuzz_sbatch_args.md
cat bench/results/fuzz_sbatch_args.md
rm -rf "$work" "$work.min"
[ $rc != 0 ] || rm -f "$log"
exit $rc
