#!/usr/bin/env bash
# The node of a running job is set DOWN: Slurm requeues the job (sbatch --requeue), the run
# starts again in a clean folder, and it does not count as a failed attempt of the run (one
# launch for the evaluator, one submission, two solver starts, the right number).
# usage: test_node_down.sh SMI_LUA SOLVER WORKDIR
SMI=$1 SOLVER=$2 W=$3
. "$(dirname "$0")/lib.sh"
NODE=$(sinfo -h -o %N | head -1)
trap 'scontrol update nodename="$NODE" state=resume 2>/dev/null; scancel_ours' EXIT
reference 4 1 60
(exec "$SMI" --quiet --allow-exec "$SOLVER" --out "$W/sl" "${FAST[@]}" "$STUDY" "$SOLVER" "$W/launches.txt" 4 1 60 \
   > "$W/slurm.txt" 2>&1) &
PID=$!
wait_for 30 test "$(lines "$W/launches.txt")" -ge 1 || fail "the run did not start"
scontrol update nodename="$NODE" state=down reason=smi-test
sleep 1
scontrol update nodename="$NODE" state=resume
wait $PID || fail "the study failed: $(cat "$W/slurm.txt")"
diff "$W/local.txt" "$W/slurm.txt" || fail "results differ after the requeue"
[ "$(lines "$W/launches.txt")" -eq 2 ] || fail "the solver started $(lines "$W/launches.txt") times, expected 2 (requeue)"
no_double_submission "$W/sl" 2
echo "ok: requeued after the node went down, counted once"
