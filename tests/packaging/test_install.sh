#!/bin/bash
# SPDX-License-Identifier: MIT
# `cmake --install` into a fresh prefix, then, from a folder outside the source tree and with only
# the prefix's bin/ added to PATH: the README's first study, `smi-lua doc smi.kde`, the installed
# steering-column study's cost plan (--dry-run: its modules, data and the solver smi-column-fe found
# without any path into the source tree), and the man page names every option of --help.
#   test_install.sh BUILD_DIR SOURCE_DIR WORK
set -u
BUILD=$1
SRC=$2
WORK=$3
rm -rf "$WORK"
mkdir -p "$WORK/home"
P=$WORK/prefix
fail() { echo "FAIL: $*"; exit 1; }
cmake --install "$BUILD" --prefix "$P" > "$WORK/install.log" 2>&1 || { cat "$WORK/install.log"; fail "cmake --install"; }
for f in bin/smi-lua bin/smi-column-fe bin/smi-beam-solver share/man/man1/smi-lua.1.gz share/man/man1/smi-column-fe.1.gz \
         share/man/man1/smi-beam-solver.1.gz share/doc/smi-lua/copyright share/doc/smi-lua/changelog.Debian.gz \
         share/doc/smi-lua/html/index.html \
         share/doc/smi-lua/README.md share/doc/smi-lua/tutorial.md share/doc/smi-lua/spec/algorithms.md \
         share/smi-lua/scripts/steering_column.lua share/smi-lua/scripts/steering_column/data/tests.csv \
         share/smi-lua/scripts/tutorial/bracket_tests.csv; do
  [ -e "$P/$f" ] || fail "not installed: $f"
done
[ -z "$(find "$P/share/smi-lua" -name CMakeLists.txt -o -name '*.cpp')" ] || fail "build files installed under share/smi-lua"
echo "ok   installed: $(find "$P" -type f | wc -l) files"

# The man page follows --help: every option word of --help is in it (roff writes '-' as '\-').
man=$(gzip -dc "$P/share/man/man1/smi-lua.1.gz" | sed 's/\\-/-/g; s/\\f[BIR]//g')
for o in $("$P/bin/smi-lua" --help | grep -oE '^  -[-a-zA-Z]+(, --[a-z-]+)?' | tr -d ' ,' | sed 's/--/ --/g'); do
  grep -qF -- "$o" <<< "$man" || fail "the man page misses the option $o of smi-lua --help"
done
# ... and every command of its command list, and the reference command doc.
for c in $("$P/bin/smi-lua" --help | awk '/^Commands/ { on = 1; next } on && /^$/ { exit } on && /^  [a-z]/ { print $1 }') doc; do
  grep -qF -- "$c" <<< "$man" || fail "the man page misses the command $c"
done
echo "ok   the man page names every option and command of --help"

cd "$WORK/home" || exit 1
export PATH=$P/bin:/usr/bin:/bin
bash "$SRC/tests/packaging/first_study.sh" "$SRC/README.md" > first.lua
[ -s first.lua ] || fail "no first study in README.md"
out=$(smi-lua first.lua 2>&1) || { echo "$out"; fail "smi-lua first.lua"; }
want=$(bash "$SRC/tests/packaging/first_study.sh" "$SRC/README.md" --output)
[ "$out" = "$want" ] || { diff <(echo "$want") <(echo "$out"); fail "the README's first study prints something else than the README shows"; }
echo "ok   the README's first study prints what the README shows ($(grep -c . <<< "$out") lines)"
out=$(smi-lua doc smi.kde 2>&1) || { echo "$out"; fail "smi-lua doc smi.kde"; }
grep -q "^smi.kde" <<< "$out" || { echo "$out"; fail "smi-lua doc smi.kde printed no entry"; }
echo "ok   smi-lua doc smi.kde"
study=$P/share/smi-lua/scripts/steering_column.lua
out=$(smi-lua --allow-exec smi-column-fe "$study" --dry-run --quick 2>&1) || { echo "$out"; fail "the installed study's dry run"; }
grep -q "$SRC" <<< "$out" && { echo "$out"; fail "the installed study's output names the source tree"; }
echo "$out" | tail -n 3
echo "ok   the installed steering-column study plans its runs with smi-column-fe from PATH"
tutorial=$P/share/smi-lua/scripts/tutorial/bracket_solver.lua
out=$(smi-lua --quiet --allow-exec smi-beam-solver "$tutorial" --points 5 2>&1) || { echo "$out"; fail "the installed tutorial's solver study"; }
grep -q "^solver: 5 points, 5 runs launched" <<< "$out" || { echo "$out"; fail "the installed tutorial ran no smi-beam-solver from PATH"; }
echo "ok   the installed tutorial runs smi-beam-solver from PATH"
# Every program installed in bin/ has its manual page.
for b in "$P"/bin/*; do
  [ -e "$P/share/man/man1/$(basename "$b").1.gz" ] || fail "no man page for bin/$(basename "$b")"
done
echo "ok   every program in bin/ has a man page"
