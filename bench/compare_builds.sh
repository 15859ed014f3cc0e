#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Do two builds give the same outputs? For a change meant to leave behaviour alone (a refactoring):
# runs, with each build, the quick steering-column study, the quick bracket-plate study (when
# CalculiX is installed), `smi-lua doc --html` and the no-gradient calibration bench, then
# compares them with what legitimately differs removed (timings, dates, pids, the two source
# trees' paths, file hashes and sizes of the edited stdlib modules).
# usage: bench/compare_builds.sh OLD_SOURCE_TREE NEW_SOURCE_TREE OUT_DIR   (each tree built in build/)
set -euo pipefail
old=$1 new=$2 out=$3
rm -rf "$out"
for side in old new; do
  src=${!side}
  b=$src/build
  mkdir -p "$out/$side"
  ( cd "$src" && "$b/smi-lua" --quiet --allow-exec "$b/smi-column-fe" --out "$out/$side/study" scripts/steering_column.lua \
      --quick --solver "$b/smi-column-fe" > "$out/$side/study.log" 2>&1 )
  if [ -x /usr/bin/ccx ]; then  # the second example study, on CalculiX
    ( cd "$src" && "$b/smi-lua" --quiet --allow-exec /usr/bin/ccx --out "$out/$side/plate" scripts/bracket_plate.lua \
        --quick --solver /usr/bin/ccx > "$out/$side/plate.log" 2>&1 ) || true
  fi
  "$b/smi-lua" doc --html "$out/$side/html" > /dev/null 2>&1
  ( cd "$src" && "$b/smi-lua" --quiet --allow-read "$src/tests/lua" --out "$out/$side/hidden" bench/calibrate_hidden.lua \
      "$src/tests/lua/hidden_problem.lua" > "$out/$side/hidden.txt" 2>&1 )
done
/usr/bin/python3 - "$old" "$new" "$out" <<'PY'
import json, os, re, sys
old, new, out = sys.argv[1:]
runtime = re.compile(r'(time|seconds|elapsed|wall|cpu|started|finished|date|host|version|build|_at$|duration|eta|pid|size)', re.I)
def load(side, root, study='study'):
    text = open(f'{out}/{side}/{study}/results.json').read().replace(root, 'ROOT').replace(f'{out}/{side}', 'OUT')
    return json.loads(text)
def clean(x):
    if isinstance(x, dict): return {k: clean(v) for k, v in x.items() if not runtime.search(k)}
    if isinstance(x, list): return [clean(v) for v in x]
    if isinstance(x, str) and x.startswith('sha256:'): return 'HASH'
    return x
diffs = []
def walk(a, b, path=''):
    if type(a) != type(b): diffs.append(f'{path}: {str(a)[:80]} | {str(b)[:80]}'); return
    if isinstance(a, dict):
        for k in sorted(set(a) | set(b)):
            if k not in a or k not in b: diffs.append(f'{path}/{k}: only in {"new" if k not in a else "old"}')
            else: walk(a[k], b[k], f'{path}/{k}')
    elif isinstance(a, list):
        if len(a) != len(b): diffs.append(f'{path}: {len(a)} vs {len(b)} entries'); return
        for i, (u, v) in enumerate(zip(a, b)): walk(u, v, f'{path}[{i}]')
    elif a != b: diffs.append(f'{path}: {str(a)[:80]} | {str(b)[:80]}')
for study in ('study', 'plate'):
    if not os.path.exists(f'{out}/old/{study}/results.json'): continue
    diffs = []
    walk(clean(load('old', old, study)), clean(load('new', new, study)))
    print(f'{study}/results.json: {len(diffs)} difference(s)')
    for d in diffs: print('  ' + d)
def norm(text, root, side):
    text = text.replace(root, 'ROOT').replace(f'{out}/{side}', 'OUT')
    text = re.sub(r'pid \d+', 'pid P', text)
    text = re.sub(r'started [0-9: -]+UTC', 'started T', text)
    text = re.sub(r'"seconds": [0-9.e-]+', '"seconds": S', text)
    text = re.sub(r'sha256:[0-9a-f]+', 'H', text)
    return re.sub(r'"size": \d+', '"size": N', text)
pages = sorted(set(os.listdir(f'{out}/old/html')) | set(os.listdir(f'{out}/new/html')))
changed = []
for p in pages:
    if not p.endswith('.html'): continue
    try: a = norm(open(f'{out}/old/html/{p}').read(), old, 'old'); b = norm(open(f'{out}/new/html/{p}').read(), new, 'new')
    except FileNotFoundError: changed.append(p + ' (only in one)'); continue
    if a != b: changed.append(p)
print(f'reference pages: {len(changed)} differ' + (': ' + ', '.join(changed) if changed else ''))
def bench(side):
    return [l for l in open(f'{out}/{side}/hidden.txt') if not re.search(r'cpu|load|time', l, re.I)]
print('calibration bench:', 'same' if bench('old') == bench('new') else 'differs')
PY
echo "study console: $(diff -q <(sed -E 's/[0-9.]+ s\b//g' "$out/old/study.log") <(sed -E 's/[0-9.]+ s\b//g' "$out/new/study.log") > /dev/null && echo same || echo differs)"
