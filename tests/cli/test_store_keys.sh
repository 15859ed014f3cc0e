#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The evaluation store against forged records: a record's key includes the
# SHA-256 of the program file, so a record made by another program of the same file name and
# a version string the script chose is not reused; a store of the old key scheme is refused
# with a message saying why; --store is read, never written.
source "$(dirname "$0")/lib.sh"

mkdir -p a b study
printf '#!/bin/sh\necho "y = 666"\n' > a/solver     # the forger's program
printf '#!/bin/sh\necho "y = 1"\n' > b/solver       # the honest program, same file name
chmod +x a/solver b/solver
cat > study/run.lua <<'LUA'
local prog = ...
local m = smi.model.command{name = "m", inputs = {"x"}, outputs = {"y"}, template_string = "x = {{x}}\n",
  command = {prog, "{deck}"}, version = "1.0",
  parse = function(dir, h) return {y = h.regex("stdout.log", "y = (\\S+)")} end}
local Y, info = m:evaluate(smi.mat{{1}})
print("y=" .. Y.y[1], "launched=" .. info.launched)
LUA
run "the forger's run" 0 "$SMI" --quiet --allow-exec "$WORK/a/solver" --out out study/run.lua "$WORK/a/solver"
has_out "y=666"
run "an honest run does not reuse the forged record" 0 "$SMI" --quiet --allow-exec "$WORK/b/solver" --out out study/run.lua "$WORK/b/solver"
has_out "y=1"
has_out "launched=1"
run "the honest record is reused" 0 "$SMI" --quiet --allow-exec "$WORK/b/solver" --out out study/run.lua "$WORK/b/solver"
has_out "launched=0"
# the same through a shared --store: its forged record is not taken either
run "a forged --store record is not reused" 0 "$SMI" --quiet --allow-exec "$WORK/b/solver" --out out2 \
    --store out/evaluations.sqlite study/run.lua "$WORK/b/solver"
has_out "y=1"
# --store is opened immutable: nothing is written beside it
ls out > before.txt
run "reading --store leaves its folder as it was" 0 "$SMI" --quiet --allow-exec "$WORK/b/solver" --out out3 \
    --store out/evaluations.sqlite study/run.lua "$WORK/b/solver"
if [ "$(ls out)" = "$(cat before.txt)" ] && [ ! -e out/evaluations.sqlite-wal ]; then ok; else bad "files appeared beside --store: $(ls out)"; fi
# a store of the old key scheme (the same table, PRAGMA user_version 0, as every store before
# key scheme 2): refused with a message naming it and the fix
run "make a store" 0 "$SMI" --quiet --allow-exec "$WORK/b/solver" --out old study/run.lua "$WORK/b/solver"
sqlite3 old/evaluations.sqlite 'PRAGMA user_version = 0;'
run "an old store is refused with a message" 1 "$SMI" --quiet --allow-exec "$WORK/b/solver" --out old study/run.lua "$WORK/b/solver"
has_err "evaluation store '$WORK/old/evaluations.sqlite' was written by an older smi-lua"
has_err "move it aside or delete it and run again"
run "an old --store is refused with a message" 1 "$SMI" --quiet --allow-exec "$WORK/b/solver" --out new \
    --store old/evaluations.sqlite study/run.lua "$WORK/b/solver"
has_err "(it was given as --store)"

# keys include the study script's hash wherever a store is read: a store made by
# another script with the same program, deck and version is not reused, --store or local
sed 's/print("y=" .. Y.y\[1\]/print("forged by another script"); print("y=" .. Y.y[1]/' study/run.lua > study/other.lua
printf '#!/bin/sh\necho "y = 1"\n' > b/solver
run "another script's run" 0 "$SMI" --quiet --allow-exec "$WORK/b/solver" --out other study/other.lua "$WORK/b/solver"
has_out "launched=1"
run "its --store is not reused by this script" 0 "$SMI" --quiet --allow-exec "$WORK/b/solver" --out mine \
    --store other/evaluations.sqlite study/run.lua "$WORK/b/solver"
has_out "launched=1"
cp -r other planted
run "nor is its store planted as this script's own" 0 "$SMI" --quiet --allow-exec "$WORK/b/solver" --out planted \
    study/run.lua "$WORK/b/solver"
has_out "launched=1"
run "this script's own records are reused" 0 "$SMI" --quiet --allow-exec "$WORK/b/solver" --out planted \
    study/run.lua "$WORK/b/solver"
has_out "launched=0"

finish
