#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# cmake/check_includes.cmake on a copy of the tree: passes as it is, then fails on planted
# forbidden includes with one line per violation naming file, line and the rule broken.
set -euo pipefail
src=${SMI_SOURCE_DIR:?set SMI_SOURCE_DIR to the source tree}
cmake=${CMAKE:-cmake}
check=$src/cmake/check_includes.cmake
work=$(mktemp -d "${TMPDIR:-/tmp}/include-check.XXXXXX")
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*"; exit 1; }

mkdir -p "$work/tree/tests"
cp -r "$src/host" "$src/bindings" "$work/tree/"
cp -r "$src/tests/kernels" "$src/tests/platform" "$work/tree/tests/"

# 1. The copy as it is passes (so the failures below come from the plants, not the tree).
"$cmake" -DROOT="$work/tree" -DSTAMP="$work/stamp" -P "$check" >"$work/clean.log" 2>&1 ||
  { cat "$work/clean.log"; fail "the unchanged tree fails the check"; }
[[ -f $work/stamp ]] || fail "a passing check writes no stamp"

# 2. Plants: a line 1 include in each file below (each rule once), then the check must fail.
plant() { sed -i "1i $2" "$work/tree/$1"; }
plant bindings/stats/args.cpp '#include "vm/limits.hpp"'
plant host/kernels/stats/kde.cpp '#include <lua.hpp>'
plant host/platform/core/rng.cpp '#include "luax/luax.hpp"'
plant host/kernels/stats/ecdf.cpp '#include "kernels/surrogate/kriging.hpp"'
plant host/vm/limits.cpp '#include "bindings/modules.hpp"'
plant host/sandbox/sandbox_files.cpp '#include "vm/limits.hpp"'   # the old vm <-> sandbox cycle
plant host/repl/printer.cpp '#include "stats/kde.hpp"'    # the old, unprefixed spelling
mkdir -p "$work/tree/tests/kernels/stats"
plant host/app/runtime.cpp '#include "bindings/modules.hpp"'   # the old arrow back up the tree
plant host/cli/commands_doc.cpp '#include "bindings/doc.hpp"'  # a second composition root
printf '// fixture\n#include <vector>\n#include "app/runtime.hpp"\n' >"$work/tree/tests/kernels/stats/test_planted.cpp"

if "$cmake" -DROOT="$work/tree" -P "$check" >"$work/planted.log" 2>&1; then
  cat "$work/planted.log"; fail "the check passed with forbidden includes planted"
fi
expect() {
  grep -qF -- "$1" "$work/planted.log" || { cat "$work/planted.log"; fail "no report: $1"; }
}
expect 'bindings/stats/args.cpp:1: #include "vm/limits.hpp" -- bindings see only platform, kernels, luax and bindings'
expect 'host/kernels/stats/kde.cpp:1: #include <lua.hpp> -- platform and kernels see only the areas they link'
expect 'host/platform/core/rng.cpp:1: #include "luax/luax.hpp" -- platform and kernels see only the areas they link'
expect 'host/kernels/stats/ecdf.cpp:1: #include "kernels/surrogate/kriging.hpp" -- platform and kernels see only the areas they link (platform/core'
expect 'host/vm/limits.cpp:1: #include "bindings/modules.hpp" -- vm sees only platform, kernels, luax and vm (no bindings'
expect 'host/sandbox/sandbox_files.cpp:1: #include "vm/limits.hpp" -- sandbox sees only platform, kernels, luax and sandbox'
expect 'host/repl/printer.cpp:1: #include "stats/kde.hpp" -- every project include names its layer first'
expect 'tests/kernels/stats/test_planted.cpp:3: #include "app/runtime.hpp" -- platform and kernels see only the areas they link'
expect 'host/app/runtime.cpp:1: #include "bindings/modules.hpp" -- app sees platform, kernels, luax, vm, sandbox and app; never bindings'
expect 'host/cli/commands_doc.cpp:1: #include "bindings/doc.hpp" -- in host/, only cli/bindings_root.cpp (the composition root) includes bindings/'
expect '10 forbidden include(s)'
n=$(grep -c ' -- ' "$work/planted.log")
[[ $n -eq 10 ]] || { cat "$work/planted.log"; fail "expected 10 reports, got $n"; }

# 3. A layer table with a cycle is refused (vm would see app, which sees vm).
sed 's/^set(SEES_vm \${_kernels} luax)$/set(SEES_vm ${_kernels} luax app)/' "$check" >"$work/cyclic.cmake"
cp "$src/cmake/source_lines.cmake" "$work/"  # the modified copy includes its helper from beside it
grep -q 'luax app)' "$work/cyclic.cmake" || fail "could not make the cyclic table (SEES_vm changed?)"
if "$cmake" -DROOT="$src" -P "$work/cyclic.cmake" >"$work/cyclic.log" 2>&1; then fail "a cyclic layer table passed"; fi
grep -q 'vm sees app, which is not below it' "$work/cyclic.log" || { cat "$work/cyclic.log"; fail "no cycle report"; }
echo "ok: include check passes the tree and reports 10 planted forbidden includes and a cyclic table"
