#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The literal-default check catches planted defaults (fixtures/literal_default.cpp: alpha's 0.1
# and loglik's 1e-300 beside their reads) and lets through stack indices, counts, strings, raw strings, comments and
# marked lines (fixtures/literal_allowed.cpp).
set -uo pipefail
here=$(cd "$(dirname "$0")" && pwd)
cd "$here"
fail=0
out=$(bash literal_defaults.sh --files fixtures/literal_default.cpp 2>&1); rc=$?
if [ $rc -ne 1 ] || ! grep -q 'fixtures/literal_default.cpp:4: 0.1 ' <<< "$out" || ! grep -q 'literal_default.cpp:5: 1e-300 ' <<< "$out"; then
  echo "FAIL: the planted default was not caught (rc $rc)"; echo "$out"; fail=1
fi
out=$(bash literal_defaults.sh --files fixtures/literal_allowed.cpp 2>&1); rc=$?
if [ $rc -ne 0 ]; then echo "FAIL: allowed literals were listed"; echo "$out"; fail=1; fi
[ $fail -eq 0 ] && echo "literal-default check: ok"
exit $fail
