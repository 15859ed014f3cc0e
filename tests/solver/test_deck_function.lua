-- SPDX-License-Identifier: MIT
-- A command model whose template is a Lua function of the point: the deck computes,
-- I/O is refused inside it, and a writable store's missing folder is made. Drives the in-tree
-- test solver (f = x1^2 + x2^2, g = x1 + 2 x2). arg[1] = its path, arg[2] = the fixtures folder.
local T = require "smi.testing"
local solver = arg[1]

local n = 0
local function model(template, opts)
  n = n + 1
  local o = {
    name = "deckfn" .. n, inputs = {"log10_x1", "x2"}, outputs = {"f", "g"},
    template = template, deck = "run.deck",
    command = {solver, "{deck}", "-o", "out.txt"}, version = "deck-fn-" .. n,
    parse = function(dir, h)
      return {f = h.regex("out.txt", "f = (\\S+)"), g = h.regex("out.txt", "g = (\\S+)")}
    end,
  }
  for k, v in pairs(opts or {}) do o[k] = v end
  return smi.model.command(o)
end

local function powers(p)   -- a deck that computes: x1 = 10^log10_x1, written with string.format
  local lines = {}
  lines[#lines + 1] = string.format("x1 = %.17g", 10 ^ p.log10_x1)
  lines[#lines + 1] = string.format("x2 = %.17g", p.x2 * p.scale)
  return table.concat(lines, "\n") .. "\n"
end

T.case("a deck function computes the deck from the point and the constants", function()
  local m = model(powers, {constants = {scale = 2}})
  local Y, info = m:evaluate(smi.mat{{0, 1}, {1, 0.5}, {-1, 0}})
  T.eq(info.launched, 3)
  T.near(Y.f[1], 1 + 4, 1e-12); T.near(Y.g[1], 1 + 4, 1e-12)
  T.near(Y.f[2], 100 + 1, 1e-12); T.near(Y.g[2], 10 + 2, 1e-12)
  T.near(Y.f[3], 0.01, 1e-12); T.near(Y.g[3], 0.1, 1e-12)
  -- the deck text is the key: the same points again are stored results, a new scale is not
  local _, again = m:evaluate(smi.mat{{0, 1}})
  T.eq(again.launched, 0)
  local _, other = model(powers, {constants = {scale = 3}, version = m.version}):evaluate(smi.mat{{0, 1}})
  T.eq(other.launched, 1)
  T.eq(m:plan(smi.mat{{1, 0.5}, {2, 2}}).runs, 1)
end)

T.case("I/O inside a deck function is refused, naming what was tried", function()
  local X = smi.mat{{0, 1}}
  for name, fn in pairs{
    io = function(p) return io.open("/etc/passwd"):read("a") end,
    os = function(p) return tostring(os.time()) end,
    require = function(p) return require("smi.testing") and "" end,
    load = function(p) return load("return 1")() and "" end,
    dofile = function(p) return dofile("/etc/passwd") end,
    print = function(p) print("x") return "" end,
    smi = function(p) return smi.csv.read("/etc/passwd") end,
    collectgarbage = function(p) collectgarbage() return "" end,
    setmetatable = function(p) setmetatable({}, {__gc = function() end}) return "" end,
  } do
    T.raises(function() model(fn):evaluate(X) end, "global '" .. name .. "' is not available: a deck function runs without I/O")
  end
  -- helpers reached through upvalues are copied with the function: their globals are the deck's
  local here = smi.script_dir .. "/test_deck_function.lua"
  local function read_helper() return io.open(here):read("l") end
  T.raises(function() model(function(p) return read_helper() end):evaluate(X) end, "global 'io' is not available")
  local out = smi.out("sneaky.txt")
  local function write_helper() return io.open(out, "w") end
  T.raises(function() model(function(p) write_helper(); return "" end):evaluate(X) end, "global 'io' is not available")
  T.raises(function() model(function(p) return 42 end):evaluate(X) end, "must return the deck text (a string), got number")
  T.raises(function() model(function(p) error({}) end):evaluate(X) end, "raised an error that is not a string (a table)")
  T.raises(function() model(function(p) return string.dump(p) end):evaluate(X) end, "attempt to call a nil value (field 'dump')")
  T.raises(function() model(print) end, "must be a Lua function")
  -- after the refusals, the study's own I/O works
  T.eq(read_helper(), "-- SPDX-License-Identifier: MIT")
  local f = assert(io.open(out, "w")); f:write("ok"); f:close()
end)

T.case("a deck function runs in a Lua state of its own: the study's objects are out of its reach", function()
  local X = smi.mat{{0, 1}}
  -- the string metatable is the deck state's own: replacing a method there leaves the study's alone
  local _, info = model(function(p)
    getmetatable("").__index.upper = function() return "taken" end
    string.lower = nil
    assert(("a"):upper() == "taken")
    return ("x1 = 1\nx2 = %s\n"):format(p.x2)
  end, {version = "own-metatable"}):evaluate(X)
  T.eq(info.launched, 1)
  T.eq(("a"):upper(), "A"); T.eq(string.upper("a"), "A"); T.eq(string.lower("B"), "b")
  -- a file handle, a smi object, a coroutine or a C function outside the standard libraries
  -- cannot be captured: the model is refused when it is made, naming the function and the upvalue
  local fh = assert(io.open(smi.out("handle.txt"), "w"))
  T.raises(function() model(function(p) fh:write("leak"); return "" end) end, "'fh' is a file handle")
  T.raises(function() model(function(p) fh:write("leak"); return "" end) end, "test_deck_function.lua:")
  local function nested() return fh end
  T.raises(function() model(function(p) nested(); return "" end) end, "'nested' > 'fh' is a file handle")
  local box = {inner = {handle = fh}}
  T.raises(function() model(function(p) return box.inner and "" end) end, "'box' > field 'inner' > field 'handle' is a file handle")
  local v = smi.vec{1, 2}
  T.raises(function() model(function(p) return tostring(v[1]) end) end, "'v' is a userdata (smi.vec)")
  local co = coroutine.create(function() end)
  T.raises(function() model(function(p) return coroutine.status(co) end) end, "'co' is a thread")
  local open = io.open
  T.raises(function() model(function(p) return open("/etc/passwd") end) end, "'open' is a C function that is not one of the standard")
  local meta = setmetatable({}, {__index = function() return fh end})
  T.raises(function() model(function(p) return meta.x end) end, "'meta' is a table with a metatable")
  local rand = math.random
  T.raises(function() model(function(p) return tostring(rand()) end) end, "'rand' is math.random, which a deck function does not have")
  fh:write("study"); fh:close()
  T.eq(io.open(smi.out("handle.txt")):read("a"), "study")
end)

T.case("what a deck function captures is copied when the model is made", function()
  local consts = {scale = 2, names = {"x1", "x2"}}
  consts.self = consts  -- a cycle stays a cycle
  local fmt = string.format  -- a standard function is the deck state's own
  local function line(name, v) return fmt("%s = %.17g", name, v) end
  local function fact(n) return n <= 1 and 1 or n * fact(n - 1) end  -- recursive: its own upvalue
  local m = model(function(p)
    assert(consts.self.self == consts)
    return line(consts.names[1], 10 ^ p.log10_x1) .. "\n" .. line(consts.names[2], p.x2 * consts.scale * fact(3) / 6) .. "\n"
  end, {version = "copied"})
  consts.scale = 100  -- changed after the model was made: the deck state has its own copy
  consts.names[1] = "nope"
  local Y = m:evaluate(smi.mat{{0, 1}})
  T.near(Y.f[1], 1 + 4, 1e-12); T.near(Y.g[1], 1 + 4, 1e-12)
end)

T.case("a writable store in a folder that does not exist yet is made there", function()
  local store = smi.out("shared/stores/plate.sqlite")
  local m = model(powers, {constants = {scale = 1}, store = store})
  local _, info = m:evaluate(smi.mat{{0, 1}})
  T.eq(info.launched, 1)
  T.truthy(io.open(store, "rb"), "the store file exists")
  local _, again = model(powers, {constants = {scale = 1}, store = store, version = m.version}):evaluate(smi.mat{{0, 1}})
  T.eq(again.launched, 0, "a second model reads the shared store")
  T.raises(function() model(powers, {constants = {scale = 1}, store = "/proc/nowhere/x.sqlite"}) end, "--allow-write")
end)

T.finish()
