#!/bin/bash
# SPDX-License-Identifier: MIT
# What the code, the tests, the scripts (the report's text) and the documents cite is in the
# repository, and they carry no development history:
#  - every specification cited by path (docs/spec/<name>.md, or shared/spec/<name>.md outside the
#    repository) exists in docs/spec/;
#  - no citation of a file outside the repository: a scratch worktree (.../wt/...), the shared
#    folder (shared/<name>.md), or an upper-case document (IMPROVE_API.md) that no tracked file is;
#  - no tracker references ("issue 16", "issues 3 and 4"): the text says what, not when.
# Fails naming the citing file and line.
#   test_spec_refs.sh SOURCE_DIR
set -u
cd "$1" || exit 1
failed=0
where=(host bindings stdlib scripts tests bench docs README.md CMakeLists.txt cmake)
kinds=(--include='*.cpp' --include='*.hpp' --include='*.lua' --include='*.md' --include='*.txt' --include='*.sh'
       --include='*.py' --include='*.cmake' --include='CMakeLists.txt' --include='*.awk')
self=tests/packaging/test_spec_refs.sh
while IFS=: read -r file line ref; do
  if [ ! -f "$ref" ]; then echo "FAIL: $file:$line cites $ref, which is not in the repository"; failed=1; fi
done < <(grep -rnoE '(docs|shared)/spec/[A-Za-z0-9_-]+\.md' "${where[@]}" "${kinds[@]}" 2>/dev/null)
while IFS=: read -r file line ref; do
  [ "$file" = "$self" ] && continue
  echo "FAIL: $file:$line cites $ref, which is outside the repository"; failed=1
done < <(grep -rnoE '/wt/[A-Za-z0-9_./-]+|(^|[^A-Za-z0-9_./-])shared/[A-Za-z0-9_-]+\.md' "${where[@]}" "${kinds[@]}" 2>/dev/null)
# upper-case document names (README.md, CHANGES.md): a file of that name must be tracked; "usage:"
# lines name an argument (OUT.md), not a file
names=$(git ls-files 2>/dev/null | sed 's|.*/||' | sort -u)
[ -n "$names" ] || names=$(find . -type f -not -path './build*' -not -path './.git/*' | sed 's|.*/||' | sort -u)
while IFS=: read -r file line ref; do
  [ "$file" = "$self" ] && continue
  sed -n "${line}p" "$file" | grep -q 'usage:' && continue
  grep -qxF "$ref" <<<"$names" || { echo "FAIL: $file:$line cites $ref, which is not in the repository"; failed=1; }
done < <(grep -rnoE '\b[A-Z][A-Z_]+\.md\b' "${where[@]}" "${kinds[@]}" 2>/dev/null)
while IFS= read -r hit; do
  echo "FAIL: $hit: a tracker reference; say what the code does and why instead"; failed=1
done < <(grep -rnE '\b[Ii]ssues? #?[0-9]+' "${where[@]}" "${kinds[@]}" 2>/dev/null | grep -v "^$self:")
count=$(ls docs/spec/*.md 2>/dev/null | wc -l)
[ "$count" -ge 2 ] || { echo "FAIL: docs/spec/ holds $count specifications"; failed=1; }
[ $failed = 0 ] && echo "ok   every cited file is in the repository ($count specifications), no tracker references"
exit $failed
