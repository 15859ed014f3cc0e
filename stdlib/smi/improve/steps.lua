-- SPDX-License-Identifier: MIT
--- smi.improve.steps: the steps of the trial loop on one smi.study. Each step computes plain data
-- with the kernels (trial.lua, calibration.lua, evidence.lua, verdict.lua) and then hands it to its
-- view (smi/improve/view/<section>.lua), which writes the report section; the words are text.lua's.
-- A step after the study has concluded records why it did not run. Steps read earlier steps'
-- results only from ctx.results, so --only/--from work. `run` is the run context
-- (run_context.lua): the checked declaration, the options, the sample sizes, the seed, the study.
local trial = require "smi.improve.trial"
local calibration = require "smi.improve.calibration"
local evidence = require "smi.improve.evidence"
local surface = require "smi.improve.surface"
local verdict = require "smi.improve.verdict"
local forms = require "smi.improve.forms"
local alternatives = require "smi.improve.alternatives"
local cost = require "smi.improve.cost"
local text = require "smi.improve.text"
local revise = require "smi.improve.revise"
local stream = require "smi.improve.stream"
local criteria = require "smi.refine.criteria"
local sanity = require "smi.sanity"

local M = {}

local function view(name) return require("smi.improve.view." .. name) end

-- Wall-clock seconds of a step and the solver solutions it made.
local function timed(fn)
  return function(ctx)
    local t0, mark = os.time(), cost.mark()
    local r = fn(ctx) or ctx.result
    r.wall_seconds = os.time() - t0
    r.solver_runs = cost.since(mark)
    return r
  end
end

local function skipped(reason) return { skipped = true, reason = reason } end

local function hook(run, name, ...)
  local f = run.D.sections[name]
  if f then return f(...) end
end

local label = text.trial_label

-- ---------------------------------------------------------------------------------------------
-- Data: the measurements, and the units check on one nominal run before any solver budget
-- ---------------------------------------------------------------------------------------------

