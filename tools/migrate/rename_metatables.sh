#!/usr/bin/env bash
# One naming scheme for the metatables users see: all lowercase, the name of the smi function or
# module that makes the value (smi.vec, smi.mat, smi.rng, smi.dist, smi.verdict, smi.decision
# already were): smi.Kriging -> smi.kriging, smi.Model -> smi.model,
# smi.ScreenResult -> smi.screen_result. Rewrites code, docs, tests and stdlib alike (type
# names appear in error messages "smi.kriging expected", doc names "smi.kriging:predict" and
# tostring). Idempotent: the new names are not matched again.
set -euo pipefail
cd "$(git -C "$(dirname "$0")" rev-parse --show-toplevel)"
git ls-files -z --cached --others --exclude-standard -- \
    '*.cpp' '*.hpp' '*.h' '*.inc' '*.lua' '*.md' '*.sh' '*.py' '*.txt' '*.html' '*.json' \
  | grep -zv '^tools/migrate/' \
  | xargs -0 grep -lZE '\bsmi\.(Kriging|Model|ScreenResult)\b' 2>/dev/null \
  | xargs -0 -r sed -i -E 's/\bsmi\.Kriging\b/smi.kriging/g; s/\bsmi\.Model\b/smi.model/g; s/\bsmi\.ScreenResult\b/smi.screen_result/g' \
  || true
# Nothing of the old names may be left (a file type not listed above would show here).
if git grep --untracked -lE '\bsmi\.(Kriging|Model|ScreenResult)\b' -- ':!tools/migrate' ':!build*' ':!tmp'; then
  echo "rename_metatables.sh: old metatable names left in the files above" >&2
  exit 1
fi
