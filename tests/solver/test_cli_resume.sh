#!/bin/sh
# SPDX-License-Identifier: MIT
# End to end through smi-lua: a study killed with SIGKILL mid-run resumes without re-running
# what had finished; --dry-run counts what is left and launches nothing; --store shares a
# store read-only with another output folder.
# usage: test_cli_resume.sh SMI_LUA SOLVER WORKDIR
set -eu
SMI=$1 SOLVER=$2 W=$3
STUDY=$(dirname "$0")/studies/resume_study.lua
rm -rf "$W"; mkdir -p "$W"
LOG=$W/launches.txt
run() { "$SMI" --quiet --allow-exec "$SOLVER" "$@" "$STUDY" "$SOLVER" "$LOG" 0.2; }
fail() { echo "FAIL: $*" >&2; exit 1; }
lines() { if [ -f "$LOG" ]; then wc -l < "$LOG" | tr -d ' '; else echo 0; fi; }

# 1. start the study, kill -9 it once three runs have started and two have surely finished
# (exec: $! must be smi-lua itself, not a subshell around it)
(exec "$SMI" --quiet --allow-exec "$SOLVER" --out "$W/a" "$STUDY" "$SOLVER" "$LOG" 0.2 > "$W/first.txt" 2>&1) &
PID=$!
i=0
while [ "$(lines)" -lt 4 ]; do
  i=$((i + 1)); [ $i -lt 500 ] || fail "the study never launched 4 runs"
  sleep 0.02
done
kill -9 $PID
wait $PID 2>/dev/null && fail "the study was not killed" || true
# The solver run in flight is orphaned (its own process group) and finishes; its record is
# lost with the study. Wait until the launch log stops growing (a loaded machine is slow).
KILLED_AT=$(lines)
while sleep 0.5; [ "$(lines)" -ne "$KILLED_AT" ]; do KILLED_AT=$(lines); done
[ "$KILLED_AT" -lt 8 ] || fail "the study finished before it was killed"

# 2. dry run: counts the runs left, launches none
run --out "$W/a" --dry-run > "$W/dry.txt" || fail "dry run failed: $(cat "$W/dry.txt")"
grep -q "would launch" "$W/dry.txt" || fail "dry run printed: $(cat "$W/dry.txt")"
[ "$(lines)" -eq "$KILLED_AT" ] || fail "the dry run launched solver runs ($KILLED_AT before, $(lines) after)"
TODO=$(sed -n 's/.*would launch \([0-9]*\) solver run.*/\1/p' "$W/dry.txt")
STORED=$(sed -n 's/.*(\([0-9]*\) found in the store).*/\1/p' "$W/dry.txt")
[ "$STORED" -ge 3 ] || fail "only $STORED runs were stored before the kill"
[ $((TODO + STORED)) -eq 8 ] || fail "dry run: $TODO to run + $STORED stored != 8"
grep -q "ETA" "$W/dry.txt" || fail "no ETA in: $(cat "$W/dry.txt")"

# 3. resume: runs exactly what was not stored, and the numbers are right (the study asserts them)
run --out "$W/a" > "$W/resume.txt" || fail "resume failed: $(cat "$W/resume.txt")"
grep -q "launched=$TODO reused=$STORED" "$W/resume.txt" || fail "resume printed $(cat "$W/resume.txt"), expected launched=$TODO"
[ "$(lines)" -eq $((KILLED_AT + TODO)) ] || fail "resume launched $(( $(lines) - KILLED_AT )) runs, expected $TODO"

# 4. another output folder sharing the first store read-only: everything is a hit
run --out "$W/b" --store "$W/a/evaluations.sqlite" > "$W/shared.txt" || fail "shared run failed: $(cat "$W/shared.txt")"
grep -q "launched=0 reused=8" "$W/shared.txt" || fail "shared store: $(cat "$W/shared.txt")"
echo "ok: killed after $KILLED_AT launches, $STORED stored, resumed $TODO"