local function read_data(run)
  local D, file = run.D, run.opt.data
  local d, header, notes = smi.csv.read(file)
  local out = { file = file, n = 0 }
  local cols = {}
  for i, r in ipairs(D.responses) do cols[i] = r.column end
  for _, r in ipairs(D.responses) do
    local col = d[r.column]
    if col == nil then
      error(("%s: response '%s': no column '%s' (columns: %s); the declaration's responses need %s"):format(
        file, r.name, r.column, table.concat(header, ", "), table.concat(cols, ", ")), 0)
    end
    if type(col) ~= "userdata" then
      error(("%s: response '%s': column '%s' holds text; every value must be a number"):format(file, r.name, r.column), 0)
    end
    if #col < 3 then
      error(("%s: %d rows; the study needs at least 3 measurements per response"):format(file, #col), 0)
    end
    for i = 1, #col do
      if not (col[i] > -math.huge and col[i] < math.huge) then
        error(("%s: row %d, %s = %s is not a finite number"):format(file, i, r.column, tostring(col[i])), 0)
      end
    end
    out[r.name] = col:totable()
    out.n = #col
  end
  local warnings = notes and notes.warnings or {}
  out.warnings = #warnings > 0 and warnings or nil
  return out
end

-- The nominal run (every declared unknown at its start mean) against the data: magnitudes a
-- power of ten away, or outside a declared plausible range. Returns the nominal run in words.
local function units_check(run, out)
  local D = run.D
  local T0 = revise.initial(D, D.unknowns)
  local Y = run.model(T0, { purpose = "nominal", name = "nominal" }):evaluate(revise.start_point(T0))
  out.nominal, out.units = {}, {}
  local words = {}
  for _, rr in ipairs(D.responses) do
    local y = Y[rr.name][1]
    out.nominal[rr.name] = y
    words[#words + 1] = ("%s %.6g%s"):format(rr.name, y, rr.unit ~= "" and (" " .. rr.unit) or "")
    local p = y > 0 and sanity.units(("response '%s' (%s)"):format(rr.name, rr.unit), out[rr.name], y, y, 5)
    local pl = rr.plausible
    if pl then
      local lo, hi = math.huge, -math.huge
      for _, v in ipairs(out[rr.name]) do lo, hi = math.min(lo, v), math.max(hi, v) end
      if lo < pl[1] or hi > pl[2] then
        p = (p and (p .. " ") or "") .. ("response '%s': the data [%.6g, %.6g] leave its declared plausible range"
          .. " [%.6g, %.6g] (%s)"):format(rr.name, lo, hi, pl[1], pl[2], rr.unit)
      end
    end
    if p then out.units[#out.units + 1] = p end
  end
  return words
end

local function data_step(run, ctx)
  local out = read_data(run)
  local words = units_check(run, out)
  view("data")(run, ctx.report, out, words)
  for _, p in ipairs(out.units) do ctx:log("%s", p) end
  if #out.units > 0 and not run.opt.accept_units then
    error(("%s: likely a units error, stopped before any solver budget is spent: %s Fix the data's units, or give"
      .. " --accept-units (or declare accept_units = true) to go on."):format(run.opt.data,
      table.concat(out.units, " ")), 0)
  end
  hook(run, "data", ctx, out)
  return out
end

-- ---------------------------------------------------------------------------------------------
-- Uncertainty characterization: KDE vs KDE-ebd
-- ---------------------------------------------------------------------------------------------

local function characterize_step(run, ctx)
  local D = run.D
  local data = run.vecs(ctx.results.data)
  local ebd = run.f_exp(ctx.results.data)
  local out, curves = {}, {}
  for _, m in ipairs(D.names) do
    local k = smi.kde(data[m], { bandwidth = "silverman" })
    local e = ebd[m]
    local lo = math.min(e.lower, data[m]:min()) - 3 * e.bandwidth
    local hi = math.max(e.upper, data[m]:max()) + 3 * e.bandwidth
    curves[m] = { kde = trial.pdf_curve(k, data[m], lo, hi), ebd = trial.pdf_curve(e, data[m], lo, hi),
                  data = data[m]:totable() }
    out[m] = { mean = data[m]:mean(), std = data[m]:std(), kde_bandwidth = k.bandwidth, ebd_bandwidth = e.bandwidth,
               ebd_lower = e.lower, ebd_upper = e.upper, ebd_added = e.added, ebd_std = e:std() }
  end
  view("characterize")(run, ctx.report, out, curves, #data[D.names[1]])
  return out
end

-- ---------------------------------------------------------------------------------------------
-- Screening (optional): eq. 3 on a surrogate or on the model; the declared rule picks the unknowns
-- ---------------------------------------------------------------------------------------------

local function screening_step(run, ctx)
  local D, cfg = run.D, run.cfg
  local sc = D.screening
  local names = {}
  for i, row in ipairs(sc.inputs) do names[i] = row[1] end
  local sur = cfg.screening == "surrogate"
  local runs = sur and cfg.screen_runs or (#names + 1) * cfg.screen_n
  local T0 = revise.initial(D, {})
  T0.unknowns = names
  local bm = run.model(T0, { purpose = "screening", batch = true, name = sur and "screening-surrogate" or "screening",
                             points = sur and cfg.screen_runs or cfg.screen_n })
  local n = sur and 10000 or cfg.screen_n
  ctx:log("%d inputs: %d solutions%s", #names, runs, sur and ", a ridge quadratic per response, eq. 3 on it" or "")
  local seed = stream(run.seed, "screening")
  local res = smi.screen{ model = bm, inputs = sc.inputs, n = n, seed = seed, sobol = false,
                          method = sur and "surrogate" or nil, runs = sur and cfg.screen_runs or nil }
  local out = { n = n, seed = seed, responses = {}, method = cfg.screening, solver_solutions = runs, inputs = #names }
  for _, m in ipairs(D.names) do
    local rows, top = {}, {}
    for i, row in ipairs(res[m]) do rows[i] = { input = row.input, e = row.e, ne = row.ne, rank = row.rank } end
    for i = 1, math.min(4, #rows) do top[i] = rows[i].input end
    out.responses[m] = { rows = rows, warnings = res[m].warnings, top = top, q2 = res[m].q2 }
  end
  out.unknowns = sc.rule and sc.rule(out) or D.unknowns
  revise.initial(D, out.unknowns) -- checks the rule's names
  view("screening")(run, ctx.report, out)
  return out
end

-- ---------------------------------------------------------------------------------------------
-- A trial: surrogate, calibration, validation
-- ---------------------------------------------------------------------------------------------

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

-- ---------------------------------------------------------------------------------------------
-- Alternatives: after a trial that fits, the evidence of each untried candidate's form on top of
-- it. A fit alone says nothing about forms the data cannot tell apart (nine specimens and free
-- means absorb most revisions), so a form is called valid only against the forms it beat.
-- ---------------------------------------------------------------------------------------------

-- The candidates no trial up to k applied (R: the steps' results), in declared order.
local function untried_candidates(run, R, k)
  local tried = {}
  for i = 1, k do tried[R["trial" .. i .. "_surrogate"].model.candidate] = true end
  local untried = {}
  for _, c in ipairs(run.D.candidates) do if not tried[c.name] then untried[#untried + 1] = c end end
  return untried
end

local function alternatives_step(run, k)
  local D, cfg = run.D, run.cfg
  return timed(function(ctx)
    local R = ctx.results
    local v, cal = R["trial" .. k .. "_validation"], R["trial" .. k .. "_calibration"]
    if v.skipped then return skipped(v.reason) end
    if verdict.needs_refinement(v) then
      return skipped(("trial %d is not valid on every response: the refinement step revises it"):format(k))
    end
    if not D.evidence.alternatives then return skipped("the declaration sets evidence.alternatives = false") end
    if not (cal.evidence and type(cal.evidence.log_evidence) == "number") then
      return skipped(("trial %d has no evidence to compare with"):format(k))
    end
    local base = R["trial" .. k .. "_surrogate"].model
    local untried = alternatives.untried_forms(run.D, R, k, base)
    if #untried == 0 then return skipped(("every form one candidate away from trial %d has been tried"):format(k)) end
    local out = { forms = {}, trial = k, base_applied = base.applied }
    for _, A in ipairs(untried) do
      ctx:log("alternative %s: %d-point design, its evidence", A.candidate, A.n_design)
      -- the design and the evidence of trial k + 1 in this form: the runs are reused if it becomes that trial
      local m = run.model(A, { purpose = "design", name = "trial" .. (k + 1) .. "-design" })
      local sur = trial.surrogate{ name = "trial" .. (k + 1), model = m, responses = D.names, unknowns = A.unknowns,
                                   specs = A.specs, trend = A.trend, n_design = A.n_design, design = cfg.design,
                                   n_test = cfg.test_points, seed = stream(run.seed, "trial design", k + 1) }
      local ev = trial_evidence(run, A, sur, R, k + 1)
      out.forms[#out.forms + 1] = { candidate = A.candidate, applied = A.applied, unknowns = A.unknowns,
                                    log_evidence = ev.log_evidence, log_evidence_error = ev.log_evidence_error,
                                    posterior = evidence.posterior_means(ev), on = ev.on }
    end
    local own = { log_evidence = cal.evidence.log_evidence, log_evidence_error = cal.evidence.log_evidence_error }
    out.better = forms.better_alternative(own, out.forms, D.evidence.margin)
    view("alternatives")(run, ctx.report, out, own, k)
    return out
  end)
end

-- ---------------------------------------------------------------------------------------------
-- Refinement: the decision matrix over the untried candidates, each on top of the kept revisions
-- ---------------------------------------------------------------------------------------------

-- A run time as the computational-cost criterion counts it: whole seconds, at least one
-- (minutes). Below a second a single timing is noise (process start, machine load), and eq. (14)
-- normalises by the largest magnitude, so 0.012 s against 0.029 s would otherwise weigh like a
-- model twice as expensive and flip the choice from run to run.
local function cost_minutes(seconds)
  return math.max(1, math.ceil(seconds - 1e-9)) / 60
end

-- The criteria of the decision matrix: the declaration's, or the paper's four
-- (smi.refine.criteria.paper: correctness eq. (13) averaged over every response used in
-- calibration, so the score does not depend on which of them the calibration gave up; robustness,
-- computational and implementation cost). Each revised model runs once, at its start means.
local function decision_criteria(run, observed, runner)
  local D, w = run.D, run.D.weights
  local cache = {}
  local function result(c)
    if not cache[c.name] then cache[c.name] = runner(c) end
    return cache[c.name]
  end
  local run_fn = function(c) local r = result(c) return r.y, r.seconds end
  if D.criteria then
    return D.criteria{ observed = observed, responses = D.calibrate, run = run_fn, weights = w }
  end
  local obs = {}
  for _, m in ipairs(D.calibrate) do obs[m] = observed[m] end
  return criteria.paper{ observed = obs, weights = { w.correctness, w.robustness, w.computational, w.implementation },
                         predict = function(c) return result(c).y end,
                         measure = function(c) return cost_minutes(result(c).seconds) end }
end

local function rank_candidates(run, R, base, untried)
  local D = run.D
  local observed = {}
  for _, m in ipairs(D.names) do observed[m] = smi.vec(R.data[m]):mean() end
  local revised = {}
  for _, c in ipairs(untried) do revised[c.name] = revise.apply(D, base, c.name) end
  local runs = {}
  local crit = decision_criteria(run, observed, function(c)
    local T = revised[c.name]
    local m = run.model(T, { purpose = "correctness", name = "refine-" .. c.short:gsub("%s", "-") })
    local Y, info = m:evaluate(revise.start_point(T))
    local y = {}
    for _, n in ipairs(D.names) do y[n] = Y[n][1] end
    runs[c.name] = { y = y, seconds = info and info.duration and info.duration[1] or 0 }
    return runs[c.name]
  end)
  local dm = smi.refine.decision_matrix{ candidates = untried, criteria = crit }
  local out = { responses = D.calibrate, observed = observed, weights = D.weights, candidates = {}, overall = {},
                criteria = {} }
  for i, c in ipairs(crit) do out.criteria[i] = c.name end
  for j, c in ipairs(untried) do
    out.overall[j] = dm.overall[j]
    local mag, std = {}, {}
    for i = 1, #crit do mag[i], std[i] = dm.M:get(j, i), dm.S:get(j, i) end
    out.candidates[j] = { name = c.name, magnitudes = mag, standardized = std, prediction = runs[c.name].y,
                          new_inputs = c.new_inputs, implement_minutes = c.implement_minutes,
                          run_seconds = runs[c.name].seconds }
  end
  local order = {}
  for j = 1, #untried do order[j] = j end
  table.sort(order, function(a, b) return dm.overall[a] > dm.overall[b] end)
  out.ranking = {}
  for i, j in ipairs(order) do out.ranking[i] = untried[j].name end
  return out
end

-- After a trial that is not valid with every candidate tried: a step back (alternatives.lua),
-- as the refinement step's result, or nil.
local function step_back(run, R, k, state)
  local m, why = alternatives.step_back(run.D, R, k, state)
  if not m then return nil end
  return { failed_responses = {}, chosen = "without " .. m.without, model = m, rank = 1, why = why, step_back = true }
end

-- After a trial valid on every response: the next trial is the alternative form whose evidence
-- beats it by the margin (alternatives_step), if any and if the limit allows.
local function refine_on_evidence(run, ctx, k, v)
  local alt = ctx.results["trial" .. k .. "_alternatives"]
  local better = alt and not alt.skipped and alt.better and alt.forms[alt.better]
  if not better then return skipped(text.nothing_to_refine(k, v)) end
  local why = text.favoured_alternative(better, ctx.results["trial" .. k .. "_calibration"].evidence, run.D.evidence.margin)
  if k > run.opt.max_refinements then
    return skipped(("%s, but the analyst's limit of %d refinement(s) is reached"):format(why, run.opt.max_refinements))
  end
  local base = revise.copy(ctx.results["trial" .. k .. "_surrogate"].model)
  local out = { failed_responses = {}, chosen = better.candidate, model = revise.apply(run.D, base, better.candidate),
                rank = 1, why = why, on_evidence = true }
  view("refinement")(run, ctx.report, out, k)
  return out
end

local function refinement_step(run, k)
  local D, opt = run.D, run.opt
  return timed(function(ctx)
    local R = ctx.results
    local v = R["trial" .. k .. "_validation"]
    if v.skipped then return skipped(v.reason) end
    if not verdict.needs_refinement(v) then return refine_on_evidence(run, ctx, k, v) end
    local state = v.verdict == "invalid" and "invalid" or ("undetermined on " .. table.concat(v.undetermined, ", "))
    if k > opt.max_refinements then
      return skipped(("trial %d is %s and the analyst's limit of %d refinement(s) is reached"):format(
        k, state, opt.max_refinements))
    end
    -- the responses that call for it: the invalid ones, else the undetermined ones
    local failed, undetermined = {}, {}
    for _, m in ipairs(D.names) do
      local rv = v.responses[m].verdict
      if rv == "invalid" then failed[#failed + 1] = m elseif rv == "inconclusive" then undetermined[#undetermined + 1] = m end
    end
    local undetermined_only = #failed == 0
    if undetermined_only then failed = undetermined end
    local untried = untried_candidates(run, R, k)
    if #untried == 0 then
      -- every candidate is in: take back the earliest revision whose removal no trial has tried
      local back = step_back(run, R, k, state)
      if back then
        view("refinement")(run, ctx.report, back, k)
        return back
      end
      return skipped(("trial %d is %s, every candidate has been tried and every step back too"):format(k, state))
    end
    -- the base of the next trial: this trial's revisions, minus the last one if it made the fit worse
    local base = revise.copy(R["trial" .. k .. "_surrogate"].model)
    local drop = revise.keep(R, k)
    if drop then
      local names = {}
      for _, a in ipairs(base.applied) do if not drop[a] then names[#names + 1] = a end end
      base.applied = names
    end
    local dm = rank_candidates(run, R, base, untried)
    local chosen = dm.ranking[1]
    local jc, jr
    for j, c in ipairs(dm.candidates) do
      if c.name == chosen then jc = j elseif not jr or dm.overall[j] > dm.overall[jr] then jr = j end
    end
    local next_model = revise.apply(D, base, chosen)
    if drop then
      local names = {}
      for name in pairs(drop) do names[#names + 1] = name end
      table.sort(names, function(a, b) return a > b end) -- each goes first: the list ends in name order, every run
      for _, name in ipairs(names) do table.insert(next_model.dropped, 1, { name = name, why = drop[name] }) end
    end
    local out = { failed_responses = failed, matrix = dm, chosen = chosen, model = next_model, rank = 1,
                  why = text.why_chosen(dm, jc, jr), undetermined_only = undetermined_only }
    view("refinement")(run, ctx.report, out, k)
    return out
  end)
end

-- ---------------------------------------------------------------------------------------------
-- Summary: the conclusion, solver runs, provenance
-- ---------------------------------------------------------------------------------------------

-- Solver runs per step, as the summary's table lists them: rows and total.
local function runs_per_step(run, R)
  local steps, per, total = {}, {}, 0
  for _, st in ipairs(run.study.steps) do
    local ok, res = pcall(function() return R[st.name] end)
    if ok and res and st.name ~= "summary" then
      if not res.skipped then steps[#steps + 1] = { st.name, res.wall_seconds or 0 } end
      local runs = res.solver_runs
      if runs and runs.solutions > 0 then
        per[#per + 1] = { st.name, runs.solutions, runs.new, runs.processes }
        total = total + runs.solutions
      end
    end
  end
  return steps, per, total
end

local function summary_step(run, ctx)
  local D, opt, cfg = run.D, run.opt, run.cfg
  local R = ctx.results
  local c = verdict.conclusion(R, D, run.max_trials, D.trial_fields)
  local out = { conclusion = c, solver_runs = cost.counts, solver_totals = cost.totals(), quick = opt.quick,
                config = cfg, seed = run.seed, data_file = opt.data, prior_file = opt.prior,
                priors = run.prior.labels, lua = _VERSION, words = text.conclusion(D, c, R) }
  local walls, per, total = runs_per_step(run, R)
  out.solver_runs_total = total
  view("summary")(run, ctx.report, out, R, walls, per)
  view("before_after")(run, ctx.report, out, R)
  view("opening")(run, ctx.report, out, R)
  hook(run, "summary", ctx, c, out)
  ctx.report:provenance{ seed = run.seed, quick = opt.quick, data = opt.data, lua = _VERSION,
                         prior = opt.prior or "none", solver_runs = out.solver_totals, sample_sizes = cfg }
  return out
end

--- Adds the study's steps to run.study.
function M.add(run)
  local s = run.study
  s:step("data", timed(function(ctx) return data_step(run, ctx) end))
  s:step("characterize", timed(function(ctx) return characterize_step(run, ctx) end))
  if run.D.screening then
    s:step("screening", timed(function(ctx) return screening_step(run, ctx) end))
  end
  for k = 1, run.max_trials do
    s:step("trial" .. k .. "_surrogate", surrogate_step(run, k))
    s:step("trial" .. k .. "_calibration", calibration_step(run, k))
    s:step("trial" .. k .. "_validation", validation_step(run, k))
    s:step("trial" .. k .. "_alternatives", alternatives_step(run, k))
    if k < run.max_trials then s:step("refinement" .. k, refinement_step(run, k)) end
  end
  s:step("summary", timed(function(ctx) return summary_step(run, ctx) end))
end

return M
