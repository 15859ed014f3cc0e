#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# cmake/check_namespaces.cmake on a copy of host/ and bindings/: passes as they are, then fails on
# planted namespaces outside their folder's with one line per violation naming file, line and rule.
set -euo pipefail
src=${SMI_SOURCE_DIR:?set SMI_SOURCE_DIR to the source tree}
cmake=${CMAKE:-cmake}
check=$src/cmake/check_namespaces.cmake
work=$(mktemp -d "${TMPDIR:-/tmp}/namespace-check.XXXXXX")
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*"; exit 1; }

mkdir -p "$work/tree"
cp -r "$src/host" "$src/bindings" "$work/tree/"

"$cmake" -DROOT="$work/tree" -P "$check" >"$work/clean.log" 2>&1 ||
  { cat "$work/clean.log"; fail "the unchanged tree fails the check"; }

# Plants: the old flat stats namespace, the old surrogate family namespace, core opening an area's.
grep -q '^namespace smi::stats {' "$work/tree/host/kernels/stats/ecdf.cpp" || fail "ecdf.cpp opens no smi::stats (moved?)"
sed -i '0,/^namespace smi::stats {/s//namespace smi {/' "$work/tree/host/kernels/stats/ecdf.cpp"
sed -i '1i namespace smi::kriging { void planted(); }' "$work/tree/host/kernels/surrogate/delta.cpp"
sed -i '1i namespace smi::stats::detail { void planted(); }' "$work/tree/host/platform/core/rng.cpp"
# The Runtime back in the VM's namespace (it lives in host/app/), and a binding outside smi::bind.
sed -i '1i namespace smi::vm { class Runtime; }' "$work/tree/host/app/runtime.hpp"
sed -i '1i namespace smi::stats { void planted(); }' "$work/tree/bindings/stats/args.cpp"

if "$cmake" -DROOT="$work/tree" -P "$check" >"$work/planted.log" 2>&1; then
  cat "$work/planted.log"; fail "the check passed with planted namespaces"
fi
expect() {
  grep -qF -- "$1" "$work/planted.log" || { cat "$work/planted.log"; fail "no report: $1"; }
}
expect ': namespace smi -- a file in host/kernels/stats/ lives in smi::stats'
expect 'host/kernels/surrogate/delta.cpp:1: namespace smi::kriging -- a file in host/kernels/surrogate/ lives in smi::surrogate'
expect 'host/app/runtime.hpp:1: namespace smi::vm -- a file in host/app/ lives in smi::app'
expect 'bindings/stats/args.cpp:1: namespace smi::stats -- a file in bindings/ lives in smi::bind'
expect 'host/platform/core/rng.cpp:1: namespace smi::stats::detail -- core is the shared vocabulary in smi'
n=$(grep -c ' -- ' "$work/planted.log")
[[ $n -eq 5 ]] || { cat "$work/planted.log"; fail "expected 5 reports, got $n"; }
echo "ok: namespace check passes host/ and bindings/ and reports 5 planted namespaces"
