-- SPDX-License-Identifier: MIT
-- smi.calibrate intervals: profile intervals that equal the closed-form
-- likelihood-ratio intervals, "not determined" for a flat parameter, and bootstrap replicates
-- that are whole calibrations.
local T = require "smi.testing"

T.case("profile intervals of a normal mean: the closed-form likelihood-ratio interval", function()
  local x = smi.rng(8):normal(25, 3, 1.5)
  local n, xbar = #x, x:mean()
  local s2 = 0
  for i = 1, n do s2 = s2 + (x[i] - xbar) ^ 2 end
  s2 = s2 / n
  local r = smi.calibrate{
    parameters = {{"mu", -5, 10, 0}, {"sigma", 0.3, 6, 1}, {"unused", 0, 1, 0.5}},
    objective = function(t)
      local s = 0
      for i = 1, n do s = s + (x[i] - t.mu) ^ 2 end
      return n * math.log(t.sigma) + s / (2 * t.sigma ^ 2)
    end,
    intervals = {level = 0.9}, xtol_rel = 1e-10, ftol_abs = 1e-12, identifiability = false,
  }
  local delta = 0.5 * 1.6448536269514722 ^ 2
  T.near(r.intervals.delta, delta, 1e-9, "delta = chi2(0.9)/2")
  local half = math.sqrt(s2 * (math.exp(2 * delta / n) - 1))
  T.near(r.intervals.mu.lower, xbar - half, 1e-4, "lower")
  T.near(r.intervals.mu.upper, xbar + half, 1e-4, "upper")
  T.eq(r.intervals.mu.determined, true)
  T.eq(r.intervals.unused.determined, false, "flat to both bounds")
  T.eq(r.intervals.unused.lower, 0)
  T.eq(r.intervals.unused.upper, 1)
  local said = false
  for _, w in ipairs(r.warnings) do said = said or w:find("'unused' is not determined by the data", 1, true) ~= nil end
  T.truthy(said, "warned")
end)

T.case("PR needs a delta; bad interval options name the field", function()
  local spec = {model = function(M) return {y = M:col(1)} end, inputs = {x = {mean = {0, 10, 1}, std = 1}}, data = {y = {1, 2, 3}}}
  spec.intervals = true
  T.raises(function() smi.calibrate(spec) end, "PR is not a log-likelihood")
  spec.intervals = {level = 0.9, delta = 1}
  T.raises(function() smi.calibrate(spec) end, "not both")
  spec.intervals = {delta = -1}
  T.raises(function() smi.calibrate(spec) end, "smi.calibrate intervals: delta must be > 0, got -1")
  spec.intervals = {levl = 0.9}
  T.raises(function() smi.calibrate(spec) end, "smi.calibrate intervals: unknown option 'levl' (did you mean 'level'?)")
  spec.intervals = {level = 0.9, observations = 0}
  T.raises(function() smi.calibrate(spec) end, "smi.calibrate intervals: observations must be >= 1, got 0")
  spec.intervals = {delta = 1, observations = 5}
  T.raises(function() smi.calibrate(spec) end, "goes with level, not delta")
  spec.intervals = nil
  spec.identifiability = {tolerance = 0}
  T.raises(function() smi.calibrate(spec) end, "smi.calibrate identifiability: tolerance must be > 0, got 0")
  spec.identifiability = {point = 5}
  T.raises(function() smi.calibrate(spec) end, "smi.calibrate identifiability: unknown option 'point' (did you mean 'points'?)")
end)

T.case("bootstrap replicates are whole calibrations from their own starts, not warm starts", function()
  -- y = x1 + 2 x2: only mu1 + 2 mu2 is determined. Warm-started replicates stay near the optimum
  -- (false confidence); whole calibrations spread along the valley.
  local g = smi.rng(3)
  local x1, x2 = g:normal(100, 1, 0.3), g:normal(100, 2, 0.3)
  local spec = {model = function(M) return {y = M:col(1) + M:col(2) * 2} end,
                inputs = {x1 = {mean = {0, 4, 0.5}, std = 0.3}, x2 = {mean = {0, 4, 3.0}, std = 0.3}},
                data = {y = x1 + x2 * 2}, n = 300, grid_nodes = 1001, seed = 4, identifiability = false, multistart = 3,
                maxeval = 120}
  spec.bootstrap = {replicates = 6, level = 0.9, warm = true}
  local warm = smi.calibrate(spec)
  spec.bootstrap = {replicates = 6, level = 0.9}
  local full = smi.calibrate(spec)
  local ww = warm.bootstrap.upper["x1.mean"] - warm.bootstrap.lower["x1.mean"]
  local fw = full.bootstrap.upper["x1.mean"] - full.bootstrap.lower["x1.mean"]
  T.truthy(fw > 3 * ww and fw > 0.5, ("whole calibrations spread along the valley: %.3f vs warm %.3f"):format(fw, ww))
end)

T.case("a Lua model on two threads takes turns: the numbers of one thread; its error on a worker stays its own", function()
  -- The replicates and the starts run side by side; only the model's calls take turns
  -- (bindings/improve/lua_gate.hpp). A model that counts its calls is safe: they never overlap.
  local g = smi.rng(5)
  local a, b = g:normal(9, 1.5, 0.2), g:normal(9, 2.5, 0.3)
  local calls, limit = 0, math.huge
  local function model(M)
    calls = calls + 1
    if calls > limit then error("the model broke at call " .. calls) end
    return {y = M:col(1) * 2 + M:col(2), z = M:col(1) - M:col(2)}
  end
  local function spec(threads, bootstrap)
    return {model = model, inputs = {x1 = {mean = {0.5, 3, 1}, std = {0.05, 0.6, 0.3}}, x2 = {mean = {1, 4, 2}, std = 0.3}},
            data = {y = a * 2 + b, z = a - b}, n = 400, grid_nodes = 1001, seed = 8, identifiability = false,
            multistart = 2, maxeval = 80, threads = threads, bootstrap = bootstrap}
  end
  local boot = {replicates = 4, level = 0.9}
  local one, two = smi.calibrate(spec(1, boot)), smi.calibrate(spec(2, boot))
  for _, name in ipairs({"x1.mean", "x1.std", "x2.mean"}) do
    T.eq(two.theta[name], one.theta[name], name .. ": the optimum of one thread")
    T.eq(two.bootstrap.std[name], one.bootstrap.std[name], name .. ": the replicates' spread of one thread")
  end
  T.eq(two.bootstrap.evaluations, one.bootstrap.evaluations, "the replicates' evaluations")
  -- The model breaks at its first call after the calibration itself: every replicate fails on a
  -- worker thread or the caller's; the optimum stands and the warning names the model's error.
  calls = 0
  smi.calibrate(spec(2, nil))
  limit, calls = calls, 0
  local r = smi.calibrate(spec(2, boot))
  T.eq(r.theta["x1.mean"], one.theta["x1.mean"], "the optimum stands")
  local said = false
  for _, w in ipairs(r.warnings) do said = said or tostring(w):find("the model broke at call", 1, true) ~= nil end
  T.truthy(said, "a warning names the model's error: " .. table.concat(r.warnings, " | "))
  T.eq(r.bootstrap, nil, "no bootstrap result")
  T.truthy(r.not_computed and r.not_computed.bootstrap:find("only 0 of 4 replicates succeeded (replicate 1: ", 1, true)
           and r.not_computed.bootstrap:find("the model broke at call", 1, true),
           "r.not_computed.bootstrap says why: " .. tostring(r.not_computed and r.not_computed.bootstrap))
end)

T.finish()
