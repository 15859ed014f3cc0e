#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# cmake/check_file_names.cmake on a copy of host/: passes as it is, then fails on an implementation
# file named after no header and on a header whose functions lost their same-named file.
set -euo pipefail
src=${SMI_SOURCE_DIR:?set SMI_SOURCE_DIR to the source tree}
cmake=${CMAKE:-cmake}
check=$src/cmake/check_file_names.cmake
work=$(mktemp -d "${TMPDIR:-/tmp}/file-names.XXXXXX")
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*"; exit 1; }

mkdir -p "$work/tree"
cp -r "$src/host" "$work/tree/"
"$cmake" -DROOT="$work/tree" -P "$check" >"$work/clean.log" 2>&1 ||
  { cat "$work/clean.log"; fail "the unchanged tree fails the check"; }

# Plants: Kriging's fit back under its old name; the Sobol' sequence's file under another name,
# which leaves doe.hpp's sobol functions with no doe_*.cpp once the LHS part is renamed too.
s=$work/tree/host/kernels/surrogate
mv "$s/kriging_fit.cpp" "$s/fit.cpp"
mv "$s/doe_sobol.cpp" "$s/sobol.cpp"
mv "$s/doe_lhs.cpp" "$s/lhs.cpp"
if "$cmake" -DROOT="$work/tree" -P "$check" >"$work/planted.log" 2>&1; then
  cat "$work/planted.log"; fail "the check passed with misnamed files"
fi
expect() { grep -qF -- "$1" "$work/planted.log" || { cat "$work/planted.log"; fail "no report: $1"; }; }
expect 'host/kernels/surrogate/fit.cpp: no header fit.hpp'
expect 'host/kernels/surrogate/sobol.cpp: no header sobol.hpp'
expect 'host/kernels/surrogate/lhs.cpp: no header lhs.hpp'
lhs_line=$(grep -n ' lhs(' "$s/doe.hpp" | head -n 1 | cut -d: -f1)
expect "host/kernels/surrogate/doe.hpp:$lhs_line: lhs() declared, but no doe.cpp or doe_<part>.cpp beside it"
grep -q 'kriging.hpp' "$work/planted.log" && { cat "$work/planted.log"; fail "kriging.hpp still has kriging_*.cpp files"; }
echo "ok: file-name check passes host/ and reports misnamed implementation files and an orphaned header"
