# SPDX-License-Identifier: MIT
# Helpers for the CLI tests: run smi-lua, check its exit status and output, count results.
# Usage in a test file:  source lib.sh; run NAME RC [cmd...]; has_out TEXT; has_err TEXT; finish
set -u
SMI=${SMI_LUA:?set SMI_LUA to the smi-lua binary}
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
cd "$WORK"
passed=0
failed=0
current=""

ok() { passed=$((passed + 1)); }
bad() {
  failed=$((failed + 1))
  echo "FAIL [$current] $*" >&2
  echo "  stdout: $(head -c 600 "$WORK/.out")" >&2
  echo "  stderr: $(head -c 600 "$WORK/.err")" >&2
}

# run NAME EXPECTED_STATUS cmd... : runs cmd (stdin from /dev/null unless redirected by the
# caller through run_in) and checks the exit status.
run() {
  current=$1
  local want=$2
  shift 2
  "$@" > "$WORK/.out" 2> "$WORK/.err" < /dev/null
  local rc=$?
  if [ "$rc" = "$want" ]; then ok; else bad "exit status $rc, expected $want"; fi
}

# run_in NAME EXPECTED_STATUS INPUT cmd... : same with INPUT on stdin.
run_in() {
  current=$1
  local want=$2 input=$3
  shift 3
  printf '%s' "$input" | "$@" > "$WORK/.out" 2> "$WORK/.err"
  local rc=$?
  if [ "$rc" = "$want" ]; then ok; else bad "exit status $rc, expected $want"; fi
}

has_out() { if grep -qF -- "$1" "$WORK/.out"; then ok; else bad "stdout lacks '$1'"; fi; }
has_err() { if grep -qF -- "$1" "$WORK/.err"; then ok; else bad "stderr lacks '$1'"; fi; }
lacks_err() { if grep -qF -- "$1" "$WORK/.err"; then bad "stderr has '$1'"; else ok; fi; }
lacks_out() { if grep -qF -- "$1" "$WORK/.out"; then bad "stdout has '$1'"; else ok; fi; }
out_is() { if [ "$(cat "$WORK/.out")" = "$1" ]; then ok; else bad "stdout is not '$1'"; fi; }

finish() {
  echo "$passed passed, $failed failed"
  [ "$failed" = 0 ]
}
