-- SPDX-License-Identifier: MIT
-- Two calibrations unlike the hidden-style problem (other families, sizes and metrics), for checking
-- that a change to the optimiser's work does not make other problems worse: prints per problem and
-- gradient choice the evaluations, model calls and passes, status and objective.
-- usage: smi-lua --quiet bench/calibrate_other_problems.lua
local problems = {}

-- B: 3 inputs (gumbel, gamma, normal), 6 parameters, 2 responses, loglik, n = 1500.
function problems.B()
  local function model(X)
    local a, b, c = X:col(1), X:col(2), X:col(3)
    return { r1 = a * 2 + b * c * 0.5, r2 = (b * 0.3):exp() + a * c * 0.1 }
  end
  local g = smi.rng(41)
  local X = smi.mat(12, 3)
  X:set_col(1, g:normal(12, 5, 0.6)); X:set_col(2, g:normal(12, 3, 0.5):abs()); X:set_col(3, g:normal(12, 2, 0.4))
  return {
    model = model,
    inputs = {
      { name = "a", dist = "gumbel", mean = { 3, 7, 4 }, std = { 0.1, 1.5, 1.0 } },
      { name = "b", dist = "gamma", mean = { 1.5, 5, 2 }, std = { 0.1, 1.5, 0.8 } },
      { name = "c", dist = "normal", mean = { 0, 4, 3 }, std = { 0.05, 1.2, 0.7 } },
    },
    data = model(X), metric = "loglik", n = 1500, seed = 11, identifiability = false,
  }
end

-- C: 4 inputs (weibull, uniform, lognormal, a fixed normal), 6 parameters, 1 response, PR, n = 2500.
function problems.C()
  local function model(X)
    local a, b, c, d = X:col(1), X:col(2), X:col(3), X:col(4)
    return { y = a * b / c + d * d }
  end
  local g = smi.rng(77)
  local X = smi.mat(15, 4)
  X:set_col(1, g:normal(15, 4, 0.7):abs()); X:set_col(2, g:uniform(15, 1.5, 2.5)); X:set_col(3, g:normal(15, 2, 0.2))
  X:set_col(4, g:normal(15, 1, 0.3))
  return {
    model = model,
    inputs = {
      { name = "a", dist = "weibull", mean = { 2, 6, 3 }, std = { 0.2, 2, 1 } },
      { name = "b", dist = "uniform", mean = { 1, 3, 2.5 }, std = { 0.05, 0.8, 0.4 } },
      { name = "c", dist = "lognormal", mean = { 1, 3, 1.5 }, std = { 0.05, 0.8, 0.3 } },
      { name = "d", dist = "normal", mean = 1, std = 0.3 },
    },
    data = model(X), metric = "pr", n = 2500, seed = 3, identifiability = false,
  }
end

for _, name in ipairs{ "B", "C" } do
  for _, extra in ipairs{ {}, { gradient = "differences", maxeval = 500 } } do
    local s = problems[name]()
    for k, v in pairs(extra) do s[k] = v end
    local c0 = os.clock()
    local r = smi.calibrate(s)
    print(("%s %-17s evaluations %3d  model calls %3d  passes %3d  %-15s objective %.10f  CPU %.2f s"):format(
      name, r.gradient, r.evaluations, r.model_runs, r.model_passes, r.status, r.objective, os.clock() - c0))
  end
end
