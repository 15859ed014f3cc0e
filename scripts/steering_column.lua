--- The steering-column study of Son et al. (2020), end to end, on the open FE model column-fe
-- (shared/spec/steering-column.md): two trials of statistical model improvement.
--
--   build/smi-lua --allow-exec build/column-fe scripts/steering_column.lua [options]
--
-- options (after the script name):
--   --data FILE.csv   measurements (columns mode1_hz, mode2_hz, mode4_hz; default: the committed
--                     scripts/steering_column/data/tests.csv). Give --allow-read for its folder.
--   --solver PATH     the column-fe program (default: <repo>/build/column-fe, next to the
--                     scripts folder); it must be allowed with --allow-exec PATH.
--   --quick           CI form: a 40-point screening sample, no bootstrap, a smaller solver check;
--                     surrogates, calibration and verdicts as in the full run.
--   --metric pr|loglik  calibration metric per mode: the paper's probability residual (default)
--                     or minus the mean log-likelihood of the data under the predicted KDE.
--   --multistart N    the PR stage from its start plus N-1 seeded points in the bounds (default 1).
--   --only STEP[,STEP], --from STEP   run some steps; the others' results come from results.json.
-- smi-lua's own --out DIR (default smi-out/steering_column/), --seed N and --quiet apply.
--
-- Steps: data, characterize (KDE vs KDE-ebd), screening (46 inputs, batch runs), then per trial
-- surrogate (Kriging on a Latin hypercube, leave-one-out), calibration (PR(mode 1) + PR(mode 4),
-- SLSQP, CRN), validation (u-pooling on modes 1, 4 and 2); refinement (weighted decision matrix)
-- between the trials; summary. Writes report.html and results.json in the output folder.
-- Solver runs go through the evaluation store (<out>/evaluations.sqlite): a rerun reuses them.
local study = require "smi.study"
local inputs = require "steering_column.inputs"
local solver = require "steering_column.solver"
local trial = require "steering_column.trial"
local figs = require "steering_column.figures"
local candidates = require "steering_column.refinement.candidates"
local criteria = require "steering_column.refinement.criteria"

local MODES = { "mode1", "mode2", "mode4" }

-- ---------------------------------------------------------------------------------------------
-- Options
-- ---------------------------------------------------------------------------------------------
local args = study.parse_args(arg)
local opt = { quick = false }
do
  local i, rest = 1, args.rest
  while i <= #rest do
    local a = rest[i]
    if a == "--quick" then opt.quick = true; i = i + 1
    elseif a == "--metric" then
      local v = rest[i + 1]
      if v ~= "pr" and v ~= "loglik" then
        error(("steering_column: --metric must be pr (the paper's probability residual) or loglik, got %s"):format(tostring(v)), 0)
      end
      opt.metric, i = v, i + 2
    elseif a == "--multistart" then
      local v = tonumber(rest[i + 1])
      if not v or v < 1 or v ~= math.floor(v) then
        error(("steering_column: --multistart needs a whole number of starts >= 1, got %s"):format(tostring(rest[i + 1])), 0)
      end
      opt.multistart, i = v, i + 2
    elseif a == "--data" or a == "--solver" then
      local v = rest[i + 1]
      if not v or v:sub(1, 2) == "--" then error(("steering_column: %s needs a value (a path)"):format(a), 0) end
      opt[a:sub(3)] = v
      i = i + 2
    else
      error(("steering_column: unknown option '%s' (use --data FILE.csv, --solver PATH, --quick, --metric pr|loglik, --multistart N, --only STEP, --from STEP)"):format(a), 0)
    end
  end
end
local here = smi.script_dir or "scripts"
opt.data = opt.data or (here .. "/steering_column/data/tests.csv")
opt.solver = opt.solver or (here .. "/../build/column-fe")

-- Sample sizes. Full: the paper's choices where stated; quick: CI.
-- Quick differs only where the verdicts do not depend on it: the screening sample, the
-- bootstrap and the solver check of the validation; surrogates and calibration are the same.
local cfg = opt.quick and {
  screen_n = 40, design1 = 80, design2 = 120, test_points = 50, cal_n = 2000, maxeval = 300, bootstrap = 0,
  val_n = 20000, solver_check = 100,
} or {
  screen_n = 200, design1 = 80, design2 = 120, test_points = 50, cal_n = 2000, maxeval = 300, bootstrap = 50,
  val_n = 20000, solver_check = 300,
}
local seed = smi.seed or 20200214

