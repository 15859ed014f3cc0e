#!/bin/sh
# SPDX-License-Identifier: MIT
# Ctrl-C during solver runs: smi-lua stops promptly with "interrupted", kills the running
# solvers' process groups, and keeps the records of runs that had finished. Then --timeout
# during solver runs: no Lua runs while smi-lua waits on solvers, yet the run stops by itself
# with "timeout" and kills them.
# usage: test_cli_interrupt.sh SMI_LUA SOLVER WORKDIR
set -eu
SMI=$1 SOLVER=$2 W=$3
STUDY=$(dirname "$0")/studies/resume_study.lua
rm -rf "$W"; mkdir -p "$W"
fail() { echo "FAIL: $*" >&2; exit 1; }
lines() { if [ -f "$LOG" ]; then wc -l < "$LOG" | tr -d ' '; else echo 0; fi; }

# stopped PID TICKS WHAT: waits for PID to exit (TICKS x 0.05 s at most: a guard against a hang,
# not a speed check), then checks it failed, said WORD in OUT, and left no solver running.
stopped() {
  i=0
  while kill -0 "$1" 2>/dev/null; do
    i=$((i + 1)); [ $i -lt "$2" ] || { kill -9 "$1"; fail "smi-lua did not stop ($3)"; }
    sleep 0.05
  done
  wait "$1" && fail "smi-lua exited 0 ($3)" || true
  grep -q "$WORD" "$OUT" || fail "no '$WORD' in: $(cat "$OUT")"
  [ "$(lines)" -ge 1 ] || fail "the study never launched a run ($3)"
  # every solver it launched is gone (pids are the first field of the launch log)
  sleep 0.2
  for pid in $(cut -d' ' -f1 "$LOG"); do
    if [ -r /proc/$pid/stat ] && [ "$(cut -d')' -f2 /proc/$pid/stat | cut -d' ' -f2)" != Z ]; then
      fail "solver $pid still runs ($3)"
    fi
  done
}

# Runs of 30 s each: without the interrupt the study would take minutes.
LOG=$W/launches.txt OUT=$W/out.txt WORD=interrupted
(exec "$SMI" --quiet --allow-exec "$SOLVER" --out "$W/a" "$STUDY" "$SOLVER" "$LOG" 30 > "$OUT" 2>&1) &
PID=$!
i=0
while [ "$(lines)" -lt 1 ]; do
  i=$((i + 1)); [ $i -lt 500 ] || fail "the study never launched a run"
  sleep 0.02
done
sleep 0.3
kill -INT $PID
stopped $PID 100 "within 5 s of SIGINT"
echo "ok: interrupted after $(lines) launches; solvers killed"

LOG=$W/launches2.txt OUT=$W/out2.txt WORD=timeout
(exec "$SMI" --quiet --timeout 2 --allow-exec "$SOLVER" --out "$W/b" "$STUDY" "$SOLVER" "$LOG" 30 > "$OUT" 2>&1) &
stopped $! 400 "--timeout 2, 20 s later"
echo "ok: --timeout stopped the run during solver waits; solvers killed"
