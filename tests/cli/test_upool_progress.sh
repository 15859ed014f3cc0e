#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The u-pooling H0 Monte Carlo (seconds at 10^6 sets for n near 50) shows a progress line with
# an ETA on a terminal, and nothing when stderr is piped or with --quiet. The terminal is a
# pseudo-terminal from script(1) (util-linux, on every Debian system).
. "$(dirname "$0")/lib.sh"
printf 'print(smi.metric.upool_threshold(30, 0.95, {replications = 1000000, seed = 11}))\n' > mc.lua

current="terminal: progress with percent and ETA, ending at 100 %"
script -qec "$SMI mc.lua" /dev/null > tty.txt 2>&1 < /dev/null
lines=$(tr '\r' '\n' < tty.txt | grep -c "u-pooling H0 Monte Carlo, n = 30: 1000000 sets, [0-9]* %, ETA")
if [ "$lines" -ge 2 ]; then ok; else bad "expected at least 2 progress lines, got $lines: $(head -c 300 tty.txt)"; fi
if tr '\r' '\n' < tty.txt | grep -q "1000000 sets, 100 %"; then ok; else bad "no final 100 % line"; fi

run "piped: no progress" 0 "$SMI" mc.lua
has_out "0."
if grep -q "u-pooling H0" "$WORK/.err"; then bad "progress written to a pipe"; else ok; fi

current="--quiet on a terminal: no progress"
script -qec "$SMI --quiet mc.lua" /dev/null > quiet.txt 2>&1 < /dev/null
if grep -q "u-pooling H0" quiet.txt; then bad "progress despite --quiet"; else ok; fi
finish
