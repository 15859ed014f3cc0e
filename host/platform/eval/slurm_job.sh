#!/bin/bash
# SPDX-License-Identifier: MIT
# smi-lua job wrapper: array task i runs the solver of line i+1 of the manifest ($1) in that
# folder, under smi-lua's own per-run timeout, and writes .smi/exit ("status timed_out seconds")
# atomically (rename) when the solver ends. That file, not the job's state, decides the outcome.
# The job is submitted with --export=NONE: nothing of the submitting shell (BASH_ENV, LD_*, PATH)
# reaches it; the solver gets exactly the variables smi-lua listed in $S/env, through env -i.
set -u
export PATH=/usr/local/bin:/usr/bin:/bin
i=${SLURM_ARRAY_TASK_ID:?smi-lua job wrapper: not an array task}
W=$(sed -n "$((i + 1))p" "$1")
S=$W/.smi
if [ -z "$W" ] || [ ! -f "$S/argv" ]; then echo "smi-lua job: no run folder for index $i in $1" >&2; exit 90; fi
# Every attempt (a requeue after a node failure too) starts clean: all but .smi goes, the inputs come back.
rm -f "$S/exit"
find "$W" -mindepth 1 -maxdepth 1 ! -name .smi -exec rm -rf {} +
cp -a "$S/input/." "$W/"
mapfile -d '' -t a < "$S/argv"     # program path, argv[0], arguments
mapfile -d '' -t e < "$S/env"      # NAME=value, the solver's whole environment
T=$(cat "$S/timeout")
cd "$W" || exit 91
t0=$(date +%s.%N)
if [ "$T" = 0 ]; then
  env -i "${e[@]}" /bin/bash --norc --noprofile -c 'exec -a "$0" "$@"' "${a[1]}" "${a[0]}" "${a[@]:2}" < /dev/null > stdout.log 2> stderr.log
else
  timeout -k 2 "$T" env -i "${e[@]}" /bin/bash --norc --noprofile -c 'exec -a "$0" "$@"' "${a[1]}" "${a[0]}" "${a[@]:2}" < /dev/null > stdout.log 2> stderr.log
fi
rc=$?
t1=$(date +%s.%N)
read -r to secs < <(awk -v a="$t0" -v b="$t1" -v T="$T" -v rc="$rc" \
  'BEGIN { d = b - a; print ((T > 0 && (rc == 124 || rc == 137) && d >= T - 0.05) ? 1 : 0), d }')
printf '%d %d %s\n' "$rc" "$to" "$secs" > "$S/exit.$$" && mv -f "$S/exit.$$" "$S/exit"
