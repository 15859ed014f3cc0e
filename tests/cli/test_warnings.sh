#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# One warning channel: a binding's warning goes to the run's sink, which collects it
# for the study (smi.warnings(), beside the functions that return theirs in a `warnings` field)
# and prints it only when the run prints. With --quiet nothing reaches stderr: smi.metric.pr's
# grid warning went to stderr whatever --quiet said, and smi.warnings() did not exist.
source "$(dirname "$0")/lib.sh"

printf 'x,y\n1,2\n1,2\n3,4\n' > dup.csv
cat > warn.lua <<'LUA'
smi.kde_bd({0.1, 0.5, 1.5, 2}, {lower = 0, upper = 1})
local sharp, wide = smi.dist.normal{mean = 0, std = 0.001}, smi.dist.normal{mean = 0, std = 1}
smi.metric.pr(sharp, wide, {grid = {lower = -5, upper = 5, nodes = 11}})
local _, _, notes = smi.csv.read("dup.csv")
print("csv notes:", #notes.warnings)
for i, w in ipairs(smi.warnings()) do print(i, w) end
LUA

run quiet 0 "$SMI" --quiet warn.lua
has_out "csv notes:	1"
has_out "1	smi.kde_bd: 2 data point(s) lie outside [0, 1]"
has_out "2	smi.metric.pr: the pdf of normal(mean=0, std=0.001) integrates to"
has_out "3	smi.csv.read: dup.csv: 1 duplicated data row (line 3 repeats line 2)"
lacks_err "warning"
if [ -s "$WORK/.err" ]; then bad "stderr is not empty under --quiet"; else ok; fi

finish