local s = study.new{ name = "steering_column", seed = seed,
  report = { title = "Steering column: statistical model improvement in two trials",
             subtitle = "Son et al. (2020) on the open FE model column-fe" .. (opt.quick and " (quick run)" or ""),
             author = "smi-lua scripts/steering_column.lua" } }

-- Wall-clock seconds of a step (os.clock counts this process only; the solver runs in others).
local function timed(fn)
  return function(ctx)
    local t0 = os.time()
    local r = fn(ctx) or ctx.result
    r.wall_seconds = os.time() - t0
    return r
  end
end

-- The experimental PDFs (KDE-ebd, alpha 0.1, critical intersection area 0.95), rebuilt
-- deterministically from the data so that any step can run alone.
local function f_exp(data)
  local d = {}
  for k, m in ipairs(MODES) do d[m] = smi.kde_ebd(smi.vec(data[m]), { alpha = 0.1, critical_area = 0.95, seed = seed + k }) end
  return d
end

local function vecs(data)
  local d = {}
  for _, m in ipairs(MODES) do d[m] = smi.vec(data[m]) end
  return d
end

-- ---------------------------------------------------------------------------------------------
-- 1. Data
-- ---------------------------------------------------------------------------------------------
s:step("data", timed(function(ctx)
  local d, header, notes = smi.csv.read(opt.data)
  local out = { file = opt.data, n = 0 }
  for _, m in ipairs(MODES) do
    local col = d[m .. "_hz"]
    if col == nil then
      error(("%s: no column '%s_hz' (columns: %s); the file needs mode1_hz, mode2_hz and mode4_hz"):format(opt.data, m, table.concat(header, ", ")), 0)
    end
    if type(col) ~= "userdata" then error(("%s: column '%s_hz' holds text; every value must be a frequency in Hz"):format(opt.data, m), 0) end
    if #col < 3 then error(("%s: %d rows; the study needs at least 3 measurements per mode"):format(opt.data, #col), 0) end
    for i = 1, #col do
      if not (col[i] > 0 and col[i] < math.huge) then error(("%s: row %d, %s_hz = %s is not a positive frequency"):format(opt.data, i, m, tostring(col[i])), 0) end
    end
    out[m] = col:totable()
    out.n = #col
  end
  local r = ctx.report
  r:section("Experimental data")
  r:text(("%d measured combinations from %s (for the committed file: 3 steering wheels × 3 column assemblies, each the mean of 5 impact tests). Modes 1 and 4 calibrate the model; mode 2 is kept for validation."):format(out.n, opt.data))
  local rows = {}
  for i = 1, out.n do rows[i] = { i, out.mode1[i], out.mode2[i], out.mode4[i] } end
  r:table{ caption = "Measured natural frequencies (Hz).", columns = { "Specimen", { title = "Mode 1", digits = 6 }, { title = "Mode 2", digits = 6 }, { title = "Mode 4", digits = 6 } }, rows = rows }
  -- data sanity (duplicated rows) in the report, not only on stderr
  local warnings = notes and notes.warnings or {}
  for _, w in ipairs(warnings) do r:callout("Data: " .. w, "warn") end
  out.warnings = #warnings > 0 and warnings or nil
  return out
end))

