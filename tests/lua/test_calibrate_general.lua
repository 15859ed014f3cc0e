-- SPDX-License-Identifier: MIT
-- smi.calibrate is general: a Lua objective, and a 2-input analytic model (not the steering
-- column) whose true input means and standard deviations are recovered from synthetic data.
local T = require "smi.testing"

T.case("objective form: a Lua function of named parameters, with per-response parts", function()
  -- (a - 1.5)^2 + 3 (b + 0.25)^2: minimum 0 at (1.5, -0.25), inside the box.
  local calls = 0
  local r = smi.calibrate{
    parameters = {{name = "a", lower = 0, upper = 4, start = 3}, {name = "b", lower = -1, upper = 1}},
    objective = function(t)
      calls = calls + 1
      local p1, p2 = (t.a - 1.5) ^ 2, 3 * (t.b + 0.25) ^ 2
      return p1 + p2, {first = p1, second = p2}
    end,
    xtol_rel = 1e-10, ftol_abs = 1e-14,
  }
  T.near(r.params.a, 1.5, 1e-5, "a")
  T.near(r.params.b, -0.25, 1e-5, "b")
  T.truthy(r.objective < 1e-9, "objective at the minimum")
  T.near(r.metrics.first + r.metrics.second, r.objective, 1e-15, "parts add up")
  T.eq(calls, r.evaluations + r.identifiability.evaluations, "one Lua call per parameter vector")
  T.eq(r.history[1].params.b, 0, "a missing start is the middle of the range")
  T.eq(r.theta[1], r.params.a, "theta in parameter order")
end)

