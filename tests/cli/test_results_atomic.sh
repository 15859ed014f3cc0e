#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Results never shrink or tear: results.json and report.html are replaced
# whole (temporary file, checked writes, fsync, rename). A full disk while results.json is
# written is an error naming the file, exit 1, and the previous results.json stays valid; a
# rerun that fails keeps every saved step (no shrinking) and leaves report.html as it was.
# The full disk is a 128 KB tmpfs (needs root to mount; the rest runs as any user).
source "$(dirname "$0")/lib.sh"

cat > study.lua <<'LUA'
local study = require "smi.study"
local mode = arg[1] or "ok"
local s = study.new{ name = "atomic", out = smi.out_dir, quiet = true, report = { title = "atomic" } }
s:step("a", function(ctx) ctx.report:text("run " .. mode) return { v = 1 } end)
s:step("b", function() if mode == "fail" then error("step b broke on purpose") end return { w = 2 } end)
s:step("c", function() return { big = mode == "big" and string.rep("x", 300000) or "small", z = 3 } end)
s:run()
LUA
py_json() { python3 -c "import json,sys; d=json.load(open(sys.argv[1])); print($2)" "$1"; }

# --- the shrink case: a rerun that fails keeps every saved step; report.html untouched
run "first full run" 0 "$SMI" --out out study.lua ok
cp out/report.html report.first
run "rerun failing at step b" 1 "$SMI" --out out study.lua fail
has_err "step b broke on purpose"
if [ "$(py_json out/results.json "d['steps']['c']['result']['z']")" = 3 ]; then ok; else bad "step c's saved result lost: $(cat out/results.json | head -c 400)"; fi
if [ "$(py_json out/results.json "d['steps']['b']['previous']['result']['w']")" = 2 ]; then ok; else bad "step b's previous result lost"; fi
if [ "$(py_json out/results.json "d['steps']['b']['status']")" = failed ]; then ok; else bad "step b's failure not recorded"; fi
if cmp -s out/report.html report.first; then ok; else bad "report.html was rewritten by a failed run"; fi

# --- the full disk: the write fails loudly and the previous results.json is intact
if [ "$(id -u)" = 0 ] && mkdir -p full && mount -t tmpfs -o size=128k tmpfs full 2>/dev/null; then
  trap 'umount "$WORK/full" 2>/dev/null; rm -rf "$WORK"' EXIT
  run "small results fit" 0 "$SMI" --out full study.lua ok
  run "300 KB result on a 128 KB disk" 1 "$SMI" --out full study.lua big
  has_err "results.json"
  has_err "No space left on device"
  if [ "$(py_json full/results.json "d['steps']['c']['result']['big']")" = small ]; then ok; else bad "results.json torn: $(head -c 300 full/results.json)"; fi
  if ls -A full | grep -q tmp; then bad "temporary file left: $(ls -A full)"; else ok; fi
  umount full
else
  echo "skip: the full-disk case needs root to mount a tmpfs"
fi
finish
