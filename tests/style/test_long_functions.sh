#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The long-function check catches what it must and accepts what it must (fixtures/):
#   - an 81-line C++ function and an 81-line Lua function without a reason fail the check;
#   - the same functions with a `long: <reason>` comment (above, or in the first lines) pass;
#   - a `long:` comment with no reason does not count;
#   - an 80-line function (at the limit) is not listed, nor are short ones, nor braces and
#     keywords inside strings, raw strings, comments and long brackets.
set -uo pipefail
here=$(cd "$(dirname "$0")" && pwd)
cd "$here"
check=(bash "$here/long_functions.sh")
fail=0
expect() {  # expect <rc> <grep pattern or -> <args...>
  local want=$1 pattern=$2; shift 2
  local out rc
  out=$("${check[@]}" "$@" 2>&1); rc=$?
  if [ $rc -ne "$want" ]; then echo "FAIL: $* exited $rc, expected $want"; echo "$out"; fail=1; return; fi
  if [ "$pattern" != - ] && ! grep -qE -- "$pattern" <<< "$out"; then
    echo "FAIL: $*: output lacks /$pattern/"; echo "$out"; fail=1
  fi
}
reject() {  # reject <pattern> <args...>: the output must not match
  local pattern=$1; shift
  local out; out=$("${check[@]}" "$@" 2>&1)
  if grep -qE -- "$pattern" <<< "$out"; then echo "FAIL: $*: output matches /$pattern/"; echo "$out"; fail=1; fi
}

expect 1 '^LONG +fixtures/long_unmarked.cpp:16 too_long \(81 lines\)' --files fixtures/long_unmarked.cpp
expect 1 '1 functions over 80 lines in 1 files: 0 with a reason, 0 allowed for now, 1 without' --files fixtures/long_unmarked.cpp
expect 0 '^ok +fixtures/long_marked.cpp:18 too_long \(81 lines' --all --files fixtures/long_marked.cpp
expect 1 '^LONG +fixtures/long_empty_reason.cpp:17 too_long' --files fixtures/long_empty_reason.cpp
expect 1 '^LONG +fixtures/long_unmarked.lua:86 too_long \(81 lines\)' --files fixtures/long_unmarked.lua
expect 0 '^ok +fixtures/long_marked.lua:86 too_long \(81 lines' --all --files fixtures/long_marked.lua
reject 'at_limit|short_one|Holder|get|<anonymous>| f ' --all --files fixtures/long_unmarked.cpp fixtures/long_unmarked.lua
# Every fixture together: exactly the two unmarked functions and the empty reason fail.
expect 1 '5 functions over 80 lines in 5 files: 2 with a reason, 0 allowed for now, 3 without' \
  --files fixtures/long_unmarked.cpp fixtures/long_marked.cpp fixtures/long_empty_reason.cpp \
          fixtures/long_unmarked.lua fixtures/long_marked.lua
[ $fail -eq 0 ] && echo "long_functions checker: all cases pass"
exit $fail
