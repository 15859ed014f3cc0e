-- SPDX-License-Identifier: MIT
-- smi.calibrate_bayes timings for bench/run_bayes.sh: a 10-parameter population problem (five
-- unknown inputs, mean and std each) on Kriging surrogates and on a cheap Lua model, and a
-- 10-parameter Gaussian objective with a known evidence (the peer NumPy TMCMC runs the same).
-- Prints "key value" lines.
local args = {...}
local samples, n = tonumber(args[1] or 1000), tonumber(args[2] or 2000)
local threads = tonumber(args[3] or 2)
local case = args[4] or "all"  -- "kriging", "lua", "gauss": one case (run_bayes.sh times each run)

-- Truth: x_k ~ N(mu_k, s_k), k = 1..5; y1 = x1 + 0.5 x2^2 + 0.3 x3 x4, y2 = x2 - x3 + 0.2 x5 x1.
local mu, sd = {1.0, 1.5, 0.5, 2.0, 1.2}, {0.10, 0.15, 0.10, 0.20, 0.10}
local function f(X)
  local x1, x2, x3, x4, x5 = X:col(1), X:col(2), X:col(3), X:col(4), X:col(5)
  return {y1 = x1 + 0.5 * x2 ^ 2 + 0.3 * x3 * x4, y2 = x2 - x3 + 0.2 * x5 * x1}
end
local g = smi.rng(21)
local Xd = smi.mat.zeros(9, 5)
for k = 1, 5 do Xd:set_col(k, g:normal(9, mu[k], sd[k])) end
local yd = f(Xd)
local names = {"x1", "x2", "x3", "x4", "x5"}
local inputs = {}
for k = 1, 5 do
  inputs[k] = {name = names[k], dist = "normal", mean = {mu[k] * 0.75, mu[k] * 1.25}, std = {0.02, 0.4}}
end
local noise = {y1 = 0.02, y2 = 0.02}

local box = {}
for k = 1, 5 do box[k] = {mu[k] * 0.75 - 1.2, mu[k] * 1.25 + 1.2} end
local D = smi.doe.lhs(80, box, {seed = 4})
local Yk = f(D)
local k1 = smi.kriging.fit(D, Yk.y1, {inputs = names, output = "y1"})
local k2 = smi.kriging.fit(D, Yk.y2, {inputs = names, output = "y2"})

local function run(label, model)
  local t0 = os.clock()
  local r = smi.calibrate_bayes{model = model, inputs = inputs, data = yd, noise = noise, n = n, samples = samples,
                                seed = 3, threads = threads}
  local cpu = os.clock() - t0
  print(("%s_seconds_cpu %.2f"):format(label, cpu))
  print(("%s_stages %d"):format(label, r.diagnostics.stages))
  print(("%s_evaluations %d"):format(label, r.evaluations))
  print(("%s_model_runs %d"):format(label, r.model_runs))
  print(("%s_log_evidence %.4f"):format(label, r.log_evidence))
  print(("%s_log_evidence_error %.4f"):format(label, r.log_evidence_error))
  print(("%s_loglik_error %.4f"):format(label, r.loglik_error))
  print(("%s_converged %s"):format(label, tostring(r.converged)))
  print(("%s_x1_mean %.4f +- %.4f"):format(label, r.mean["x1.mean"], r.std["x1.mean"]))
  io.stdout:flush()
end

if case == "all" or case == "kriging" then run("kriging", {y1 = k1, y2 = k2}) end
if case == "all" or case == "lua" then run("lua", function(X) return f(X) end) end
if case ~= "all" and case ~= "gauss" then return end

-- 10-D Gaussian objective: prior N(0, 10^2) on each, likelihood N(y_k; t_k, 1) with y_k = 25.
local params = {}
for k = 1, 10 do params[k] = {name = "t" .. k, prior = {dist = "normal", mean = 0, std = 10}} end
local t0 = os.clock()
local r = smi.calibrate_bayes{
  parameters = params, samples = samples, seed = 3,
  loglik = function(Th)
    local s = smi.vec.zeros(Th:rows())
    for k = 1, 10 do s = s + (Th:col(k) - 25) ^ 2 end
    return -0.5 * s - 10 * 0.5 * math.log(2 * math.pi)
  end,
}
print(("gauss_seconds_cpu %.2f"):format(os.clock() - t0))
print(("gauss_stages %d"):format(r.diagnostics.stages))
print(("gauss_evaluations %d"):format(r.evaluations))
print(("gauss_log_evidence %.4f"):format(r.log_evidence))
print(("gauss_log_evidence_error %.4f"):format(r.log_evidence_error))
