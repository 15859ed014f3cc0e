# SPDX-License-Identifier: MIT
# Helpers of the library tests that make libraries as git repositories with tagged releases.
gitc() { git -C "$1" -c user.name=t -c user.email=t@example.org -c init.defaultBranch=main "${@:2}" > /dev/null 2>&1; }
# release DIR NAME VERSION REQUIRES_LUA [SOURCES_LUA] [TAG]: commit a release and tag it (TAG,
# default vVERSION); the description is $DESC, default "test library"
release() {
  mkdir -p "$1"
  [ -d "$1/.git" ] || gitc "$1" init -q
  printf 'name = "%s"\nversion = "%s"\ndescription = "%s"\nrequires = {%s}\nsources = {%s}\n' \
    "$2" "$3" "${DESC:-test library}" "$4" "${5:-}" > "$1/smi-lib.lua"
  printf 'return { version = "%s" }\n' "$3" > "$1/init.lua"
  gitc "$1" add -A && gitc "$1" commit -q -m "release $3" && gitc "$1" tag "${6:-v$3}"
}
