-- SPDX-License-Identifier: MIT
--- smi.improve.calibration: the calibration of one trial (Son et al. 2020 §4.1.3 and §4.2): the
-- means and stds of the unknowns that minimize the sum of PR over the calibrated responses (or
-- minus the log-likelihood) over the KDEs of a common-random-number sample through the Krigings,
-- SLSQP; then what the data leave open (the tolerance of "fits as well", the near-optimal set,
-- each mean's range over it) and, in the full run, bootstrap intervals. One function per job;
-- M.calibrate strings them together. t.calibrate / t.validate: the declared response names.
--
-- Nothing but the data and the analyst's priors enters the objective: the calibrated responses
-- may leave combinations of the means undetermined, and the study reports what that leaves open
-- (near_optimal.lua, the validation's "inconclusive") instead of choosing for the analyst.
local trial = require "smi.improve.trial"
local near = require "smi.improve.near_optimal"
local stream = require "smi.improve.stream"

local M = {}

--- The analyst's prior part at th: smi.calibrate's own r.prior_at (its sum and weight), so the
-- near-optimal points are checked against the very objective the calibration minimized. 0
-- without a prior.
local function prior_at(prior, th, r)
  if not prior then return 0 end
  return r.prior_at(th)
end

-- The parameters' bounds and starts as the model declares them ({name, lower, upper, start}).
local function declared_params(t)
  local p = {}
  for _, n in ipairs(t.unknowns) do
    local u = t.specs[n]
    p[#p + 1] = { name = n .. ".mean", lower = u.mean[1], upper = u.mean[2], start = u.mean[3] }
    p[#p + 1] = { name = n .. ".std", lower = u.std[1], upper = u.std[2], start = u.std[3] }
  end
  return p
end

local function with_prior(t, spec)
  if t.prior then spec.prior = t.prior end
  return spec
end

--- The experimental PDFs f_exp of every response (KDE-ebd, alpha 0.1, critical intersection area
-- 0.95), rebuilt deterministically from the data ({response = list or vec}, names in declared
-- order) and the study's seed, so that any step, or a benchmark of one, builds the same ones.
function M.experimental_pdfs(data, seed, names)
  local d = {}
  for k, m in ipairs(names) do
    d[m] = smi.kde_ebd(smi.vec(data[m]), { alpha = 0.1, critical_area = 0.95, seed = stream(seed, "experimental pdf", k) })
  end
  return d
end

--- Fixed PR grids per calibrated response: the data's range ± the declared grid margin (default
-- 10 data stds), 6001 nodes. margins: {response = number or nil}.
function M.grids_of(data, names, margins)
  local g = {}
  for _, m in ipairs(names) do
    local w = margins and margins[m] or 10 * data[m]:std()
    g[m] = { lower = data[m]:min() - w, upper = data[m]:max() + w, nodes = 6001 }
  end
  return g
end
local grids_of = M.grids_of

--- The study's objective on its own CRN sample (smi.propagate through the Krigings): "pr" against
-- the experimental PDFs f_exp, or minus the log-likelihood of the data points. Returns
-- objective(th) -> sum, {response = part}.
function M.objective(metric, predicted, grids, f_exp, data, responses)
  return function(th)
    local Y = predicted(th, responses)
    local parts, sum = {}, 0
    for _, m in ipairs(responses) do
      parts[m] = metric == "pr" and smi.metric.pr(f_exp[m], smi.kde(Y[m]), { grid = grids[m] })
        or -smi.metric.loglik(data[m], smi.kde(Y[m]))
      sum = sum + parts[m]
    end
    return sum, parts
  end
end

--- Stage 2, the paper's metric, in smi.calibrate's model form: the Krigings of the calibrated responses as
-- the model (or the model itself, t.direct, with its differences for the gradient), the unknowns'
-- distributions as the inputs (every Kriging input is an unknown: the fixed inputs are in the deck the Krigings were fitted on), the experimental PDFs (KDE-ebd) for
-- "pr" (with their data points, which smi.calibrate resamples for its tolerance and bootstrap) or
-- the data points for "loglik". The kernel then has the analytic gradient (Kriging predictor,
-- quantile chain rule, KDE, metric), the overlapping start when PR saturates, the tolerance of
-- "fits as well" (for PR the spread of the summed PR over resamples of the data rows) and the
-- identifiability directions of the objective itself. o: {f_exp, data, start, maxeval,
-- identifiability, multistart, threads (nil: smi.calibrate's default), moment_start, overlap_start,
-- bootstrap (smi.calibrate's)}. Exported for bench/calibrate_trial2.lua, which times this very call.
function M.pr_stage(t, grids, o)
  local responses = t.calibrate
  local ins, dat, g = {}, {}, {}
  local model = trial.responses_model(t.kriging, t.direct, responses)
  for i, n in ipairs(t.unknowns) do
    local u = t.specs[n]
    ins[i] = { name = n, dist = u.dist, mean = { u.mean[1], u.mean[2], o.start[n .. ".mean"] },
               std = { u.std[1], u.std[2], o.start[n .. ".std"] } }
  end
  for _, m in ipairs(responses) do
    dat[m] = t.metric == "pr" and { points = o.data[m], pdf = o.f_exp[m] } or o.data[m]
    g[m] = { grids[m].lower, grids[m].upper, grids[m].nodes }
  end
  return smi.calibrate(with_prior(t, {
    model = model, inputs = ins, data = dat, metric = t.metric, n = t.n, seed = t.seed, grid = g,
    method = "slsqp", maxeval = o.maxeval, identifiability = o.identifiability, multistart = o.multistart or 1,
    threads = o.threads, moment_start = o.moment_start, overlap_start = o.overlap_start, bootstrap = o.bootstrap,
  }))
end
local pr_stage = M.pr_stage

-- Stage 1 is smi.calibrate's moment start (overlap_start.cpp), the first part of the PR call:
-- every start is moved by Levenberg-Marquardt on the means and sds of the calibrated responses with the
-- Krigings' analytic Jacobian, the smallest steps that lower the mismatch (directions the moments
-- do not see stay at the declared values), and kept when PR is lower there. PR saturates at 2
-- when the predicted and measured PDFs do not overlap (the steering column's initial values put mode1 about 4 Hz
-- below the data), so SLSQP needs an overlapping start (algorithms.md §2.1). The study's own
-- objective-form stage 1 (SLSQP on central differences, 21 evaluations a gradient) ran out of
-- its 400 evaluations on trial 2 of the committed data instead of ending on its tolerances. The
-- analyst's prior enters the PR objective, where the optimum is decided; the moment match sees
-- the data's moments alone (a start needs no more).

--- Stage 1's record, read from the PR call r0 that began with it: the first start as moved (the
-- declared one, moved = false, when the kernel kept it: PR no lower at the moved point), the model
-- runs moving every start cost, the moment mismatch before and after, and why Levenberg-Marquardt
-- stopped: "tolerance_reached", "ftol_reached" (a step lowered it by less than 1e-3 of itself
-- + 1e-4: matched as well as a start needs), "stationary" (no step within the bounds lowers it)
-- or "max_iterations" (its budget: not converged).
local ENDS_ON_CRITERION = { tolerance_reached = true, ftol_reached = true, stationary = true }
local function moments_record(r0, params, direct)
  local s1, moved = r0.starts[1], false
  local p = s1.prepared or {}
  -- the kernel hands the start back through scaled units: a kept start differs by rounding only
  for _, q in ipairs(params) do moved = moved or math.abs(s1.start[q.name] - q.start) > 1e-9 * (q.upper - q.lower) end
  return { method = direct and "smi.calibrate's moment start (Levenberg-Marquardt, the model's differences)"
             or "smi.calibrate's moment start (Levenberg-Marquardt, the Krigings' analytic Jacobian)",
           params = s1.start, moved = moved, evaluations = r0.start_evaluations, objective_start = p.before,
           objective = p.after, status = p.status or "none",
           converged = ENDS_ON_CRITERION[p.status] == true }
end

--- The optimum: stage 1 and stage 2 from the declared starts (one call, which also measures the
-- tolerance at its optimum), and a second call from the optimum (it stops at once) that computes
-- the identifiability directions and near-optimal points at that tolerance. Returns the merged
-- result, the tolerance {value, basis} and stage 1's record.
local function optimum(t, grids, params)
  local start = {}
  for _, q in ipairs(params) do start[q.name] = q.start end
  local r0 = pr_stage(t, grids, { f_exp = t.f_exp, data = t.data, start = start, maxeval = t.maxeval,
                                  identifiability = false, multistart = t.multistart, moment_start = true })
  local tol = { value = r0.tolerance, basis = r0.tolerance_basis }
  local r = pr_stage(t, grids, { f_exp = t.f_exp, data = t.data, start = r0.params, maxeval = 40,
                                 identifiability = { rel_tol = 1e-9, abs_tol = tol.value, tolerance = tol.value } })
  r.evaluations = r.evaluations + r0.evaluations
  local kept = r.objective <= r0.objective + 1e-9
  if not kept then r.params, r.objective, r.metrics = r0.params, r0.objective, r0.metrics end
  -- the restart is SLSQP again from the first call's point: when that call stopped on its budget
  -- and the restart on its tolerances (at a point no worse), the optimum is converged
  local restarted = kept and not r0.converged and r.converged
  r.status = restarted and ("%s, then %s on the restart from its point"):format(r0.status, r.status) or r0.status
  r.converged = r0.converged or restarted
  -- with --multistart: the starts, their distinct optima and whether they reached the same
  -- optimum where the data can tell (smi.calibrate's agreement, at its PR tolerance)
  r.starts, r.history, r.optima, r.agreement = r0.starts, r0.history, r0.optima, r0.agreement
  if not restarted then r.at_bounds = r0.at_bounds end
  return r, tol, moments_record(r0, params, t.direct)
end

-- The calibrated parameters as the report lists them.
local function param_rows(t, r, r1)
  local params = {}
  for _, n in ipairs(t.unknowns) do
    local u = t.specs[n]
    params[#params + 1] = { input = n, dist = u.dist, unit = u.unit,
      mean = r.params[n .. ".mean"], std = r.params[n .. ".std"],
      mean_bounds = { u.mean[1], u.mean[2] }, std_bounds = { u.std[1], u.std[2] },
      mean_start = u.mean[3], std_start = u.std[3],
      stage1_mean = r1.params[n .. ".mean"], stage1_std = r1.params[n .. ".std"] }
  end
  return params
end

-- Beyond the paper: the kernel's warnings, and whether the calibrated sample stays inside the
-- Kriging design box.
-- smi.calibrate's "at a bound" warning says "widen the range if physically allowed". For a mean
-- the range is the analyst's prior: the data ask for more than it allows, which counts against
-- the form (forms.lua). For a standard deviation a few specimens cannot resolve it: its bound is
-- where a flat objective ended, not a reason to widen the range.
local function bound_words(w, n)
  local name = w:match("^parameter '([^']+)' = .- sits at a bound")
  if not name then return w end
  local head = w:gsub(": widen the range if physically allowed$", "")
  if name:match("%.std$") then
    return ("%s: %d specimens resolve a standard deviation poorly, so its value at the bound is weakly determined"
      .. " (not a reason to widen the range)"):format(head, n)
  end
  return ("%s: the data ask for a mean beyond the declared range, the prior; this counts against the form (widen"
    .. " the range only if the physics allows it)"):format(head)
end

local function box_warnings(r, params, design_bounds, n, direct)
  local warnings = {}
  for _, w in ipairs(r.warnings) do warnings[#warnings + 1] = bound_words(w, n) end
  -- on the model itself there is no surrogate to extrapolate
  for _, p in ipairs(direct and {} or params) do
    local d = smi.dist[p.dist]{ mean = p.mean, std = p.std }
    local lo, hi = d:quantile(0.001), d:quantile(0.999)
    local box = design_bounds[p.input]
    if lo < box[1] or hi > box[2] then
      warnings[#warnings + 1] = ("input '%s': the calibrated distribution's 0.1-99.9 %% range [%.4g, %.4g] leaves the"
        .. " Kriging design range [%.4g, %.4g]: the surrogate extrapolates there"):format(
        p.input, lo, hi, box[1], box[2])
    end
  end
  return warnings
end

--- {input = {lower, upper}} of each unknown's mean over a list of parameter points.
function M.mean_ranges(unknowns, points)
  local r = {}
  for _, n in ipairs(unknowns) do
    local lo, hi = math.huge, -math.huge
    for _, p in ipairs(points) do
      local v = p[n .. ".mean"]
      if v then lo, hi = math.min(lo, v), math.max(hi, v) end
    end
    if lo <= hi then r[n] = { lo, hi } end
  end
  return r
end

--- The calibrations that fit the calibrated responses as well as the optimum (objective within the
-- tolerance): smi.calibrate's r.near_optimal (points along the weak directions of the objective,
-- to the bounds) and the study's pushes of the validation response's prediction up and down
-- (near_optimal.lua). The union: a generic set cannot know which prediction matters, and a
-- verdict over too narrow a set would be falsely decisive.
local function near_optimal_set(t, r, tol, params, predicted, data_objective)
  local function full_objective(th) return data_objective(th) + prior_at(t.prior, th, r) end
  local pushes = #t.validate == 0 and { points = {}, directions = {} } or near.by_prediction_extremes{ params = params, optimum = r.params, objective = full_objective,
    value = full_objective(r.params), predicted = predicted, prior = t.prior, tolerance = tol.value,
    calibration_responses = t.calibrate, validation_responses = t.validate, data = t.data }
  local points, from_calib = {}, 0
  for _, p in ipairs(r.near_optimal and r.near_optimal.points or {}) do points[#points + 1] = p end
  from_calib = #points
  for i, p in ipairs(pushes.points) do if i > 1 or from_calib == 0 then points[#points + 1] = p end end
  return { tolerance = tol.value, tolerance_basis = tol, points = points, directions = pushes.directions,
    from_calibrate = from_calib, from_pushes = #points - from_calib, mean_ranges = M.mean_ranges(t.unknowns, points),
    source = from_calib > 0
      and ("%d from smi.calibrate's r.near_optimal, %d from the study's pushes of %s"):format(
        from_calib, #points - from_calib, table.concat(t.validate, ", "))
      or ("%d from the study's pushes of %s (smi.calibrate gave no r.near_optimal)"):format(#points,
        table.concat(t.validate, ", ")) }
end

--- Bootstrap CIs (beyond the paper): smi.calibrate's bootstrap (kernels/improve/bootstrap.cpp),
-- the one implementation. The data rows are resampled with replacement (paired across responses),
-- plain KDEs of the resamples are the experimental PDFs, and each replicate restarts SLSQP at the
-- optimum with a small budget (a warm start); replicates run side by side on the pool when the
-- model is C++ (the Krigings) and on an in-process Lua model too (its calls take turns,
-- bindings/improve/lua_gate.hpp; the KDE sums, most of a replicate, do not). A replicate that fails
-- is counted and its error is a warning, never dropped silently.
-- The interval the study reports is the kernel's normal one (r.bootstrap.normal), estimate ± z sd
-- of the replicates, z = 1.645 at 90 %, clipped to the bounds: the replicates show the local pull
-- of the data, and their percentiles can sit to one side of the estimate (seen: a thickness
-- estimate of 4.385 with percentiles [4.387, 4.429]), since a replicate's PDFs are plain KDEs and
-- the estimate's the KDE-ebd. The kernel's percentiles are kept, with their Monte Carlo errors
-- and the replicates they need.
local function bootstrap(t, grids, r)
  local rb = pr_stage(t, grids, {
    f_exp = t.f_exp, data = t.data, start = r.params, maxeval = 1, identifiability = false,
    moment_start = false, overlap_start = false,
    bootstrap = { replicates = t.bootstrap, level = 0.9, seed = stream(t.seed, "bootstrap"),
                  maxeval = t.boot_maxeval, multistart = 1, warm = true } })
  local b = rb.bootstrap
  -- the failed replicates' messages, from smi.calibrate's fields (how many replicates the
  -- percentiles need is in replicates_needed, worded by the report's caption with the study's option)
  local failures = {}
  for _, f in ipairs(b and b.failures or {}) do
    failures[#failures + 1] = ("bootstrap replicate %d failed: %s"):format(f.replicate, f.message)
  end
  if not b then  -- the bootstrap as a whole failed (fewer than two replicates succeeded): its error
    failures[#failures + 1] = rb.not_computed and rb.not_computed.bootstrap or "the bootstrap was not computed"
    return { level = 0.9, kind = "none", replicates = 0, failed = t.bootstrap, failures = failures,
             maxeval = t.boot_maxeval, lower = {}, upper = {}, std = {} }
  end
  return { level = 0.9, kind = "normal (estimate ± 1.645 sd)", replicates = b.replicates, failed = b.failed,
           failures = failures, maxeval = t.boot_maxeval, lower = b.normal.lower, upper = b.normal.upper, std = b.std,
           replicates_needed = b.replicates_needed, evaluations = b.evaluations,
           percentile = { lower = b.lower, upper = b.upper, lower_mc_error = b.lower_mc_error,
                          upper_mc_error = b.upper_mc_error } }
end

--- Calibration: t {unknowns, specs (name -> {dist, mean = {lo, hi, start}, std = {...}, unit}),
-- calibrate, validate (response names), data = {response = vec}, f_exp = {response = dist},
-- grid_margins = {response = number}, kriging, direct (the in-process smi.model when the trial runs
-- on it, surface.lua: then it replaces the Krigings everywhere), design_bounds, n, seed, maxeval, bootstrap,
-- boot_maxeval, metric = "pr"|"loglik", multistart, prior (the analyst's, smi.calibrate's `prior`
-- list; nil: none), prior_labels}. Both stages are one smi.calibrate call in its model form:
-- stage 1 its moment start, stage 2 the paper's metric (analytic gradients).
--- True when a calibration found no overlap (status no_overlap) AND the predictions and the data
-- are about a power of ten apart (smi.calibrate's units hint): the inputs or the data are in
-- other units than the model expects. A no_overlap without that hint is a model-form misfit (the
-- steering column's rigid airbag cannot reach mode 4): the trial is validated, found invalid on
-- that response, and refined like any other invalid trial.
function M.units_stop(cal)
  if not (cal and cal.converged == false and cal.status == "no_overlap") then return false end
  for _, row in ipairs(cal.no_overlap or {}) do
    if row.units_hint then return true end
  end
  return false
end

function M.calibrate(t)
  t.metric = t.metric or "pr"
  local predicted = trial.predictor(t.kriging, t.unknowns, t.specs, t.n, t.seed, t.direct)
  local params1 = declared_params(t)
  local grids = grids_of(t.data, t.calibrate, t.grid_margins)
  local r, tol, r1 = optimum(t, grids, params1)
  local params = param_rows(t, r, r1)
  local out = { prior_part = r.metrics.prior, metrics = {}, evaluations = r.evaluations,
    converged = r.converged,
    status = r.status, message = r.message, no_overlap = r.no_overlap,
    warnings = box_warnings(r, params, t.design_bounds, #t.data[t.calibrate[1]], t.direct), at_bounds = r.at_bounds,
    params = params,
    theta = r.params, weak = r.identifiability and r.identifiability.weak or {},
    n = t.n, seed = t.seed, calibrate = t.calibrate, on = t.direct and "model" or "surrogate",
    maxeval = t.maxeval, metric = t.metric, starts = r.starts, optima = r.optima, agreement = r.agreement,
    priors = t.prior_labels or {}, moments_stage = r1 }
  out.objective = 0
  for _, m in ipairs(t.calibrate) do
    out.metrics[m] = r.metrics[m]
    out.objective = out.objective + r.metrics[m]
  end
  out.history = {}
  for i, h in ipairs(r.history) do
    if not h.probe then out.history[#out.history + 1] = { i, h.objective, h.metrics.prior } end
  end
  -- the predicted and measured PDFs never overlap with magnitudes a power of ten apart: a units
  -- mistake no refinement fixes, so the study stops on it and nothing more is computed here
  if M.units_stop(out) then return out, r end
  local data_objective = M.objective(t.metric, predicted, grids, t.f_exp, t.data, t.calibrate)
  -- the objective on the study's own CRN sample at this optimum: before/after comparisons
  out.objective_study_sample = data_objective(r.params)
  out.near_optimal = near_optimal_set(t, r, tol, params1, predicted, data_objective)
  if (t.bootstrap or 0) > 0 then
    out.bootstrap = bootstrap(t, grids, r)
    if out.bootstrap.failed > 0 then
      out.warnings[#out.warnings + 1] = ("bootstrap: %d of %d replicates failed (first: %s)"):format(
        out.bootstrap.failed, t.bootstrap, out.bootstrap.failures[1] or "no message")
    end
  end
  out.sensitivity = trial.sensitivity(t.kriging, out, t)
  return out, r
end

return M
