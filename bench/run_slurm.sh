#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The Slurm executor against the local one on the quick steering-column study: wall time and
# overhead per solver run, the scheduler load (sbatch/squeue/sacct/scancel calls per minute,
# counted by logging shims put in front of the real tools with --slurm-opt bin_dir=), and whether
# results.json carries the same numbers. Needs root (starts tests/slurm/start-slurm.sh's cluster,
# MaxArraySize 8 there) and a Release build in build/. Writes bench/results/slurm.md.
# usage: bash bench/run_slurm.sh [BUILD_DIR]   (SLURM_OPTS: extra --slurm-opt flags, e.g. poll=1)
set -euo pipefail
cd "$(dirname "$0")/.."
B=${1:-build}
W=${TMPDIR:-/tmp}/smi-bench-slurm
rm -rf "$W"; mkdir -p "$W/shim"
bash tests/slurm/start-slurm.sh
for t in sbatch squeue sacct scancel scontrol; do
  real=$(command -v $t)
  printf '#!/bin/sh\necho "$(date +%%s.%%N) %s" >> %s/calls.log\nexec %s "$@"\n' "$t" "$W" "$real" > "$W/shim/$t"
  chmod +x "$W/shim/$t"
done
run() {  # run NAME [options]
  local name=$1; shift
  local t0; t0=$(date +%s.%N)
  "$B/smi-lua" --quiet --allow-exec "$B/smi-column-fe" --out "$W/$name" "$@" scripts/steering_column.lua --quick \
    --solver "$B/smi-column-fe" > "$W/$name.log" 2>&1
  echo "$(date +%s.%N) - $t0" | bc
}
t_local=$(run local)
opts=(--executor slurm --slurm-opt "bin_dir=$W/shim")
for o in ${SLURM_OPTS:-}; do opts+=(--slurm-opt "$o"); done
t_slurm=$(run slurm "${opts[@]}")
runs=$(cat "$W"/slurm/runs/*/.slurm/submissions.log | wc -l)
arrays=$(grep -c ' sbatch$' "$W/calls.log" || true)
python3 - "$W/local/results.json" "$W/slurm/results.json" > "$W/compare.txt" <<'PY'
import json, sys
# Left out: timings, provenance, and the decision matrix's overall rating, which weighs the
# measured solver run time (it differs between two local runs as well).
skip = ("seconds", "wall", "time", "provenance", "path", "out_dir", "date", "host", "overall")
def flat(x, p=""):
    if isinstance(x, dict):
        for k, v in x.items():
            if not any(s in k for s in skip): yield from flat(v, p + "/" + k)
    elif isinstance(x, list):
        for i, v in enumerate(x): yield from flat(v, f"{p}[{i}]")
    elif isinstance(x, (int, float)) and not isinstance(x, bool):
        yield p, x
a, b = dict(flat(json.load(open(sys.argv[1])))), dict(flat(json.load(open(sys.argv[2]))))
diff = [k for k in a if k not in b or a[k] != b[k]] + [k for k in b if k not in a]
print(f"{len(a)} numbers compared, {len(diff)} differ" + ("".join(f"\n  {k}: {a.get(k)} vs {b.get(k)}" for k in diff[:20])))
PY
minutes=$(echo "$t_slurm / 60" | bc -l)
count() { grep -c " $1\$" "$W/calls.log" || true; }
{
  echo "# Slurm executor vs local: quick steering-column study"
  echo
  echo "Measured $(date -u +%Y-%m-%d) on $(nproc) cores, single-node Slurm $(slurmctld -V | awk '{print $2}') from tests/slurm/start-slurm.sh"
  echo "(scheduling loop every 1 s, MaxArraySize 8, OverSubscribe 4), executor options: defaults ${SLURM_OPTS:-} (poll 5 s -> 60 s)."
  echo
  echo "| | local | slurm |"
  echo "|---|---|---|"
  printf '| wall time | %.1f s | %.1f s |\n' "$t_local" "$t_slurm"
  echo "| solver runs | | $runs (in $arrays sbatch calls) |"
  printf '| overhead per run | | %.2f s |\n' "$(echo "($t_slurm - $t_local) / $runs" | bc -l)"
  echo
  echo "Scheduler load during the Slurm run ($(printf %.1f "$minutes") min):"
  echo
  echo "| command | calls | per minute |"
  echo "|---|---|---|"
  for c in sbatch squeue sacct scancel scontrol; do
    n=$(count $c); printf '| %s | %d | %.1f |\n' "$c" "$n" "$(echo "$n / $minutes" | bc -l)"
  done
  echo
  echo "results.json: $(cat "$W/compare.txt") (timings and the decision matrix's overall rating, which"
  echo "weighs measured run seconds, left out; they differ between two local runs too)."
} | tee bench/results/slurm.md
