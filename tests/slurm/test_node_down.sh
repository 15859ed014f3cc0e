#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The node of a running job is set DOWN: Slurm requeues the job (sbatch --requeue), the run
# starts again in a clean folder, and it does not count as a failed attempt of the run (one
# launch for the evaluator, one submission, two solver starts, the right number).
# usage: test_node_down.sh SMI_LUA SOLVER WORKDIR
SMI=$1 SOLVER=$2 W=$3
. "$(dirname "$0")/lib.sh"
NODE=$(sinfo -h -o %N | head -1)
trap 'scontrol update nodename="$NODE" state=resume 2>/dev/null || true; scancel_ours' EXIT
STUDY_ARGS=nohang
reference 4 1 60
(exec "$SMI" --quiet --allow-exec "$SOLVER" --out "$W/sl" "${FAST[@]}" "$STUDY" "$SOLVER" "$W/launches.txt" 4 1 60 nohang \
   > "$W/slurm.txt" 2>&1) &
PID=$!
wait_for 30 'test "$(lines "$W/launches.txt")" -ge 1' || fail "the run did not start"
scontrol update nodename="$NODE" state=down reason=smi-test
# ReturnToService=2 brings the node back when its slurmd registers again; resume it if not.
sleep 1
case "$(sinfo -h -n "$NODE" -o %T)" in down*|drain*) scontrol update nodename="$NODE" state=resume;; esac
wait $PID || fail "the study failed: $(cat "$W/slurm.txt")"
diff "$W/local.txt" "$W/slurm.txt" || fail "results differ after the requeue"
starts=$(awk '$2 == "0.25"' "$W/launches.txt" | wc -l)
[ "$starts" -eq 2 ] || fail "the solver started $starts times for the run, expected 2 (requeue): $(cat "$W/launches.txt")"
grep -q "^row 1 ok" "$W/slurm.txt" || fail "the requeued run did not succeed: $(cat "$W/slurm.txt")"
no_double_submission "$W/sl" 2
echo "ok: requeued after the node went down, counted once"
