-- SPDX-License-Identifier: MIT
-- smi.calibrate_bayes: a non-linear posterior (banana) and a model-form population case against
-- the quadrature references of tests/reference/bayes_nonlinear.py; same seed, same numbers; the
-- errors that name the culprit.
local T = require "smi.testing"
local ref = smi.json.read(os.getenv("SMI_TEST_REFERENCE_DIR") .. "/bayes_nonlinear.json")

local function banana(seed)
  return smi.calibrate_bayes{
    parameters = {{name = "a", lower = -3, upper = 3}, {name = "b", lower = -2, upper = 4}},
    loglik = function(Th)
      local a, b = Th:col(1), Th:col(2)
      return -0.5 * ((a - 0.5) ^ 2 / 0.09 + (b - a ^ 2) ^ 2 / 0.04)
    end,
    samples = 2000, seed = seed,
  }
end

T.case("banana: evidence and posterior moments against quadrature", function()
  local r = banana(3)
  local want = ref.banana
  T.truthy(r.converged, "converged: " .. table.concat(r.diagnostics.reasons, "; "))
  T.near(r.log_evidence, want.log_evidence, math.max(0.05, 3 * r.log_evidence_error), "log evidence")
  for _, k in ipairs{"a", "b"} do
    T.near(r.mean[k], want.mean[k], 0.05 * want.std[k] + 3 * want.std[k] / math.sqrt(2000), "mean of " .. k)
    T.rel(r.std[k], want.std[k], 0.05, "std of " .. k)
    T.truthy(r.interval[k][1] < r.mean[k] and r.mean[k] < r.interval[k][2], "interval of " .. k)
  end
  T.eq(r.names[1], "a", "names in parameter order")
  T.eq(r.samples:rows(), 2000, "one row per sample")
  T.eq(r.diagnostics.beta[r.diagnostics.stages], 1, "beta ends at 1")
  T.eq(#r.diagnostics.acceptance, r.diagnostics.stages, "acceptance per stage")
  T.eq(r.loglik_error, 0, "the objective form's likelihood is exact")
  T.truthy(tostring(r):find("log evidence", 1, true), "tostring summary")
end)

T.case("same seed, same numbers; another seed, other samples", function()
  local a, b, c = banana(7), banana(7), banana(8)
  T.eq(a.log_evidence, b.log_evidence, "same evidence")
  T.eq(a.samples:get(17, 2), b.samples:get(17, 2), "same samples")
  T.truthy(a.samples:get(17, 2) ~= c.samples:get(17, 2), "another seed")
end)

T.case("model form: population posterior and evidence against quadrature", function()
  local pop = ref.population
  local calls = 0
  local r = smi.calibrate_bayes{
    model = function(X)
      calls = calls + 1
      local x1, x2 = X:col(1), X:col(2)
      return {y1 = x1 + 0.2 * x1 ^ 2 + x2, y2 = (0.3 * x1):exp() - x2}
    end,
    inputs = {{name = "x1", dist = "normal", mean = {0, 2.5}, std = {0.05, 0.8}},
              {name = "x2", dist = "normal", mean = 0, std = 0.2}},
    data = {y1 = smi.vec(pop.data.y1), y2 = smi.vec(pop.data.y2)},
    noise = {y1 = 0.1, y2 = 0.1},
    prior = {{param = "x1.mean", dist = "normal", mean = 1.0, std = 0.3}},
    bandwidth = 0, n = 2000, samples = 400, seed = 5,
  }
  T.truthy(r.converged, "converged")
  T.eq(r.names[1], "x1.mean", "names")
  -- The kernel estimate's error is common to every theta (common random numbers): it adds to
  -- the sampler's error of the evidence.
  local err = math.sqrt(r.log_evidence_error ^ 2 + r.loglik_error ^ 2)
  T.truthy(r.loglik_error > 0 and r.loglik_error < 0.3, "loglik error stated: " .. r.loglik_error)
  T.near(r.log_evidence, pop.log_evidence, 3 * err + 0.02, "log evidence")
  -- The posterior moves by a fraction of its sd with the estimate's common error (r.loglik_error
  -- about 0.13 at n = 2000) and the 400 samples' own error: 0.4 sd.
  for _, k in ipairs{"x1.mean", "x1.std"} do
    T.near(r.mean[k], pop.mean[k], 0.4 * pop.std[k], "mean of " .. k)
    T.rel(r.std[k], pop.std[k], 0.2, "std of " .. k)
  end
  T.eq(r.model_runs, calls, "model runs counted")
  T.truthy(r.model_runs < r.evaluations, "the model runs on stacked batches, not per theta")
  T.eq(r.noise.y1, 0.1, "noise as given")
end)

T.case("errors name the culprit", function()
  local ok = {{name = "a", lower = 0, upper = 1}}
  local ll = function(Th) return smi.vec.zeros(Th:rows()) end
  T.raises(function() smi.calibrate_bayes{parameters = ok} end, "give either loglik")
  T.raises(function() smi.calibrate_bayes{parameters = {{name = "a"}}, loglik = ll} end, "give lower and upper")
  T.raises(function() smi.calibrate_bayes{parameters = ok, loglik = function() return smi.vec{1} end, samples = 20} end,
           "loglik returned 1 values for the 20 rows")
  T.raises(function()
    smi.calibrate_bayes{parameters = {{name = "a", prior = {dist = "lognormal", mean = -1, std = 1}}}, loglik = ll}
  end, "mean > 0")
  T.raises(function() smi.calibrate_bayes{parameters = ok, loglik = ll, sampels = 10} end, "did you mean 'samples'")
  local model = function(X) return {y = X:col(1)} end
  T.raises(function()
    smi.calibrate_bayes{model = model, inputs = {x = {mean = {0, 1}, std = 0.1}}, data = {y = smi.vec{1}}}
  end, "give noise")
  T.raises(function()
    smi.calibrate_bayes{model = model, inputs = {x = {mean = {0, 1}, std = 0.1}}, data = {y = smi.vec{1, 2}},
                        prior = {{param = "x.sd", mean = 1, std = 1}}}
  end, "no calibrated parameter named \"x.sd\"")
end)

T.finish()
