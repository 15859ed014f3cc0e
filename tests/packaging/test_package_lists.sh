#!/bin/bash
# SPDX-License-Identifier: MIT
# One package list: the `apt-get install` lines of README.md and docs/tutorial.md name exactly the
# packages .ci/setup installs for building (its `packages=(...)` array), so a reader who copies
# them gets a machine that configures. Fails naming the file and the packages that differ.
#   test_package_lists.sh SOURCE_DIR
set -u
src=$1
# The array's words, from "packages=(" to the closing ")".
want=$(awk '/^packages=\(/ { on = 1; sub(/^packages=\(/, "") } on { line = $0; done = sub(/\).*/, "", line); print line; if (done) exit }' \
         "$src/.ci/setup" | tr -s ' \t' '\n' | sed '/^$/d' | sort -u)
[ -n "$want" ] || { echo "FAIL: no packages=(...) array in .ci/setup"; exit 1; }
failed=0
for doc in README.md docs/tutorial.md; do
  # Every `apt-get install` command of the page, continuation lines joined, options dropped.
  lines=$(awk '{ if (cont) { buf = buf " " $0 } else { buf = $0 } cont = sub(/\\$/, "", buf); if (!cont) print buf }' "$src/$doc" |
          grep -E 'apt-get install' || true)
  if [ -z "$lines" ]; then echo "FAIL: $doc has no apt-get install line"; failed=1; continue; fi
  while IFS= read -r line; do
    got=$(printf '%s\n' "$line" | sed 's/.*apt-get install//; s/`.*//' | tr -s ' \t' '\n' | grep -v '^-' | grep -v '^\./' | sed '/^$/d' | sort -u)
    # A line installing the package itself (./smi-lua_*.deb) is not a build line.
    [ -z "$got" ] && continue
    if [ "$got" != "$want" ]; then
      echo "FAIL: $doc: $line"
      echo "  missing: $(comm -23 <(echo "$want") <(echo "$got") | tr '\n' ' ')"
      echo "  not in .ci/setup: $(comm -13 <(echo "$want") <(echo "$got") | tr '\n' ' ')"
      failed=1
    else
      echo "ok   $doc: $(echo "$got" | wc -l) packages, as .ci/setup"
    fi
  done <<< "$lines"
done
exit $failed
