#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# What a rerun costs: each study run three times in one fresh output folder, the wall time of each
# written to bench/results/rerun.md:
#   first      nothing saved
#   unchanged  the same command again (every step reused; the report rewritten)
#   data       one data value changed (the steps from the first that read the data run again)
#   --force    every step recomputed (solver runs come from the evaluation store)
# Studies: the small Lua-model product of the tests (tests/lua/small_product.lua) in its --quick
# and full modes, and the steering column --quick on smi-column-fe.
# usage: bash bench/run_rerun.sh [BUILD_DIR] [all | small | column]   (default all)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
which=${2:-all}
cmake --build "$build" --target smi-lua smi-column-fe > /dev/null
smi=$(realpath "$build/smi-lua")
fe=$(realpath "$build/smi-column-fe")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p bench/results
out=bench/results/rerun.md

# the small product's study, reading its data from in/data.csv (outside the output folder)
mkdir -p "$work/small/in"
cp tests/lua/small_product.lua "$work/small/"
cat > "$work/small/study.lua" <<'LUA'
local small = require "small_product"
require("smi.improve").run(small.declaration("small", "in/data.csv"), arg)
LUA
cat > "$work/small/write_data.lua" <<'LUA'
require("small_product").write_data(arg[1])
LUA
(cd "$work/small" && "$smi" --quiet --out in write_data.lua in/data.csv > /dev/null)

seconds() {  # seconds since the epoch, with ms
  date +%s.%N | cut -c1-14
}
timed() {  # LABEL FOLDER cmd... : wall seconds of one run into $work/LABEL.t
  local label=$1 dir=$2; shift 2
  local t0 t1
  t0=$(seconds)
  (cd "$dir" && nice -n 5 "$@") > "$work/$label.log" 2>&1 || { echo "$label failed:"; tail -20 "$work/$label.log"; exit 1; }
  t1=$(seconds)
  echo "$t1 - $t0" | bc > "$work/$label.t"
  echo "$label: $(cat "$work/$label.t") s"
}
bump_value() {  # FILE COLUMN: adds 0.01 to the second line's value in COLUMN (one data value)
  awk -F, -v c="$2" 'NR == 2 { $c = $c + 0.01 } { print }' OFS=, "$1" > "$1.new" && mv "$1.new" "$1"
}
row() {  # NAME: one table row from the four timings
  local n=$1 f u d r
  f=$(cat "$work/$n-first.t"); u=$(cat "$work/$n-unchanged.t"); d=$(cat "$work/$n-data.t"); r=$(cat "$work/$n-force.t")
  printf '| %s | %s | %s (%.1f %%) | %s | %s |\n' "$2" "$f" "$u" "$(echo "100 * $u / $f" | bc -l)" "$d" "$r"
}

series() {  # NAME LABEL FOLDER DATA COLUMN smi-lua args...
  local n=$1 label=$2 dir=$3 data=$4 col=$5; shift 5
  timed "$n-first" "$dir" "$smi" --quiet "$@"
  timed "$n-unchanged" "$dir" "$smi" --quiet "$@"
  bump_value "$data" "$col"
  timed "$n-data" "$dir" "$smi" --quiet "$@"
  timed "$n-force" "$dir" "$smi" --quiet "$@" --force
  rows+=("$(row "$n" "$label")")
}
rows=()
if [ "$which" != column ]; then
  cp "$work/small/in/data.csv" "$work/small/in/data.orig"
  series small-quick "small Lua-model study, --quick" "$work/small" "$work/small/in/data.csv" 1 --out out-quick study.lua --quick
  cp "$work/small/in/data.orig" "$work/small/in/data.csv"
  series small-full "small Lua-model study, full" "$work/small" "$work/small/in/data.csv" 1 --out out-full study.lua
fi
if [ "$which" != small ]; then
  mkdir -p "$work/column"
  cp scripts/steering_column/data/tests.csv "$work/column/tests.csv"
  series column "steering column --quick (smi-column-fe)" "$PWD" "$work/column/tests.csv" 4 \
    --allow-exec "$fe" --allow-read "$work/column" --out "$work/column/out" scripts/steering_column.lua --solver "$fe" \
    --quick --data "$work/column/tests.csv"
fi

{
  echo "# Reruns"
  echo
  echo "\`bash bench/run_rerun.sh $build\`, $(date -u '+%Y-%m-%d %H:%M UTC'), $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg) at the end,"
  echo "\`nice -n 5\`. Wall seconds of one study run into one output folder: the first run, the same"
  echo "command again, after one data value changed, and with \`--force\`."
  echo
  echo "| study | first | unchanged rerun (of first) | one data value changed | --force |"
  echo "|---|---|---|---|---|"
  printf '%s\n' "${rows[@]}"
} > "$out.new"
# a partial run (small or column) keeps the other rows of the last file
if [ "$which" != all ] && [ -f "$out" ]; then grep -E '^\| ' "$out" | grep -v -E '^\| (study|---)' | grep -v -F "$( [ "$which" = small ] && echo small || echo column)" >> "$out.new" || true; fi
mv "$out.new" "$out"
cat "$out"
