#!/usr/bin/env bash
# (1) Ctrl-C while runs are queued and running on Slurm: smi-lua stops promptly, one scancel takes
# every job of the study out of the queue (running ones get TERM), and no solver finishes.
# (2) on_failure = "stop": the first run times out while the others wait in the queue (throttle
# 1): the study stops with the failure, the queued runs are cancelled and never start.
# usage: test_cancel.sh SMI_LUA SOLVER WORKDIR
SMI=$1 SOLVER=$2 W=$3
. "$(dirname "$0")/lib.sh"
(exec "$SMI" --quiet --allow-exec "$SOLVER" --out "$W/sl" "${FAST[@]}" "$STUDY" "$SOLVER" "$W/launches.txt" 20 12 60 \
   > "$W/run.txt" 2>&1) &
PID=$!
wait_for 30 'test "$(running_jobs)" -gt 0' || fail "no job started running: $(squeue)"
[ "$(live_jobs)" -eq 12 ] || fail "expected 12 live tasks, squeue: $(squeue -r)"
t0=$(date +%s.%N)
kill -INT $PID
rc=0; wait $PID || rc=$?
[ $rc -ne 0 ] || fail "the interrupted study exited 0"
grep -q "interrupted" "$W/run.txt" || fail "no 'interrupted' message: $(cat "$W/run.txt")"
wait_for 5 'test "$(live_jobs)" -eq 0' || fail "jobs still live 5 s after Ctrl-C: $(squeue -r)"
echo "stopped and cancelled in $(awk -v a="$t0" -v b="$(date +%s.%N)" 'BEGIN { printf "%.2f", b - a }') s"
states=$(squeue -h -r -t all -o '%j %T' | awk '/^smi-arr/{print $2}' | sort | uniq -c | tr '\n' ' ')
case "$states" in *CANCELLED*) ;; *) fail "our tasks are not CANCELLED: $states";; esac
sleep 1
for d in "$W"/sl/runs/arr/*/; do
  [ ! -e "$d/.smi/exit" ] || fail "a run finished although cancelled: $d"
done
echo "Ctrl-C ok: $states"

rc=0; STUDY_ARGS=first,stop study "$W/stop" "$W/stop-launches.txt" 0.2 6 2 "${FAST[@]}" --slurm-opt throttle=1 \
  > "$W/stop.txt" 2>&1 || rc=$?
[ $rc -eq 1 ] || fail "on_failure = 'stop': exit status $rc: $(cat "$W/stop.txt")"
grep -q "on_failure = 'stop'" "$W/stop.txt" || fail "no stop message: $(cat "$W/stop.txt")"
grep -q "timeout after 2 s" "$W/stop.txt" || fail "the failure is not named: $(cat "$W/stop.txt")"
wait_for 5 'test "$(live_jobs)" -eq 0' || fail "queued runs left after the stop: $(squeue -r)"
sleep 2
# Slurm may start the next task the moment the failing one's slot frees, before smi-lua has read
# its exit file (it is cancelled, or reported if it was seen running, as locally): at most that one.
[ "$(lines "$W/stop-launches.txt")" -le 2 ] || fail "$(lines "$W/stop-launches.txt") runs started after the stop"
job=$(awk '{sub(/_.*/, "", $1); print $1}' "$W/stop/runs/arr/.slurm/submissions.log" | head -1)
cancelled=$(squeue -h -r -t all -j "$job" -o %T | grep -c CANCELLED || true)
# (tasks that never left the queue show as one CANCELLED record of the array)
[ "$cancelled" -ge 1 ] || fail "the queued tasks were not cancelled: $(squeue -h -r -t all -j "$job")"
echo "ok: Ctrl-C cancelled everything; on_failure = 'stop' cancelled the 5 queued runs"
