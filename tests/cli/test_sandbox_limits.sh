#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Limits that reach C++: --timeout and Ctrl-C stop long
# kernels through smi::cancel; a pattern match or a finalizer that the Lua hook cannot reach is
# ended by the watchdog with a message; vec/mat data count against --max-memory; os.getenv
# answers only for --allow-env names; the globals are an allow-list. Every case here hung,
# exited 0 or answered on the build before these changes.
source "$(dirname "$0")/lib.sh"

# elapsed CMD...: runs CMD like run does and sets $secs to the whole seconds it took.
timed() {
  local start=$SECONDS
  run "$@"
  secs=$((SECONDS - start))
}
fast() { if [ "$secs" -le "$1" ]; then ok; else bad "took ${secs} s, more than $1 s"; fi; }

# --- kernels poll the deadline: the error names the function and says timeout
timed "u-pooling Monte Carlo stops at --timeout" 1 timeout 30 "$SMI" --timeout 0.5 -e \
  "smi.metric.upool_threshold(50, 0.95, {replications = 10000000, seed = 5})"
has_err "smi.metric.upool_threshold: timeout: the run took longer than --timeout 0.5 s"
lacks_out "did not stop"
fast 6
timed "LHS optimisation stops at --timeout" 1 timeout 30 "$SMI" --timeout 0.5 -e \
  "local s = {} for i = 1, 10 do s[i] = {0, 1} end smi.doe.lhs(300, s, {iterations = 100000})"
has_err "smi.doe.lhs: timeout:"
fast 6
timed "a timeout inside a kernel is not swallowed by pcall" 1 timeout 30 "$SMI" --timeout 0.5 -e \
  "print(pcall(smi.metric.upool_threshold, 50, 0.95, {replications = 10000000, seed = 5})) while true do end"
has_out "timeout:"
has_err "timeout:"
fast 6

# --- Ctrl-C reaches a kernel (it took 48 s)
current="Ctrl-C stops the u-pooling kernel"
start=$SECONDS
"$SMI" -e "smi.metric.upool_threshold(50, 0.95, {replications = 10000000, seed = 5})" > "$WORK/.out" 2> "$WORK/.err" &
pid=$!
sleep 1
kill -INT $pid
for _ in $(seq 100); do kill -0 $pid 2> /dev/null || break; sleep 0.1; done
if kill -0 $pid 2> /dev/null; then kill -KILL $pid; fi  # still running 10 s after Ctrl-C: a failure below
wait $pid
rc=$?
secs=$((SECONDS - start))
if [ "$rc" = 130 ]; then ok; else bad "exit status $rc, expected 130 (128 + SIGINT)"; fi
has_err "interrupted"
fast 6

# --- the watchdog: code the hook cannot reach is ended after the grace, with a message
timed "a backtracking string pattern is ended" 1 timeout 30 "$SMI" --timeout 0.5 -e \
  'string.find(string.rep("a", 3000), ".-.-.-.-.-.-.-.-.-.-.-.-x")'
has_err "timeout: the run took longer than --timeout 0.5 s"
has_err "did not stop within"
fast 8
timed "a finalizer that never returns (hooks are off in __gc)" 1 timeout 30 "$SMI" --timeout 0.5 -e \
  'setmetatable({}, {__gc = function() while true do end end}) collectgarbage()'
has_err "a __gc finalizer that does not return"
fast 8
timed "a finalizer that never returns when the state closes" 1 timeout 30 "$SMI" --timeout 0.5 -e \
  'X = setmetatable({}, {__gc = function() while true do end end})'
has_err "timeout:"
fast 8

# --- memory held by vecs counts against --max-memory (a script held 4 GB under 64 MB)
run "vecs held count against --max-memory" 1 timeout 30 "$SMI" --max-memory 64 -e \
  "local t = {} for i = 1, 100 do t[i] = smi.vec(1e6) end"
has_err "memory limit exceeded: smi.vec needs 7.6 MB"
has_err "--max-memory 64 MB"
run "garbage vecs are collected under --max-memory" 0 timeout 30 "$SMI" --max-memory 64 -e \
  "for i = 1, 200 do local v = smi.vec(1e6) end"
run "a mat beyond --max-memory" 1 timeout 30 "$SMI" --max-memory 16 -e "local m = smi.mat.zeros(2000, 2000)"
has_err "smi.mat.zeros(rows, cols) needs 30.5 MB"

# --- environment variables: only those named by --allow-env
run "os.getenv of a name not allowed" 1 env SMI_SECRET=s3cret "$SMI" -e 'print(os.getenv("SMI_SECRET"))'
has_err "os.getenv: the sandbox does not let scripts read the environment variable 'SMI_SECRET'"
has_err "--allow-env SMI_SECRET"
lacks_out "s3cret"
run "os.getenv of an allowed name" 0 env SMI_SECRET=s3cret "$SMI" --allow-env SMI_SECRET -e 'print(os.getenv("SMI_SECRET"))'
out_is "s3cret"
run "--help documents --allow-env" 0 "$SMI" --help
has_out "--allow-env NAME"

# --- the globals are built from an allow-list
run "only listed library entries exist" 0 "$SMI" -e \
  'assert(package.searchers == nil and package.loadlib == nil and package.cpath == "", "package")
   assert(require("string") == string and ("x"):upper() == "X", "string methods")
   assert(os.execute == nil and io.popen == nil and debug.getinfo == nil and string.dump == nil, "removed")
   assert(_G == _ENV, "_G")'

# --- a long --timeout is long, not over at once (1e10 s overflowed the clock into the past)
for t in 1e10 1e15 1e300; do
  run "--timeout $t" 0 "$SMI" --timeout "$t" -e 'local s = 0 for i = 1, 1e6 do s = s + i end print("ran")'
  has_out "ran"
done

# --- a deck function runs in a Lua state of its own: --timeout, Ctrl-C and --max-memory hold there
deck_model() {  # a command model whose deck function is $1; /bin/true never runs (the deck comes first)
  printf 'local m = smi.model.command{name = "d", inputs = {"x"}, outputs = {"y"}, deck = "in.txt",\n'
  printf '  command = {"/bin/true"}, version = "1", template = function(p) %s end,\n' "$1"
  printf '  parse = function() return {y = 1} end}\n'
  printf 'm:evaluate{{1}}\n'
}
deck_model 'while true do pcall(error, "x") end return ""' > deck_loop.lua
timed "a deck function's endless loop stops at --timeout" 1 timeout 30 "$SMI" --allow-exec /bin/true --timeout 0.5 deck_loop.lua
has_err "timeout"
lacks_err "did not stop"
fast 6
deck_model 'local t = {} for i = 1, 1e9 do t[i] = ("x"):rep(1000) .. i end return ""' > deck_mem.lua
timed "a deck function's memory counts against --max-memory" 1 timeout 30 "$SMI" --allow-exec /bin/true --max-memory 64 deck_mem.lua
has_err "--max-memory 64 MB"
fast 20

finish
