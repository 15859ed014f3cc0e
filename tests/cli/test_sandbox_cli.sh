#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Sandbox rules that need flags, files or a fresh process: symlinks out of the study folder,
# --allow-read/--allow-write, the output folder, module search, --timeout and --max-memory
# (neither can be swallowed by pcall), and the stdlib from disk.
source "$(dirname "$0")/lib.sh"

mkdir -p study/data outside lib1 lib2 stdlib/smi
echo "secret" > outside/secret.txt
echo "1,2" > study/data/points.csv
ln -s "$WORK/outside" study/data/link_dir
ln -s "$WORK/outside/secret.txt" study/data/link_file
ln -s /etc/passwd study/passwd

# --- reading: own folder yes; symlinks and absolute paths out of it no
cat > study/read.lua <<'LUA'
local what = ...
local f = assert(io.open(what))
print(f:read("l"))
LUA
run "read own folder" 0 "$SMI" study/read.lua study/data/points.csv
out_is "1,2"
run "read relative to a nested folder" 0 "$SMI" study/read.lua study/data/../data/points.csv
run "symlinked dir out" 1 "$SMI" study/read.lua study/data/link_dir/secret.txt
has_err "io.open: reading 'study/data/link_dir/secret.txt' (a link on the way leads outside the folders allowed) is not allowed"
has_err "allow its folder with --allow-read"
lacks_err "$WORK/outside"
run "symlinked file out" 1 "$SMI" study/read.lua study/data/link_file
has_err "reading 'study/data/link_file' (a link on the way leads outside the folders allowed)"
lacks_err "$WORK/outside"
run "symlink to /etc/passwd" 1 "$SMI" study/read.lua study/passwd
lacks_err "/etc/passwd"
run "dot-dot out" 1 "$SMI" study/read.lua study/../outside/secret.txt
has_err "is not allowed"
run "../../etc/passwd" 1 "$SMI" study/read.lua ../../../../../../../../../etc/passwd
has_err "resolved to '/etc/passwd'"
run "absolute path" 1 "$SMI" study/read.lua "$WORK/outside/secret.txt"
run "--allow-read opens it" 0 "$SMI" --allow-read outside study/read.lua study/data/link_file
out_is "secret"

# --- writing: only under --out (made on demand) and --allow-write
cat > study/write.lua <<'LUA'
local path = ...
local f = assert(io.open(path or smi.out("result.txt"), "w"))
f:write("ok\n")
f:close()
print(smi.out_dir)
LUA
printf 'print("nothing written")\n' > study/idle.lua
run "no output folder unless written" 0 "$SMI" study/idle.lua
if [ -e smi-out ]; then bad "smi-out was created by a script that wrote nothing"; else ok; fi
run "default --out" 0 "$SMI" study/write.lua
out_is "smi-out/write"
if [ -f smi-out/write/result.txt ]; then ok; else bad "smi-out/write/result.txt missing"; fi
run "--out" 0 "$SMI" --out results/run1 study/write.lua
if [ -f results/run1/result.txt ]; then ok; else bad "results/run1/result.txt missing"; fi
run "write into the study folder" 1 "$SMI" study/write.lua study/x.txt
has_err "io.open: writing 'study/x.txt'"
has_err "--allow-write $WORK/study to allow it"
run "write through a symlink out" 1 "$SMI" --allow-write study study/write.lua study/data/link_dir/planted.txt
has_err "writing 'study/data/link_dir/planted.txt' (a link on the way leads outside the folders allowed)"
lacks_err "$WORK/outside"
run "--allow-write" 0 "$SMI" --allow-write study study/write.lua study/x.txt
if [ -f study/x.txt ]; then ok; else bad "study/x.txt missing"; fi

