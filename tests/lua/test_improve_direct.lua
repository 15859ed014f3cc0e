-- SPDX-License-Identifier: MIT
-- smi.improve on a model that runs in-process (tests/lua/chain_product.lua, an smi.model.lua of a
-- closed form): the trial's calibration, validation and evidence run on the model itself when a
-- pass of it is measured cheaper than the Krigings' fit and predict, and the choice is recorded;
-- where the Krigings are used and do not resolve the specimens' scatter, the fixed design grows
-- once and the report warns.
-- References: the specimens' true stiffnesses (the draws chain_product.write_data made, their
-- sample means; two standard errors of a mean of 9 specimens as the tolerance, what the data
-- resolve), and for the warning the data's own sample std against the Krigings' leave-one-out
-- RMSE (a scatter a thousand times below the declared one is below what a 40-point design of
-- the whole box resolves).
local T = require "smi.testing"
local improve = require "smi.improve"
local chain = require "chain_product"

local N, SEED = 9, 11
-- the true means, away from the declared start values (1000, 600) so that a calibration that
-- moved nothing fails
local TRUTH = { k1 = 1080, k2 = 560 }

local function fresh(name)
  local results = smi.out(name .. "_results.json")
  os.remove(results)
  return results
end

T.case("a cheap Lua model: calibration, validation and evidence run on it, and the means are the truth's", function()
  local data = smi.out("chain_initial.csv")
  chain.write_data(data, {}, TRUTH, SEED, N)
  local d = chain.declaration("chain_direct", data, false)
  d.candidates = { d.candidates[1] } -- one alternative form keeps the test short
  local R = improve.run(d, { "--quick" }, { results = fresh("chain_direct") })
  local sur, cal, val = R.trial1_surrogate, R.trial1_calibration, R.trial1_validation
  -- (1) one measured decision, recorded, used by every step of the trial
  T.eq(sur.on, "model")
  T.truthy(sur.cost.model_seconds < sur.cost.kriging_seconds, "the model pass measured cheaper than the Krigings' fit and predict")
  T.eq(sur.cost.points, 2000)
  T.eq(cal.on, "model")
  T.eq(cal.evidence.on, "model")
  T.eq(val.on, "model")
  T.eq(val.n_solver, 0) -- no surrogate for a solver check to check
  -- (2) the calibrated means against the specimens' true values: the same draws write_data made
  local g = smi.rng(SEED, "chain specimens")
  local k = { k1 = g:normal(N, TRUTH.k1, chain.scatter.k1), k2 = g:normal(N, TRUTH.k2, chain.scatter.k2) }
  for _, p in ipairs(cal.params) do
    -- two standard errors of a mean of N specimens: what N specimens resolve of it
    local tol = 2 * chain.scatter[p.input] / math.sqrt(N)
    print(("  %s: calibrated mean %.3f, specimens' mean %.3f, tolerance %.3f"):format(
      p.input, p.mean, k[p.input]:mean(), tol))
    T.near(p.mean, k[p.input]:mean(), tol, p.input .. "'s calibrated mean")
  end
  T.eq(val.verdict, "valid")
end)

T.case("a slow model whose Krigings miss the specimens' scatter: the design grows once, then a warning", function()
  local data = smi.out("chain_tight.csv")
  local scatter = chain.scatter
  chain.scatter = { k1 = 0.02, k2 = 0.015, kb = 0.06 } -- a thousandth of the declared scatter
  chain.write_data(data, {}, nil, SEED, N)
  chain.scatter = scatter
  local d = chain.declaration("chain_tight", data, false)
  -- the same closed form, slowed to a solver's pace per call (never per point): the Krigings are cheaper
  local model = d.model
  d.model = function(applied, unknowns, ctx)
    local m = model(applied, unknowns, ctx)
    return smi.model.lua{ name = ctx.name, inputs = unknowns, outputs = m.outputs, fn = function(X)
      local t0 = smi.now()
      while smi.now() - t0 < 0.2 do end
      return m:evaluate(X)
    end }
  end
  local R = improve.run(d, { "--quick", "--only", "data,trial1_surrogate" }, { results = fresh("chain_tight") })
  local sur = R.trial1_surrogate
  T.eq(sur.on, "surrogate")
  T.truthy(sur.cost.model_seconds > sur.cost.kriging_seconds, "the model pass was measured slower")
  T.eq(sur.added_points, 20)
  T.eq(sur.n_design, 40)
  local y = smi.vec(R.data.f1)
  local w = table.concat(sur.diagnostics.f1.warnings or {}, "\n")
  T.truthy(w:find("leave-one-out RMSE", 1, true) and w:find(("%.4g"):format(sur.diagnostics.f1.loo_rmse), 1, true)
    and w:find(("%.4g"):format(y:std()), 1, true) and w:find("Fix:", 1, true),
    "f1's warning names both figures and the fix: " .. w)
  T.truthy(sur.diagnostics.f1.loo_rmse > 0.3 * y:std(), "the LOO error is above the threshold")
end)
T.case("the bootstrap: smi.calibrate's replicates, their sd on the scale of a mean's standard error", function()
  local data = smi.out("chain_boot.csv")
  chain.write_data(data, {}, TRUTH, SEED, N)
  local d = chain.declaration("chain_boot", data, false)
  d.candidates = { d.candidates[1] }
  local R = improve.run(d, { "--quick", "--bootstrap", "20", "--only", "data,trial1_surrogate,trial1_calibration" },
                       { results = fresh("chain_boot") })
  local cal = R.trial1_calibration
  local b = cal.bootstrap
  T.eq(b.replicates, 20)
  T.eq(b.failed, 0)
  for _, p in ipairs(cal.params) do
    local name = p.input .. ".mean"
    -- the closed-form reference: the standard error of a mean of N specimens. The calibrated mean
    -- rests on two responses that mix both stiffnesses, so its spread is of that order, not equal
    local se = chain.scatter[p.input] / math.sqrt(N)
    print(("  %s: bootstrap sd %.3f, standard error of a %d-specimen mean %.3f; 90 %% interval [%.2f, %.2f]"):format(
      name, b.std[name], N, se, b.lower[name], b.upper[name]))
    T.truthy(b.std[name] > 0.4 * se and b.std[name] < 2.5 * se, name .. "'s bootstrap sd on the scale of the standard error")
    -- z = Φ⁻¹(0.95) = 1.6448536269514722 (closed form; the bounds are far from the estimate here)
    T.near(b.upper[name] - b.lower[name], 2 * 1.6448536269514722 * b.std[name], 1e-9 * se,
           name .. ": the interval is estimate ± z sd")
    T.near(0.5 * (b.upper[name] + b.lower[name]), p.mean, 1e-9 * se, name .. ": centred on the estimate")
    T.truthy(b.lower[name] < p.mean and p.mean < b.upper[name], name .. ": the interval holds the estimate")
    T.truthy(b.percentile.lower[name] < b.percentile.upper[name], name .. ": the kernel's percentiles kept")
  end
  T.truthy(b.replicates_needed >= 100, "20 replicates are too few for a 90 % percentile interval: 5 beyond each end need 100")
end)
T.finish()
