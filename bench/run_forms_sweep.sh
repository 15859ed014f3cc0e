#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The model-form sweep (bench/forms_sweep.lua) on the two small products of tests/lua: every true
# form, BATCHES batches of nine specimens each, with and without the design values as priors.
# Writes bench/results/forms_sweep.md (the per-study lines and the counts of each product).
# usage: bash bench/run_forms_sweep.sh [BUILD_DIR] [BATCHES] [FIRST_SEED] [--quick]
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
batches=${2:-4}
seed=${3:-9100}
quick=${4:-}
cmake --build "$build" --target smi-lua > /dev/null
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p bench/results
out=bench/results/forms_sweep.md
{
  echo "# Model-form sweep"
  echo
  echo "bench/run_forms_sweep.sh $build $batches $seed $quick, $(date -u +%Y-%m-%d), load $(cut -d' ' -f1-3 /proc/loadavg)."
  echo "Per study: product, batch, true form, priors or none, verdict, chosen form, judged, each form's"
  echo "log evidence (x: invalid by u-pooling; *: chosen), wall time."
  echo
  for product in isolator chain; do
    echo "## $product"
    echo
    echo '```'
    nice -n 5 "$build/smi-lua" --quiet --allow-read tests/lua --out "$work/$product" bench/forms_sweep.lua \
      "tests/lua/${product}_product.lua" "$batches" "$seed" $quick | grep -E "^($product |with priors|without priors)"
    echo '```'
    echo
  done
} > "$out"
echo "wrote $out"
