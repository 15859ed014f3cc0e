#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The sandbox's path checks against hostile paths: one test per denial,
# for every function that opens, writes, removes or renames a file a script names. Each attack
# here got through the resolver of before (it canonicalised the existing part of a path, then
# normalised the rest as text and opened the *name*): a missing folder then "..", an over-long
# component, a dangling symlink in the output folder, a hard link, a symlink swapped between
# check and open. The fixed runtime walks each path component by component through
# descriptors and opens through the folder it checked (host/platform/core/path_walk.hpp).
source "$(dirname "$0")/lib.sh"

mkdir -p study out outside stdlib/smi
echo "secret-data" > outside/secret.txt
echo "inside-data" > study/inside.txt
ln -s "$WORK/outside" study/link_dir                  # link to a folder out of the read roots
ln -s "$WORK/outside/secret.txt" study/link_file      # link to a file out of the read roots
ln -s "$WORK/outside" out/link_dir                    # the same, planted in the output folder
LONG=$(printf 'a%.0s' $(seq 1 300))                   # longer than NAME_MAX: stat fails
NX="study/nonexistent/../link_dir/secret.txt"         # a missing folder, "..", then a link out
NXF="study/nonexistent/../link_file"
LG="study/$LONG/../link_dir/secret.txt"
LGF="study/$LONG/../link_file"

