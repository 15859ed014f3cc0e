#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The same study on the local executor and on Slurm prints the same numbers and the same failure
# records (a timeout, an exit status); 11 runs under MaxArraySize 8 become two throttled arrays;
# a second run reuses every stored success and submits only the two failures again.
# usage: test_same_results.sh SMI_LUA SOLVER WORKDIR
SMI=$1 SOLVER=$2 W=$3
. "$(dirname "$0")/lib.sh"
reference 0.3 11 3
study "$W/sl" "$W/sl-launches.txt" 0.3 11 3 "${FAST[@]}" --slurm-opt throttle=3 > "$W/slurm.txt" 2>&1 ||
  fail "slurm run: $(cat "$W/slurm.txt")"
diff "$W/local.txt" "$W/slurm.txt" || fail "the Slurm run differs from the local one (above)"
grep -q "timeout after 3 s" "$W/slurm.txt" || fail "no timeout record: $(cat "$W/slurm.txt")"
no_double_submission "$W/sl" 12
arrays=$(awk '{sub(/_.*/, "", $1); print $1}' "$W/sl/runs/arr/.slurm/submissions.log" | sort -u)
[ "$(echo "$arrays" | wc -l)" -eq 2 ] || fail "11 runs under MaxArraySize 8 should be 2 arrays, got: $arrays"
for a in $arrays; do
  info=$(scontrol show job "$a")
  case "$info" in *ArrayTaskThrottle=3*) ;; *) fail "array $a is not throttled to 3: $info";; esac
done
study "$W/sl" "$W/sl-launches.txt" 0.3 11 3 "${FAST[@]}" > "$W/again.txt" 2>&1 || fail "second run: $(cat "$W/again.txt")"
# failures are run again (reuse_failed = false), the 10 successes are reused
grep -q "launched=2 reused=10" "$W/again.txt" || fail "second run: $(tail -1 "$W/again.txt")"
diff "$W/local.txt" <(sed 's/^launched=2 reused=10$/launched=12 reused=0/' "$W/again.txt") || fail "second run differs"
# the job script and exact sbatch lines with the cost plan, launching nothing
study "$W/dry" "$W/dry-launches.txt" 0.3 11 3 "${FAST[@]}" --slurm-opt partition=debug --dry-run > "$W/dry.txt" 2>&1 ||
  fail "dry run: $(cat "$W/dry.txt")"
grep -q -- "sbatch --parsable --job-name=smi-arr-TOKEN-1 --array=0-2%50 " "$W/dry.txt" || fail "dry run: $(cat "$W/dry.txt")"
grep -q -- "--partition=debug --time=2" "$W/dry.txt" || fail "dry run lacks the options: $(cat "$W/dry.txt")"
grep -q "cost plan: 11 runs x 1 CPU x 2 min limit" "$W/dry.txt" || fail "dry run lacks the cost plan: $(cat "$W/dry.txt")"
grep -q 'timeout -k 2 "$T"' "$W/dry.txt" || fail "dry run lacks the job script"
[ ! -e "$W/dry-launches.txt" ] || fail "the dry run launched solver runs"
echo "ok: same results, 2 arrays throttled, nothing submitted twice"
