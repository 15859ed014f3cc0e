-- SPDX-License-Identifier: MIT
-- smi.calibrate with the analytic gradient: through Kriging surrogates in
-- closed form and through a model's own gradient method; the same optimum as finite
-- differences, on tolerances, in fewer evaluations.
local T = require "smi.testing"

local g = smi.rng(99)
local a, b = g:normal(300, 5, 0.3), g:normal(300, 2, 0.2)
local data = {y1 = a + b * b, y2 = a * 3 - b}
local box = {{1.0, 3.0}, {3.5, 6.5}}
local D = smi.doe.lhs(40, box, {seed = 3})
local B, A = D:col(1), D:col(2)
local k1 = smi.kriging.fit(D, A + B * B, {inputs = {"b", "a"}, output = "f"})
local k2 = smi.kriging.fit(D, A * 3 - B, {inputs = {"b", "a"}, output = "g"})
local inputs = {a = {mean = {4, 6, 4.5}, std = {0.05, 1, 0.5}}, b = {mean = {1.5, 2.5, 1.8}, std = {0.05, 1, 0.5}}}

T.case("Kriging surrogates: analytic gradient, same optimum as differences, ends on tolerances", function()
  for _, metric in ipairs{"pr", "loglik"} do
    local spec = {model = {y1 = k1, y2 = k2}, inputs = inputs, data = data, n = 600, grid_nodes = 1501, seed = 5,
                  metric = metric, identifiability = false}
    local an = smi.calibrate(spec)
    spec.gradient = "differences"
    local fd = smi.calibrate(spec)
    T.eq(an.gradient, "analytic", metric)
    T.eq(fd.gradient, "differences", metric)
    T.truthy(an.converged and an.status ~= "maxeval_reached", metric .. " converged: " .. an.status)
    for k, v in pairs(fd.params) do T.near(an.params[k], v, 2e-3, metric .. " " .. k) end
    T.truthy(an.objective <= fd.objective + 1e-6 * math.abs(fd.objective), metric .. " objective at least as low")
    -- differences cost 2k = 8 probes a gradient (none at a line-search trial SLSQP rejects)
    T.truthy(an.evaluations * 2 < fd.evaluations, ("%s: %d evaluations vs %d"):format(metric, an.evaluations, fd.evaluations))
  end
end)

T.case("method = \"lbfgs\": the analytic gradient, the same optimum as SLSQP with differences", function()
  local spec = {model = {y1 = k1, y2 = k2}, inputs = inputs, data = data, n = 600, grid_nodes = 1501, seed = 5,
                identifiability = false, gradient = "differences"}
  local fd = smi.calibrate(spec)
  spec.gradient, spec.method = nil, "lbfgs"
  local lb = smi.calibrate(spec)
  T.eq(lb.method, "lbfgs")
  T.eq(lb.gradient, "analytic")
  T.truthy(lb.converged and lb.status ~= "maxeval_reached", "converged: " .. lb.status)
  for k, v in pairs(fd.params) do T.near(lb.params[k], v, 2e-3, k) end
  T.truthy(lb.objective <= fd.objective + 1e-5 * math.abs(fd.objective), "objective at least as low")
end)

T.case("Kriging models with threads = 2: the starts run side by side, with the result of one after another", function()
  local spec = {model = {y1 = k1, y2 = k2}, inputs = inputs, data = data, n = 400, grid_nodes = 1001, seed = 5,
                multistart = 4, identifiability = false, threads = 1}
  local one = smi.calibrate(spec)
  spec.threads = 2
  local two = smi.calibrate(spec)
  T.eq(two.evaluations, one.evaluations, "evaluations")
  T.eq(two.objective, one.objective, "objective")
  for k, v in pairs(one.params) do T.eq(two.params[k], v, k) end
  T.eq(#two.history, #one.history, "history rows")
  for i = 1, #one.history, 7 do T.eq(two.history[i].objective, one.history[i].objective, "history row " .. i) end
  for s = 1, 4 do T.eq(two.starts[s].objective, one.starts[s].objective, "start " .. s) end
  T.eq(two.starts_agree, one.starts_agree, "starts_agree")
end)

T.case("a model object's own gradient method is used; a function model is differentiated itself", function()
  local calls = 0
  local model = {
    evaluate = function(self, M) return {y1 = M:col(1) + M:col(2) * M:col(2), y2 = M:col(1) * 3 - M:col(2)} end,
    gradient = function(self, M)
      calls = calls + 1
      local J1, J2 = {}, {}  -- tables of rows
      local b = M:col(2)
      for i = 1, M:rows() do
        J1[i] = {1, 2 * b[i]}
        J2[i] = {3, -1}
      end
      return {y1 = J1, y2 = J2}
    end,
  }
  local spec = {model = model, inputs = {a = inputs.a, b = inputs.b}, order = {"a", "b"}, data = data, n = 500,
                grid_nodes = 1001, seed = 5, identifiability = false}
  local r = smi.calibrate(spec)
  T.eq(r.gradient, "analytic")
  T.truthy(calls > 0 and calls <= r.evaluations, "gradient called")
  T.near(r.params["a.mean"], 5, 0.05, "a.mean")
  T.near(r.params["b.mean"], 2, 0.05, "b.mean")
  local f = smi.calibrate{model = function(M) return model:evaluate(M) end, inputs = spec.inputs, order = {"a", "b"}, data = data,
                          n = 500, grid_nodes = 1001, seed = 5, identifiability = false, maxeval = 30}
  T.eq(f.gradient, "model_differences", "a function model: its own differences at the CRN sample")
  T.near(f.params["a.mean"], r.params["a.mean"], 0.01, "the same optimum as the analytic gradient")
  local o = smi.calibrate{model = function(M) return model:evaluate(M) end, inputs = spec.inputs, order = {"a", "b"}, data = data,
                          n = 500, grid_nodes = 1001, seed = 5, identifiability = false, maxeval = 30, gradient = "differences"}
  T.eq(o.gradient, "differences", "objective differences on request")
  T.raises(function()
    smi.calibrate{model = function(M) return model:evaluate(M) end, inputs = spec.inputs, order = {"a", "b"}, data = data, gradient = "analytic"}
  end, "needs metric")
  T.raises(function() smi.calibrate{model = model, inputs = spec.inputs, data = data, gradient = "exact"} end, "gradient must be")
end)

T.finish()
