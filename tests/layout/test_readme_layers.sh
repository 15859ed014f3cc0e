#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The README's layer table matches the tree and the include check: every folder it names exists,
# every folder of host/ (and bindings/) is in it, and its layers appear in the order of
# SMI_LAYERS in cmake/check_includes.cmake (bottom up).
set -euo pipefail
src=${SMI_SOURCE_DIR:?set SMI_SOURCE_DIR to the source tree}
fail() { echo "FAIL: $*"; exit 1; }
table=$(awk '/^## Source layout/{on=1; next} on && /^## /{exit} on && /^\| /' "$src/README.md")
[[ -n $table ]] || fail "README.md has no '## Source layout' table"
named=$(grep -o '`[a-z/_]*/`' <<<"$table" | tr -d '`' | sed 's#/$##')
for f in $named; do [[ -d $src/$f ]] || fail "README names $f/, which does not exist"; done
# Every layer folder of the tree is in the table.
tree=$( (cd "$src" && ls -d host/*/ host/platform/*/ host/kernels/*/ bindings/) | sed 's#/$##' | grep -vx 'host/platform\|host/kernels')
for f in $tree; do grep -qx "$f" <<<"$named" || fail "$f/ is a folder of the tree but not in the README's layer table"; done
# Order: the first folder of each layer in the table follows SMI_LAYERS.
layers=$(sed -n '/^set(SMI_LAYERS/,/)/p' "$src/cmake/check_includes.cmake" | tr -s ' ()\n' '\n' | grep -v '^set$\|^SMI_LAYERS$\|^$')
last=0
for l in $layers; do
  case $l in bindings) f=bindings ;; *) f=host/$l ;; esac
  row=$(grep -n "\`$f/\`" <<<"$table" | head -1 | cut -d: -f1)
  [[ -n $row ]] || fail "layer $l ($f/) of SMI_LAYERS is not in the README's table"
  (( row >= last )) || fail "layer $l comes before an earlier layer in the README's table (SMI_LAYERS order: $layers)"
  last=$row
done
echo "ok: README's layer table names $(wc -w <<<"$named") folders, all present, in SMI_LAYERS order"
