#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Robustness harness of the bracket-plate study: makes each experiment of experiments.csv with the
# data generator (truth form, true means:stds, noise, seed; the study never sees them), runs the
# study on it with --quick and prints the confusion table, the calibrated means against the truth
# and the ccx runs (summarize.lua).
#   usage: run.sh BUILD_DIR OUT_DIR [ci|full|all] [--check]
# ci: one experiment per truth (clamped; joint + sensor; joint only); full: three more at other
# truths' values and seeds; all: both. Exit 1 when a study fails; with --check also unless every
# experiment reaches the issue's conclusion for its truth. SOLVER: the ccx program (default ccx).
set -euo pipefail
build=$(cd "$1" && pwd) out=$2 set=${3:-ci} check=${4:-}
here=$(cd "$(dirname "$0")" && pwd)
src=$(cd "$here/../../.." && pwd)
mkdir -p "$out"
out=$(cd "$out" && pwd)
smi=$build/smi-lua ccx=${SOLVER:-ccx}
export OMP_NUM_THREADS=1   # one thread per ccx run: the study runs two at a time
failed=0
while IFS=, read -r id eset truth noise seed E rho t kw; do
  [ "$id" = id ] && continue
  if [ "$set" != all ] && [ "$eset" != "$set" ]; then continue; fi
  dir=$out/exp$id
  rm -rf "$dir"; mkdir -p "$dir"
  (cd "$src" && "$smi" --quiet --allow-exec "$ccx" --allow-read scripts/bracket_plate --allow-write "$dir" \
     --out "$dir/generator" scripts/bracket_plate/data/generate.lua --csv "$dir/tests.csv" --truth "$truth" \
     --seed "$seed" --noise "$noise" --set "E=$E" --set "rho=$rho" --set "t=$t" --set "log10_kw=$kw" \
     --solver "$ccx") 2> "$dir/generator.log"
  start=$(date +%s)
  (cd "$src" && "$smi" --quiet --allow-exec "$ccx" --allow-read "$dir" --out "$dir/study" \
     scripts/bracket_plate.lua --quick --solver "$ccx" --data "$dir/tests.csv") > "$dir/study.log" 2>&1 ||
    { echo "experiment $id: the study failed (see $dir/study.log)"; failed=1; }
  echo "experiment $id ($truth truth): $(tail -1 "$dir/study.log") [$(( $(date +%s) - start )) s]"
done < "$here/experiments.csv"
(cd "$src" && "$smi" --quiet --allow-read "$out" --allow-read "$here" --out "$out/summary" \
   "$here/summarize.lua" "$here/experiments.csv" "$out" "$set" $check) || failed=1
exit $failed
