-- SPDX-License-Identifier: MIT
-- The sandbox, from inside: every rule a hostile script could try, and what stays allowed.
-- Run by ctest as `smi-lua --quiet --allow-read tests/reference --out <build>/test-out/... file`
-- from the build directory (tests/cli/ covers the rules that need other flags or files).
local T = require "smi.testing"

local here = smi.script_dir
local reference = os.getenv("SMI_TEST_REFERENCE_DIR")

local function denied(fn, path_part, flag)
  local err = T.raises(fn, "is not allowed")
  T.truthy(err:find(path_part, 1, true), "the denial names the path: " .. err)
  T.truthy(err:find(flag, 1, true), "the denial names the flag " .. flag .. ": " .. err)
  return err
end

T.case("reading outside the allowed folders is denied, whatever the spelling", function()
  denied(function() io.open("/etc/passwd") end, "/etc/passwd", "--allow-read")
  denied(function() io.open("../../../../../../../../etc/passwd") end, "/etc/passwd", "--allow-read")
  denied(function() io.open(here .. "/../../../../../../../etc/passwd") end, "/etc/passwd", "--allow-read")
  denied(function() io.lines("/etc/passwd") end, "/etc/passwd", "--allow-read")
  denied(function() io.input("/etc/passwd") end, "/etc/passwd", "--allow-read")
  denied(function() dofile("/etc/passwd") end, "/etc/passwd", "--allow-read")
  denied(function() loadfile("/etc/passwd") end, "/etc/passwd", "--allow-read")
  local err = denied(function() io.open("/etc/passwd") end, "/etc/passwd", "--allow-read")
  T.truthy(err:find("io.open", 1, true), "the denial names the function")
end)

T.case("the script's folder, --allow-read folders and the output folder are readable", function()
  local f = assert(io.open(here .. "/test_sandbox.lua"))
  T.eq(f:read("l"), "-- SPDX-License-Identifier: MIT")
  T.eq(f:read("l"), "-- The sandbox, from inside: every rule a hostile script could try, and what stays allowed.")
  f:close()
  T.truthy(reference, "SMI_TEST_REFERENCE_DIR is set by ctest")
  local n = 0
  for _ in io.lines(reference .. "/normal_quantile.csv") do n = n + 1 end
  T.truthy(n > 1, "a reference file reads through --allow-read")
end)

T.case("writing goes under --out only", function()
  local p = smi.out("probe.txt")
  local f = assert(io.open(p, "w"))
  f:write("42\n")
  f:close()
  T.eq(io.open(p):read("n"), 42)
  T.eq(os.rename(p, smi.out("probe2.txt")), true)
  T.eq(os.remove(smi.out("probe2.txt")), true)
  denied(function() io.open(here .. "/written.txt", "w") end, "written.txt", "--allow-write")
  denied(function() io.open(here .. "/test_sandbox.lua", "a") end, "test_sandbox.lua", "--allow-write")
  denied(function() io.open(here .. "/test_sandbox.lua", "r+") end, "test_sandbox.lua", "--allow-write")
  denied(function() io.output(here .. "/written.txt") end, "written.txt", "--allow-write")
  denied(function() os.remove(here .. "/test_sandbox.lua") end, "test_sandbox.lua", "--allow-write")
  denied(function() os.rename(smi.out("x"), here .. "/x") end, "/x", "--allow-write")
  -- ".." out of the output folder is resolved before the check
  denied(function() io.open(smi.out("../../escape.txt"), "w") end, "escape.txt", "--allow-write")
end)

T.case("process, loader and introspection functions are gone", function()
  T.eq(io.popen, nil); T.eq(io.tmpfile, nil)
  T.eq(os.execute, nil); T.eq(os.tmpname, nil); T.eq(os.setlocale, nil)
  T.eq(package.loadlib, nil); T.eq(package.searchpath, nil)
  T.eq(string.dump, nil); T.eq(("").dump, nil)
  T.eq(debug.getinfo, nil); T.eq(debug.sethook, nil); T.eq(debug.getupvalue, nil)
  T.eq(debug.getregistry, nil); T.eq(debug.setmetatable, nil)
  T.eq(require("debug"), debug)
  T.eq(type(debug.traceback), "function")
  T.truthy(debug.traceback("x"):find("stack traceback", 1, true), "traceback still works")
  T.eq(type(os.getenv), "function"); T.eq(type(os.clock), "function"); T.eq(type(os.date), "function")
end)

