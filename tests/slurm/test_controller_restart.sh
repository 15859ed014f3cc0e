#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# (1) slurmctld restarted while a study runs: the study rides it out (scheduler commands retry)
# and gives the local executor's numbers. (2) slurmctld stopped for good: the study stops with a
# message naming Slurm, finished runs stay in the store; once the controller is back a rerun
# reattaches and finishes, submitting nothing twice.
# usage: test_controller_restart.sh SMI_LUA SOLVER WORKDIR
SMI=$1 SOLVER=$2 W=$3
. "$(dirname "$0")/lib.sh"
ctld_pid() { awk '$1=="slurmctld"{print $2}' "$SLURM_DIR/pids" | tail -1; }
stop_ctld() { local p; p=$(ctld_pid); kill -TERM "$p"; for _ in $(seq 1 100); do kill -0 "$p" 2>/dev/null || return 0; sleep 0.1; done; kill -KILL "$p"; }
start_ctld() {
  slurmctld -D >> "$SLURM_DIR/log/slurmctld.out" 2>&1 &
  echo "slurmctld $!" >> "$SLURM_DIR/pids"
  wait_for 30 'sinfo -h >/dev/null 2>&1' || fail "slurmctld did not come back"
}
trap 'kill -0 "$(ctld_pid)" 2>/dev/null || start_ctld; scancel_ours' EXIT
STUDY_ARGS=nohang
reference 2 10 20

(exec "$SMI" --quiet --allow-exec "$SOLVER" --out "$W/a" "${FAST[@]}" --slurm-opt throttle=4 --slurm-opt down_after=60 \
   "$STUDY" "$SOLVER" "$W/a-launches.txt" 2 10 20 nohang > "$W/a.txt" 2>&1) &
PID=$!
wait_for 30 'test "$(running_jobs)" -gt 0' || fail "no job started running"
stop_ctld; sleep 3; start_ctld
wait $PID || fail "the study did not survive a controller restart: $(cat "$W/a.txt")"
diff <(grep -v '^launched=' "$W/local.txt") <(grep -v '^launched=' "$W/a.txt") || fail "results differ after the restart"
no_double_submission "$W/a" 11
echo "survived a controller restart"

(exec "$SMI" --quiet --allow-exec "$SOLVER" --out "$W/b" "${FAST[@]}" --slurm-opt throttle=4 --slurm-opt down_after=4 \
   "$STUDY" "$SOLVER" "$W/b-launches.txt" 2 10 20 nohang > "$W/b.txt" 2>&1) &
PID=$!
wait_for 30 'test "$(lines "$W/b-launches.txt")" -ge 4' || fail "no run started"
stop_ctld
rc=0; wait $PID || rc=$?
[ $rc -eq 1 ] || fail "the study went on without a controller (rc=$rc): $(cat "$W/b.txt")"
grep -q "Slurm is not answering" "$W/b.txt" || fail "unclear message: $(cat "$W/b.txt")"
grep -q "finished runs are stored" "$W/b.txt" || fail "the message does not say what was kept: $(cat "$W/b.txt")"
start_ctld
"$SMI" --quiet --allow-exec "$SOLVER" --out "$W/b" --executor slurm --dry-run "$STUDY" "$SOLVER" "$W/b-launches.txt" 2 10 20 \
  > "$W/b-dry.txt" 2>&1 || fail "dry run: $(cat "$W/b-dry.txt")"
stored=$(sed -n 's/.*(\([0-9]*\) found in the store).*/\1/p' "$W/b-dry.txt" | head -1)
[ "${stored:-0}" -ge 1 ] || fail "no finished run was kept: $(cat "$W/b-dry.txt")"
study "$W/b" "$W/b-launches.txt" 2 10 20 "${FAST[@]}" > "$W/b2.txt" 2>&1 || fail "rerun: $(cat "$W/b2.txt")"
diff <(grep -v '^launched=' "$W/local.txt") <(grep -v '^launched=' "$W/b2.txt") || fail "results differ after the rerun"
no_double_submission "$W/b" 11
echo "ok: stopped with a clear message ($stored runs kept), rerun reattached"
