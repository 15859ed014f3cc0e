# SPDX-License-Identifier: MIT
# Shared by the slurm tests: sourced with SMI, SOLVER and W (a fresh work folder) set.
# Polling is made fast here (poll 0.3 s backing off to 1 s, exit files waited for 2 s) so the
# tests take seconds; the defaults (5 s -> 60 s, 30 s) are for real clusters.
set -euo pipefail
STUDY=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/studies/array_study.lua
SLURM_DIR=${SMI_SLURM_DIR:-/var/tmp/smi-slurm}
FAST=(--executor slurm --slurm-opt poll=0.3 --slurm-opt poll_max=1 --slurm-opt exit_wait=2 --slurm-opt cmd_timeout=10)
rm -rf "$W"; mkdir -p "$W"
fail() { echo "FAIL: $*" >&2; exit 1; }
# study OUT LOG SLEEP N TIMEOUT [smi-lua options...]   (STUDY_ARGS: more study arguments)
study() {
  local out=$1 log=$2 sleep=$3 n=$4 timeout=$5; shift 5
  "$SMI" --quiet --allow-exec "$SOLVER" --out "$out" "$@" "$STUDY" "$SOLVER" "$log" "$sleep" "$n" "$timeout" ${STUDY_ARGS:-}
}
# the same study on the local executor: the reference every Slurm run must reproduce
reference() { study "$W/local" "$W/local-launches.txt" "$@" > "$W/local.txt" 2>&1 || fail "local run: $(cat "$W/local.txt")"; }
# our jobs still queued or running (by job name)
live_jobs() { squeue -h -r -t PENDING,RUNNING,CONFIGURING,COMPLETING,REQUEUED -o '%j %i' | grep -c '^smi-' || true; }
running_jobs() { squeue -h -r -t RUNNING -o '%j %i' | grep -c '^smi-' || true; }
wait_for() {  # wait_for SECONDS 'CONDITION' (evaluated anew each time)
  local t=$1; shift
  for _ in $(seq 1 $((t * 10))); do eval "$1" && return 0; sleep 0.1; done
  return 1
}
lines() { if [ -f "$1" ]; then wc -l < "$1" | tr -d ' '; else echo 0; fi; }
# no run key was submitted twice (the submission logs of every model under OUT)
no_double_submission() {
  local out=$1 want=$2 got dup
  got=$(cat "$out"/runs/*/.slurm/submissions.log | wc -l | tr -d ' ')
  dup=$(cat "$out"/runs/*/.slurm/submissions.log | awk '{print $2}' | sort | uniq -d | head -1)
  [ -z "$dup" ] || fail "run $dup was submitted twice: $(cat "$out"/runs/*/.slurm/submissions.log)"
  [ "$got" -eq "$want" ] || fail "$got array tasks submitted, expected $want"
}
scancel_ours() { local ids; ids=$(squeue -h -o "%j %F" | awk "/^smi-/{print \$2}" | sort -u); [ -z "$ids" ] || scancel $ids || true; }
trap scancel_ours EXIT
