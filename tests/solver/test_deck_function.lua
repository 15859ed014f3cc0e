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
  } do
    T.raises(function() model(fn):evaluate(X) end, "global '" .. name .. "' is not available: a deck function runs without I/O")
  end
  -- helpers reached through upvalues keep the study's environment, but the sandbox bars their I/O
  local here = smi.script_dir .. "/test_deck_function.lua"
  local function read_helper() return io.open(here):read("l") end
  T.raises(function() model(function(p) return read_helper() end):evaluate(X) end,
           "reading '" .. here .. "' is not allowed: a deck function runs without I/O")
  local out = smi.out("sneaky.txt")
  local function write_helper() return io.open(out, "w") end
  T.raises(function() model(function(p) write_helper(); return "" end):evaluate(X) end,
           "writing '" .. out .. "' is not allowed")
  T.raises(function() model(function(p) return 42 end):evaluate(X) end, "must return the deck text (a string), got number")
  T.raises(function() model(print) end, "must be a Lua function")
  -- after the refusals, the study's own I/O works again
  T.eq(read_helper(), "-- A command model whose template is a Lua function of the point: the deck computes,")
  local f = assert(io.open(out, "w")); f:write("ok"); f:close()
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
