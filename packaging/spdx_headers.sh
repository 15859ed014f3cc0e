#!/bin/bash
# The licence tag of every source file: "SPDX-License-Identifier: MIT" in the file's own comment
# syntax, on its first line (on the second after a "#!" line). Source files: the C++ (.cpp .hpp .h
# .inc), Lua, shell, Python, awk and CMake files git tracks, and .ci/setup and .ci/run. Test
# fixtures (tests/**/fixtures/) are data whose line numbers the tests assert: they keep their bytes.
#   packaging/spdx_headers.sh [ROOT]           add the tag where it is missing (idempotent)
#   packaging/spdx_headers.sh --check [ROOT]   list the files without it; exit 1 if any
set -euo pipefail
check=0
if [ "${1:-}" = --check ]; then check=1; shift; fi
root=${1:-$(cd "$(dirname "$0")/.." && pwd)}
cd "$root"
tag="SPDX-License-Identifier: MIT"

comment_for() {
  case "$1" in
    *.cpp | *.hpp | *.h | *.inc) echo "//" ;;
    *.lua) echo "--" ;;
    *.sh | *.py | *.awk | *.cmake | */CMakeLists.txt | CMakeLists.txt | .ci/setup | .ci/run) echo "#" ;;
  esac
}

# The files git tracks; in a tree without git (an unpacked source archive), every file.
source_files() {
  if git rev-parse --is-inside-work-tree > /dev/null 2>&1; then
    git ls-files -- '*.cpp' '*.hpp' '*.h' '*.inc' '*.lua' '*.sh' '*.py' '*.awk' '*.cmake' \
                    'CMakeLists.txt' '*/CMakeLists.txt' .ci/setup .ci/run
  else
    find . -path ./.git -prune -o -type f -print | sed 's|^\./||' | grep -v '^build'
  fi
}

missing=0
while IFS= read -r f; do
  [ -f "$f" ] || continue
  c=$(comment_for "$f")
  [ -n "$c" ] || continue
  head -n 3 "$f" | grep -qF "$tag" && continue
  if [ $check = 1 ]; then echo "no licence tag: $f"; missing=$((missing + 1)); continue; fi
  if head -n 1 "$f" | grep -q '^#!'; then
    { head -n 1 "$f"; echo "$c $tag"; tail -n +2 "$f"; } > "$f.spdx"
  else
    { echo "$c $tag"; cat "$f"; } > "$f.spdx"
  fi
  chmod --reference="$f" "$f.spdx" && mv "$f.spdx" "$f"
done < <(source_files | grep -v '/fixtures/')
if [ $check = 1 ] && [ $missing -gt 0 ]; then
  echo "$missing files without \"$tag\": run bash packaging/spdx_headers.sh"
  exit 1
fi
exit 0