# --- require: script folder, --lib, SMI_PATH; text only; every place listed on failure
printf 'return "from study"\n' > study/near.lua
printf 'return "from lib1"\n' > lib1/one.lua
mkdir -p lib2/pkg && printf 'return "from lib2 init"\n' > lib2/pkg/init.lua
printf 'print(require "near", require "one", (require "pkg"))\n' > study/req.lua
run "require search" 0 env SMI_PATH="$WORK/lib2" "$SMI" --lib lib1 study/req.lua
out_is "$(printf 'from study\tfrom lib1\tfrom lib2 init')"
printf 'require "missing.mod"\n' > study/req_missing.lua
run "require lists places" 1 env SMI_PATH="$WORK/lib2" "$SMI" --lib lib1 study/req_missing.lua
has_err "module 'missing.mod' not found"
has_err "no file 'study/missing/mod.lua'"
has_err "no file 'lib1/missing/mod.lua'"
has_err "no file '$WORK/lib2/missing/mod/init.lua'"
has_err "no embedded stdlib module 'missing.mod'"
run "-E ignores SMI_PATH" 1 env SMI_PATH="$WORK/lib2" "$SMI" -E study/req.lua
printf '\033Lua\124\000\031\223\r\n\032\n\004\010\010xV\000\000' > study/bin.lua
printf 'require "bin"\n' > study/req_bin.lua
run "require refuses bytecode" 1 "$SMI" study/req_bin.lua
has_err "attempt to load a binary chunk (mode is 't')"
ln -s "$WORK/outside" lib1/escape && printf 'return 1\n' > outside/evil.lua
printf 'require "escape.evil"\n' > study/req_escape.lua
run "require through a symlink out" 1 "$SMI" --lib lib1 study/req_escape.lua
has_err "require: reading 'lib1/escape/evil.lua'"

# --- the stdlib: embedded, with real chunk names; or from disk for development
printf 'local T = require "smi.testing"\nT.near(1, 2, 0.1)\n' > study/near_fail.lua
run "embedded stdlib chunk names" 1 "$SMI" study/near_fail.lua
has_err "stdlib/smi/testing.lua:"
printf 'return {origin = "disk"}\n' > stdlib/smi/testing.lua
run "--stdlib-dir" 0 "$SMI" --stdlib-dir stdlib -e 'print(require("smi.testing").origin)'
out_is "disk"
run "SMI_STDLIB_DIR" 0 env SMI_STDLIB_DIR="$WORK/stdlib" "$SMI" -e 'print(require("smi.testing").origin)'
out_is "disk"
run "stdlib fallback to embedded" 0 "$SMI" --stdlib-dir lib1 -e 'print(type(require("smi.testing").near))'
out_is "function"

# --- limits that pcall cannot swallow
run "timeout" 1 timeout 20 "$SMI" --timeout 0.3 -e "while true do end"
has_err "(command line):1: timeout: the run took longer than --timeout 0.3 s"
run "timeout vs pcall" 1 timeout 20 "$SMI" --timeout 0.3 -e \
    "for i = 1, math.huge do pcall(function() while true do end end) end print('escaped')"
has_err "timeout"
lacks_out "escaped"
run "timeout vs coroutines" 1 timeout 20 "$SMI" --timeout 0.3 -e \
    "while true do local co = coroutine.create(function() while true do end end); coroutine.resume(co) end"
has_err "timeout"
run "timeout vs xpcall handler" 1 timeout 20 "$SMI" --timeout 0.3 -e \
    "while true do xpcall(function() while true do end end, function(m) return m end) end"
run "no timeout when fast" 0 "$SMI" --timeout 5 -e "local s = 0 for i = 1, 1e6 do s = s + i end"
run "max-memory" 1 timeout 20 "$SMI" --max-memory 32 -e "local t = {} for i = 1, 1e9 do t[i] = ('x'):rep(64) .. i end"
has_err "memory limit exceeded: the Lua heap would pass --max-memory 32 MB"
run "max-memory vs pcall" 1 timeout 20 "$SMI" --max-memory 32 -e \
    "local keep = {} while true do pcall(function() for i = 1, 1e9 do keep[#keep + 1] = ('y'):rep(64) .. i end end) end"
has_err "memory limit exceeded"
run "max-memory one big string" 1 timeout 20 "$SMI" --max-memory 16 -e "local s = ('x'):rep(64 * 1024 * 1024)"
has_err "memory limit exceeded"
run "max-memory leaves room" 0 "$SMI" --max-memory 64 -e "local t = {} for i = 1, 1e5 do t[i] = i end"

# --- process functions are absent, and say so
run "io.popen absent" 1 "$SMI" -e "io.popen('ls')"
has_err "attempt to call a nil value (field 'popen')"
has_err "io.popen is removed by the sandbox"
run "os.execute absent" 1 "$SMI" -e "os.execute('true')"
has_err "attempt to call a nil value (field 'execute')"
has_err "--allow-exec"

finish
