#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# No literal default in the bindings: lists the numeric literals of bindings/**/*.cpp
# outside the allow-list of literal_defaults.awk; exits 1 when there is one. A default belongs
# in its option struct (a kernel's *Options, platform/core/defaults.hpp), read through the
# function's option schema (host/luax/option_schema.hpp).
#   literal_defaults.sh <source dir>          check bindings/ of the tree
#   literal_defaults.sh --files <file>...     check the given files (the checker's own test)
set -uo pipefail
here=$(cd "$(dirname "$0")" && pwd)
if [ "${1:-}" = --files ]; then
  shift
  files=("$@")
else
  root=${1:?usage: literal_defaults.sh <source dir> | --files <file>...}
  mapfile -t files < <(find "$root/bindings" -name '*.cpp' | sort)
fi
out=$(awk -f "$here/literal_defaults.awk" "${files[@]}")
rc=$?
if [ $rc -ne 0 ]; then
  echo "$out"
  echo "$(grep -c . <<< "$out") numeric literal(s) in bindings outside the allow-list: move a default into its option"
  echo "struct and read it through the schema, or mark a fixed value with // literal: <reason>"
  exit 1
fi
echo "no literal defaults in ${#files[@]} binding files"
