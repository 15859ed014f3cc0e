#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Soak test of "nothing lost": runs the quick steering-column study once to the end
# (the reference), then again in a fresh folder killed with SIGKILL at KILLS random moments,
# resuming each time, and finally to the end. Reports per kill the moment, the solver processes
# launched and the runs reused by the resume (from the store), PRAGMA integrity_check, whether
# a solver outlived smi-lua, and whether the final results.json holds the same numbers as the
# reference (timings and run counts excluded). Writes bench/results/soak_kill_resume.md.
# usage: bench/soak_kill_resume.sh [KILLS=20] [MAX_SECONDS]   (from the source folder, after a build)
# MAX_SECONDS defaults to a third of the reference run, so that the kills land while solver runs
# are still being made (a kill after the last solver run only tests the resume of a finished store).
set -euo pipefail
cd "$(dirname "$0")/.."
KILLS=${1:-20} MAX=${2:-}
SMI=${SMI_LUA:-build/smi-lua} FE=${COLUMN_FE:-build/smi-column-fe}
W=${SOAK_DIR:-$(mktemp -d)}
mkdir -p "$W"
OUT=bench/results/soak_kill_resume.md
py=/usr/bin/python3
study() { "$SMI" --quiet --allow-exec "$PWD/$FE" --out "$1" scripts/steering_column.lua --quick --solver "$PWD/$FE"; }
records() { $py -c "import sqlite3,sys; c=sqlite3.connect(sys.argv[1]); print(c.execute('select count(*) from evaluations').fetchone()[0])" "$1" 2>/dev/null || echo 0; }
integrity() { $py -c "import sqlite3,sys; c=sqlite3.connect(sys.argv[1]); print(c.execute('pragma integrity_check').fetchone()[0])" "$1" 2>/dev/null || echo "no store"; }
# solver processes still running whose working folder is under $1 (orphans of a killed smi-lua)
orphans() { local n=0; for p in /proc/[0-9]*; do case "$(readlink "$p/cwd" 2>/dev/null)" in "$1"/*) n=$((n + 1));; esac; done; echo $n; }

echo "reference run in $W/ref ..."
t0=$(date +%s)
study "$W/ref" > "$W/ref.log" 2>&1
ref_s=$(( $(date +%s) - t0 ))
echo "reference: ${ref_s} s, $(records "$W/ref/evaluations.sqlite") records"
[ -n "$MAX" ] || MAX=$(( ref_s / 3 > 2 ? ref_s / 3 : 2 ))

{
  echo "# Soak: kill -9 the quick study at random moments and resume"
  echo
  echo "$(date -u '+%Y-%m-%d %H:%M UTC'), $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg); reference run ${ref_s} s."
  echo "KILLS=$KILLS, each after a random 1..$MAX s (the run to the end follows the last kill)."
  echo
  echo "| kill | after (s) | records before start | records after kill | new records | integrity | solvers left running |"
  echo "|---|---|---|---|---|---|---|"
} > "$OUT"

S="$W/soak"
for k in $(seq 1 "$KILLS"); do
  before=$(records "$S/evaluations.sqlite")
  wait_s=$(( (RANDOM % MAX) + 1 ))
  ( exec "$SMI" --quiet --allow-exec "$PWD/$FE" --out "$S" scripts/steering_column.lua --quick --solver "$PWD/$FE" > "$W/soak-$k.log" 2>&1 ) &
  pid=$!
  sleep "$wait_s"
  kill -9 "$pid" 2>/dev/null || true
  wait "$pid" 2>/dev/null || true
  sleep 0.5
  after=$(records "$S/evaluations.sqlite")
  left=$(orphans "$S")
  echo "| $k | $wait_s | $before | $after | $((after - before)) | $(integrity "$S/evaluations.sqlite") | $left |" >> "$OUT"
  echo "kill $k after ${wait_s}s: records $before -> $after, solvers left $left"
done

before=$(records "$S/evaluations.sqlite")
t0=$(date +%s)
study "$S" > "$W/final.log" 2>&1
final_s=$(( $(date +%s) - t0 ))
after=$(records "$S/evaluations.sqlite")
same=$($py bench/soak_compare.py "$W/ref" "$S")
{
  echo
  echo "Final run to the end: ${final_s} s (reference ${ref_s} s), records $before -> $after (new solver runs: $((after - before)))."
  echo "Final results.json against the reference (timings and run counts excluded): **$same**."
  echo "Store integrity after the final run: $(integrity "$S/evaluations.sqlite")."
} >> "$OUT"
echo "final: ${final_s}s, records $before -> $after; results: $same"
echo "written $OUT"
