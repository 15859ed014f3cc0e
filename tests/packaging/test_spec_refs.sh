#!/bin/bash
# Every specification the code, the tests, the scripts (the report's text) and the documents cite
# by path (docs/spec/<name>.md, or the old shared/spec/<name>.md outside the repository) exists in the
# repository. Fails naming the citing file and line.
#   test_spec_refs.sh SOURCE_DIR
set -u
cd "$1" || exit 1
failed=0
while IFS=: read -r file line ref; do
  if [ ! -f "$ref" ]; then echo "FAIL: $file:$line cites $ref, which is not in the repository"; failed=1; fi
done < <(grep -rnoE '(docs|shared)/spec/[A-Za-z0-9_-]+\.md' host bindings stdlib scripts tests bench docs README.md \
           --include='*.cpp' --include='*.hpp' --include='*.lua' --include='*.md' --include='*.txt' --include='*.sh' \
           --include='*.py' --include='*.cmake' --include='CMakeLists.txt' 2>/dev/null)
count=$(ls docs/spec/*.md 2>/dev/null | wc -l)
[ "$count" -ge 2 ] || { echo "FAIL: docs/spec/ holds $count specifications"; failed=1; }
[ $failed = 0 ] && echo "ok   every cited specification is in docs/spec/ ($count files)"
exit $failed
