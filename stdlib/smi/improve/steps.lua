--- smi.improve.steps: the steps of the trial loop on one smi.study (smi.improve.run builds E:
-- {D (the checked declaration), opt, cfg, seed, study, prior, max_trials}). Each step computes
-- with the kernels through trial.lua / calibration.lua and writes its report section from the
-- declaration (text.lua, figures.lua); a step after the study has concluded records why it did
-- not run. Steps read earlier steps' results only from ctx.results, so --only/--from work.
local trial = require "smi.improve.trial"
local calibration = require "smi.improve.calibration"
local verdict = require "smi.improve.verdict"
local criteria = require "smi.improve.criteria"
local cost = require "smi.improve.cost"
local text = require "smi.improve.text"
local figs = require "smi.improve.figures"
local revise = require "smi.improve.revise"
local sanity = require "smi.sanity"

local M = {}
local BADGE = { valid = "pass", invalid = "fail", inconclusive = "inconclusive" }

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

local function assignments(t)
  local parts = {}
  for k, v in pairs(t) do parts[#parts + 1] = ("%s = %.6g"):format(k, v) end
  table.sort(parts)
  return table.concat(parts, ", ")
end

local function label(model, k)
  return ("Trial %d (%s)"):format(k, model.candidate == "initial" and "initial model" or model.candidate)
end

local function hook(E, name, ...)
  local f = E.D.sections[name]
  if f then return f(...) end
end

-- The run's shared pieces on E: the factory's models (checked, counted), the data as vecs, the
-- experimental PDFs and the PR grid margins.
local function prepare(E)
  local D, seed = E.D, E.seed
  E.model = function(T, ctx) return require("smi.improve").model(D, E.opt, T, ctx) end
  E.vecs = function(data)
    local d = {}
    for _, m in ipairs(D.names) do d[m] = smi.vec(data[m]) end
    return d
  end
  E.f_exp = function(data) return calibration.experimental_pdfs(data, seed, D.names) end
  E.margins = {}
  for _, r in ipairs(D.responses) do E.margins[r.name] = r.grid_margin end
end

local function data_step(E, ctx)
  local D, opt, cfg, seed, model, vecs, f_exp, margins = E.D, E.opt, E.cfg, E.seed, E.model, E.vecs, E.f_exp, E.margins
  local d, header, notes = smi.csv.read(opt.data)
  local out = { file = opt.data, n = 0 }
  local cols = {}
  for i, r in ipairs(D.responses) do cols[i] = r.column end
  for _, r in ipairs(D.responses) do
    local col = d[r.column]
    if col == nil then
      error(("%s: response '%s': no column '%s' (columns: %s); the declaration's responses need %s"):format(
        opt.data, r.name, r.column, table.concat(header, ", "), table.concat(cols, ", ")), 0)
    end
    if type(col) ~= "userdata" then
      error(("%s: response '%s': column '%s' holds text; every value must be a number"):format(opt.data, r.name,
        r.column), 0)
    end
    if #col < 3 then
      error(("%s: %d rows; the study needs at least 3 measurements per response"):format(opt.data, #col), 0)
    end
    for i = 1, #col do
      if not (col[i] > -math.huge and col[i] < math.huge) then
        error(("%s: row %d, %s = %s is not a finite number"):format(opt.data, i, r.column, tostring(col[i])), 0)
      end
    end
    out[r.name] = col:totable()
    out.n = #col
  end
  local r = ctx.report
  r:section("Experimental data")
  r:text(text.data_intro(out.n, opt.data))
  local rows, columns = {}, { "Specimen" }
  for j, rr in ipairs(D.responses) do
    columns[j + 1] = { title = rr.title .. (rr.unit ~= "" and (" (" .. rr.unit .. ")") or ""), digits = 6 }
  end
  for i = 1, out.n do
    rows[i] = { i }
    for j, rr in ipairs(D.responses) do rows[i][j + 1] = out[rr.name][i] end
  end
  r:table{ caption = "Measured responses.", rows = rows, columns = columns }
  local warnings = notes and notes.warnings or {}
  for _, w in ipairs(warnings) do r:callout("Data: " .. w, "warn") end
  out.warnings = #warnings > 0 and warnings or nil
  -- units: the nominal run (every declared unknown at its start mean) against the data
  local T0 = revise.initial(D, D.unknowns)
  local Y = model(T0, { purpose = "nominal", name = "nominal" }):evaluate(revise.start_point(T0))
  out.nominal, out.units = {}, {}
  local words, problems = {}, {}
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
    if p then problems[#problems + 1] = p end
  end
  r:text(text.units_intro(words))
  out.units = problems
  for _, p in ipairs(problems) do r:callout(p, "warn") ctx:log("%s", p) end
  if #problems > 0 and not opt.accept_units then
    error(("%s: likely a units error, stopped before any solver budget is spent: %s Fix the data's units, or give"
      .. " --accept-units (or declare accept_units = true) to go on."):format(opt.data, table.concat(problems, " ")), 0)
  end
  hook(E, "data", ctx, out)
  return out
end

local function characterize_step(E, ctx)
  local D, opt, cfg, seed, model, vecs, f_exp, margins = E.D, E.opt, E.cfg, E.seed, E.model, E.vecs, E.f_exp, E.margins
  local data = vecs(ctx.results.data)
  local ebd = f_exp(ctx.results.data)
  local out, figures, rows = {}, {}, {}
  for _, m in ipairs(D.names) do
    local k = smi.kde(data[m], { bandwidth = "silverman" })
    local e = ebd[m]
    local lo = math.min(e.lower, data[m]:min()) - 3 * e.bandwidth
    local hi = math.max(e.upper, data[m]:max()) + 3 * e.bandwidth
    local c = { kde = trial.pdf_curve(k, data[m], lo, hi), ebd = trial.pdf_curve(e, data[m], lo, hi),
                data = data[m]:totable() }
    out[m] = { mean = data[m]:mean(), std = data[m]:std(), kde_bandwidth = k.bandwidth, ebd_bandwidth = e.bandwidth,
               ebd_lower = e.lower, ebd_upper = e.upper, ebd_added = e.added, ebd_std = e:std() }
    figures[#figures + 1] = { figs.kde_vs_ebd(m, c), figs.title[m] .. ": KDE of the data and KDE with estimated bounded data." }
    rows[#rows + 1] = { figs.title[m], out[m].mean, out[m].std, k.bandwidth, e.bandwidth, e.lower, e.upper, e.added }
  end
  local r = ctx.report
  r:section("Uncertainty characterization (KDE vs KDE-ebd)")
  r:text(text.characterize_intro(#data[D.names[1]]))
  r:figures(figures)
  r:table{ caption = "Data summary and bandwidths.", rows = rows,
           columns = { "Response", "Mean", "Std", "h KDE", "h KDE-ebd", "ebd lower", "ebd upper",
                       { title = "Points added", format = "%d" } } }
  return out
end

local function screening_step(E, ctx)
  local D, opt, cfg, seed, model, vecs, f_exp, margins = E.D, E.opt, E.cfg, E.seed, E.model, E.vecs, E.f_exp, E.margins
  local sc = D.screening
  local names = {}
  for i, row in ipairs(sc.inputs) do names[i] = row[1] end
  local sur = cfg.screening == "surrogate"
  local runs = sur and cfg.screen_runs or (#names + 1) * cfg.screen_n
  local T0 = revise.initial(D, {})
  T0.unknowns = names
  local bm = model(T0, { purpose = "screening", batch = true, name = sur and "screening-surrogate" or "screening",
                                 points = sur and cfg.screen_runs or cfg.screen_n })
  local n = sur and 10000 or cfg.screen_n
  ctx:log("%d inputs: %d solutions%s", #names, runs, sur and ", a ridge quadratic per response, eq. 3 on it" or "")
  local res = smi.screen{ model = bm, inputs = sc.inputs, n = n, seed = seed + 20, sobol = false,
                          method = sur and "surrogate" or nil, runs = sur and cfg.screen_runs or nil }
  local out = { n = n, seed = seed + 20, responses = {}, method = cfg.screening, solver_solutions = runs,
                inputs = #names }
  for _, m in ipairs(D.names) do
    local rows, top = {}, {}
    for i, row in ipairs(res[m]) do rows[i] = { input = row.input, e = row.e, ne = row.ne, rank = row.rank } end
    for i = 1, math.min(4, #rows) do top[i] = rows[i].input end
    out.responses[m] = { rows = rows, warnings = res[m].warnings, top = top, q2 = res[m].q2 }
  end
  out.unknowns = sc.rule and sc.rule(out) or D.unknowns
  revise.initial(D, out.unknowns) -- checks the rule's names
  local chosen, figures = {}, {}
  for _, n in ipairs(out.unknowns) do chosen[n] = true end
  for _, m in ipairs(D.names) do
    figures[#figures + 1] = { figs.screening(m, out.responses[m].rows, chosen), figs.title[m]
      .. ": the ten largest normalized area metrics; highlighted: the trial-1 unknowns." }
  end
  local r = ctx.report
  r:section("Variable screening")
  r:text(text.screening_intro(out))
  r:figures(figures)
  local rows = {}
  for _, m in ipairs(D.names) do
    local t = out.responses[m].rows
    rows[#rows + 1] = { figs.title[m] }
    for i = 1, 4 do rows[#rows][i + 1] = t[i] and ("%s %.3f"):format(t[i].input, t[i].ne) or "" end
  end
  r:table{ caption = "The four most influential inputs per response (normalized area metric).",
           columns = { "Response", "1st", "2nd", "3rd", "4th" }, rows = rows }
  if sc.note then local w, kind = sc.note(out) if w then r:callout(w, kind or "info") end end
  r:text(("Trial 1's unknowns (the declaration's screening rule): %s."):format(table.concat(out.unknowns, ", ")))
  return out
end

-- The model of trial k, or nil and why the study ended before it.
local function trial_model(E, R, k)
  local D, opt, cfg, seed, model, vecs, f_exp, margins = E.D, E.opt, E.cfg, E.seed, E.model, E.vecs, E.f_exp, E.margins
  if k == 1 then
    local sc = D.screening and R.screening
    return revise.initial(D, sc and sc.unknowns or D.unknowns)
  end
  local ref = R["refinement" .. (k - 1)]
  if ref.skipped then return nil, ref.reason end
  return ref.model
end

local function surrogate_step(E, k)
  local D, opt, cfg, seed, model, vecs, f_exp, margins = E.D, E.opt, E.cfg, E.seed, E.model, E.vecs, E.f_exp, E.margins
  return timed(function(ctx)
    local T, why = trial_model(E, ctx.results, k)
    if not T then return skipped(why) end
    ctx:log("%s: %s of %d unknowns; %d test points", label(T, k), cfg.design == "sequential"
      and ("sequential design of at most " .. T.n_design .. " points") or (T.n_design .. "-point Latin hypercube"),
      #T.unknowns, cfg.test_points)
    local m = model(T, { purpose = "design", name = "trial" .. k .. "-design" })
    local res = trial.surrogate{ name = "trial" .. k, model = m, responses = D.names, unknowns = T.unknowns,
                                 specs = T.specs, trend = T.trend, n_design = T.n_design, design = cfg.design,
                                 n_test = cfg.test_points, seed = seed + 100 * k }
    res.model = T
    local r = ctx.report
    r:section(label(T, k) .. ": surrogate model")
    if #T.dropped > 0 then r:callout("Revisions dropped before this trial: " .. text.dropped(T.dropped) .. ".", "info") end
    r:text(text.surrogate_intro(T, res, next(T.fixed) and (", fixed " .. assignments(T.fixed)) or "", cfg.test_points))
    local figures, rows = {}, {}
    for _, name in ipairs(D.names) do
      local d = res.diagnostics[name]
      figures[#figures + 1] = { figs.loo(name, d), figs.title[name] .. ": leave-one-out predictions." }
      rows[#rows + 1] = { figs.title[name], d.loo_q2, d.loo_rmse, d.test_rmse }
      for _, w in ipairs(d.warnings or {}) do r:callout(figs.title[name] .. ": " .. w, "warn") end
      -- data far outside everything the model gives over the design box: likely units
      local lo, hi = math.huge, -math.huge
      for _, v in ipairs(d.observed) do lo, hi = math.min(lo, v), math.max(hi, v) end
      local units = sanity.units(figs.title[name], ctx.results.data[name], lo, hi)
      if units then r:callout(units, "warn") ctx:log("%s", units) end
    end
    r:figures(figures)
    r:table{ caption = "Kriging accuracy.", columns = { "Response", "LOO Q²", "LOO RMSE", "Test RMSE" }, rows = rows }
    local box = {}
    for _, n in ipairs(T.unknowns) do box[#box + 1] = { n, res.design_bounds[n][1], res.design_bounds[n][2] } end
    r:table{ caption = "Design box of the unknowns.", columns = { "Input", "Lower", "Upper" }, rows = box }
    return res
  end)
end

local function parameter_rows(E, res)
  local D, opt, cfg, seed, model, vecs, f_exp, margins = E.D, E.opt, E.cfg, E.seed, E.model, E.vecs, E.f_exp, E.margins
  local rows = {}
  for _, p in ipairs(res.params) do
    rows[#rows + 1] = { p.input, p.dist, p.unit, ("[%.4g, %.4g]"):format(p.mean_bounds[1], p.mean_bounds[2]),
                        ("[%.4g, %.4g]"):format(p.std_bounds[1], p.std_bounds[2]), p.mean_start, p.std_start,
                        p.stage1_mean, p.stage1_std, p.mean, p.std, text.bootstrap_cell(res, p.input) }
  end
  return rows
end

local function calibration_report(E, ctx, L, T, res)
  local D, opt, cfg, seed, model, vecs, f_exp, margins = E.D, E.opt, E.cfg, E.seed, E.model, E.vecs, E.f_exp, E.margins
  local r = ctx.report
  r:section(L .. ": calibration")
  r:text(text.calibration_intro(T, res, cfg, opt.prior, E.prior.labels))
  r:figure(figs.history(res, L), L .. ": calibration history.")
  r:table{ caption = text.parameters_caption(res), rows = parameter_rows(E, res),
           columns = { "Input", "Type", "Unit", "Mean bounds", "Std bounds", "Initial mean", "Initial std",
                       "Stage-1 mean", "Stage-1 std", "Calibrated mean", "Calibrated std", "Bootstrap CI" } }
  for _, w in ipairs(res.warnings) do r:callout(L .. ": " .. w, "warn") end
  if calibration.units_stop(res) then return end
  local sv = res.sensitivity
  local srows, columns = {}, { "Input" }
  for _, m in ipairs(sv.responses) do columns[#columns + 1] = figs.title[m] end
  for _, n in ipairs(sv.inputs) do
    srows[#srows + 1] = { n }
    for _, m in ipairs(sv.responses) do srows[#srows][#srows[#srows] + 1] = sv.sensitivity[m][n] end
  end
  r:table{ caption = "Relative sensitivities d ln y / d ln x of the Krigings at the calibrated means.",
           rows = srows, columns = columns }
  r:callout(text.identifiability(res), sv.most_unconstrained_share > 0.2 and "warn" or "info")
  if #res.weak > 0 then r:callout(text.weak_parameters(res.weak), "warn") end
end

local function calibration_step(E, k)
  local D, opt, cfg, seed, model, vecs, f_exp, margins = E.D, E.opt, E.cfg, E.seed, E.model, E.vecs, E.f_exp, E.margins
  return timed(function(ctx)
    local sur = ctx.results["trial" .. k .. "_surrogate"]
    if sur.skipped then return skipped(sur.reason) end
    local T = sur.model
    ctx:log("SLSQP on %d CRN samples, %d parameters, at most %d evaluations", cfg.cal_n, 2 * #T.unknowns, cfg.maxeval)
    local res = calibration.calibrate{
      unknowns = T.unknowns, specs = T.specs, calibrate = D.calibrate, validate = D.validate,
      data = vecs(ctx.results.data), f_exp = f_exp(ctx.results.data), grid_margins = margins,
      kriging = trial.krigings(sur), design_bounds = sur.design_bounds, n = cfg.cal_n, seed = seed + 100 * k + 10,
      maxeval = cfg.maxeval, bootstrap = cfg.bootstrap, boot_maxeval = 80, metric = opt.metric,
      multistart = opt.multistart, prior = E.prior.entries, prior_labels = E.prior.labels }
    calibration_report(E, ctx, label(T, k), T, res)
    local extra = hook(E, "calibration", ctx, T, res)
    if type(extra) == "table" then for key, v in pairs(extra) do res[key] = v end end
    return res
  end)
end

local function validation_report(E, ctx, L, res, cal)
  local D, opt, cfg, seed, model, vecs, f_exp, margins = E.D, E.opt, E.cfg, E.seed, E.model, E.vecs, E.f_exp, E.margins
  local r = ctx.report
  local ebd = f_exp(ctx.results.data)
  r:section(L .. ": validity check")
  r:text(text.validation_intro(res, #ctx.results.data[D.names[1]], cfg))
  local pdfs, cdfs, rows = {}, {}, {}
  for _, m in ipairs(D.names) do
    local v = res.responses[m]
    local data = ctx.results.data[m]
    local exp_curve = trial.pdf_curve(ebd[m], smi.vec(data), v.pdf.x[1], v.pdf.x[#v.pdf.x])
    pdfs[#pdfs + 1] = { figs.pdf_over_data(m, v, data, exp_curve), figs.title[m] .. ": calibrated PDF over the data." }
    cdfs[#cdfs + 1] = { figs.upool(m, v), figs.title[m] .. ": ECDF of the u-values against the uniform CDF." }
    local range = v.range and ("[%.4f, %.4f] over %d"):format(v.range.lower, v.range.upper, v.range.points) or "—"
    local sv = v.solver or {}
    rows[#rows + 1] = { figs.title[m], v.used_in_calibration and "calibration" or "validation only", v.predicted_mean,
                        v.predicted_std, v.metric, range, v.threshold, { status = BADGE[v.verdict], text = v.verdict },
                        sv.metric or "—", v.solver and { status = sv.pass and "pass" or "fail",
                                                         text = sv.pass and "valid" or "invalid" } or "—" }
    v.detail = v.range and text.range_detail(v, cal) or text.decisive_detail(v)
    -- one entry per response: the verdict with its solver check beside it, and when the two
    -- disagree the sentence saying which one governs and why
    local checks = v.solver and { { name = "Solver check", pass = sv.pass, value = sv.metric } } or nil
    r:verdict{ name = ("%s, %s"):format(L, figs.title[m]), status = BADGE[v.verdict], value = v.metric,
               threshold = v.threshold, detail = v.detail, checks = checks,
               governs = v.solver and v.pass ~= sv.pass and text.solver_disagrees(L, figs.title[m], sv.metric, cfg) or nil }
  end
  r:figures(pdfs)
  r:figures(cdfs)
  r:table{ caption = "Validity check. U range: over the near-optimal calibrations.", rows = rows,
           columns = { "Response", "Role", "Pred. mean", "Pred. std", "U", "U range", "Threshold", "Verdict",
                       "U (solver check)", "Solver check" } }
  r:text(text.trial_verdict(L, res))
end

local function validation_step(E, k)
  local D, opt, cfg, seed, model, vecs, f_exp, margins = E.D, E.opt, E.cfg, E.seed, E.model, E.vecs, E.f_exp, E.margins
  return timed(function(ctx)
    local sur = ctx.results["trial" .. k .. "_surrogate"]
    if sur.skipped then return skipped(sur.reason) end
    local T = sur.model
    local cal = ctx.results["trial" .. k .. "_calibration"]
    if calibration.units_stop(cal) then
      local why = ("trial %d's calibration found no overlap between the predicted and the measured distributions,"
        .. " a power of ten apart (status no_overlap): %s The study stops before validation: check the data's"
        .. " units and the units the model expects."):format(k, tostring(cal.message))
      ctx.report:callout(why, "fail")
      return skipped(why)
    end
    local check = cfg.solver_check > 0 and model(T, { purpose = "check", batch = true,
      name = "trial" .. k .. "-check", points = cfg.solver_check }) or nil
    local res = trial.validate{ name = "trial" .. k, model = T, check_model = check, kriging = trial.krigings(sur),
                                calibration = cal, data = vecs(ctx.results.data), responses = D.names,
                                calibrate = D.calibrate, n = cfg.val_n, n_solver = cfg.solver_check,
                                n_near = cfg.near_n, seed = seed + 100 * k + 30 }
    validation_report(E, ctx, label(T, k), res, cal)
    return res
  end)
end

-- Refinement: the decision matrix over the untried candidates, each on top of the kept revisions.
local function rank_candidates(E, ctx, base, untried)
  local D, opt, cfg, seed, model, vecs, f_exp, margins = E.D, E.opt, E.cfg, E.seed, E.model, E.vecs, E.f_exp, E.margins
  local observed = {}
  for _, m in ipairs(D.names) do observed[m] = smi.vec(ctx.results.data[m]):mean() end
  local runs, revised = {}, {}
  for _, c in ipairs(untried) do revised[c.name] = revise.apply(D, base, c.name) end
  local run = function(c)
    local R = revised[c.name]
    local m = model(R, { purpose = "correctness", name = "refine-" .. c.short:gsub("%s", "-") })
    local Y, info = m:evaluate(revise.start_point(R))
    local y = {}
    for _, n in ipairs(D.names) do y[n] = Y[n][1] end
    local secs = info and info.duration and info.duration[1] or 0
    runs[c.name] = { y = y, seconds = secs }
    return y, secs
  end
  local crit = D.criteria and D.criteria{ observed = observed, responses = D.calibrate, run = run, weights = D.weights }
    or criteria.build{ observed = observed, responses = D.calibrate, run = run, weights = D.weights }
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
  return out, revised
end

local function why_chosen(E, dm, jc, jr)
  local D, opt, cfg, seed, model, vecs, f_exp, margins = E.D, E.opt, E.cfg, E.seed, E.model, E.vecs, E.f_exp, E.margins
  local w = { dm.weights.correctness, dm.weights.robustness, dm.weights.computational, dm.weights.implementation }
  local why = {}
  for i, name in ipairs(dm.criteria) do
    local d = (w[i] or 1) * (dm.candidates[jc].standardized[i] - (jr and dm.candidates[jr].standardized[i] or 0))
    why[#why + 1] = ("%s %+.3f"):format(name, d)
  end
  return ("rating %.3f%s; weighted difference by criterion: %s"):format(dm.overall[jc],
    jr and (" against %.3f for %s"):format(dm.overall[jr], dm.candidates[jr].name) or "", table.concat(why, ", "))
end

local function refinement_report(E, r, k, out)
  local D, opt, cfg, seed, model, vecs, f_exp, margins = E.D, E.opt, E.cfg, E.seed, E.model, E.vecs, E.f_exp, E.margins
  local dm = out.matrix
  r:section(("Model refinement after trial %d"):format(k))
  local M_rows, pred, cols = {}, {}, { "Candidate" }
  for _, n in ipairs(dm.criteria) do cols[#cols + 1] = "M " .. n end
  for _, n in ipairs(dm.criteria) do cols[#cols + 1] = "S " .. n end
  cols[#cols + 1] = "Rating"
  for j, c in ipairs(dm.candidates) do
    M_rows[j] = { c.name }
    for i = 1, #dm.criteria do M_rows[j][#M_rows[j] + 1] = c.magnitudes[i] end
    for i = 1, #dm.criteria do M_rows[j][#M_rows[j] + 1] = c.standardized[i] end
    M_rows[j][#M_rows[j] + 1] = dm.overall[j]
    pred[j] = { c.name }
    for _, m in ipairs(D.names) do pred[j][#pred[j] + 1] = c.prediction[m] end
  end
  pred[#pred + 1] = { "data mean" }
  for _, m in ipairs(D.names) do pred[#pred][#pred[#pred] + 1] = dm.observed[m] end
  local pcols = { "Model" }
  for _, m in ipairs(D.names) do pcols[#pcols + 1] = figs.title[m] end
  r:text(text.refinement_intro(k, out))
  r:table{ caption = "Weighted decision matrix: magnitudes M, standardized S, overall rating.", rows = M_rows,
           columns = cols }
  r:table{ caption = "Revised models at the start means.", rows = pred, columns = pcols }
  local names = {}
  for j, c in ipairs(dm.candidates) do names[j] = c.name end
  r:figure(figs.decision{ candidates = names, overall = dm.overall, best_name = out.chosen },
           "Overall rating of the candidates.")
  r:callout(("Refinement after trial %d: %s (%s)."):format(k, out.chosen, out.why), "info")
end

local function refinement_step(E, k)
  local D, opt, cfg, seed, model, vecs, f_exp, margins = E.D, E.opt, E.cfg, E.seed, E.model, E.vecs, E.f_exp, E.margins
  return timed(function(ctx)
    local R = ctx.results
    local v = R["trial" .. k .. "_validation"]
    if v.skipped then return skipped(v.reason) end
    if v.verdict ~= "invalid" then return skipped(text.nothing_to_refine(k, v)) end
    if k > opt.max_refinements then
      return skipped(("trial %d is invalid and the analyst's limit of %d refinement(s) is reached"):format(
        k, opt.max_refinements))
    end
    local failed = {}
    for _, m in ipairs(D.names) do if v.responses[m].verdict == "invalid" then failed[#failed + 1] = m end end
    local tried = {}
    for i = 1, k do tried[R["trial" .. i .. "_surrogate"].model.candidate] = true end
    local untried = {}
    for _, c in ipairs(D.candidates) do if not tried[c.name] then untried[#untried + 1] = c end end
    if #untried == 0 then
      return skipped(("trial %d is invalid and every candidate has been tried"):format(k))
    end
    -- the base of the next trial: this trial's revisions, minus the last one if it made the fit worse
    local base = revise.copy(R["trial" .. k .. "_surrogate"].model)
    local drop = revise.keep(R, k)
    if drop then
      local names = {}
      for _, a in ipairs(base.applied) do if not drop[a] then names[#names + 1] = a end end
      base.applied = names
    end
    local dm = rank_candidates(E, ctx, base, untried)
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
                  why = why_chosen(E, dm, jc, jr) }
    refinement_report(E, ctx.report, k, out)
    return out
  end)
end

local function summary_tables(E, r, R)
  local D, opt, cfg, seed, model, vecs, f_exp, margins = E.D, E.opt, E.cfg, E.seed, E.model, E.vecs, E.f_exp, E.margins
  local rows = {}
  for name, cnt in pairs(cost.counts) do rows[#rows + 1] = { name, cnt.points, cnt.launched, cnt.reused } end
  table.sort(rows, function(a, b) return a[1] < b[1] end)
  if #rows > 0 then
    r:table{ caption = text.solver_use_caption, rows = rows,
             columns = { "Model", { title = "Points", format = "%d" }, { title = "Launched", format = "%d" },
                         { title = "Reused", format = "%d" } } }
  end
  local steps, per, total = {}, {}, 0
  for _, st in ipairs(E.study.steps) do
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
  r:table{ caption = "Wall-clock time per step (s, 1 s resolution).", rows = steps,
           columns = { "Step", { title = "Wall (s)", format = "%d" } } }
  per[#per + 1] = { "total", total, "", "" }
  r:table{ caption = ("Solver runs per step (new: not found in the evaluation store). Screening: %s; Kriging test"
             .. " points %d; solver check %d points."):format(D.screening and (cfg.screening == "surrogate"
             and ("surrogate, " .. cfg.screen_runs .. " runs") or "full eq. 3") or "none", cfg.test_points,
             cfg.solver_check),
           columns = { "Step", { title = "Solutions", format = "%d" }, { title = "New", format = "%s" },
                       { title = "Processes", format = "%s" } }, rows = per }
  return total
end

local function summary_step(E, ctx)
  local D, opt, cfg, seed, model, vecs, f_exp, margins = E.D, E.opt, E.cfg, E.seed, E.model, E.vecs, E.f_exp, E.margins
  local R = ctx.results
  local c = verdict.conclusion(R, D, E.max_trials, D.trial_fields)
  local out = { conclusion = c, solver_runs = cost.counts, solver_totals = cost.totals(), quick = opt.quick,
                config = cfg, seed = seed, data_file = opt.data, prior_file = opt.prior,
                priors = E.prior.labels, lua = _VERSION, words = text.conclusion(c, R) }
  local r = ctx.report
  r:section("Summary")
  r:text(text.story(c, R, E.prior.labels))
  r:verdict{ name = "Conclusion: the model is " .. c.verdict, status = BADGE[c.verdict],
             detail = text.conclusion_detail(c, R) }
  out.solver_runs_total = summary_tables(E, r, R)
  hook(E, "summary", ctx, c, out)
  r:provenance{ seed = seed, quick = opt.quick, data = opt.data, lua = _VERSION, prior = opt.prior or "none",
                solver_runs = out.solver_totals, sample_sizes = cfg }
  return out
end

function M.add(E)
  prepare(E)
  local D, opt, cfg, seed, s = E.D, E.opt, E.cfg, E.seed, E.study
  -- 1. Data, and the units check on one nominal run before any solver budget is spent
  s:step("data", timed(function(ctx) return data_step(E, ctx) end))

  -- 2. Uncertainty characterization: KDE vs KDE-ebd
  s:step("characterize", timed(function(ctx) return characterize_step(E, ctx) end))

  -- 3. Screening (optional): eq. 3 on a surrogate or on the model; the rule picks the unknowns
  if D.screening then
    s:step("screening", timed(function(ctx) return screening_step(E, ctx) end))
  end

  for k = 1, E.max_trials do
    s:step("trial" .. k .. "_surrogate", surrogate_step(E, k))
    s:step("trial" .. k .. "_calibration", calibration_step(E, k))
    s:step("trial" .. k .. "_validation", validation_step(E, k))
    if k < E.max_trials then s:step("refinement" .. k, refinement_step(E, k)) end
  end

  -- Summary: the conclusion, solver runs, provenance

  s:step("summary", timed(function(ctx) return summary_step(E, ctx) end))
end

return M
