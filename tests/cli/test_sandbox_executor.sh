#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The executor is the user's choice: a study's executor = {...} may only
# narrow what --executor/--slurm-opt allow. Slurm runs only with --executor slurm; partition,
# account, qos, time, mem, cpus and sbatch arguments only from --slurm-opt; sbatch arguments are
# read as sbatch reads them and held to an allow-list. Fake sbatch/scontrol first in PATH record
# any call: a refused study must not reach them. The solver's environment is a list
# (base variables + --allow-env), never the whole of smi-lua's.
source "$(dirname "$0")/lib.sh"

mkdir -p fakebin study
for t in sbatch scontrol squeue sacct scancel; do
  printf '#!/bin/sh\necho "%s $*" >> "%s/called"\necho 1\n' "$t" "$WORK" > fakebin/$t
done
chmod +x fakebin/*
export PATH="$WORK/fakebin:$PATH"
printf '#!/bin/sh\nenv > env.txt\necho "y = 1"\necho "seen=${SMI_TEST_SECRET:-none}"\n' > solver
chmod +x solver
cat > study/run.lua <<'LUA'
local spec, prog = ...
local exec = load("return " .. spec)()
local m = smi.model.command{name = "m", inputs = {"x"}, outputs = {"y"}, template_string = "x = {{x}}\n",
  command = {prog, "{deck}"}, version = "1.0", executor = exec,
  parse = function(dir, h) print(h.read("stdout.log"):match("seen=%S+")) ; return {y = h.regex("stdout.log", "y = (\\S+)")} end}
local Y, info = m:evaluate(smi.mat{{1}})
print("y=" .. Y.y[1])
LUA
called() { if [ -e "$WORK/called" ]; then bad "a Slurm command ran: $(cat "$WORK/called")"; rm -f "$WORK/called"; else ok; fi; }
S=("$SMI" --quiet --allow-exec "$WORK/solver" --out out)

# --- kind: the study cannot choose the cluster
run "kind=slurm without --executor" 1 "${S[@]}" study/run.lua '{kind = "slurm"}' "$WORK/solver"
has_err "executor option kind = 'slurm' comes from the study"
has_err "--executor slurm"
called
run "kind=slurm with a partition of its own" 1 "${S[@]}" study/run.lua '{kind = "slurm", partition = "big", mem = "500G"}' "$WORK/solver"
has_err "--executor slurm"
called
run "kind=local narrows --executor slurm" 0 "${S[@]}" --executor slurm study/run.lua '{kind = "local"}' "$WORK/solver"
has_out "y=1"
called
run "an unknown kind" 1 "${S[@]}" study/run.lua '{kind = "k8s"}' "$WORK/solver"
has_err "kind = 'k8s'"

# --- resources: only the command line's
D=("$SMI" --quiet --allow-exec "$WORK/solver" --out dry --dry-run --executor slurm --slurm-opt max_array=10)
for kv in 'partition = "big"' 'account = "other"' 'qos = "high"' 'time = "99:00:00"' 'mem = "500G"' 'cpus = 64'; do
  run "study sets $kv" 1 "${D[@]}" study/run.lua "{$kv}" "$WORK/solver"
  has_err "comes from the study"
  has_err "--slurm-opt"
done
called
run "a study repeating the command line's partition" 0 "${D[@]}" --slurm-opt partition=big study/run.lua '{partition = "big"}' "$WORK/solver"
has_out "--partition=big"
run "a study asking another partition than the command line" 1 "${D[@]}" --slurm-opt partition=big study/run.lua '{partition = "bigger"}' "$WORK/solver"
has_err "partition = 'bigger'"
run "throttle above the command line's" 1 "${D[@]}" study/run.lua '{throttle = 1000}' "$WORK/solver"
has_err "throttle = '1000'"
run "throttle below it" 0 "${D[@]}" study/run.lua '{throttle = 2}' "$WORK/solver"
has_out "%2"
run "max_array unbounded over a bound" 1 "${D[@]}" study/run.lua '{max_array = 0}' "$WORK/solver"
run "detach without --detach" 1 "${D[@]}" study/run.lua '{detach = true}' "$WORK/solver"
has_err "--detach"
run "bin_dir from the study" 1 "${D[@]}" study/run.lua '{bin_dir = "/tmp"}' "$WORK/solver"
has_err "bin_dir"

# --- sbatch arguments: the study's are refused, the command line's are parsed and allow-listed
for a in '-o/tmp/x' '-e/tmp/x' '-D/tmp' '-i/tmp/x' '--outp=/tmp/x' '--err=/tmp/x' '--chd=/tmp' '--wra=id' '-a0-9' '-Jx'; do
  run "study sbatch $a" 1 "${D[@]}" study/run.lua "{sbatch = {'$a'}}" "$WORK/solver"
  has_err "comes from the study"
  run "--slurm-opt sbatch=$a" 1 "${D[@]}" --slurm-opt "sbatch=$a" study/run.lua '{}' "$WORK/solver"
  has_err "$a"
done
run "--export from the command line" 1 "${D[@]}" --slurm-opt "sbatch=--export=ALL,BASH_ENV=$WORK/out/e" study/run.lua '{}' "$WORK/solver"
has_err "--export"
run "a bare word would become the job script" 1 "${D[@]}" --slurm-opt "sbatch=$WORK/evil.sh" study/run.lua '{}' "$WORK/solver"
has_err "job script"
run "an allowed sbatch argument" 0 "${D[@]}" --slurm-opt "sbatch=--gres=gpu:1 -Cavx2" study/run.lua '{}' "$WORK/solver"
has_out "--gres=gpu:1"
has_out "--export=NONE"
has_out "<job name>/job.sh"
called

# --- the solver's environment: a list, not an inheritance
export SMI_TEST_SECRET=hunter2
run "a variable not allowed does not reach the solver" 0 "${S[@]}" --out env1 study/run.lua '{}' "$WORK/solver"
has_out "seen=none"
if grep -rq hunter2 env1/runs 2>/dev/null; then bad "the secret reached a run folder"; else ok; fi
run "--allow-env passes it" 0 "${S[@]}" --out env2 --allow-env SMI_TEST_SECRET study/run.lua '{}' "$WORK/solver"
has_out "seen=hunter2"

finish
