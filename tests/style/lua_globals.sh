#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# No undefined globals in the Lua the project ships (stdlib/ and scripts/): every global a chunk
# reads or writes (luac's GETTABUP/SETTABUP on _ENV) must be one the sandbox gives a script (the
# Lua base library and `smi`). A misspelt local or a forgotten `local` reads or makes a global,
# which Lua allows silently: nil where a value was meant, or state shared between modules.
# Then a planted file with an undefined read must fail the same check.
#   lua_globals.sh SOURCE_DIR LUAC
set -u
src=$1 luac=${2:-luac5.4}
known=" _G _VERSION arg assert collectgarbage coroutine debug dofile error getmetatable io ipairs load loadfile
 math next os package pairs pcall print rawequal rawget rawlen rawset require select setmetatable smi string
 table tonumber tostring type utf8 warn xpcall "
known=$(echo $known | tr "\n" " ")
known=" $known "

# check FILE...: prints "file:line: global NAME (read|written)" for each unknown one; status 1 if any.
check() {
  local bad=0 f
  for f in "$@"; do
    while read -r line op name; do
      case "$known" in *" $name "*) continue ;; esac
      echo "$f:$line: undefined global '$name' ($([ "$op" = SETTABUP ] && echo written || echo read))"
      bad=1
    done < <("$luac" -p -l "$f" | sed -nE 's/^[[:space:]]*[0-9]+[[:space:]]+\[([0-9]+)\][[:space:]]+(GETTABUP|SETTABUP).*_ENV "([A-Za-z_][A-Za-z0-9_]*)".*/\1 \2 \3/p')
  done
  return $bad
}

mapfile -t files < <(find "$src/stdlib" "$src/scripts" -name '*.lua' | sort)
[ "${#files[@]}" -gt 20 ] || { echo "FAIL: found only ${#files[@]} Lua files under $src"; exit 1; }
out=$(check "${files[@]}") || { echo "$out"; echo "FAIL: undefined globals (make them local, or fix the name)"; exit 1; }

work=$(mktemp -d "${TMPDIR:-/tmp}/lua-globals.XXXXXX")
trap 'rm -rf "$work"' EXIT
printf 'local M = {}\nlocal BADGE_TABLE = {}\nM.BADGE = BADGE\nreturn M\n' > "$work/planted.lua"
planted=$(check "$work/planted.lua") && { echo "FAIL: the planted undefined global passed the check"; exit 1; }
grep -q "planted.lua:3: undefined global 'BADGE' (read)" <<<"$planted" || { echo "$planted"; echo "FAIL: wrong report"; exit 1; }
echo "ok: ${#files[@]} Lua files use only the sandbox's globals; a planted undefined read is reported"