T.case("binary chunks are refused by load, loadfile and require", function()
  -- The header of a Lua 5.4 binary chunk: ESC "Lua" 0x54 ...
  local bytecode = "\27Lua\84\0\25\147\13\10\26\10\4\8\8\120\86\0\0\0\0\0\0\0\0\0\0\0\40\119\64\1"
  local f, err = load(bytecode)
  T.eq(f, nil)
  T.truthy(err:find("binary chunk", 1, true), "load says why: " .. tostring(err))
  T.raises(function() load(bytecode, "x", "b") end, "binary chunks are not allowed")
  T.raises(function() load("return 1", "x", "b") end, "binary chunks are not allowed")
  f, err = load(bytecode, "x", "bt")
  T.eq(f, nil)
  T.raises(function() loadfile(here .. "/test_sandbox.lua", "b") end, "binary chunks are not allowed")
  -- text still loads, with an explicit environment too
  T.eq(load("return 1 + 1")(), 2)
  T.eq(load("return x", "chunk", "t", {x = 5})(), 5)
end)

T.case("C modules cannot be required; a failed require lists every place searched", function()
  local err = T.raises(function() require "lfs" end, "module 'lfs' not found")
  T.truthy(err:find("no field package.preload['lfs']", 1, true), err)
  T.truthy(err:find("no embedded stdlib module 'lfs'", 1, true), err)
  T.truthy(err:find("/lfs.lua'", 1, true), "the script folder is searched: " .. err)
  T.truthy(not err:find(".so", 1, true), "no C library path is searched: " .. err)
  T.eq(package.cpath, "")
  T.raises(function() require "a/../b" end, "may not contain '/'")
  T.raises(function() require "..etc" end, "empty component")
end)

T.case("math.random is seeded from --seed", function()
  local a = {math.random(1, 1000000), math.random(1, 1000000), math.random()}
  math.randomseed()  -- reseeds with smi.seed, not the clock
  local b = {math.random(1, 1000000), math.random(1, 1000000), math.random()}
  for i = 1, 3 do T.eq(a[i], b[i], "value " .. i) end
  math.randomseed(smi.seed)
  T.eq(math.random(1, 1000000), a[1])
  T.eq(smi.seed, 20200214)
end)

T.case("no internal function is reachable: every name starting with '_' a script can see is meant for it", function()
  -- read-only views of the reference (docs/sandbox.md, "Internal functions"), and Lua's own
  local meant = {_docs = true, _closest = true, _known_options = true, _VERSION = true, _G = true}
  local internal = {inputs = true, digest = true, sha256 = true, not_input = true}
  local seen, found, leaked = {}, {}, {}
  local function walk(t, path, depth)
    if seen[t] or depth > 8 then return end
    seen[t] = true
    for k, v in next, t do
      if type(k) == "string" then
        local p = path .. "." .. k
        if k:match("^_") and not k:match("^__") and not meant[k] then found[#found + 1] = p end
        if internal[k] and type(v) == "function" then leaked[#leaked + 1] = p end
      end
      local sub = type(k) == "string" and path .. "." .. k or path .. "[?]"
      if type(v) == "table" then walk(v, sub, depth + 1) end
      if type(v) == "userdata" and type(getmetatable(v)) == "table" then walk(getmetatable(v), sub .. "<meta>", depth + 1) end
    end
    local mt = getmetatable(t)
    if type(mt) == "table" then walk(mt, path .. "<meta>", depth + 1) end
  end
  -- a script that replaced the global functions first still catches nothing the stdlib holds
  local caught = {}
  local real = {select = select, type = type, pairs = pairs, next = next, tostring = tostring}
  for name, fn in pairs(real) do
    _G[name] = function(...)
      for i = 1, real.select("#", ...) do
        local v = real.select(i, ...)
        if real.type(v) == "table" and real.type(rawget(v, "not_input")) == "function" then caught[#caught + 1] = name end
      end
      return fn(...)
    end
  end
  package.loaded["smi.study"], package.loaded["smi.study_inputs"] = nil, nil
  local ok, err = pcall(function()
    local st = require "smi.study"  -- loads the stdlib modules that hold the internal functions
    st.new{name = "internal", out = smi.out(), results = smi.out("internal.json"), quiet = true}
    require("smi.study_inputs").hash({1})
  end)
  for name, fn in real.pairs(real) do _G[name] = fn end
  T.truthy(ok, tostring(err))
  T.eq(table.concat(caught, ", "), "", "global functions that were handed the internal table")
  walk(_G, "_G", 0)
  walk(getmetatable(""), "<string meta>", 0)
  table.sort(found)
  table.sort(leaked)
  T.eq(table.concat(found, ", "), "", "undocumented internal names")
  T.eq(table.concat(leaked, ", "), "", "internal functions reachable")
  T.eq(smi._not_input, nil); T.eq(smi._digest, nil); T.eq(smi._inputs, nil); T.eq(smi._sha256, nil)
  -- the study's own results file leaves the provenance only where the run may write it: a data
  -- file the run only reads stays an input, whatever a study calls its results file
  T.raises(function() require("smi.study").new{name = "r", results = here .. "/test_sandbox.lua"} end,
           "does not lie under --out or an --allow-write folder")
  -- require's second result (the loader data) is the module's path, not the internal table
  package.loaded["smi.study"] = nil
  local _, data = require("smi.study")
  T.eq(type(data), "string")
end)

T.finish()
