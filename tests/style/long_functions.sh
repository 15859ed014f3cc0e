#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Fails when a C++ or Lua function runs over 80 lines without a comment saying why it must be
# long (`// long: <reason>` or `-- long: <reason>`, in the comment block above the function or
# in its first lines). Functions in long_functions.allow (files other work owns, split there)
# are listed but do not fail the check.
#
#   bash tests/style/long_functions.sh [--all] [ROOT]      check the tree at ROOT (default: the repo)
#   bash tests/style/long_functions.sh --files F...        check only these files (the checker's own test)
#
# Trees that count: every *.cpp, *.hpp and *.lua under host/, bindings/, bench/, scripts/, stdlib/
# and tests/ (tests/style/fixtures excepted: they are long on purpose). Generated code (build
# folders) is not in these trees. Needs bash, find, sort and POSIX awk only (mawk on Debian).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
limit=${SMI_LONG_LIMIT:-80}
all=0
if [ "${1:-}" = --all ]; then all=1; shift; fi
if [ "${1:-}" = --files ]; then
  shift
  root=.
  files=("$@")
  allow=/dev/null
else
  root=$(cd "${1:-$here/../..}" && pwd)
  allow=$here/long_functions.allow
  cd "$root"
  mapfile -t files < <(find host bindings bench scripts stdlib tests \
                         -path tests/style/fixtures -prune -o \
                         -type f \( -name '*.cpp' -o -name '*.hpp' -o -name '*.lua' \) -print | LC_ALL=C sort)
fi
[ ${#files[@]} -gt 0 ] || { echo "long_functions: no files to check under $root" >&2; exit 2; }

# One awk process per file: FILENAME-keyed state resets cleanly and a broken file names itself.
found=$(for f in "${files[@]}"; do awk -v limit="$limit" -f "$here/long_functions.awk" "$f"; done)

# Allow-list lines: "path name   # who splits it"; blank lines and comments ignored.
allowed() {
  local path=$1 name=$2
  grep -v '^[[:space:]]*#' "$allow" | awk -v p="$path" -v n="$name" '$1 == p && $2 == n { hit = 1 } END { exit !hit }'
}

missing=0 reasoned=0 pending=0
while read -r status where name lines; do
  [ -n "${status:-}" ] || continue
  path=${where%:*}
  if [ "$status" = reasoned ]; then
    reasoned=$((reasoned + 1))
    [ $all = 1 ] && echo "ok       $where $name ($lines lines, has a long: reason)"
  elif allowed "$path" "$name"; then
    pending=$((pending + 1))
    echo "pending  $where $name ($lines lines, in long_functions.allow)"
  else
    missing=$((missing + 1))
    echo "LONG     $where $name ($lines lines): split it by what it does, or say why it must be long" \
         "with a '// long: <reason>' (C++) or '-- long: <reason>' (Lua) comment just above it"
  fi
done <<< "$found"

echo "long_functions: $((missing + reasoned + pending)) functions over $limit lines in ${#files[@]} files:" \
     "$reasoned with a reason, $pending allowed for now, $missing without a reason"
[ $missing -eq 0 ]
