#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Links planted before the run, as a study bundle unpacked in the working
# folder brings them: at smi-out, smi-out/<script>, --out, .smi-lock, the store and its -wal and
# -shm. Roots are opened, never resolved: a link where smi-lua will make a folder or write a
# file is refused by name, and nothing outside changes. Hard links are refused for every write.
source "$(dirname "$0")/lib.sh"

mkdir -p outside study
echo "precious" > outside/file
cat > study/w.lua <<'LUA'
local f = assert(io.open(smi.out("x.txt"), "w"))
f:write("planted\n")
f:close()
LUA
outside_intact() {
  if [ "$(ls outside)" = "file" ] && [ "$(cat outside/file)" = "precious" ]; then ok; else
    bad "outside changed: $(ls -la outside) / $(cat outside/file)"; fi
}

# --- the output root
ln -s "$WORK/outside" smi-out
run "a link at smi-out" 1 "$SMI" study/w.lua
has_err "'$WORK/smi-out' is a symbolic link"
outside_intact
rm smi-out; mkdir smi-out
ln -s "$WORK/outside" smi-out/w
run "a link at smi-out/<script>" 1 "$SMI" study/w.lua
has_err "'$WORK/smi-out/w' is a symbolic link"
outside_intact
rm -rf smi-out
ln -s "$WORK/outside" res
run "a link at a relative --out" 1 "$SMI" --out res/run study/w.lua
has_err "'$WORK/res' is a symbolic link"
outside_intact
rm res
run "a real --out still works" 0 "$SMI" --out res/run study/w.lua
if [ "$(cat res/run/x.txt)" = "planted" ]; then ok; else bad "res/run/x.txt missing"; fi

# --- the lock
printf 'smi.lock_out()\nprint("locked")\n' > study/lock.lua
mkdir -p o1 && ln -s "$WORK/outside/file" o1/.smi-lock
run "a link at .smi-lock" 1 "$SMI" --out o1 study/lock.lua
has_err ".smi-lock' is a symbolic link"
outside_intact
mkdir -p o2 && ln "$WORK/outside/file" o2/.smi-lock
run "a hard link at .smi-lock" 1 "$SMI" --out o2 study/lock.lua
has_err "a hard link (2 names)"
outside_intact
rm o2/.smi-lock
run "a fresh lock" 0 "$SMI" --out o2 study/lock.lua
has_out "locked"

# --- the store and its companions
printf '#!/bin/sh\necho "y = 1"\n' > solver
chmod +x solver
cat > study/run.lua <<'LUA'
local m = smi.model.command{name = "m", inputs = {"x"}, outputs = {"y"}, template_string = "x = {{x}}\n",
  command = {(...), "{deck}"}, version = "1.0",
  parse = function(dir, h) return {y = h.regex("stdout.log", "y = (\\S+)")} end}
local Y = m:evaluate(smi.mat{{1}})
print("y=" .. Y.y[1])
LUA
S=("$SMI" --quiet --allow-exec "$WORK/solver")
for f in evaluations.sqlite evaluations.sqlite-wal evaluations.sqlite-shm; do
  rm -rf s1 s2; mkdir -p s1 s2
  ln -s "$WORK/outside/file" "s1/$f"
  run "a link at $f" 1 "${S[@]}" --out s1 study/run.lua "$WORK/solver"
  has_err "$f"
  has_err "symbolic link"
  outside_intact
  ln "$WORK/outside/file" "s2/$f"
  run "a hard link at $f" 1 "${S[@]}" --out s2 study/run.lua "$WORK/solver"
  has_err "$f"
  has_err "hard links"
  outside_intact
done
rm -rf s3
run "a fresh store opens through its folder" 0 "${S[@]}" --out s3 study/run.lua "$WORK/solver"
has_out "y=1"
run "and is reused" 0 "${S[@]}" --out s3 study/run.lua "$WORK/solver"
has_out "y=1"
if [ -f s3/evaluations.sqlite ] && [ ! -L s3/evaluations.sqlite ]; then ok; else bad "the store is not in s3"; fi

finish
