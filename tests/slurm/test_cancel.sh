#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# (1) Ctrl-C while runs are queued and running on Slurm: smi-lua stops promptly, one scancel takes
# every job of the study out of the queue (running ones get TERM), and no solver finishes.
# (2) on_failure = "stop": the first run times out while the others wait in the queue (throttle
# 1): the study stops with the failure, the queued runs are cancelled and never start.
# usage: test_cancel.sh SMI_LUA SOLVER WORKDIR
SMI=$1 SOLVER=$2 W=$3
. "$(dirname "$0")/lib.sh"
# The same for SIGTERM (what Slurm, timeout and systemd send to a study running in a job itself):
# it stops like Ctrl-C, so the one scancel runs too (exit 128 + 15).
interrupt() {
  local sig=$1 out=$W/$2
  (exec "$SMI" --quiet --allow-exec "$SOLVER" --out "$out" "${FAST[@]}" "$STUDY" "$SOLVER" "$W/launches-$2.txt" 20 12 60 \
     > "$W/run-$2.txt" 2>&1) &
  local pid=$!
  wait_for 30 'test "$(running_jobs)" -gt 0' || fail "$sig: no job started running: $(squeue)"
  [ "$(live_jobs)" -eq 12 ] || fail "$sig: expected 12 live tasks, squeue: $(squeue -r)"
  local t0; t0=$(date +%s.%N)
  kill -"$sig" $pid
  local rc=0; wait $pid || rc=$?
  [ $rc -ne 0 ] || fail "$sig: the interrupted study exited 0"
  if [ "$sig" = TERM ]; then [ $rc -eq 143 ] || fail "SIGTERM: exit status $rc, expected 143"; fi
  grep -q "interrupted" "$W/run-$2.txt" || fail "$sig: no 'interrupted' message: $(cat "$W/run-$2.txt")"
  wait_for 5 'test "$(live_jobs)" -eq 0' || fail "$sig: jobs still live 5 s after the signal: $(squeue -r)"
  echo "$sig: stopped and cancelled in $(awk -v a="$t0" -v b="$(date +%s.%N)" 'BEGIN { printf "%.2f", b - a }') s"
  local states
  states=$(squeue -h -r -t all -o '%j %T' | awk '/^smi-arr/{print $2}' | sort | uniq -c | tr '\n' ' ')
  case "$states" in *CANCELLED*) ;; *) fail "$sig: our tasks are not CANCELLED: $states";; esac
  sleep 1
  for d in "$out"/runs/arr/*/; do
    [ ! -e "$d/.smi/exit" ] || fail "$sig: a run finished although cancelled: $d"
  done
  echo "$sig ok: $states"
}
interrupt INT sl
interrupt TERM sl-term

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
echo "ok: Ctrl-C and SIGTERM cancelled everything; on_failure = 'stop' cancelled the 5 queued runs"
