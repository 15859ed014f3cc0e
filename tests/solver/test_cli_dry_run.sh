#!/bin/sh
# SPDX-License-Identifier: MIT
# --dry-run plans a study whose later steps depend on solver outputs: with an
# empty store it stops cleanly (exit 0) at the first evaluation that needs runs, prints the plan
# so far, launches nothing and writes no results (before: exit 1, "model output 1 is not
# finite"). After a real run, a dry run plans the whole study from the store: 0 runs.
# usage: test_cli_dry_run.sh SMI_LUA SOLVER WORKDIR
set -eu
SMI=$1 SOLVER=$2 W=$3
STUDY=$(dirname "$0")/studies/dry_study.lua
rm -rf "$W"; mkdir -p "$W"
fail() { echo "FAIL: $*" >&2; exit 1; }
lines() { if [ -f "$1" ]; then wc -l < "$1" | tr -d ' '; else echo 0; fi; }
run() { "$SMI" --quiet --allow-exec "$SOLVER" --out "$W/out" "$@" "$STUDY" "$SOLVER" "$W/launch.log" > "$W/o.txt" 2>&1; }

st=0; run --dry-run || st=$?
[ "$st" = 0 ] || fail "dry run with an empty store: exit $st: $(cat "$W/o.txt")"
grep -q "dry run: stopped at model 'dry': 3 of its runs are not in the store" "$W/o.txt" || fail "no stop message: $(cat "$W/o.txt")"
grep -q "plan so far: 3 solver runs for 3 points (0 already stored)" "$W/o.txt" || fail "no plan so far: $(cat "$W/o.txt")"
grep -q "study finished\|not finite" "$W/o.txt" && fail "the dry run went on past the stop: $(cat "$W/o.txt")"
[ "$(lines "$W/launch.log")" = 0 ] || fail "a dry run launched solvers"
[ ! -e "$W/out/results.json" ] || fail "a dry run wrote results.json"
echo "ok: empty store: clean stop with the plan so far"

run || fail "real run: $(cat "$W/o.txt")"
[ "$(lines "$W/launch.log")" = 6 ] || fail "real run launched $(lines "$W/launch.log") runs, expected 6"
cp "$W/out/results.json" "$W/results.before"
st=0; run --dry-run || st=$?
[ "$st" = 0 ] || fail "dry run after the real run: exit $st: $(cat "$W/o.txt")"
grep -q "study finished" "$W/o.txt" || fail "dry run did not plan the whole study: $(cat "$W/o.txt")"
grep -q "stopped at model" "$W/o.txt" && fail "dry run stopped although everything is stored"
[ "$(lines "$W/launch.log")" = 6 ] || fail "the second dry run launched solvers"
cmp -s "$W/out/results.json" "$W/results.before" || fail "the dry run rewrote results.json"
echo "ok: full store: the whole study planned, 0 runs, results untouched"
