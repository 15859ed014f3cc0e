#!/bin/bash
# Runs every command of docs/tutorial.md (the "$ build/smi-lua ..." lines of its ```console
# blocks), in order, in a fresh folder that sees the build and the scripts as the tutorial's
# reader does (build/, scripts/), and compares each output with the one the page shows: the
# text must match exactly, numbers within 10 % (so a kernel change that moves a digit does not
# fail the test, but a changed message, option or result structure does).
#   run_tutorial.sh BUILD_DIR SOURCE_DIR WORK
set -u
BUILD=$1
SRC=$2
WORK=$3
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

# Compares two outputs line by line: numbers within a relative 10 % (absolute 1e-9), the rest exact.
compare() {
  awk '
    function split_nums(s, nums,   out, k) {
      out = ""; k = 0
      while (match(s, /-?[0-9]+(\.[0-9]+)?([eE][-+]?[0-9]+)?/)) {
        out = out substr(s, 1, RSTART - 1) "#"; nums[++k] = substr(s, RSTART, RLENGTH) + 0
        s = substr(s, RSTART + RLENGTH)
      }
      nums[0] = k
      return out s
    }
    FNR == NR { want[FNR] = $0; nw = FNR; next }
    {
      ng = FNR
      if (FNR > nw) { print "extra line " FNR ": " $0; bad = 1; next }
      delete a; delete b
      ta = split_nums(want[FNR], a); tb = split_nums($0, b)
      if (ta != tb || a[0] != b[0]) { print "line " FNR ":\n  page: " want[FNR] "\n  got:  " $0; bad = 1; next }
      for (i = 1; i <= a[0]; i++) {
        d = a[i] - b[i]; if (d < 0) d = -d
        m = a[i] < 0 ? -a[i] : a[i]
        if (d > 1e-9 && d > 0.1 * m) { print "line " FNR ", number " i ": page " a[i] ", got " b[i] "\n  got: " $0; bad = 1 }
      }
    }
    END { if (ng < nw) { print "missing lines from " ng + 1 ": " want[ng + 1]; bad = 1 } exit bad }
  ' "$1" "$2"
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
[ "$failed" = 0 ]
