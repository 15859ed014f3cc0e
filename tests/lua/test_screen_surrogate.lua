-- SPDX-License-Identifier: MIT
-- smi.screen{method = "surrogate"}: the model runs `runs` times in one call, the
-- eq.-3 indices on the surrogate match spec §8.5's analytic N_e for a model the surrogate
-- reproduces, a poor surrogate is reported, and misplaced options are errors.
local T = require "smi.testing"

local N = smi.dist.normal{mean = 0, std = 1}

T.case("linear model of spec 8.5 from 30 runs: analytic N_e, one model call", function()
  local calls, rows = 0, 0
  local function model(M)
    calls, rows = calls + 1, rows + #M
    return M:col(1) + M:col(2) * 2 + M:col(3) * 3
  end
  local r = smi.screen{model = model, inputs = {{"x1", N}, {"x2", N}, {"x3", N}, {"x4", 5}}, n = 40000, seed = 2,
                       sobol = false, method = "surrogate", runs = 30}
  T.eq(calls, 1); T.eq(rows, 30)
  T.eq(r.method, "surrogate"); T.eq(r.runs, 30); T.eq(r.terms, 6)
  T.truthy(r.q2 > 0.999999, "exact surrogate, Q2 = " .. r.q2)
  T.eq(#r.warnings, 0)
  local by = r.by_input
  T.near(by.x1.ne, 0.0522824, 0.01); T.near(by.x2.ne, 0.2368465, 0.01); T.near(by.x3.ne, 0.7108711, 0.01)
  T.eq(by.x4.e, 0)
  T.eq(r[1].input, "x3")
  T.truthy(tostring(r):find("30 model runs, leave-one-out Q2 = 1.0000", 1, true), "printed table names the surrogate")
  -- Borgonovo's delta from the 30 runs ranks x3 first too
  T.truthy(by.x3.delta > by.x2.delta and by.x2.delta > by.x1.delta, "delta ranks x3 > x2 > x1")
  T.truthy(r.delta_floor >= 0 and r.delta_classes >= 2, "delta's noise floor and class count reported")
  -- the full screening's result says which it is
  T.eq(smi.screen{model = model, inputs = {{"x1", N}, {"x2", N}, {"x3", N}}, n = 100, sobol = false}.method, "full")
end)

T.case("a poor surrogate carries a warning with its Q2", function()
  local U = smi.dist.uniform{lower = -math.pi, upper = math.pi}
  local function wiggle(M)
    local y = smi.vec(#M)
    for i = 1, #M do y[i] = math.sin(3 * M[i][1]) * M[i][2] end
    return y
  end
  local r = smi.screen{model = wiggle, inputs = {{"a", U}, {"b", U}}, n = 2000, sobol = false, method = "surrogate",
                       runs = 80}
  T.truthy(r.q2 < 0.5, "Q2 = " .. r.q2)
  T.truthy(r.warnings[1] and r.warnings[1]:find("Q2", 1, true), "warning names Q2")
end)

T.case("bad options name the culprit", function()
  local m = function(M) return M:col(1) end
  T.raises(function() smi.screen{model = m, inputs = {{"x", N}}, n = 100, runs = 50} end,
           "'runs' applies to method = \"surrogate\" only")
  T.raises(function() smi.screen{model = m, inputs = {{"x", N}}, n = 100, method = "kriging"} end, "method must be")
  T.raises(function() smi.screen{model = m, inputs = {{"x", N}}, n = 100, method = "surrogate", basis = "cubic"} end,
           "basis must be")
end)

T.finish()
