-- SPDX-License-Identifier: MIT
-- Object lifetimes in bindings: a bound function holds every object it uses
-- until it returns, whatever Lua code runs in between. Each case passes a Kriging inside a table
-- and an options table whose __index, when a later option is read, empties that table, drops
-- every other reference and collects (and closes through a <close> variable, which must only
-- mark it). The old bindings kept a raw pointer to the freed model (SIGSEGV, or ASan's
-- heap-use-after-free); the result must equal the one of a plain call.
local T = require "smi.testing"

local X = smi.doe.lhs(25, {{-2, 2}, {0, 1}}, {seed = 3})
local function fitted()
  local y = {}
  for i = 1, 25 do y[i] = 3 * X[i][1] + X[i][2] end
  return smi.kriging.fit(X, y, {trend = "linear", inputs = {"a", "b"}, output = "y"})
end
local dists = {a = smi.dist.normal{mean = 0.5, std = 1}, b = smi.dist.uniform{lower = 0, upper = 1}}

-- opts: the plain options; trigger: the option whose read drops the model; how: "gc" or "close".
local function hostile(plain, trigger, how)
  local km = fitted()
  local models = {y = km}
  km = nil
  local dropped = false
  return setmetatable({}, {__index = function(_, k)
    if k == "model" then return models end
    if k == trigger and not dropped then
      dropped = true
      if how == "close" then
        local c <close> = models.y
      end
      models.y = nil
      collectgarbage(); collectgarbage()
      -- memory the freed model had is reused at once
      local junk = {}
      for i = 1, 2000 do junk[i] = string.rep("x", 64) .. i end
    end
    return plain[k]
  end, __pairs = function() return next, plain, nil end})
end

for _, how in ipairs{"gc", "close"} do
  T.case("smi.propagate keeps a Kriging from {y = km} alive while options are read (" .. how .. ")", function()
    local plain = {inputs = dists, n = 200, seed = 4}
    local want = smi.propagate{model = {y = fitted()}, inputs = dists, n = 200, seed = 4}
    for _, trigger in ipairs{"inputs", "n", "seed"} do
      local got = smi.propagate(hostile(plain, trigger, how))
      for i = 1, 200 do T.near(got.y[i], want.y[i], 1e-9, trigger) end
    end
  end)

  T.case("smi.screen keeps it alive (" .. how .. ")", function()
    local plain = {inputs = {{"a", dists.a}, {"b", dists.b}}, n = 400, seed = 2, sobol = false}
    local want = smi.screen{model = {y = fitted()}, inputs = plain.inputs, n = 400, seed = 2, sobol = false}
    for _, trigger in ipairs{"inputs", "n"} do
      local got = smi.screen(hostile(plain, trigger, how))
      T.eq(smi.json.encode(got), smi.json.encode(want), trigger)
    end
  end)

  T.case("smi.kriging.sequential keeps it alive (" .. how .. ")", function()
    local design = smi.doe.lhs(6, {{-2, 2}, {0, 1}}, {seed = 5})
    local cand = smi.doe.lhs(40, {{-2, 2}, {0, 1}}, {seed = 6})
    local plain = {design = design, candidates = cand, batch = 2, max = 10, q2 = 0.999999, seed = 1}
    local want = smi.kriging.sequential{model = {y = fitted()}, design = design, candidates = cand, batch = 2,
                                        max = 10, q2 = 0.999999, seed = 1}
    for _, trigger in ipairs{"design", "candidates", "batch", "seed"} do
      local got = smi.kriging.sequential(hostile(plain, trigger, how))
      T.eq(got.X:rows(), want.X:rows(), trigger)
      for i = 1, got.X:rows() do T.near(got.Y.y[i], want.Y.y[i], 1e-9, trigger) end
    end
  end)
end

T.finish()
