-- SPDX-License-Identifier: MIT
-- smi.calibrate: identifiability as directions, near-optimal sets, priors, distinct optima
-- (the contract in `smi-lua doc smi.calibrate`).
local T = require "smi.testing"

local function find_weak(r)
  local weak = {}
  for _, d in ipairs(r.identifiability.directions) do
    if not d.determined then weak[#weak + 1] = d end
  end
  return weak
end

T.case("y = x1 + 2 x2 with unknown means and stds: (2, -1)/sqrt5 in the means is not determined", function()
  local g = smi.rng(3)
  local x1, x2 = g:normal(200, 1, 0.5), g:normal(200, 2, 0.3)
  local r = smi.calibrate{
    model = function(M) return {y = M:col(1) + M:col(2) * 2} end,
    -- equal ranges for both means, so scaled units keep the (2, -1) shape
    inputs = {x1 = {mean = {0, 4, 1.5}, std = {0.1, 1, 0.4}}, x2 = {mean = {0, 4, 1.5}, std = {0.1, 1, 0.4}}},
    data = {y = x1 + x2 * 2}, n = 1000, grid_nodes = 2001, seed = 4,
  }
  local dirs = r.identifiability.directions
  T.eq(#dirs, 4, "one direction per parameter")
  local found
  for _, d in ipairs(find_weak(r)) do
    if math.abs(d.loadings["x1.mean"] - 2 / math.sqrt(5)) < 1e-3 and math.abs(d.loadings["x2.mean"] + 1 / math.sqrt(5)) < 1e-3 then found = d end
  end
  T.truthy(found, "the (2, -1)/sqrt5 mean direction is among the undetermined")
  T.truthy(found.curvature < 1e-6 * dirs[1].curvature, "flat along it")
  T.truthy(dirs[1].determined, "the strongest direction (mean of y) is determined")
  T.near(math.abs(dirs[1].loadings["x1.mean"]), 1 / math.sqrt(5), 0.02, "mean of y: (1, 2)/sqrt5")
  -- curvatures strongest first; profiles reported
  for i = 2, #dirs do T.truthy(dirs[i].curvature <= dirs[i - 1].curvature, "sorted") end
  T.truthy(#found.profile.t == #found.profile.objective and #found.profile.t >= 3, "profile to the bounds")
  -- near-optimal points: the optimum first, all within tolerance, spread along the weak directions
  local no = r.near_optimal
  T.truthy(#no.points >= 3, "optimum + both ends of the mean valley")
  T.eq(no.points[1]["x1.mean"], r.params["x1.mean"], "optimum first")
  local spread = 0
  for i, p in ipairs(no.points) do
    T.truthy(no.objectives[i] <= r.objective + no.tolerance + 1e-12, "within tolerance")
    -- kept to well within what 200 data tell of it: their standard error sqrt(0.5² + 4·0.3²)/sqrt(200) = 0.055
    T.near(p["x1.mean"] + 2 * p["x2.mean"], r.params["x1.mean"] + 2 * r.params["x2.mean"], 0.03, "mean of y kept")
    spread = math.max(spread, math.abs(p["x1.mean"] - r.params["x1.mean"]))
  end
  T.truthy(spread > 1, "spread along the valley")
end)

local g = smi.rng(99)
local a, b = g:normal(300, 5, 0.3), g:normal(300, 2, 0.2)
local data = {y1 = a + b * b, y2 = a * 3 - b}
local function model(M)
  local A, B = M:col(1), M:col(2)
  return {y1 = A + B * B, y2 = A * 3 - B}
end
local inputs = {a = {dist = "normal", mean = {3, 7, 4}, std = {0.05, 1, 0.5}},
                b = {dist = "normal", mean = {1, 3, 2.5}, std = {0.05, 1, 0.5}}}

T.case("every parameter identifiable: every direction determined, the near-optimal set is the optimum", function()
  local r = smi.calibrate{model = model, inputs = inputs, data = data, n = 1000, grid_nodes = 2001, seed = 5}
  for i, d in ipairs(r.identifiability.directions) do T.truthy(d.determined, "direction " .. i) end
  T.eq(#r.near_optimal.points, 1, "only the optimum")
  local norm = 0
  for _, w in pairs(r.identifiability.directions[1].loadings) do norm = norm + w * w end
  T.near(norm, 1, 1e-9, "unit loadings")
end)

T.case("prior on a parameter and on a function of the parameters (closed form)", function()
  -- metric (mean(y) - 3)^2 on a symmetric CRN sample; prior N(5, s) on x.mean adds
  -- 0.5 ((mu - 5)/s)^2, so the optimum is mu = (3 + 5 l)/(1 + l) with l = 0.5/s^2 (times weight).
  local base = {
    model = function(M) return {y = M:col(1)} end,
    inputs = {x = {mean = {0, 10, 1}, std = 1}}, data = {y = {1, 2, 3}},
    metric = function(pred) return (pred.y:mean() - 3) ^ 2 end,
    n = 1001, crn = "quantiles", xtol_rel = 1e-12, ftol_abs = 1e-15, identifiability = false,
  }
  local function with(extra)
    local s = {}
    for k, v in pairs(base) do s[k] = v end
    for k, v in pairs(extra) do s[k] = v end
    return smi.calibrate(s)
  end
  for _, case in ipairs{{prior = {{param = "x.mean", mean = 5, std = 1}}, l = 0.5},
                        {prior = {{param = "x.mean", mean = 5, std = 1}}, prior_weight = 4, l = 2},
                        -- 2 mu ~ N(10, 1) is mu ~ N(5, 0.5): l = 0.5 / 0.25
                        {prior = {{name = "twice", fn = function(t) return 2 * t["x.mean"] end, mean = 10, std = 1}}, l = 2}} do
    local r = with{prior = case.prior, prior_weight = case.prior_weight}
    local mu = (3 + 5 * case.l) / (1 + case.l)
    T.near(r.params["x.mean"], mu, 1e-5, "optimum")
    T.near(r.metrics.prior, case.l * (mu - 5) ^ 2, 1e-6, "metrics.prior")
    -- a custom metric of one response returning a bare number: its part is named by the response
    T.near(r.metrics.y + r.metrics.prior, r.objective, 1e-12, "parts add up")
    local h = r.history[#r.history]
    T.near(h.metrics.prior, case.l * (h.params["x.mean"] - 5) ^ 2, 1e-9, "history rows carry the prior")
  end
  -- prior and penalty together: both parts
  local r = with{prior = {{param = "x.mean", mean = 5, std = 1}}, penalty = function(t) return 0.5 * (t["x.mean"] - 5) ^ 2 end}
  T.near(r.params["x.mean"], (3 + 5) / 2, 1e-5, "penalty + prior")
  T.near(r.metrics.penalty, r.metrics.prior, 1e-9, "equal parts")
  -- objective form too
  local o = smi.calibrate{parameters = {{"m", 0, 10, 1}}, objective = function(t) return (t.m - 3) ^ 2 end,
                          prior = {{param = "m", mean = 5, std = 1}}, xtol_rel = 1e-12, ftol_abs = 1e-15}
  T.near(o.params.m, (3 + 5 * 0.5) / 1.5, 1e-5, "objective form")
  T.near(o.metrics.objective + o.metrics.prior, o.objective, 1e-12, "objective form parts")
  -- bad priors name the culprit
  T.raises(function() with{prior = {{param = "x.sd", mean = 1, std = 1}}} end, "no calibrated parameter named \"x.sd\"")
  T.raises(function() with{prior = {{param = "x.mean", mean = 1, std = 0}}} end, "prior[1]: std must be > 0, got 0")
  T.raises(function() with{prior = {{param = "x.mean", mean = 1}}} end, "needs mean = and std =")
  T.raises(function() with{prior = {{fn = function() return 1 end, mean = 1, std = 1}}} end, "needs name =")
  -- the entry's schema names the entry: a misspelt key, a wrong type
  T.raises(function() with{prior = {{param = "x.mean", mean = 1, sd = 1}}} end, "prior[1]: unknown option 'sd' (did you mean 'std'?)")
  T.raises(function() with{prior = {{param = "x.mean", mean = 1, std = 1}, {param = "x.mean", mean = "1", std = 1}}} end,
    "prior[2]: option 'mean' must be a number, got string")
  T.raises(function() with{prior = {{name = "f", fn = function() return 0 / 0 end, mean = 1, std = 1}}} end, "prior 'f'")
end)

T.case("a strong prior is used in bootstrap refits too", function()
  local r = smi.calibrate{model = model, inputs = inputs, data = data, n = 400, grid_nodes = 1001, seed = 5,
                          identifiability = false, maxeval = 150,
                          prior = {{param = "a.mean", mean = 4.5, std = 0.02}}, bootstrap = {replicates = 4, level = 0.9}}
  -- without the prior a.mean is 5 (the data's truth); the prior holds it (and every replicate) near 4.5
  T.near(r.params["a.mean"], 4.5, 0.01, "pinned by the prior")
  T.near(r.bootstrap.lower["a.mean"], 4.5, 0.02, "replicates pinned too")
  T.near(r.bootstrap.upper["a.mean"], 4.5, 0.02, "replicates pinned too")
end)

T.case("multistart: starts_agree and the distinct optima with their objectives", function()
  -- two minima: m = -1 (objective 0.4) and m = 1 (objective 0)
  local f = function(t) return (t.m * t.m - 1) ^ 2 + 0.1 * (t.m - 1) ^ 2 end
  local r = smi.calibrate{parameters = {{"m", -2, 2, -1.5}}, objective = f, multistart = 6, seed = 3,
                          xtol_rel = 1e-10, ftol_abs = 1e-14, identifiability = false}
  T.eq(r.starts_agree, false, "two basins")
  T.eq(#r.optima, 2, "two distinct optima")
  T.near(r.optima[1].params.m, 1, 1e-4, "best first")
  T.truthy(r.optima[2].objective > r.optima[1].objective, "ordered by objective")
  T.near(r.optima[2].params.m, -0.95, 0.1, "the other basin")
  local one = smi.calibrate{parameters = {{"m", -2, 2, -1.5}}, objective = function(t) return (t.m - 0.5) ^ 2 end,
                            multistart = 4, seed = 3, identifiability = false}
  T.eq(one.starts_agree, true, "convex: one optimum")
  T.eq(#one.optima, 1)
end)

T.finish()