-- ---------------------------------------------------------------------------------------------
-- 2. Uncertainty characterization: KDE vs KDE-ebd
-- ---------------------------------------------------------------------------------------------
s:step("characterize", timed(function(ctx)
  local data = vecs(ctx.results.data)
  local ebd = f_exp(ctx.results.data)
  local out, figures, rows = {}, {}, {}
  for _, m in ipairs(MODES) do
    local k = smi.kde(data[m], { bandwidth = "silverman" })
    local e = ebd[m]
    local lo = math.min(e.lower, data[m]:min()) - 3 * e.bandwidth
    local hi = math.max(e.upper, data[m]:max()) + 3 * e.bandwidth
    local c = { kde = trial.pdf_curve(k, data[m], lo, hi), ebd = trial.pdf_curve(e, data[m], lo, hi), data = data[m]:totable() }
    out[m] = { mean = data[m]:mean(), std = data[m]:std(), kde_bandwidth = k.bandwidth, ebd_bandwidth = e.bandwidth,
               ebd_lower = e.lower, ebd_upper = e.upper, ebd_added = e.added, ebd_std = e:std() }
    figures[#figures + 1] = { figs.kde_vs_ebd(m, c), figs.title[m] .. ": KDE of the data and KDE with estimated bounded data." }
    rows[#rows + 1] = { figs.title[m], out[m].mean, out[m].std, k.bandwidth, e.bandwidth, e.lower, e.upper, e.added }
  end
  local r = ctx.report
  r:section("Uncertainty characterization (KDE vs KDE-ebd)")
  r:text("With nine data the plain KDE is bumpy; KDE-ebd (Kang et al. 2018) adds points drawn uniformly in bounds estimated from the data (significance 0.1) until the PDF changes by less than a critical intersection area of 0.95, smoothing it. The KDE-ebd PDFs are the experimental PDFs of the calibration.")
  r:figures(figures)
  r:table{ caption = "Data summary and bandwidths (Hz).", columns = { "Mode", "Mean", "Std", "h KDE", "h KDE-ebd", "ebd lower", "ebd upper", { title = "Points added", format = "%d" } }, rows = rows }
  return out
end))

-- ---------------------------------------------------------------------------------------------
-- 3. Screening of the 46 inputs (model A, batch runs of column-fe)
-- ---------------------------------------------------------------------------------------------
s:step("screening", timed(function(ctx)
  local base = solver.write_deck(smi.out("screening_base_rigid.deck"), "rigid")
  local bm = solver.batch{ solver = opt.solver, airbag = "rigid", vary = inputs.names, name = "screening", base = base,
                           batch_size = math.ceil(cfg.screen_n / 2), concurrency = 2 }
  ctx:log("%d inputs x %d samples (common random numbers): %d solutions in batch runs", #inputs.names, cfg.screen_n, (#inputs.names + 1) * cfg.screen_n)
  local res = smi.screen{ model = bm, inputs = inputs.screening_inputs(), n = cfg.screen_n, seed = seed + 20, sobol = false }
  local out = { n = cfg.screen_n, seed = seed + 20, modes = {} }
  local chosen = { column_frame_E = true, ecu_bracket_thickness = true, wheel_cover_rho = true, wheel_cover_thickness = true }
  local figures = {}
  for _, m in ipairs(MODES) do
    local rows = {}
    for i, row in ipairs(res[m]) do rows[i] = { input = row.input, e = row.e, ne = row.ne, rank = row.rank } end
    out.modes[m] = { rows = rows, warnings = res[m].warnings, top = { rows[1].input, rows[2].input, rows[3].input, rows[4].input } }
    figures[#figures + 1] = { figs.screening(m, rows, chosen), figs.title[m] .. ": the ten largest normalized area metrics (Table 2 analog); highlighted: the trial-1 unknowns." }
  end
  local top1 = out.modes.mode1.top
  out.dominant_confirmed = (top1[1] == "column_frame_E" or top1[1] == "ecu_bracket_thickness")
    and (top1[2] == "column_frame_E" or top1[2] == "ecu_bracket_thickness")
  local r = ctx.report
  r:section("Variable screening")
  r:text(("Area-metric screening (eq. 3 and 7): each of the 46 inputs is fixed at its mean in turn on one common-random-number sample of %d points of the spec's default distributions, model A (rigid airbag), %d column-fe solutions run in batch mode."):format(cfg.screen_n, (#inputs.names + 1) * cfg.screen_n))
  r:figures(figures)
  local rows = {}
  for _, m in ipairs(MODES) do
    local t = out.modes[m].rows
    rows[#rows + 1] = { figs.title[m], ("%s %.3f"):format(t[1].input, t[1].ne), ("%s %.3f"):format(t[2].input, t[2].ne), ("%s %.3f"):format(t[3].input, t[3].ne), ("%s %.3f"):format(t[4].input, t[4].ne) }
  end
  r:table{ caption = "The four most influential inputs per mode (normalized area metric).", columns = { "Mode", "1st", "2nd", "3rd", "4th" }, rows = rows }
  r:callout(out.dominant_confirmed and "As in the paper's Table 2, the column frame's modulus and the ECU bracket's thickness dominate mode 1; with the wheel cover's density and thickness (whose statistics are unknown) they are the trial-1 unknowns."
    or "The screening ranks other inputs above the column modulus and the ECU bracket thickness for mode 1; the study keeps the paper's unknowns.", out.dominant_confirmed and "info" or "warn")
  return out
end))

-- ---------------------------------------------------------------------------------------------
-- Trials: surrogate, calibration, validation
-- ---------------------------------------------------------------------------------------------
local TRIALS = {
  trial1 = { label = "Trial 1", airbag = "rigid", unknowns = inputs.trial1_unknowns, trend = "linear", n_design = cfg.design1, seed = seed + 100 },
  trial2 = { label = "Trial 2", airbag = "spring", unknowns = inputs.trial2_unknowns, trend = "constant", n_design = cfg.design2, seed = seed + 200 },
}

local function surrogate_step(name)
  local T = TRIALS[name]
  return timed(function(ctx)
    ctx:log("%d-point Latin hypercube of %d unknowns, %s airbag; %d test points", T.n_design, #T.unknowns, T.airbag, cfg.test_points)
    local res = trial.surrogate{ name = name, airbag = T.airbag, unknowns = T.unknowns, trend = T.trend, n_design = T.n_design,
                                 n_test = cfg.test_points, seed = T.seed, solver = opt.solver }
    local r = ctx.report
    r:section(T.label .. ": surrogate model")
    r:text(("Kriging (Gauss correlation, %s trend, hyperparameters by maximum likelihood) of modes 1, 2 and 4 on a %d-point maximin Latin hypercube of the unknowns %s over the design box (mean bounds widened by 3 std bounds; uniform: √3), %s airbag. Every solution is a column-fe run through smi.model.command, kept in the evaluation store. An independent %d-point hypercube measures the test RMSE (the paper's Tables 3 and 7)."):format(T.trend, T.n_design, table.concat(T.unknowns, ", "), T.airbag, cfg.test_points))
    local figures, rows = {}, {}
    for _, m in ipairs(MODES) do
      local d = res.diagnostics[m]
      figures[#figures + 1] = { figs.loo(m, d), figs.title[m] .. ": leave-one-out predictions." }
      rows[#rows + 1] = { figs.title[m], d.loo_q2, d.loo_rmse, d.test_rmse }
      for _, w in ipairs(d.warnings or {}) do r:callout(figs.title[m] .. ": " .. w, "warn") end
      -- data far outside everything the model gives over the design box: likely units (issue 14)
      local lo, hi = math.huge, -math.huge
      for _, v in ipairs(d.observed) do lo, hi = math.min(lo, v), math.max(hi, v) end
      local units = require("smi.sanity").units(figs.title[m] .. " (Hz)", ctx.results.data[m], lo, hi)
      if units then r:callout(units, "warn") ctx:log("%s", units) end
    end
    r:figures(figures)
    r:table{ caption = "Kriging accuracy (Hz).", columns = { "Mode", "LOO Q²", "LOO RMSE", "Test RMSE" }, rows = rows }
    local box = {}
    for _, n in ipairs(T.unknowns) do box[#box + 1] = { n, res.design_bounds[n][1], res.design_bounds[n][2] } end
    r:table{ caption = "Design box of the unknowns.", columns = { "Input", "Lower", "Upper" }, rows = box }
    return res
  end)
end

local function calibration_step(name)
  local T = TRIALS[name]
  return timed(function(ctx)
    local sur = ctx.results[name .. "_surrogate"]
    local k = trial.krigings(sur)
    ctx:log("SLSQP on %d CRN samples, %d parameters, at most %d evaluations", cfg.cal_n, 2 * #T.unknowns, cfg.maxeval)
    local res = trial.calibrate{ unknowns = T.unknowns, data = vecs(ctx.results.data), f_exp = f_exp(ctx.results.data), kriging = k,
                                 design_bounds = sur.design_bounds, n = cfg.cal_n, seed = T.seed + 10, maxeval = cfg.maxeval,
                                 bootstrap = cfg.bootstrap, boot_maxeval = 80, metric = opt.metric, multistart = opt.multistart }
    local r = ctx.report
    r:section(T.label .. ": calibration")
    r:text(("Means and standard deviations of the %d unknowns (types and bounds of Table %s) minimize %s over the KDEs of %d common-random-number samples propagated through the Kriging models; SLSQP (NLopt) with central-difference gradients. PR saturates when the PDFs do not overlap, and the paper's initial values put mode 1 about 4 Hz below the data, so a first stage (also SLSQP, %d evaluations) matches the means and stds of modes 1 and 4 from the initial values; the PR stage starts from there. Modes 1 and 4 leave three combinations of the five means undetermined, so both stages add two pieces of prior knowledge as penalties: the wheel cover's mass is known from weighing the wheels (±5 %%), and means move as little as possible from their initial values (a light tie-breaker). Without them the PR optimum walks along the valley of equally good fits (to a cover 37 %% lighter than the weighing allows, in development runs). Objective at the optimum %.4f (%s mode 1 %.4f, mode 4 %.4f), %d evaluations from %d start(s), %s."):format(
      #T.unknowns, name == "trial1" and "4" or "8",
      res.metric == "pr" and "PR(mode 1) + PR(mode 4) between the KDE-ebd PDFs of the data and"
        or "minus the mean log-likelihood of the data points of modes 1 and 4 under", cfg.cal_n, res.moments_stage.evaluations, res.objective, res.metric == "pr" and "PR" or "-logL/n", res.metrics.mode1, res.metrics.mode4, res.evaluations, res.starts and #res.starts or 1, res.status))
    r:figure(figs.history(res, T.label), T.label .. ": calibration history.")
    local rows = {}
    for _, p in ipairs(res.params) do
      local ci = res.bootstrap and res.bootstrap.replicates > 0 and ("[%.4g, %.4g] / [%.4g, %.4g]"):format(res.bootstrap.lower[p.input .. ".mean"], res.bootstrap.upper[p.input .. ".mean"],
        res.bootstrap.lower[p.input .. ".std"], res.bootstrap.upper[p.input .. ".std"])
        or (res.bootstrap and ("all %d replicates failed"):format(res.bootstrap.failed) or "not computed (--quick)")
      rows[#rows + 1] = { p.input, p.dist, p.unit, ("[%.4g, %.4g]"):format(p.mean_bounds[1], p.mean_bounds[2]), ("[%.4g, %.4g]"):format(p.std_bounds[1], p.std_bounds[2]),
                          p.mean_start, p.std_start, p.stage1_mean, p.stage1_std, p.mean, p.std, ci }
    end
    r:table{ caption = ("Calibrated statistical parameters (the paper's Table %s analog). CI: %s."):format(name == "trial1" and "4" or "8",
               res.bootstrap and ("90 %% bootstrap over the 9 data (mean / std), estimate ± 1.645 sd of %d replicates that restart SLSQP at the optimum with %d evaluations each: the local pull of the data, which understates the spread along the directions modes 1 and 4 leave undetermined"):format(res.bootstrap.replicates, res.bootstrap.maxeval) or "none (--quick)"),
             columns = { "Input", "Type", "Unit", "Mean bounds", "Std bounds", "Initial mean", "Initial std", "Stage-1 mean", "Stage-1 std", "Calibrated mean", "Calibrated std", "Bootstrap CI" }, rows = rows }
    if res.cover_mass_ratio then
      r:text(("Wheel cover mass relative to nominal (density × cover tube area): %.3f after stage 1, %.3f at the optimum (the weighing prior: 1 ± 0.05). Prior penalty at the optimum %.4f (the objective above excludes it)."):format(res.moments_stage.cover_mass_ratio, res.cover_mass_ratio, res.prior_penalty))
    end
    for _, w in ipairs(res.warnings) do r:callout(T.label .. ": " .. w, "warn") end
    local sv = res.sensitivity
    local srows = {}
    for _, n in ipairs(sv.inputs) do srows[#srows + 1] = { n, sv.sensitivity.mode1[n], sv.sensitivity.mode2[n], sv.sensitivity.mode4[n] } end
    r:table{ caption = "Relative sensitivities d ln f / d ln x of the Kriging modes at the calibrated means.", columns = { "Input", "Mode 1", "Mode 2", "Mode 4" }, rows = srows }
    r:callout(("Identifiability (beyond the paper): modes 1 and 4 fix 2 combinations of the %d means and leave %d undetermined; %.0f %% of mode 2's sensitivity lies outside what modes 1 and 4 constrain, so the mode-2 check tests those undetermined combinations (here: how the stiffening is split between column_frame_E, which mode 2 feels, and the ECU bracket, which it does not)."):format(
      #sv.inputs, sv.undetermined, 100 * sv.mode2_unconstrained_share), sv.mode2_unconstrained_share > 0.2 and "warn" or "info")
    if #res.weak > 0 then
      r:callout(("Identifiability: the objective hardly changes with %s over its whole range; these parameters are not determined by modes 1 and 4."):format(table.concat(res.weak, ", ")), "warn")
    end
    return res
  end)
end

local function validation_step(name)
  local T = TRIALS[name]
  return timed(function(ctx)
    local sur = ctx.results[name .. "_surrogate"]
    local res = trial.validate{ name = name, airbag = T.airbag, kriging = trial.krigings(sur), calibration = ctx.results[name .. "_calibration"],
                                data = vecs(ctx.results.data), n = cfg.val_n, n_solver = cfg.solver_check, seed = T.seed + 30, solver = opt.solver }
    local ebd = f_exp(ctx.results.data)
    local r = ctx.report
    r:section(T.label .. ": validity check")
    r:text(("u-pooling area metric (eq. 11 and 12) of the 9 data of each mode against the KDE of %d samples of the calibrated model (Kriging), with the exact 95 %% threshold for n = 9 (0.1927, shared/spec/algorithms.md §5; the paper's 0.1818 is its 93.3 %% point). Mode 2 was not used by the calibration. As a check of the surrogate, %d samples were also run through column-fe itself."):format(cfg.val_n, cfg.solver_check))
    local pdfs, cdfs, rows = {}, {}, {}
    res.all_pass = true
    for _, m in ipairs(MODES) do
      local v = res.modes[m]
      local c = ebd[m]
      pdfs[#pdfs + 1] = { figs.pdf_over_data(m, v, ctx.results.data[m], trial.pdf_curve(c, smi.vec(ctx.results.data[m]), v.pdf.x[1], v.pdf.x[#v.pdf.x])), figs.title[m] .. ": calibrated PDF over the data." }
      cdfs[#cdfs + 1] = { figs.upool(m, v), figs.title[m] .. ": ECDF of the u-values against the uniform CDF." }
      rows[#rows + 1] = { figs.title[m], v.used_in_calibration and "calibration" or "validation only", v.predicted_mean, v.predicted_std, v.metric, v.threshold, v.p,
                          { status = v.pass and "pass" or "fail", text = v.pass and "valid" or "invalid" }, v.solver.metric, { status = v.solver.pass and "pass" or "fail", text = v.solver.pass and "valid" or "invalid" } }
      r:verdict{ name = ("%s, %s"):format(T.label, figs.title[m]), pass = v.pass, value = v.metric, threshold = v.threshold,
                 detail = ("U = %.4f %s %.4f (p = %.3f)%s"):format(v.metric, v.pass and "≤" or ">", v.threshold, v.p, v.used_in_calibration and "" or "; not used by the calibration") }
      if v.pass ~= v.solver.pass then
        r:callout(("%s, %s: the solver check (U = %.4f) disagrees with the Kriging verdict: the surrogate's error matters here."):format(T.label, figs.title[m], v.solver.metric), "warn")
      end
      res.all_pass = res.all_pass and v.pass
    end
    r:figures(pdfs)
    r:figures(cdfs)
    r:table{ caption = "Validity check (frequencies in Hz).", columns = { "Mode", "Role", "Pred. mean", "Pred. std", "U", "Threshold", "p", "Verdict", "U (solver check)", "Solver check" }, rows = rows }
    return res
  end)
end

s:step("trial1_surrogate", surrogate_step("trial1"))
s:step("trial1_calibration", calibration_step("trial1"))
s:step("trial1_validation", validation_step("trial1"))

-- ---------------------------------------------------------------------------------------------
-- Refinement: weighted decision matrix over the three candidates
-- ---------------------------------------------------------------------------------------------
s:step("refinement", timed(function(ctx)
  local v = ctx.results.trial1_validation
  local failed = {}
  -- the calibrated responses that failed the check (the paper: mode 4); mode 2 is kept for
  -- validating the refined model, not for choosing the refinement
  for _, m in ipairs{ "mode1", "mode4" } do if not v.modes[m].pass then failed[#failed + 1] = m end end
  if #failed == 0 then failed = { "mode4" } end -- trial 1 valid: still rank the candidates on the paper's mode
  local data = ctx.results.data
  local observed = {}
  for _, m in ipairs(MODES) do observed[m] = smi.vec(data[m]):mean() end
  -- the revised model at the mean of the initial unknowns (Table 4 initial means = nominal)
  local runs = {}
  local crit = criteria.build{ observed = observed, responses = failed, run = function(c)
    local names = { "column_frame_E" }
    local m = solver.command{ solver = opt.solver, airbag = c.airbag, vary = names, fixed = c.fixed, name = "refine-" .. c.short:gsub("%s", "-") }
    local Y, info = m:evaluate(smi.mat{ { inputs.nominal.column_frame_E } })
    local y = { mode1 = Y.mode1[1], mode2 = Y.mode2[1], mode4 = Y.mode4[1] }
    runs[c.name] = { y = y, seconds = info.duration[1] }
    return y, info.duration[1]
  end }
  local dm = smi.refine.decision_matrix{ candidates = candidates, criteria = crit }
  local out = { failed_responses = failed, observed = observed, weights = criteria.weights, candidates = {}, overall = {}, best = dm.best,
                best_name = dm.best_name, picks_airbag_modelling = dm.best_name == "airbag modelling type" }
  local names, M_rows, S_rows = {}, {}, {}
  for j, c in ipairs(candidates) do
    names[j] = c.name
    out.overall[j] = dm.overall[j]
    local mag, std = {}, {}
    for i = 1, 4 do mag[i], std[i] = dm.M:get(j, i), dm.S:get(j, i) end
    out.candidates[j] = { name = c.name, magnitudes = mag, standardized = std, prediction = runs[c.name].y, new_inputs = c.new_inputs,
                          implement_minutes = c.implement_minutes, run_seconds = runs[c.name].seconds }
    M_rows[j] = { c.name, mag[1], mag[2], mag[3], mag[4], std[1], std[2], std[3], std[4], dm.overall[j] }
  end
  local r = ctx.report
  r:section("Model refinement")
  r:text(("Trial 1 failed on %s. Three candidate sources of invalid modelling (the paper's §4.1.5): %s. Each revised model is run at the mean of the initial unknowns; correctness is eq. (13) on the failed response(s), robustness the number of new inputs, computational cost the measured run time (minutes), implementation cost the analyst's estimate (minutes). Weights: correctness 0.4, the others 0.2 (criteria.lua explains why). Standardized magnitude S = 1 − M / max M (eq. 14); rating = Σ w·S."):format(
    table.concat(failed, ", "), table.concat(names, "; ")))
  r:table{ caption = "Weighted decision matrix (Table 6 analog): magnitudes M, standardized S, overall rating.",
           columns = { "Candidate", "M correctness", "M robustness", "M comp. (min)", "M impl. (min)", "S corr.", "S rob.", "S comp.", "S impl.", "Rating" }, rows = M_rows }
  local pred = {}
  for j, c in ipairs(candidates) do pred[j] = { c.name, runs[c.name].y.mode1, runs[c.name].y.mode2, runs[c.name].y.mode4 } end
  pred[#pred + 1] = { "data mean", observed.mode1, observed.mode2, observed.mode4 }
  r:table{ caption = "Revised models at the initial means (Hz).", columns = { "Model", "Mode 1", "Mode 2", "Mode 4" }, rows = pred }
  r:figure(figs.decision{ candidates = names, overall = out.overall, best_name = dm.best_name }, "Overall rating of the candidates.")
  r:verdict{ name = "Refinement picks the airbag modelling", pass = out.picks_airbag_modelling, detail = "best candidate: " .. dm.best_name }
  return out
end))

s:step("trial2_surrogate", surrogate_step("trial2"))
s:step("trial2_calibration", calibration_step("trial2"))
s:step("trial2_validation", validation_step("trial2"))

-- ---------------------------------------------------------------------------------------------
-- Summary: verdicts, solver runs, provenance
-- ---------------------------------------------------------------------------------------------
s:step("summary", timed(function(ctx)
  local R = ctx.results
  local t1, t2 = R.trial1_validation.modes, R.trial2_validation.modes
  local out = {
    trial1_fails_mode4 = not t1.mode4.pass,
    refinement_picks_airbag = R.refinement.picks_airbag_modelling,
    trial2_passes_all = t2.mode1.pass and t2.mode2.pass and t2.mode4.pass,
    trial2_passes_calibrated_modes = t2.mode1.pass and t2.mode4.pass,
    mode2_unconstrained_share = R.trial2_calibration.sensitivity.mode2_unconstrained_share,
    solver_runs = solver.counts, solver_totals = solver.totals(), quick = opt.quick, config = cfg, seed = seed,
    data_file = opt.data, solver_path = opt.solver, lua = _VERSION,
  }
  out.paper_reproduced = out.trial1_fails_mode4 and out.refinement_picks_airbag and out.trial2_passes_all
  local r = ctx.report
  r:section("Summary")
  r:text("The paper's course of events on the open model: trial 1 (rigid airbag, 4 unknowns) calibrates mode 1 but fails the validity check of mode 4; the decision matrix points at the airbag modelling; trial 2 (spring airbag, airbag stiffness as fifth unknown) passes the calibrated modes 1 and 4 and, as in the paper, the unseen mode 2. On this model the mode-2 verdict leans on the prior knowledge used by the calibration (the wheel cover's weighed mass), because modes 1 and 4 leave combinations of the unknowns undetermined (see the identifiability notes).")
  r:verdict{ name = "Trial 1 fails on mode 4 (as in the paper)", pass = out.trial1_fails_mode4, detail = ("U = %.4f vs %.4f"):format(t1.mode4.metric, t1.mode4.threshold) }
  r:verdict{ name = "Trial 2 passes modes 1, 2 and 4 (as in the paper)", pass = out.trial2_passes_all,
             detail = ("U = %.4f, %.4f, %.4f (threshold %.4f); mode 2 unseen by the calibration, %.0f %% of its sensitivity not constrained by modes 1 and 4"):format(
               t2.mode1.metric, t2.mode2.metric, t2.mode4.metric, t2.mode2.threshold, 100 * out.mode2_unconstrained_share) }
  if not t2.mode2.pass then
    r:callout("Mode 2 is not determined by modes 1 and 4 on this model: they fix the column's overall stiffening but not how it is split between column_frame_E (which mode 2 feels) and the ECU bracket (which it does not, by symmetry), nor the wheel cover's density against its thickness. The u-pooling check of mode 2 therefore tests the priors as much as the data. Calibrating on modes 1, 2 and 4 would settle it.", "warn")
  end
  local rows = {}
  for name, c in pairs(solver.counts) do rows[#rows + 1] = { name, c.points, c.launched, c.reused } end
  table.sort(rows, function(a, b) return a[1] < b[1] end)
  if #rows > 0 then
    r:table{ caption = "column-fe use in this run (steps run alone count only their own runs): points evaluated, processes launched, points reused from the store.",
             columns = { "Model", { title = "Points", format = "%d" }, { title = "Launched", format = "%d" }, { title = "Reused", format = "%d" } }, rows = rows }
  end
  local steps = {}
  for _, name in ipairs{ "data", "characterize", "screening", "trial1_surrogate", "trial1_calibration", "trial1_validation", "refinement",
                         "trial2_surrogate", "trial2_calibration", "trial2_validation" } do
    local ok, res = pcall(function() return R[name] end)
    if ok and res then steps[#steps + 1] = { name, res.wall_seconds or 0 } end
  end
  r:table{ caption = "Wall-clock time per step (s, 1 s resolution).", columns = { "Step", { title = "Wall (s)", format = "%d" } }, rows = steps }
  r:provenance{ seed = seed, quick = opt.quick, data = opt.data, solver = opt.solver, lua = _VERSION,
                solver_runs = out.solver_totals, sample_sizes = cfg }
  return out
end))

s:run(args)
