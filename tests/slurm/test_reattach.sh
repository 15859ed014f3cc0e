#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Jobs outlive smi-lua: (1) --detach and Ctrl-C leave them queued and running; (2) a rerun
# reattaches and is killed with kill -9; (3) a third run reattaches again, finishes, and the
# numbers equal the local executor's, with every run submitted once and solved once.
# usage: test_reattach.sh SMI_LUA SOLVER WORKDIR
SMI=$1 SOLVER=$2 W=$3
. "$(dirname "$0")/lib.sh"
STUDY_ARGS=nohang
reference 3 10 20
start() {
  (exec "$SMI" --quiet --allow-exec "$SOLVER" --out "$W/sl" "${FAST[@]}" --slurm-opt throttle=4 "$@" "$STUDY" "$SOLVER" \
     "$W/launches.txt" 3 10 20 nohang >> "$W/run.txt" 2>&1) &
  PID=$!
}
start --detach
wait_for 30 'test "$(running_jobs)" -gt 0' || fail "no job started running"
kill -INT $PID; wait $PID || true
grep -q "interrupted" "$W/run.txt" || fail "no 'interrupted' message: $(cat "$W/run.txt")"
[ "$(live_jobs)" -gt 0 ] || fail "--detach: the jobs did not stay in the queue"
no_double_submission "$W/sl" 10
echo "detached with $(live_jobs) live tasks"

start
sleep 1.5
kill -9 $PID; wait $PID 2>/dev/null || true
no_double_submission "$W/sl" 10
echo "killed -9 with $(live_jobs) live tasks"

study "$W/sl" "$W/launches.txt" 3 10 20 "${FAST[@]}" > "$W/slurm.txt" 2>&1 || fail "reattach run: $(cat "$W/slurm.txt")"
grep -v '^launched=' "$W/local.txt" > "$W/a.txt"; grep -v '^launched=' "$W/slurm.txt" > "$W/b.txt"
diff "$W/a.txt" "$W/b.txt" || fail "the reattached run differs from the local one (above)"
no_double_submission "$W/sl" 11   # the 10 runs and the one of the second model
n=$(awk '{print $2}' "$W/launches.txt" | sort | uniq -d | wc -l)
[ "$(lines "$W/launches.txt")" -eq 11 ] && [ "$n" -eq 0 ] || fail "the solver ran $(lines "$W/launches.txt") times for 11 runs"
echo "ok: reattached twice, 11 runs submitted once and solved once"
