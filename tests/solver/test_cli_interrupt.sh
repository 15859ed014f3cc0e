#!/bin/sh
# Ctrl-C during solver runs: smi-lua stops promptly with "interrupted", kills the running
# solvers' process groups, and keeps the records of runs that had finished. Then --timeout
# during solver runs: no Lua runs while smi-lua waits on solvers, yet the run stops by itself
# with "timeout" and kills them.
# usage: test_cli_interrupt.sh SMI_LUA SOLVER WORKDIR
set -eu
SMI=$1 SOLVER=$2 W=$3
STUDY=$(dirname "$0")/studies/resume_study.lua
rm -rf "$W"; mkdir -p "$W"
LOG=$W/launches.txt
fail() { echo "FAIL: $*" >&2; exit 1; }
lines() { if [ -f "$LOG" ]; then wc -l < "$LOG" | tr -d ' '; else echo 0; fi; }

# runs of 30 s each: without the interrupt the study would take minutes
(exec "$SMI" --quiet --allow-exec "$SOLVER" --out "$W/a" "$STUDY" "$SOLVER" "$LOG" 30 > "$W/out.txt" 2>&1) &
PID=$!
i=0
while [ "$(lines)" -lt 1 ]; do
  i=$((i + 1)); [ $i -lt 500 ] || fail "the study never launched a run"
  sleep 0.02
done
sleep 0.3
kill -INT $PID
i=0
while kill -0 $PID 2>/dev/null; do
  i=$((i + 1)); [ $i -lt 100 ] || { kill -9 $PID; fail "smi-lua did not stop within 5 s of SIGINT"; }
  sleep 0.05
done
wait $PID && fail "smi-lua exited 0 after SIGINT" || true
grep -q "interrupted" "$W/out.txt" || fail "no 'interrupted' in: $(cat "$W/out.txt")"
# every solver it launched is gone (pids are the first field of the launch log)
sleep 0.2
for pid in $(cut -d' ' -f1 "$LOG"); do
  if [ -r /proc/$pid/stat ] && [ "$(cut -d')' -f2 /proc/$pid/stat | cut -d' ' -f2)" != Z ]; then
    fail "solver $pid still runs after the interrupt"
  fi
done
echo "ok: interrupted after $(lines) launches; solvers killed"

LOG=$W/launches2.txt
(exec "$SMI" --quiet --timeout 2 --allow-exec "$SOLVER" --out "$W/b" "$STUDY" "$SOLVER" "$LOG" 30 > "$W/out2.txt" 2>&1) &
PID=$!
i=0
while kill -0 $PID 2>/dev/null; do
  # a guard against a hang, not a speed check: each run sleeps 30 s, several runs are queued
  i=$((i + 1)); [ $i -lt 400 ] || { kill -9 $PID; fail "smi-lua --timeout 2 still waits on its solvers after 20 s"; }
  sleep 0.05
done
wait $PID && fail "smi-lua exited 0 after its timeout" || true
grep -q "timeout" "$W/out2.txt" || fail "no 'timeout' in: $(cat "$W/out2.txt")"
[ "$(lines)" -ge 1 ] || fail "the timed-out study never launched a run"
sleep 0.2
for pid in $(cut -d' ' -f1 "$LOG"); do
  if [ -r /proc/$pid/stat ] && [ "$(cut -d')' -f2 /proc/$pid/stat | cut -d' ' -f2)" != Z ]; then
    fail "solver $pid still runs after the timeout"
  fi
done
echo "ok: --timeout stopped the run during solver waits; solvers killed"
