#!/bin/sh
# SPDX-License-Identifier: MIT
# One study per output folder: while one smi-lua runs solvers in --out X, a
# second smi-lua on X stops at once with a message naming the holder (pid, host, start time)
# and the fix, and launches nothing (before the lock both ran, shared work folders and one
# failed "exit status 1"). Once the first has stopped, the folder is free again (flock: even
# kill -9 frees it).
# usage: test_cli_lock.sh SMI_LUA SOLVER WORKDIR
set -eu
SMI=$1 SOLVER=$2 W=$3
STUDY=$(dirname "$0")/studies/resume_study.lua
rm -rf "$W"; mkdir -p "$W"
fail() { echo "FAIL: $*" >&2; exit 1; }
lines() { if [ -f "$1" ]; then wc -l < "$1" | tr -d ' '; else echo 0; fi; }

(exec "$SMI" --quiet --allow-exec "$SOLVER" --out "$W/x" "$STUDY" "$SOLVER" "$W/a.log" 30 > "$W/a.out" 2>&1) &
A=$!
i=0
while [ "$(lines "$W/a.log")" -lt 1 ]; do
  i=$((i + 1)); [ $i -lt 500 ] || { kill -9 $A; fail "the first study never launched a run"; }
  sleep 0.02
done
st=0
"$SMI" --quiet --allow-exec "$SOLVER" --out "$W/x" "$STUDY" "$SOLVER" "$W/b.log" 0.01 > "$W/b.out" 2>&1 || st=$?
kill -9 $A; wait $A 2>/dev/null || true
[ "$st" = 1 ] || fail "second study: exit status $st, expected 1: $(cat "$W/b.out")"
grep -q "is in use by another smi-lua (pid $A on host $(hostname)" "$W/b.out" || fail "holder not named: $(cat "$W/b.out")"
grep -q "started 2" "$W/b.out" && grep -q "another --out" "$W/b.out" || fail "no start time or fix: $(cat "$W/b.out")"
[ "$(lines "$W/b.log")" = 0 ] || fail "the second study launched runs"
echo "ok: second smi-lua refused, holder named"
sleep 0.3  # the first one's solver dies with it (PR_SET_PDEATHSIG)
"$SMI" --quiet --allow-exec "$SOLVER" --out "$W/x" "$STUDY" "$SOLVER" "$W/b.log" 0.01 > "$W/b.out" 2>&1 || fail "after kill -9 of the holder: $(cat "$W/b.out")"
echo "ok: the folder is free again after kill -9 of the holder"
