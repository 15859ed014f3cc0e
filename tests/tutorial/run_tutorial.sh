#!/bin/bash
# SPDX-License-Identifier: MIT
# Runs every command of docs/tutorial.md (the "$ build/smi-lua ..." lines of its ```console
# blocks), in order, in a fresh folder that sees the build and the scripts as the tutorial's
# reader does (build/, scripts/), and compares each output with the one the page shows, exactly:
# the page promises "what you read here is what you get", so a changed digit, count, message or
# option fails the test (same seed, same numbers on every build).
#   run_tutorial.sh BUILD_DIR SOURCE_DIR WORK [--update]
# --update rewrites the page's outputs with what this build prints (then review the diff).
set -u
BUILD=$1
SRC=$2
WORK=$3
UPDATE=${4:-}
rm -rf "$WORK"
mkdir -p "$WORK"
ln -s "$BUILD" "$WORK/build"
ln -s "$SRC/scripts" "$WORK/scripts"

# Split the page into commands and expected outputs: cmd.N and want.N.
awk -v dir="$WORK" '
  /^```console/ { inblock = 1; next }
  /^```/ && inblock { inblock = 0; next }
  inblock && /^\$ / { n++; print substr($0, 3) > (dir "/cmd." n); printf "" > (dir "/want." n); next }
  inblock && n { print >> (dir "/want." n) }
  END { print n > (dir "/count") }
' "$SRC/docs/tutorial.md"
count=$(cat "$WORK/count")
[ "$count" -ge 6 ] || { echo "FAIL: only $count commands found in docs/tutorial.md"; exit 1; }

# Compares two outputs line by line, exactly; prints the first lines that differ.
compare() {
  diff -U0 --label page --label got "$1" "$2" | sed -n '3,40p'
  cmp -s "$1" "$2"
}

failed=0
for i in $(seq 1 "$count"); do
  cmd=$(cat "$WORK/cmd.$i")
  (cd "$WORK" && eval "$cmd") > "$WORK/got.$i" 2>&1
  if compare "$WORK/want.$i" "$WORK/got.$i" > "$WORK/diff.$i"; then
    echo "ok   $cmd"
  else
    echo "FAIL $cmd"
    sed 's/^/     /' "$WORK/diff.$i"
    failed=$((failed + 1))
  fi
done
[ -s "$WORK/smi-out/bracket_solver/report.html" ] || { echo "FAIL: the tutorial's report was not written"; failed=$((failed + 1)); }
echo "$count commands, $failed failed"
if [ "$UPDATE" = --update ]; then
  # The page again, each console block's outputs replaced by this run's (got.N after cmd.N).
  awk -v dir="$WORK" '
    /^```console/ { print; inblock = 1; next }
    /^```/ && inblock { inblock = 0; print; next }
    inblock && /^\$ / { n++; print; f = dir "/got." n; while ((getline line < f) > 0) print line; close(f); next }
    inblock { next }
    { print }
  ' "$SRC/docs/tutorial.md" > "$WORK/tutorial.md" && cp "$WORK/tutorial.md" "$SRC/docs/tutorial.md"
  echo "docs/tutorial.md updated from this run: review it with git diff"
  exit 0
fi
[ "$failed" = 0 ]
