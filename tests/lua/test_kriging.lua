-- SPDX-License-Identifier: MIT
-- smi.kriging from Lua: DACE reference values (spec §8.4) through the outside-check call
-- forms, LOO, save/load through the sandbox, errors that name the culprit.
local T = require "smi.testing"

local S1 = {{0}, {0.2}, {0.45}, {0.7}, {1.0}}
local Y1 = {}
for i, r in ipairs(S1) do Y1[i] = r[1] + math.sin(5 * r[1]) end
local S2 = {{0, 0}, {1, 0.2}, {0.3, 0.9}, {0.8, 0.7}, {0.5, 0.4}, {0.1, 0.6}, {0.9, 1}, {0.6, 0.05}}
local Y2 = {}
for i, r in ipairs(S2) do Y2[i] = r[1] ^ 2 + math.sin(3 * r[2]) end

T.case("1-D regpoly0 / regpoly1 at theta = 1 (spec 8.4)", function()
  local m = smi.kriging.fit(S1, Y1, {trend = "constant", corr = "gauss", theta = {1}})
  local mu, mse = m:predict({{0.3}, {0.85}})
  T.near(mu[1], 1.3372431829, 1e-9); T.near(mse[1], 0.0012880874, 1e-10)
  T.near(mu[2], 0.0607423314, 1e-9); T.near(mse[2], 0.0078628370, 1e-10)
  T.near(m.psi, 0.8100877481, 1e-9); T.near(m.sigma2, 0.5251229240, 1e-9)
  local l = smi.kriging.fit(smi.mat(S1), smi.vec(Y1), {trend = "linear", corr = "gauss", theta = {1}})
  mu, mse = l:predict(smi.mat{{0.3}, {0.85}})
  T.near(mu[1], 1.3305753210, 1e-9); T.near(mse[2], 0.0091648461, 1e-10)
end)

T.case("2-D regpoly0 fixed theta and boxmin with its evaluation count (spec 8.4)", function()
  local m = smi.kriging.fit(S2, Y2, {trend = "constant", corr = "gauss", theta = {1, 1}})
  local mu, mse = m:predict({{0.4, 0.5}, {0.95, 0.1}})
  T.near(mu[1], 1.1653196913, 1e-9); T.near(mse[1], 0.0375782760, 1e-10)
  T.near(mu[2], 1.3724446936, 1e-9); T.near(mse[2], 0.0361267652, 1e-10)
  local b = smi.kriging.fit(S2, Y2, {method = "boxmin", theta0 = {1, 1}, lower = 0.1, upper = 20})
  T.near(b.theta[1], 0.25, 1e-12); T.near(b.theta[2], 0.5, 1e-12)
  T.eq(b.evaluations, 18, "boxmin evaluations")
  T.near(b.psi, 0.7160889914, 1e-9)
end)

T.case("default fit (ML) reaches the true minimiser of psi (spec 8.4: 0.680280)", function()
  local m = smi.kriging.fit(S2, Y2)
  T.near(m.psi, 0.680280, 2e-6)
  T.eq(m.method, "ml")
end)

T.case("loo returns residuals, q2 and rmse consistent with each other", function()
  local m = smi.kriging.fit(S2, Y2, {theta = {1, 1}})
  local r = m:loo()
  local ss, mean = 0, 0
  for i = 1, #Y2 do mean = mean + Y2[i] / #Y2 end
  local sy = 0
  for i = 1, #Y2 do ss = ss + r.residuals[i] ^ 2; sy = sy + (Y2[i] - mean) ^ 2 end
  T.near(r.rmse, math.sqrt(ss / #Y2), 1e-12)
  T.near(r.q2, 1 - ss / sy, 1e-12)
  T.truthy(r.q2 < 1 and r.rmse > 0, "an interpolator's LOO residuals are not zero")
end)

T.case("save / load round trip through the sandbox", function()
  local m = smi.kriging.fit(S2, Y2, {trend = "linear", corr = "matern52"})
  local path = smi.out("kriging_model.txt")
  m:save(path)
  local l = smi.kriging.load(path)
  local a1, b1 = m:predict({{0.4, 0.5}})
  local a2, b2 = l:predict({{0.4, 0.5}})
  T.eq(a1[1], a2[1]); T.eq(b1[1], b2[1])
  T.raises(function() m:save("/etc/smi_forbidden_model.txt") end, "is not allowed")
  -- names travel with the file: a loaded model still maps named inputs to its columns
  local named = smi.kriging.fit(S2, Y2, {trend = "linear", inputs = {"a", "b"}, output = "f"})
  named:save(path)
  local ln = smi.kriging.load(path)
  T.eq(table.concat(ln.inputs, ","), "a,b"); T.eq(ln.output, "f")
  local ins = {{"b", 0.25}, {"a", smi.dist.uniform{mean = 0.5, std = 0.1}}}  -- given out of column order
  local y1 = smi.propagate{model = named, inputs = ins, n = 100, seed = 4}
  local y2 = smi.propagate{model = ln, inputs = ins, n = 100, seed = 4}
  T.eq((y1.f - y2.f):abs():max(), 0, "same outputs from the loaded model")
end)

T.case("errors name the culprit", function()
  T.raises(function() smi.kriging.fit({{0}, {0.5}, {0.5}}, {1, 2, 3}) end, "rows 2 and 3 are identical")
  T.raises(function() smi.kriging.fit(S1, {1, 2}) end, "y has 2 values")
  T.raises(function() smi.kriging.fit(S1, Y1, {corr = "gaus"}) end, "unknown corr 'gaus'")
  T.raises(function() smi.kriging.fit(S1, Y1, {thetta = 1}) end, "theta")
  local m = smi.kriging.fit(S1, Y1, {theta = 1})
  T.raises(function() m:predict({{1, 2}}) end, "2 columns but the model has 1 inputs")
end)

T.case("sequential: rmse targets apply to the named output; an unknown output or a bad target is an error", function()
  local f = function(X)
    local y = {}
    for i = 1, X:rows() do y[i] = math.sin(3 * X[i][1]) + X[i][2] end
    return {y = smi.vec(y)}
  end
  local C = {}
  for i = 1, 40 do C[i] = {(i % 7) / 7, (i % 5) / 5} end
  local base = {model = f, design = {{0, 0}, {1, 1}, {0.5, 0.2}, {0.2, 0.8}}, candidates = C, batch = 2, max = 8, q2 = -math.huge}
  local function with(t) local c = {} for k, v in pairs(base) do c[k] = v end for k, v in pairs(t) do c[k] = v end return c end
  T.eq(smi.kriging.sequential(with{rmse = {y = 1e9}}).reached, true, "a loose RMSE target is met at once")
  local tight = smi.kriging.sequential(with{rmse = {y = 1e-12}})
  T.eq(tight.reached, false, "an unreachable RMSE target is not met")
  T.eq(tight.X:rows(), 8, "the design grew to max")
  T.raises(function() smi.kriging.sequential(with{rmse = {Y = 1e-9}}) end, "rmse: 'Y' is not an output of the model (its outputs: y)")
  T.raises(function() smi.kriging.sequential(with{rmse = {y = "small"}}) end, "rmse.y must be a positive finite number")
  T.raises(function() smi.kriging.sequential(with{rmse = {y = 0 / 0}}) end, "rmse.y must be a positive finite number")
end)

T.finish()