# probe.lua FUNCTION PATH: does one read with FUNCTION and prints what it read (or the error).
cat > study/probe.lua <<'LUA'
local fn, path = ...
local ok, res = pcall(function()
  if fn == "io.open" then local f, e = io.open(path); if not f then return e end return f:read("a")
  elseif fn == "io.lines" then local t = {} for l in io.lines(path) do t[#t + 1] = l end return table.concat(t)
  elseif fn == "io.input" then io.input(path); return io.read("a")
  elseif fn == "dofile" then return dofile(path)
  elseif fn == "loadfile" then local f, e = loadfile(path); if not f then return e end return f()
  elseif fn == "smi.csv.read" then local c, h = smi.csv.read(path, {strings = {"secret-data"}}); return h[1]
  elseif fn == "smi.json.read" then return smi.json.read(path)
  elseif fn == "smi.model.parse.read" then return smi.model.parse.read(path)
  elseif fn == "smi.kriging.load" then return tostring(smi.kriging.load(path))
  end
end)
print(fn, ok, res)
LUA
# Files that are code, data or JSON, so that every reader would show the secret if it got there.
printf 'return "secret-data"\n' > outside/secret.lua
printf '"secret-data"\n' > outside/secret.json
ln -s "$WORK/outside/secret.lua" study/link_lua
ln -s "$WORK/outside/secret.json" study/link_json

for fn in io.open io.lines io.input smi.csv.read smi.model.parse.read; do
  for p in "$NX" "$NXF" "$LG" "$LGF"; do
    run "read $fn $(echo "$p" | cut -c1-40)" 0 "$SMI" study/probe.lua "$fn" "$p"
    lacks_out "secret-data"
  done
done
for fn in dofile loadfile; do
  for p in study/nonexistent/../link_lua "study/$LONG/../link_lua"; do
    run "read $fn $(echo "$p" | cut -c1-40)" 0 "$SMI" study/probe.lua "$fn" "$p"
    lacks_out "secret-data"
  done
done
for p in study/nonexistent/../link_json "study/$LONG/../link_json"; do
  run "read smi.json.read $(echo "$p" | cut -c1-40)" 0 "$SMI" study/probe.lua smi.json.read "$p"
  lacks_out "secret-data"
done
run "read smi.kriging.load through nonexistent/.." 0 "$SMI" study/probe.lua smi.kriging.load "$NX"
has_out "No such file or directory"      # before: it read the secret and failed to parse it
# the allowed cases still read (the walk is not simply refusing everything)
run "read inside through nonexistent/.. is ENOENT, as the kernel says" 0 "$SMI" study/probe.lua io.open study/nonexistent/../inside.txt
has_out "No such file or directory"
run "read inside" 0 "$SMI" study/probe.lua io.open study/sub/../inside.txt
has_out "No such file or directory"
mkdir -p study/sub
run "read inside through a real folder and .." 0 "$SMI" study/probe.lua io.open study/sub/../inside.txt
has_out "inside-data"
ln -s inside.txt study/link_inside
run "a symlink that stays inside is followed" 0 "$SMI" study/probe.lua io.open study/link_inside
has_out "inside-data"

# --- require: a module file swapped for a link out is not loaded ----------------------------
# (require takes module names, not paths; its attack is the race, below)

# --- writes: a dangling symlink planted in the output folder, a missing folder then "..", an
# over-long component, a hard link to a file outside; none may create or change a file outside.
cat > study/write.lua <<'LUA'
local fn, path = ...
local ok, err = pcall(function()
  if fn == "io.open.w" then local f = assert(io.open(path, "w")); f:write("x"); f:close()
  elseif fn == "io.open.a" then local f = assert(io.open(path, "a")); f:write("x"); f:close()
  elseif fn == "io.open.r+" then local f = assert(io.open(path, "r+")); f:write("x"); f:close()
  elseif fn == "io.output" then io.output(path); io.write("x"); io.close()
  elseif fn == "smi.csv.write" then smi.csv.write(path, {a = {1}})
  elseif fn == "smi.json.write" then smi.json.write(path, {a = 1})
  elseif fn == "smi.kriging:save" then smi.kriging.fit({{0}, {1}, {2}}, {0, 1, 4}, {theta = {1}}):save(path)
  elseif fn == "os.remove" then assert(os.remove(path))
  elseif fn == "os.rename.from" then assert(os.rename(path, smi.out("stolen.txt")))
  elseif fn == "os.rename.to" then local f = io.open(smi.out("mine.txt"), "w"); f:write("x"); f:close()
    assert(os.rename(smi.out("mine.txt"), path))
  end
end)
print(fn, ok, err)
LUA
n=0
for fn in io.open.w io.open.a io.output smi.csv.write smi.json.write smi.kriging:save; do
  n=$((n + 1))
  ln -s "$WORK/outside/planted$n.txt" out/dangling$n
  run "write $fn through a dangling link in the output folder" 0 "$SMI" --out out study/write.lua "$fn" out/dangling$n
  if [ -e outside/planted$n.txt ]; then bad "$fn created outside/planted$n.txt"; else ok; fi
  has_out "is not allowed"
  run "write $fn through nonexistent/.." 0 "$SMI" --out out study/write.lua "$fn" out/nonexistent/../link_dir/nx$n.txt
  if [ -e outside/nx$n.txt ]; then bad "$fn created outside/nx$n.txt"; else ok; fi
  run "write $fn through a long component" 0 "$SMI" --out out study/write.lua "$fn" "out/$LONG/../link_dir/lg$n.txt"
  if [ -e outside/lg$n.txt ]; then bad "$fn created outside/lg$n.txt"; else ok; fi
done
echo "victim" > outside/victim.txt
for fn in io.open.w io.open.a io.open.r+ smi.json.write; do
  rm -f out/hardlink.txt && ln outside/victim.txt out/hardlink.txt
  run "write $fn through a hard link to a file outside" 0 "$SMI" --out out study/write.lua "$fn" out/hardlink.txt
  if [ "$(cat outside/victim.txt)" = "victim" ]; then ok; else bad "$fn changed outside/victim.txt"; fi
  has_out "hard links"
done
rm -f out/hardlink.txt
run "os.remove through nonexistent/.." 0 "$SMI" --out out study/write.lua os.remove out/nonexistent/../link_dir/victim.txt
if [ -e outside/victim.txt ]; then ok; else bad "os.remove deleted outside/victim.txt"; fi
run "os.remove through a long component" 0 "$SMI" --out out study/write.lua os.remove "out/$LONG/../link_dir/victim.txt"
if [ -e outside/victim.txt ]; then ok; else bad "os.remove deleted outside/victim.txt"; fi
run "os.rename from outside through nonexistent/.." 0 "$SMI" --out out study/write.lua os.rename.from out/nonexistent/../link_dir/victim.txt
if [ -e outside/victim.txt ]; then ok; else bad "os.rename took outside/victim.txt"; fi
run "os.rename to outside through nonexistent/.." 0 "$SMI" --out out study/write.lua os.rename.to out/nonexistent/../link_dir/moved.txt
if [ -e outside/moved.txt ]; then bad "os.rename put a file outside"; else ok; fi
run "os.remove of a link removes the link, not its target" 0 "$SMI" --out out study/write.lua os.remove out/link_dir
has_out "os.remove	true"
if [ -e outside/victim.txt ] && [ ! -L out/link_dir ]; then ok; else bad "os.remove followed the link"; fi
ln -s "$WORK/outside" out/link_dir

# --- solver models: template and extra files are read through the sandbox --------------------
printf '#!/bin/sh\ncat "$1"\n' > study/solver && chmod +x study/solver
printf 'x = {{x}} secret-data\n' > outside/template.txt
ln -s "$WORK/outside/template.txt" study/link_tmpl
cat > study/model.lua <<'LUA'
local what, path = ...
local o = {name = "m", inputs = {"x"}, outputs = {"y"}, command = {smi.script_dir .. "/solver", "{deck}"},
           parse = function(dir, h) return {y = 1} end}
if what == "template" then o.template = path else o.template_string = "x = {{x}}"; o.files = {path} end
local ok, err = pcall(smi.model.command, o)
print(what, ok, err)
LUA
for p in study/nonexistent/../link_tmpl "study/$LONG/../link_tmpl"; do
  run "solver template $(echo "$p" | cut -c1-30)" 0 "$SMI" --allow-exec study/solver --out out study/model.lua template "$p"
  has_out "template	false"
done
for p in "$NX" "$LG"; do
  run "solver extra file $(echo "$p" | cut -c1-30)" 0 "$SMI" --allow-exec study/solver --out out study/model.lua files "$p"
  has_out "files	false"
done

# --- the race: a symlink swapped between a file inside and one outside for ~1 s ------------
# The script opens (or writes, or requires) the name in a loop; no open may reach outside.
# perl (perl-base is Essential in Debian) swaps thousands of times a second; a shell loop
# spawning ln/mv swapped too slowly for the race to show reliably against the old resolver.
swap() {  # swap NAME INSIDE_FILE OUTSIDE_TARGET STOPFILE
  perl -e 'my ($n, $in, $out, $stop) = @ARGV;
    open(my $i, "<", $in) or die "$in: $!"; local $/; my $data = <$i>; close $i;
    until (-e $stop) {
      unlink "$n.l"; symlink($out, "$n.l"); rename("$n.l", $n);
      open(my $f, ">", "$n.f") or next; print {$f} $data; close $f; rename("$n.f", $n);
    }' "$1" "$2" "$3" "$4"
}
cat > study/race.lua <<'LUA'
local fn, path, seconds = ...
local t0, opens, escapes = smi.now(), 0, 0
while smi.now() - t0 < tonumber(seconds) do
  if fn == "read" then
    local ok, f = pcall(io.open, path)
    if ok and f then opens = opens + 1; if (f:read("a") or ""):find("secret") then escapes = escapes + 1 end f:close() end
  elseif fn == "write" then
    local ok, f = pcall(io.open, path, "w")
    if ok and f then opens = opens + 1; f:write("overwritten"); f:close() end
  elseif fn == "require" then
    package.loaded.racemod = nil
    local ok, v = pcall(require, "racemod")
    if ok then opens = opens + 1; if v == "secret" then escapes = escapes + 1 end end
  end
end
print("opens=" .. opens, "escapes=" .. escapes)
LUA
rm -f stop; swap study/race.txt study/inside.txt "$WORK/outside/secret.txt" stop & sp=$!
run "race: io.open while a link is swapped" 0 "$SMI" study/race.lua read study/race.txt 1.5
touch stop; wait $sp
has_out "escapes=0"
lacks_out "opens=0"
echo "precious" > outside/precious.txt; echo "mine" > out/mine.txt
rm -f stop; swap out/race.txt out/mine.txt "$WORK/outside/precious.txt" stop & sp=$!
run "race: io.open(w) while a link is swapped" 0 "$SMI" --out out study/race.lua write out/race.txt 1.5
touch stop; wait $sp
if [ "$(cat outside/precious.txt)" = "precious" ]; then ok; else bad "a write reached outside/precious.txt"; fi
lacks_out "opens=0"
printf 'return "inside"\n' > study/inside_mod.lua
printf 'return "secret"\n' > outside/secret_mod.lua
rm -f stop; swap study/racemod.lua study/inside_mod.lua "$WORK/outside/secret_mod.lua" stop & sp=$!
run "race: require while a link is swapped" 0 "$SMI" study/race.lua require x 1.5
touch stop; wait $sp
has_out "escapes=0"
lacks_out "opens=0"

# --- item 5: roots a script can choose ---------------------------------------------------------
mkdir -p names && cd names
printf 'local f = io.open(smi.out("x.txt"), "w"); f:write("x"); f:close()\nprint(pcall(function() assert(io.open("victim.txt", "w")) end))\n' > w.lua
for name in ...lua ..lua .lua; do
  cp w.lua "$name"
  run "script named $name" 0 "$SMI" "./$name"
  if [ -e x.txt ] || [ -e victim.txt ] || [ -e ../x.txt ]; then bad "a script named $name wrote into the working folder"; else ok; fi
  lacks_out "true"
  rm -f x.txt victim.txt
done
if [ -f smi-out/__/x.txt ] && [ -f smi-out/_/x.txt ] && [ -f smi-out/_lua/x.txt ]; then ok; else bad "outputs not under smi-out/__, smi-out/_, smi-out/_lua"; fi
cd "$WORK"
printf 'placeholder\n' > shared.sqlite
run "--store cannot be written by a script" 0 "$SMI" --store shared.sqlite -e \
    'print(pcall(function() local f = assert(io.open("shared.sqlite", "a")); f:write("forged"); f:close() end))'
has_out "is not allowed"
if grep -q forged shared.sqlite; then bad "the script wrote the --store file"; else ok; fi
run "--store can be read" 0 "$SMI" --store shared.sqlite -e 'print(io.open("shared.sqlite"):read("l"))'
out_is "placeholder"

# --- item 6: SMI_STDLIB_DIR loads the stdlib but does not widen what scripts read -----------
echo "stdlib-private" > stdlib/notes.txt
printf 'return {origin = "disk"}\n' > stdlib/smi/testing.lua
printf 'print(require("smi.testing").origin, pcall(io.open, os.getenv("SMI_STDLIB_DIR") .. "/notes.txt"))\n' > study/stdlib_read.lua
run "SMI_STDLIB_DIR is not a read root" 0 env SMI_STDLIB_DIR="$WORK/stdlib" "$SMI" --allow-env SMI_STDLIB_DIR study/stdlib_read.lua
has_out "disk"
has_out "is not allowed"
lacks_out "stdlib-private"
ln -s "$WORK/outside/secret.lua" stdlib/smi/escape.lua
run "the stdlib searcher refuses a link out of the stdlib folder" 1 env SMI_STDLIB_DIR="$WORK/stdlib" "$SMI" -e 'print(require("smi.escape"))'
has_err "is not allowed"
lacks_out "secret-data"

finish
