-- SPDX-License-Identifier: MIT
--- smi.improve.step.trial_run: the three steps of one trial: its surrogate (or the model itself,
-- where that is cheaper: surface.lua), its calibration with the trial's evidence, its validation.
local trial = require "smi.improve.trial"
local calibration = require "smi.improve.calibration"
local evidence = require "smi.improve.evidence"
local surface = require "smi.improve.surface"
local revise = require "smi.improve.revise"
local stream = require "smi.improve.stream"
local text = require "smi.improve.text"
local sanity = require "smi.sanity"
local common = require "smi.improve.step.common"
local view, timed, skipped, hook, label = common.view, common.timed, common.skipped, common.hook, common.label

local M = {}

-- The model of trial k, or nil and why the study ended before it.
local function trial_model(run, R, k)
  if k == 1 then
    local sc = run.D.screening and R.screening
    return revise.initial(run.D, sc and sc.unknowns or run.D.unknowns)
  end
  local ref = R["refinement" .. (k - 1)]
  if ref.skipped then return nil, ref.reason end
  return ref.model
end

local function surrogate_step(run, k)
  local D, cfg = run.D, run.cfg
  return timed(function(ctx)
    local T, why = trial_model(run, ctx.results, k)
    if not T then return skipped(why) end
    ctx:log("%s: %s of %d unknowns; %d test points", label(T, k), cfg.design == "sequential"
      and ("sequential design of at most " .. T.n_design .. " points") or (T.n_design .. "-point Latin hypercube"),
      #T.unknowns, cfg.test_points)
    local m = run.model(T, { purpose = "design", name = "trial" .. k .. "-design" })
    -- where the trial runs, measured once (surface.lua); Krigings it runs on must resolve the data's scatter
    local res = surface.surrogate(function(added)
      return trial.surrogate{ name = "trial" .. k, model = m, responses = D.names, unknowns = T.unknowns,
                              specs = T.specs, trend = T.trend, n_design = T.n_design, design = cfg.design,
                              n_test = cfg.test_points, seed = stream(run.seed, "trial design", k), added = added }
    end, { m = m, responses = D.names, n = cfg.cal_n, seed = surface.seed(run.seed, k), trend = T.trend },
      ctx.results.data, T.n_design, cfg.design == "sequential", function(...) ctx:log(...) end)
    ctx:log("%s: calibration, validation and evidence on the %s (%s)", label(T, k), res.on, res.cost.why)
    res.model = T
    -- data far outside everything the model gives over the design box: likely units
    local units = {}
    for _, name in ipairs(D.names) do
      local lo, hi = math.huge, -math.huge
      for _, v in ipairs(res.diagnostics[name].observed) do lo, hi = math.min(lo, v), math.max(hi, v) end
      units[name] = sanity.units(D.by_name[name].title, ctx.results.data[name], lo, hi)
      if units[name] then ctx:log("%s", units[name]) end
    end
    view("surrogate")(run, ctx.report, res, k, units)
    return res
  end)
end

-- The trial's posterior and log evidence under the declared priors (evidence.lua): where the
-- trial runs (its surrogate step's measured decision, surface.lua; an alternative form's design
-- is measured here). --quick halves the sizes.
local function trial_evidence(run, T, sur, R, k)
  local D = run.D
  local n, samples = D.evidence.n, D.evidence.samples
  if run.opt.quick then n, samples = math.ceil(n / 2), math.ceil(samples / 2) end
  local m = run.model(T, { purpose = "evidence", name = "trial" .. k .. "-evidence" })
  local cost = sur.cost or surface.decide(m, sur, D.names, run.cfg.cal_n, surface.seed(run.seed, k), T.trend)
  local direct = cost.on == "model" and m.model or nil
  return evidence.calibrate{ unknowns = T.unknowns, specs = T.specs, responses = D.names, data = run.vecs(R.data),
    kriging = trial.krigings(sur), direct = direct, cost = cost,
    priors = evidence.priors(T.unknowns, T.specs, run.prior.entries),
    n = n, samples = samples, seed = stream(run.seed, "trial evidence", k) }
end

local function calibration_step(run, k)
  local D, cfg, opt = run.D, run.cfg, run.opt
  return timed(function(ctx)
    local sur = ctx.results["trial" .. k .. "_surrogate"]
    if sur.skipped then return skipped(sur.reason) end
    local T = sur.model
    ctx:log("SLSQP on %d CRN samples, %d parameters, at most %d evaluations", cfg.cal_n, 2 * #T.unknowns, cfg.maxeval)
    local direct = surface.direct(sur, function(c) return run.model(T, c) end, "calibration",
                                  "trial" .. k .. "-calibration")
    local res = calibration.calibrate{
      unknowns = T.unknowns, specs = T.specs, calibrate = D.calibrate, validate = D.validate,
      data = run.vecs(ctx.results.data), f_exp = run.f_exp(ctx.results.data), grid_margins = run.margins,
      kriging = trial.krigings(sur), direct = direct, design_bounds = sur.design_bounds, n = cfg.cal_n,
      seed = stream(run.seed, "trial calibration", k),
      maxeval = cfg.maxeval, bootstrap = cfg.bootstrap, boot_maxeval = cfg.boot_maxeval, metric = opt.metric,
      multistart = opt.multistart, prior_labels = run.prior.labels }
    res.cost = sur.cost
    if not calibration.units_stop(res) then
      local t0 = smi.now()
      res.evidence = trial_evidence(run, T, sur, ctx.results, k)
      res.evidence.seconds = smi.now() - t0
      ctx:log("log evidence %.3f ± %.3f on the %s", res.evidence.log_evidence, res.evidence.log_evidence_error, res.evidence.on)
    end
    view("calibration")(run, ctx.report, res, T, k)
    local extra = hook(run, "calibration", ctx, T, res)
    if type(extra) == "table" then for key, v in pairs(extra) do res[key] = v end end
    return res
  end)
end

local function validation_step(run, k)
  local D, cfg = run.D, run.cfg
  return timed(function(ctx)
    local sur = ctx.results["trial" .. k .. "_surrogate"]
    if sur.skipped then return skipped(sur.reason) end
    local T = sur.model
    -- the near-optimal fits the declared priors allow (the PR fit ignores them)
    local cal = evidence.plausible_near_optimal(ctx.results["trial" .. k .. "_calibration"])
    if calibration.units_stop(cal) then
      local why = ("trial %d's calibration found no overlap between the predicted and the measured distributions,"
        .. " a power of ten apart (status no_overlap): %s The study stops before validation: check the data's"
        .. " units and the units the model expects."):format(k, tostring(cal.message))
      ctx.report:callout(why, "fail")
      return skipped(why)
    end
    -- on the model itself there is no surrogate for a solver check to check
    local direct = surface.direct(sur, function(c) return run.model(T, c) end, "validation",
                                  "trial" .. k .. "-validation")
    local n_check = direct and 0 or cfg.solver_check
    local check = n_check > 0 and run.model(T, { purpose = "check", batch = true,
      name = "trial" .. k .. "-check", points = n_check }) or nil
    local res = trial.validate{ name = "trial" .. k, model = T, check_model = check, kriging = trial.krigings(sur),
                                direct = direct,
                                calibration = cal, data = run.vecs(ctx.results.data), responses = D.names,
                                calibrate = D.calibrate, n = cfg.val_n, n_solver = n_check,
                                n_near = cfg.near_n, seed = stream(run.seed, "trial validation", k) }
    for _, m in ipairs(D.names) do
      local v = res.responses[m]
      v.detail = v.range and text.range_detail(D, v, cal) or text.decisive_detail(v)
    end
    view("validation")(run, ctx.report, res, cal, k, label(T, k), ctx.results.data)
    return res
  end)
end

M.surrogate, M.calibration, M.validation, M.evidence = surrogate_step, calibration_step, validation_step, trial_evidence

return M