T.case("every method and multistart through Lua", function()
  for _, m in ipairs{"slsqp", "cobyla", "bobyqa", "neldermead"} do
    local r = smi.calibrate{
      parameters = {{"u", -2, 2, 1.5}, {"v", -2, 2, -1.5}},
      objective = function(t) return (t.u - 0.3) ^ 2 + (t.v - 0.7) ^ 2 end,
      method = m, multistart = 3, seed = 7, xtol_rel = 1e-9, ftol_abs = 1e-14,
    }
    T.near(r.params.u, 0.3, 1e-4, m .. " u")
    T.near(r.params.v, 0.7, 1e-4, m .. " v")
    T.eq(#r.starts, 3, m .. " starts")
  end
end)

T.case("an ignored parameter is flagged unidentifiable; a bound optimum is reported", function()
  local r = smi.calibrate{
    parameters = {{"k", 0, 2, 1}, {"unused", 0, 10, 5}},
    objective = function(t) return (t.k + 1) ^ 2 + 1e-7 * t.unused end,
  }
  T.eq(r.identifiability.weak[1], "unused", "weak parameter")
  T.eq(#r.identifiability.weak, 1, "only one")
  T.near(r.params.k, 0, 1e-6, "k at its lower bound")
  T.eq(r.at_bounds[1], "k", "at_bounds")
  local found = false
  for _, w in ipairs(r.warnings) do found = found or w:find("unidentifiable", 1, true) ~= nil end
  T.truthy(found, "warning text")
end)

-- Synthetic experiment: a ~ N(5, 0.3), b ~ N(2, 0.2); responses y1 = a + b^2, y2 = 3a - b.
-- The four moments enter y1 and y2 differently, so all four are identifiable.
local g = smi.rng(99)
local a, b = g:normal(300, 5, 0.3), g:normal(300, 2, 0.2)
local data = {y1 = a + b * b, y2 = a * 3 - b}
local function model(M)
  local A, B = M:col(1), M:col(2)
  return {y1 = A + B * B, y2 = A * 3 - B, unused = A}
end
local inputs = {a = {dist = "normal", mean = {3, 7, 4}, std = {0.05, 1, 0.5}},
                b = {dist = "normal", mean = {1, 3, 2.5}, std = {0.05, 1, 0.5}}}

T.case("model form: true input means and stds recovered from synthetic data (PR, SLSQP)", function()
  local r = smi.calibrate{model = model, inputs = inputs, data = data, n = 1000, grid_nodes = 2001, seed = 5}
  T.near(r.params["a.mean"], 5.0, 0.03, "a.mean")
  T.near(r.params["b.mean"], 2.0, 0.03, "b.mean")
  T.near(r.params["a.std"], 0.3, 0.05, "a.std")
  T.near(r.params["b.std"], 0.2, 0.05, "b.std")
  T.truthy(r.metrics.y1 > 0 and r.metrics.y2 > 0, "per-response PR")
  T.near(r.metrics.y1 + r.metrics.y2, r.objective, 1e-12, "objective = sum of PRs")
  T.eq(r.inputs.a.dist, "normal")
  T.near(r.distributions.b:mean(), r.params["b.mean"], 1e-12, "calibrated distribution")
  -- Same seed, same numbers.
  local short = {model = model, inputs = inputs, data = data, n = 1000, grid_nodes = 2001, seed = 5,
                 identifiability = false, maxeval = 20}
  local once, twice = smi.calibrate(short), smi.calibrate(short)
  T.eq(once.objective, twice.objective, "reproducible")
  T.eq(once.params["b.std"], twice.params["b.std"], "reproducible")
  short.seed = 6
  T.truthy(smi.calibrate(short).objective ~= once.objective, "another seed, other CRN")
end)

T.case("model as an object with :evaluate, loglik metric, lognormal and uniform inputs", function()
  local obj = {evaluate = function(self, M) return {y1 = M:col(1) + M:col(2) * M:col(2), y2 = M:col(1) * 3 - M:col(2)} end}
  local r = smi.calibrate{
    model = obj, data = data, n = 1000, seed = 5, metric = "loglik", identifiability = false,
    inputs = {a = {dist = "lognormal", mean = {3, 7, 4}, std = {0.05, 1, 0.5}},
              b = {dist = "uniform", mean = {1, 3, 2.5}, std = {0.05, 1, 0.5}}},
  }
  T.near(r.params["a.mean"], 5.0, 0.05, "a.mean")
  T.near(r.params["b.mean"], 2.0, 0.05, "b.mean")
  T.eq(r.distributions.a.family, "lognormal")
  T.eq(r.distributions.b.family, "uniform")
  T.near(r.distributions.b:std(), r.params["b.std"], 1e-12, "uniform std")
  T.eq(r.metric, "loglik")
end)

T.case("custom metric: squared mean and std mismatch, written in Lua", function()
  local function mom(v) return v:mean(), v:std() end
  local r = smi.calibrate{
    model = function(M) return {y = M:col(1) * 2 + 1} end,
    inputs = {x = {mean = {0, 5, 1}, std = {0.1, 3, 1}}},
    data = {y = {5.1, 6.9, 6.2, 5.4, 7.3, 4.8, 6.0, 6.3}},
    metric = function(pred, d)
      local pm, ps = mom(pred.y)
      local dm, ds = mom(smi.vec(d.y))
      return (pm - dm) ^ 2 + (ps - ds) ^ 2
    end,
    n = 500, seed = 3, xtol_rel = 1e-10, ftol_abs = 1e-14,
  }
  local dy = smi.vec{5.1, 6.9, 6.2, 5.4, 7.3, 4.8, 6.0, 6.3}
  -- y = 2x + 1 with x = mu + s z: matching moments gives mu = (mean - 1)/2, s = sd/2 / sd(z).
  T.near(r.params["x.mean"], (dy:mean() - 1) / 2, 2e-2, "mean by moment matching")
  T.truthy(r.objective < 1e-6, "moments matched")
  T.eq(r.metric, "custom")
end)

T.case("penalty: prior knowledge on the parameters is added to the metric (closed form)", function()
  -- y = x, x ~ N(mu, 1) on a symmetric quantile CRN sample (mean of z exactly 0): the metric
  -- (mean(y) - 3)^2 plus the penalty lambda (mu - 5)^2 is least at mu = (3 + 5 lambda)/(1 + lambda).
  for _, lambda in ipairs{1, 3} do
    local r = smi.calibrate{
      model = function(M) return {y = M:col(1)} end,
      inputs = {x = {mean = {0, 10, 1}, std = 1}},
      data = {y = {1, 2, 3}},
      metric = function(pred) return (pred.y:mean() - 3) ^ 2 end,
      penalty = function(th) return lambda * (th["x.mean"] - 5) ^ 2 end,
      n = 1001, crn = "quantiles", xtol_rel = 1e-12, ftol_abs = 1e-15, identifiability = false,
    }
    local mu = (3 + 5 * lambda) / (1 + lambda)
    T.near(r.params["x.mean"], mu, 1e-5, "optimum with lambda = " .. lambda)
    T.near(r.metrics.penalty, lambda * (mu - 5) ^ 2, 1e-6, "penalty part")
    T.near(r.objective, (mu - 3) ^ 2 + lambda * (mu - 5) ^ 2, 1e-6, "objective = metric + penalty")
    T.near(r.history[#r.history].metrics.penalty + 0, r.history[#r.history].objective - (r.history[#r.history].params["x.mean"] - 3) ^ 2,
           1e-9, "history rows carry the penalty part")
  end
  T.raises(function()
    smi.calibrate{model = function(M) return {y = M:col(1)} end, inputs = {x = {mean = {0, 10, 1}, std = 1}}, data = {y = {1, 2, 3}},
                  penalty = 2}
  end, "penalty must be a function")
  T.raises(function()
    smi.calibrate{parameters = {{"a", 0, 1}}, objective = function() return 1 end, penalty = function() return 0 end}
  end, "penalty belongs to the model form")
  T.raises(function()
    smi.calibrate{model = function(M) return {y = M:col(1)} end, inputs = {x = {mean = {0, 10, 1}, std = 1}}, data = {y = {1, 2, 3}},
                  metric = function(pred) return 0 end, penalty = function() return 1 / 0 end}
  end, "penalty")
end)

T.case("bootstrap intervals and design-range warnings", function()
  local X = {30.12, 30.45, 29.88, 30.61, 30.02, 29.75, 30.33, 30.90, 30.20}
  local r = smi.calibrate{
    model = function(M) return {y = M:col(1)} end,
    inputs = {x = {mean = {29, 31, 30}, std = {0.05, 1, 0.5}}},
    data = {y = X}, n = 400, crn = "quantiles", grid_nodes = 2001,
    bootstrap = {replicates = 20, seed = 4, maxeval = 200}, design_bounds = {x = {29.5, 30.8}},
  }
  local bs = r.bootstrap
  T.eq(bs.replicates + bs.failed, 20, "replicates")
  T.truthy(bs.lower["x.mean"] < r.params["x.mean"] and r.params["x.mean"] < bs.upper["x.mean"], "mean inside its interval")
  -- The interval of the mean is of the order of sd/sqrt(n) = 0.12 each side.
  T.truthy(bs.upper["x.mean"] - bs.lower["x.mean"] > 0.1 and bs.upper["x.mean"] - bs.lower["x.mean"] < 0.8, "interval width")
  local found = false
  for _, w in ipairs(r.warnings) do found = found or w:find("design range", 1, true) ~= nil end
  T.truthy(found, "the calibrated sample reaches beyond [29.5, 30.8]")
end)

T.case("a model object's input_names fix the columns of X", function()
  -- y = 10 b + a with b fixed at 5 (tiny spread): the data (mean 50.4) pin a.mean near 0.4.
  local obj = {input_names = {"b", "a"}, evaluate = function(self, M) return {y = M:col(1) * 10 + M:col(2)} end}
  local r = smi.calibrate{model = obj, inputs = {a = {mean = {0, 1}, std = 0.1}, b = {mean = 5, std = 0.001}},
                          data = {y = {50.2, 50.5, 50.4, 50.3, 50.6}}, n = 400, identifiability = false}
  T.near(r.params["a.mean"], 0.4, 0.02, "a.mean")
  T.raises(function()
    smi.calibrate{model = obj, inputs = {a = {mean = {0, 1}, std = 0.1}}, data = {y = {1, 2, 3}}}
  end, "name different inputs")
end)

T.case("data given as a distribution: PR against N(30.25, 0.36^2)", function()
  -- f_pre is a KDE of 2000 normal quantile points with the normal-reference bandwidth
  -- h = (4/(3n))^(1/5) sigma, so its spread is sigma sqrt(1 + (4/(3n))^(2/5)); matching the
  -- target std gives sigma = 0.36 / sqrt(1 + (4/6000)^0.4) (spec §2.1: the bias of small N).
  local r = smi.calibrate{
    model = function(M) return {y = M:col(1)} end,
    inputs = {x = {mean = {29, 31, 30}, std = {0.05, 1, 0.5}}},
    data = {y = smi.dist.normal{mean = 30.25, std = 0.36}}, n = 2000, crn = "quantiles", identifiability = false,
  }
  T.near(r.params["x.mean"], 30.25, 2e-4, "mean")
  T.near(r.params["x.std"], 0.36 / math.sqrt(1 + (4 / 6000) ^ 0.4), 2e-3, "std")
  T.raises(function()
    smi.calibrate{model = function(M) return {y = M:col(1)} end, inputs = {x = {mean = {29, 31}, std = 0.3}},
                  data = {y = smi.dist.normal{mean = 30.25, std = 0.36}}, metric = "loglik"}
  end, "needs the data points")
end)

T.case("progress is called once per optimiser step, never for gradient probes", function()
  local rows = {}
  local r = smi.calibrate{
    parameters = {{"a", -3, 3, 2}, {"b", -3, 3, -2}},
    objective = function(t) return (t.a - 1) ^ 2 + (t.b + 1) ^ 2 end,
    progress = function(row) rows[#rows + 1] = row end, identifiability = false,
  }
  local steps = 0
  for _, h in ipairs(r.history) do if not h.probe then steps = steps + 1 end end
  T.eq(#rows, steps, "one progress row per step")
  T.truthy(steps < r.evaluations, "SLSQP probes were not reported")
  T.eq(rows[#rows].best <= rows[1].objective, true, "best so far")
  T.eq(rows[1].params.a, 2, "first step is the start")
end)

T.case("errors name the culprit", function()
  T.raises(function()
    smi.calibrate{parameters = {{"a", 0, 1}}, objective = function(t) error("solver run 17 failed") end}
  end, "solver run 17 failed")
  T.raises(function() smi.calibrate{parameters = {{"a", 0, 1}}, objective = function() return 1 end, methd = "cobyla"} end,
           "method")
  T.raises(function()
    smi.calibrate{model = model, data = data, inputs = {a = {dist = "lognormal", mean = {0, 7}, std = 0.3}, b = {mean = 2, std = 0.2}}}
  end, "mean > 0")
  T.raises(function()
    smi.calibrate{model = function(M) return {z = M:col(1)} end, data = {y = {1, 2, 3}}, inputs = {x = {mean = {0, 1}, std = 1}}}
  end, "no 'y'")
  T.raises(function()
    smi.calibrate{parameters = {{"a", 1, 0}}, objective = function() return 1 end}
  end, "lower < upper")
  T.raises(function()
    smi.calibrate{parameters = {{"a", 0, 1}}, objective = function() return 0 / 0 end}
  end, "finite")
  T.raises(function()
    smi.calibrate{model = model, data = data, inputs = {a = {dist = "gama", mean = 1, std = 1}}}
  end, "inputs.a.dist")
  T.raises(function() smi.calibrate{parameters = {{"a", 0, 1}}, objective = function() return 1 end, model = model} end,
           "either objective")
end)

T.case("the options' ranges are the schema's: a bad value is named, with the range and the value, before any model runs", function()
  local calls = 0
  local model = function(X) calls = calls + 1; return { y = X:col(1) } end
  local function spec(extra)
    local s = { model = model, order = { "x" }, inputs = { x = { mean = { 0.1, 0.9, 0.5 }, std = 0.1 } },
                data = { y = smi.vec{ 0.4, 0.5, 0.6, 0.55 } }, n = 200 }
    for k, v in pairs(extra) do s[k] = v end
    return s
  end
  for _, c in ipairs{
    { { fd_step = 0.5 }, "smi.calibrate: fd_step must be in (0, 0.1], got 0.5" },
    { { xtol_rel = -1 }, "smi.calibrate: xtol_rel must be >= 0, got -1" },
    { { hop_step = 0 }, "smi.calibrate: hop_step must be in (0, 1], got 0" },
    { { bootstrap = { replicates = 1 } }, "smi.calibrate bootstrap: replicates must be >= 2, got 1" },
    { { bootstrap = { level = 1.5 } }, "smi.calibrate bootstrap: level must be in (0, 1), got 1.5" },
    -- the ranges the kernels check, read from their constants (kMaxModelStep, kMinCrnSize, ...)
    { { model_step = 0.5 }, "smi.calibrate: model_step must be in (0, 0.1), got 0.5" },
    { { prior_weight = -1 }, "smi.calibrate: prior_weight must be >= 0, got -1" },
    { { prior_weight = math.huge }, "smi.calibrate: prior_weight must be >= 0, got inf" },
    { { n = 5 }, "smi.calibrate: n must be >= 10, got 5" },
    { { threads = 0 }, "smi.calibrate: threads must be >= 1, got 0" },
    { { identifiability = { points = 2 } }, "smi.calibrate identifiability: points must be >= 3, got 2" },
    { { identifiability = { step = 0.1 } }, "smi.calibrate identifiability: step must be in (0, 0.05], got 0.1" },
    { { identifiability = { resamples = -1 } }, "smi.calibrate identifiability: resamples must be >= 0, got -1" },
    { { prior = { { param = "x.mean", mean = 0 / 0, std = 1 } } }, "prior[1]: mean must be a finite number, got " },
    { { prior = { { param = "x.mean", mean = 0.5, std = 0 } } }, "prior[1]: std must be > 0, got 0" },
  } do
    T.raises(function() smi.calibrate(spec(c[1])) end, c[2])
  end
  T.eq(calls, 0) -- refused while the options were read
end)
T.finish()
