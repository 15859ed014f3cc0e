#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# What a study's full run costs against its --quick, on in-process Lua models (where the model
# costs microseconds and the study's own computing is all there is): the chain product of the
# tests (tests/lua/chain_product.lua, through bench/direct_model.lua) and a three-unknown shaft
# (bench/shaft_product.lua). Each study runs --quick, then full, in one fresh folder; wall and CPU
# seconds, the ratio, and the full run's evidence seconds and bootstrap evaluations per trial go
# to bench/results/study_modes.md.
# usage: bash bench/run_study_modes.sh [BUILD_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
cmake --build "$build" --target smi-lua > /dev/null
smi=$(realpath "$build/smi-lua")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p bench/results
out=bench/results/study_modes.md

mkdir -p "$work/shaft"
cp bench/shaft_product.lua "$work/shaft/"
cat > "$work/shaft/study.lua" <<'LUA'
require("smi.improve").run(require("shaft_product").declaration("shaft", "data.csv"), arg)
LUA
cat > "$work/shaft/write_data.lua" <<'LUA'
require("shaft_product").write_data(arg[1], 3)
LUA
(cd "$work/shaft" && "$smi" --quiet --out . write_data.lua data.csv > /dev/null)

# run LABEL DIR cmd...: wall and CPU seconds into $work/LABEL.t
run() {
  local label=$1 dir=$2; shift 2
  (cd "$dir" && /usr/bin/time -f "%e %U %S" -o "$work/$label.t" "$@" > "$work/$label.log" 2>&1)
}
run chain_quick . "$smi" --quiet --allow-read tests/lua --out "$work/chain_quick" bench/direct_model.lua tests/lua/chain_product.lua --quick
run chain_full . "$smi" --quiet --allow-read tests/lua --out "$work/chain_full" bench/direct_model.lua tests/lua/chain_product.lua
run shaft_quick "$work/shaft" "$smi" --quiet --out quick study.lua --quick
run shaft_full "$work/shaft" "$smi" --quiet --out full study.lua

# per trial of a full run: evidence seconds and bootstrap evaluations, from its results JSON
trials() {
  python3 - "$1" <<'PY'
import json, sys
steps = json.load(open(sys.argv[1]))["steps"]
out = []
for k in range(1, 5):
    c = steps.get(f"trial{k}_calibration", {}).get("result") or {}
    if "evidence" not in c: continue
    ev = c["evidence"]; b = c.get("bootstrap") or {}
    out.append(f"trial {k}: evidence {ev.get('seconds', 0):.1f} s ({2 * len(c.get('params', [])) or '?'} parameters), "
               f"bootstrap {b.get('replicates', 0)} replicates, {b.get('evaluations', 0)} evaluations")
print("; ".join(out))
PY
}
{
  echo "# A study's full run against its --quick (in-process Lua models)"
  echo
  echo "\`bash bench/run_study_modes.sh\`, $(date -u +%Y-%m-%d), $(nproc) cores, load average $(cut -d' ' -f1-3 /proc/loadavg)."
  echo
  echo "| study | --quick wall (CPU) | full wall (CPU) | full / quick | the full run's trials |"
  echo "|---|---|---|---|---|"
  for s in chain shaft; do
    read -r qw qu qs < "$work/${s}_quick.t"
    read -r fw fu fs < "$work/${s}_full.t"
    json=$([ $s = chain ] && echo "$work/chain_full/direct_model.json" || echo "$work/shaft/full/results.json")
    ratio=$(python3 -c "print(f'{$fw / $qw:.2f}x')")
    cpu_q=$(python3 -c "print(f'{$qu + $qs:.1f}')")
    cpu_f=$(python3 -c "print(f'{$fu + $fs:.1f}')")
    echo "| $s | $qw s ($cpu_q s) | $fw s ($cpu_f s) | $ratio | $(trials "$json") |"
  done
} > "$out"
cat "$out"
