#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Solvers: the environment is a list (tested in test_sandbox_executor.sh);
# a failing solver's log is read without following a link it left in its place; an allowed
# program that lies under a folder the script may write is refused (write or execute, not both).
source "$(dirname "$0")/lib.sh"

mkdir -p outside study bin
echo "TOP-SECRET-LINE" > outside/secret
cat > study/run.lua <<'LUA'
local m = smi.model.command{name = "m", inputs = {"x"}, outputs = {"y"}, template_string = "x = {{x}}\n",
  command = {(...), "{deck}"}, version = "1.0", on_failure = "stop",
  parse = function(dir, h) return {y = h.regex("stdout.log", "y = (\\S+)")} end}
print(pcall(m.evaluate, m, smi.mat{{1}}))
LUA

# --- a log replaced by a link: its target is not shown
printf '#!/bin/sh\nrm -f stderr.log stdout.log\nln -s %s/outside/secret stderr.log\nln -s %s/outside/secret stdout.log\nexit 3\n' "$WORK" "$WORK" > bin/linker
chmod +x bin/linker
run "a failing solver that leaves links for logs" 0 "$SMI" --quiet --allow-exec "$WORK/bin/linker" --out o1 study/run.lua "$WORK/bin/linker"
has_out "exit status 3"
if grep -q TOP-SECRET "$WORK/.out" "$WORK/.err"; then bad "the link's target was shown"; else ok; fi
# a FIFO in its place does not hang the host
printf '#!/bin/sh\nrm -f stderr.log\nmkfifo stderr.log\nexit 4\n' > bin/fifo
chmod +x bin/fifo
run "a FIFO for a log" 0 timeout 60 "$SMI" --quiet --allow-exec "$WORK/bin/fifo" --out o2 study/run.lua "$WORK/bin/fifo"
has_out "exit status 4"

# --- write xor execute
mkdir -p w
printf '#!/bin/sh\necho "y = 1"\n' > w/solver
chmod +x w/solver
run "a program under --allow-write" 1 "$SMI" --quiet --allow-write w --allow-exec "$WORK/w/solver" --out o3 study/run.lua "$WORK/w/solver"
has_err "a folder the script may write"
mkdir -p o4
cp w/solver o4/solver
run "a program under --out" 1 "$SMI" --quiet --allow-exec "$WORK/o4/solver" --out o4 study/run.lua "$WORK/o4/solver"
has_err "a folder the script may write"
run "the same program outside" 0 "$SMI" --quiet --allow-exec "$WORK/bin/linker" --out o5 study/run.lua "$WORK/bin/linker"

# --- a parser that evaluates another model: the nested scheduler's clean-up must not kill the
# outer model's solver still running (it carries the same mark; the old code SIGKILLed it, and the
# outer run ended "lost track of process" or "killed by signal 9")
printf '#!/bin/sh\nx=$(sed -n "s/x = //p" "$1")\n[ "$x" = 2 ] && sleep 2\necho "y = $x"\n' > bin/slow
printf '#!/bin/sh\necho "z = 7"\n' > bin/fast
chmod +x bin/slow bin/fast
cat > study/nested.lua <<'LUA'
local slow, fast = ...
local inner = smi.model.command{name = "inner", inputs = {"x"}, outputs = {"z"}, template_string = "x = {{x}}\n",
  command = {fast, "{deck}"}, version = "1",
  parse = function(dir, h) return {z = h.regex("stdout.log", "z = (\\S+)")} end}
local n = 0
local outer = smi.model.command{name = "outer", inputs = {"x"}, outputs = {"y"}, template_string = "x = {{x}}\n",
  command = {slow, "{deck}"}, version = "1", concurrency = 2,
  parse = function(dir, h)
    n = n + 1
    local Z = inner:evaluate(smi.mat{{n + 0.5}})
    return {y = h.regex("stdout.log", "y = (\\S+)") + Z.z[1] - 7}
  end}
local Y = outer:evaluate(smi.mat{{1}, {2}})
print(("y=%g,%g"):format(Y.y[1], Y.y[2]))
LUA
run "a nested evaluation leaves the outer solvers alone" 0 "$SMI" --quiet --allow-exec "$WORK/bin/slow" \
    --allow-exec "$WORK/bin/fast" --out o6 study/nested.lua "$WORK/bin/slow" "$WORK/bin/fast"
has_out "y=1,2"

finish
