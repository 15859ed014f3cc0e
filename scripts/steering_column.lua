--- The steering-column study of Son et al. (2020), end to end, on the open FE model column-fe
-- (docs/spec/steering-column.md): trials of statistical model improvement until the model is
-- valid, the data cannot decide, or the analyst's limit of refinements is reached.
--
--   build/smi-lua --allow-exec build/column-fe scripts/steering_column.lua [options]
--
-- options (after the script name):
--   --data FILE.csv   measurements (columns mode1_hz, mode2_hz, mode4_hz; default: the committed
--                     scripts/steering_column/data/tests.csv). Give --allow-read for its folder.
--   --solver PATH     the column-fe program (default: <repo>/build/column-fe, next to the
--                     scripts folder; installed: column-fe on PATH); allow it with --allow-exec.
--   --quick           CI form: a 40-point screening sample, no bootstrap, a smaller solver check;
--                     surrogates, calibration and verdicts as in the full run.
--   --metric pr|loglik  calibration metric per mode: the paper's probability residual (default)
--                     or minus the log-likelihood of the data under the predicted KDE.
--   --multistart N    the PR stage from its start plus N-1 seeded points in the bounds (default 1).
--   --prior FILE.lua  the analyst's prior knowledge: a Lua file returning smi.calibrate `prior`
--                     entries ({param=, mean=, std=} or {name=, fn=, mean=, std=}); listed in the
--                     report. Default: none, the data file alone (example: steering_column/priors/).
--   --max-refinements N  how many revised models to try after an invalid trial (default 2).
--   --screening surrogate|full  eq.-3 screening on a ridge quadratic of 300 runs (default) or on
--                     the model itself, (46 + 1) x 200 runs; --design fixed|sequential, --test-points
--                     N, --solver-check N: the solver-run budget of the trials (cost.lua).
--   --dry-run         print the cost plan (runs per step x minutes per run / concurrency) and stop;
--                     --minutes-per-run X declares the solver's time (default: the store's mean).
--   --only STEP[,STEP], --from STEP   run some steps; the others' results come from results.json.
-- smi-lua's own --out DIR (default smi-out/steering_column/), --seed N and --quiet apply.
--
-- Steps: data, characterize (KDE vs KDE-ebd), screening (46 inputs, batch runs), then per trial k
-- trialk_surrogate (Kriging on a Latin hypercube, leave-one-out), trialk_calibration (PR(mode 1)
-- + PR(mode 4), SLSQP, CRN), trialk_validation (u-pooling on modes 1, 4 and 2) and, after an
-- invalid trial, refinementk (weighted decision matrix over the candidates of refinement/, the
-- next trial is the chosen candidate's declared revision); summary. Steps after the study has
-- concluded record why they did not run. Writes report.html and results.json (with a top-level
-- `conclusion`) in the output folder.
-- Solver runs go through the evaluation store (<out>/evaluations.sqlite): a rerun reuses them.
local study = require "smi.study"
local inputs = require "steering_column.inputs"
local solver = require "steering_column.solver"
local trial = require "steering_column.trial"
local calibration = require "steering_column.calibration"
local figs = require "steering_column.figures"
local models = require "steering_column.models"
local candidates = require "steering_column.refinement.candidates"
local criteria = require "steering_column.refinement.criteria"
local verdict = require "steering_column.verdict"
local text = require "steering_column.report_text"
local cost = require "steering_column.cost"

local MODES = { "mode1", "mode2", "mode4" }

-- ---------------------------------------------------------------------------------------------
-- Options
-- ---------------------------------------------------------------------------------------------
local here = smi.script_dir or "scripts"
-- The solver: in the source tree (scripts/CMakeLists.txt beside this script) the one built in
-- build/; an installed copy (share/smi-lua/scripts, no build files) runs column-fe from PATH.
local in_tree = io.open(here .. "/CMakeLists.txt")
if in_tree then in_tree:close() end
local options = require "smi.options"
local opt = options.parse(arg, {
  name = "steering_column",
  summary = "the steering-column study of Son et al. (2020) on the FE model column-fe",
  usage = "smi-lua --allow-exec build/column-fe scripts/steering_column.lua [options]",
  { name = "data", type = "path", default = here .. "/steering_column/data/tests.csv",
    meaning = "measurements, columns mode1_hz, mode2_hz, mode4_hz (give --allow-read for its folder)" },
  { name = "solver", type = "path", default = in_tree and here .. "/../build/column-fe" or "column-fe",
    meaning = "the column-fe program; allow it with --allow-exec PATH" },
  { name = "quick", type = "flag", default = false,
    meaning = "CI form: a 40-point screening sample, no bootstrap, a smaller solver check" },
  { name = "metric", type = "string", default = "pr", allowed = { "pr", "loglik" },
    meaning = "calibration metric per mode: the paper's probability residual, or minus the log-likelihood" },
  { name = "multistart", type = "integer", default = 1, min = 1,
    meaning = "the PR stage from its start plus N-1 seeded points in the bounds" },
  { name = "prior", type = "path",
    meaning = "a Lua file returning smi.calibrate prior entries (the analyst's knowledge, e.g. a weighed"
      .. " mass); none by default" },
  { name = "max-refinements", type = "integer", default = 2, min = 0,
    meaning = "how many refinements (revised trials) to try after an invalid trial" },
  { name = "screening", type = "string", default = "surrogate", allowed = { "surrogate", "full" },
    meaning = "eq.-3 screening on a ridge quadratic fitted to --screening-runs runs (economical), or on the"
      .. " model itself ((46 + 1) x 200 runs, 40 with --quick)" },
  { name = "screening-runs", type = "integer", default = 300, min = 50,
    meaning = "solver runs of the surrogate screening" },
  { name = "design", type = "string", default = "fixed", allowed = { "fixed", "sequential" },
    meaning = "the trials' Kriging designs: the maximin hypercube of the model's n_design points, or"
      .. " sequential: start small and add batches until every mode's leave-one-out Q2 reaches 0.999 (at"
      .. " most n_design points; on the committed data it reaches neither and moves trial 1's calibration,"
      .. " README)" },
  { name = "test-points", type = "integer", min = 5,
    meaning = "independent test points of each Kriging (default 20; the paper's-size run: 50)" },
  { name = "solver-check", type = "integer", min = 10,
    meaning = "points of the validation's solver check, stratified over the calibrated distributions"
      .. " (default 40; before issue 16: 300, 100 with --quick)" },
  { name = "dry-run", type = "flag", default = false,
    meaning = "print the cost plan (runs per step x minutes per run / concurrency, total runs and wall time)"
      .. " and stop before anything runs" },
  { name = "minutes-per-run", type = "number", min = 0,
    meaning = "the solver's minutes per run for the cost plan (default: the mean of the runs in the"
      .. " evaluation store)" },
  options.study_steps,
  epilog = "smi-lua's own --out DIR (default smi-out/steering_column/), --seed N and --quiet apply.",
})

-- The analyst's prior knowledge (--prior FILE.lua), checked; none by default.
local PRIOR = require("steering_column.prior_file").load(opt.prior)

-- Sample sizes. Full: the paper's choices where stated; quick: CI.
-- Quick differs only where the verdicts do not depend on it: the screening sample, the
-- bootstrap and the solver check of the validation; surrogates and calibration are the same.
local cfg = opt.quick and {
  screen_n = 40, test_points = 50, cal_n = 2000, maxeval = 300, bootstrap = 0,
  val_n = 20000, solver_check = 100, near_n = 5000,
} or {
  screen_n = 200, test_points = 50, cal_n = 2000, maxeval = 300, bootstrap = 50,
  val_n = 20000, solver_check = 300, near_n = 5000,
}
-- The solver-run budget (issue 16, cost.lua): surrogate screening, 20 test points and a 40-point
-- stratified solver check by default; --screening full --test-points 50 --solver-check 300 is
-- the study before it (bench/run_study_budget.sh runs both and compares the conclusions).
cfg.screening, cfg.screen_runs, cfg.design = opt.screening, opt.screening_runs, opt.design
cfg.test_points = opt.test_points or 20
cfg.solver_check = opt.solver_check or 40
local seed = smi.seed or 20200214

local s = study.new{ name = "steering_column", seed = seed,
  report = { title = "Steering column: statistical model improvement",
             subtitle = "Son et al. (2020) on the open FE model column-fe" .. (opt.quick and " (quick run)" or ""),
             author = "smi-lua scripts/steering_column.lua" } }

-- Wall-clock seconds of a step (os.clock counts this process only; the solver runs in others)
-- and the column-fe solutions it made (cost.lua).
local function timed(fn)
  return function(ctx)
    local t0, mark = os.time(), cost.mark()
    local r = fn(ctx) or ctx.result
    r.wall_seconds = os.time() - t0
    r.solver_runs = cost.since(mark)
    return r
  end
end

-- The experimental PDFs (KDE-ebd), rebuilt deterministically from the data so that any step can
-- run alone (calibration.lua, which bench/calibrate_trial2.lua shares).
local function f_exp(data) return calibration.experimental_pdfs(data, seed) end

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
    local col, name = d[m .. "_hz"], m .. "_hz"
    if col == nil then
      error(("%s: no column '%s' (columns: %s); the file needs mode1_hz, mode2_hz and mode4_hz"):format(
        opt.data, name, table.concat(header, ", ")), 0)
    end
    if type(col) ~= "userdata" then
      error(("%s: column '%s' holds text; every value must be a frequency in Hz"):format(opt.data, name), 0)
    end
    if #col < 3 then
      error(("%s: %d rows; the study needs at least 3 measurements per mode"):format(opt.data, #col), 0)
    end
    for i = 1, #col do
      if not (col[i] > 0 and col[i] < math.huge) then
        error(("%s: row %d, %s = %s is not a positive frequency"):format(opt.data, i, name, tostring(col[i])), 0)
      end
    end
    out[m] = col:totable()
    out.n = #col
  end
  local r = ctx.report
  r:section("Experimental data")
  r:text(text.data_intro(out.n, opt.data))
  local rows = {}
  for i = 1, out.n do rows[i] = { i, out.mode1[i], out.mode2[i], out.mode4[i] } end
  r:table{ caption = "Measured natural frequencies (Hz).", rows = rows,
           columns = { "Specimen", { title = "Mode 1", digits = 6 }, { title = "Mode 2", digits = 6 },
                       { title = "Mode 4", digits = 6 } } }
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
    local c = { kde = trial.pdf_curve(k, data[m], lo, hi), ebd = trial.pdf_curve(e, data[m], lo, hi),
                data = data[m]:totable() }
    out[m] = { mean = data[m]:mean(), std = data[m]:std(), kde_bandwidth = k.bandwidth,
               ebd_bandwidth = e.bandwidth,
               ebd_lower = e.lower, ebd_upper = e.upper, ebd_added = e.added, ebd_std = e:std() }
    figures[#figures + 1] = { figs.kde_vs_ebd(m, c),
                              figs.title[m] .. ": KDE of the data and KDE with estimated bounded data." }
    rows[#rows + 1] = { figs.title[m], out[m].mean, out[m].std, k.bandwidth, e.bandwidth, e.lower, e.upper, e.added }
  end
  local r = ctx.report
  r:section("Uncertainty characterization (KDE vs KDE-ebd)")
  r:text(text.characterize_intro(#data.mode1))
  r:figures(figures)
  r:table{ caption = "Data summary and bandwidths (Hz).", rows = rows,
           columns = { "Mode", "Mean", "Std", "h KDE", "h KDE-ebd", "ebd lower", "ebd upper",
                       { title = "Points added", format = "%d" } } }
  return out
end))

-- ---------------------------------------------------------------------------------------------
-- 3. Screening of the 46 inputs (model A, batch runs of column-fe)
-- ---------------------------------------------------------------------------------------------
s:step("screening", timed(function(ctx)
  local base = solver.write_deck(smi.out("screening_base_rigid.deck"), "rigid")
  -- surrogate (default, issue 16): eq. 3 on a ridge quadratic of all 46 inputs fitted to
  -- screen_runs runs, 10,000 CRN points on it (bench/results/screening_budget.md: the same top
  -- four per mode as the full screening's 9,400 runs); full: eq. 3 on column-fe itself
  local sur = cfg.screening == "surrogate"
  local runs = sur and cfg.screen_runs or (#inputs.names + 1) * cfg.screen_n
  local bm = solver.batch{ solver = opt.solver, airbag = "rigid", vary = inputs.names,
                           name = sur and "screening-surrogate" or "screening", base = base,
                           batch_size = math.ceil((sur and cfg.screen_runs or cfg.screen_n) / 2), concurrency = 2 }
  local n = sur and 10000 or cfg.screen_n
  if sur then
    ctx:log("%d inputs: %d solutions on a Latin hypercube (batch runs), a ridge quadratic per mode,"
            .. " eq. 3 on it with %d CRN samples", #inputs.names, runs, n)
  else
    ctx:log("%d inputs x %d samples (common random numbers): %d solutions in batch runs",
            #inputs.names, cfg.screen_n, runs)
  end
  local res = smi.screen{ model = bm, inputs = inputs.screening_inputs(), n = n, seed = seed + 20, sobol = false,
                          method = sur and "surrogate" or nil, runs = sur and cfg.screen_runs or nil }
  local out = { n = n, seed = seed + 20, modes = {}, method = cfg.screening, solver_solutions = runs }
  local chosen = { column_frame_E = true, ecu_bracket_thickness = true, wheel_cover_rho = true,
                   wheel_cover_thickness = true }
  local figures = {}
  for _, m in ipairs(MODES) do
    local rows = {}
    for i, row in ipairs(res[m]) do rows[i] = { input = row.input, e = row.e, ne = row.ne, rank = row.rank } end
    out.modes[m] = { rows = rows, warnings = res[m].warnings,
                     top = { rows[1].input, rows[2].input, rows[3].input, rows[4].input },
                     q2 = res[m].q2 }
    figures[#figures + 1] = { figs.screening(m, rows, chosen), figs.title[m]
      .. ": the ten largest normalized area metrics (Table 2 analog); highlighted: the trial-1 unknowns." }
  end
  local top1 = out.modes.mode1.top
  out.dominant_confirmed = (top1[1] == "column_frame_E" or top1[1] == "ecu_bracket_thickness")
    and (top1[2] == "column_frame_E" or top1[2] == "ecu_bracket_thickness")
  local r = ctx.report
  r:section("Variable screening")
  r:text(text.screening_intro(out))
  r:figures(figures)
  local rows = {}
  for _, m in ipairs(MODES) do
    local t = out.modes[m].rows
    rows[#rows + 1] = { figs.title[m], ("%s %.3f"):format(t[1].input, t[1].ne), ("%s %.3f"):format(t[2].input, t[2].ne),
                        ("%s %.3f"):format(t[3].input, t[3].ne), ("%s %.3f"):format(t[4].input, t[4].ne) }
  end
  r:table{ caption = "The four most influential inputs per mode (normalized area metric).",
           columns = { "Mode", "1st", "2nd", "3rd", "4th" }, rows = rows }
  r:callout(text.screening_callout(out.dominant_confirmed), out.dominant_confirmed and "info" or "warn")
  return out
end))

-- ---------------------------------------------------------------------------------------------
-- Trials: surrogate, calibration, validation; refinement after an invalid trial
-- ---------------------------------------------------------------------------------------------
local MAX_TRIALS = 1 + opt.max_refinements

local function assignments(t)
  local parts = {}
  for k, v in pairs(t) do parts[#parts + 1] = ("%s = %.6g"):format(k, v) end
  table.sort(parts)
  return table.concat(parts, ", ")
end

local function label(model, k)
  return ("Trial %d (%s)"):format(k, model.candidate == "initial" and "initial model" or model.candidate)
end

-- The model of trial k, or nil and why the study ended before it.
local function trial_model(R, k)
  if k == 1 then return models.initial() end
  local ref = R["refinement" .. (k - 1)]
  if ref.skipped then return nil, ref.reason end
  return ref.model
end

-- A step that does not run because the study has concluded: its record says why.
local function skipped(reason) return { skipped = true, reason = reason } end

local function surrogate_step(k)
  return timed(function(ctx)
    local T, why = trial_model(ctx.results, k)
    if not T then return skipped(why) end
    ctx:log("%s: %s of %d unknowns, %s airbag; %d test points", label(T, k),
      cfg.design == "sequential" and ("sequential design of at most " .. T.n_design .. " points")
      or (T.n_design .. "-point Latin hypercube"), #T.unknowns, T.airbag, cfg.test_points)
    local res = trial.surrogate{ name = "trial" .. k, airbag = T.airbag, fixed = T.fixed, unknowns = T.unknowns,
                                 specs = T.specs, trend = T.trend, n_design = T.n_design, design = cfg.design,
                                 n_test = cfg.test_points, seed = seed + 100 * k, solver = opt.solver }
    res.model = T
    local r = ctx.report
    r:section(label(T, k) .. ": surrogate model")
    local fixed = next(T.fixed) and (", fixed " .. assignments(T.fixed)) or ""
    r:text(text.surrogate_intro(T, res, fixed, cfg.test_points))
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
    r:table{ caption = "Kriging accuracy (Hz).", columns = { "Mode", "LOO Q²", "LOO RMSE", "Test RMSE" },
             rows = rows }
    local box = {}
    for _, n in ipairs(T.unknowns) do box[#box + 1] = { n, res.design_bounds[n][1], res.design_bounds[n][2] } end
    r:table{ caption = "Design box of the unknowns.", columns = { "Input", "Lower", "Upper" }, rows = box }
    return res
  end)
end

-- The calibrated parameters' table (means and stds against their bounds, starts and stage 1).
local function parameter_rows(res)
  local rows = {}
  for _, p in ipairs(res.params) do
    rows[#rows + 1] = { p.input, p.dist, p.unit, ("[%.4g, %.4g]"):format(p.mean_bounds[1], p.mean_bounds[2]),
                        ("[%.4g, %.4g]"):format(p.std_bounds[1], p.std_bounds[2]), p.mean_start, p.std_start,
                        p.stage1_mean, p.stage1_std, p.mean, p.std, text.bootstrap_cell(res, p.input) }
  end
  return rows
end

local function calibration_report(r, L, T, res)
  r:section(L .. ": calibration")
  r:text(text.calibration_intro(T, res, cfg, opt.prior, PRIOR.labels))
  r:figure(figs.history(res, L), L .. ": calibration history.")
  r:table{ caption = text.parameters_caption(res), rows = parameter_rows(res),
           columns = { "Input", "Type", "Unit", "Mean bounds", "Std bounds", "Initial mean", "Initial std",
                       "Stage-1 mean", "Stage-1 std", "Calibrated mean", "Calibrated std", "Bootstrap CI" } }
  if res.cover_mass_ratio then r:text(text.cover_mass(res.cover_mass_ratio)) end
  for _, w in ipairs(res.warnings) do r:callout(L .. ": " .. w, "warn") end
  local sv = res.sensitivity
  local srows = {}
  local sens = sv.sensitivity
  for _, n in ipairs(sv.inputs) do srows[#srows + 1] = { n, sens.mode1[n], sens.mode2[n], sens.mode4[n] } end
  r:table{ caption = "Relative sensitivities d ln f / d ln x of the Kriging modes at the calibrated means.",
           rows = srows, columns = { "Input", "Mode 1", "Mode 2", "Mode 4" } }
  r:callout(text.identifiability(res), sv.mode2_unconstrained_share > 0.2 and "warn" or "info")
  if #res.weak > 0 then r:callout(text.weak_parameters(res.weak), "warn") end
end

local function calibration_step(k)
  return timed(function(ctx)
    local sur = ctx.results["trial" .. k .. "_surrogate"]
    if sur.skipped then return skipped(sur.reason) end
    local T = sur.model
    ctx:log("SLSQP on %d CRN samples, %d parameters, at most %d evaluations", cfg.cal_n, 2 * #T.unknowns, cfg.maxeval)
    local res = calibration.calibrate{
      unknowns = T.unknowns, specs = T.specs, data = vecs(ctx.results.data), f_exp = f_exp(ctx.results.data),
      kriging = trial.krigings(sur), design_bounds = sur.design_bounds, n = cfg.cal_n, seed = seed + 100 * k + 10,
      maxeval = cfg.maxeval, bootstrap = cfg.bootstrap, boot_maxeval = 80, metric = opt.metric,
      multistart = opt.multistart, prior = PRIOR.entries, prior_labels = PRIOR.labels }
    calibration_report(ctx.report, label(T, k), T, res)
    return res
  end)
end

local BADGE = { valid = "pass", invalid = "fail", inconclusive = "warn" }

-- The validity check's figures, table and verdict list (one verdict per mode).
local function validation_report(ctx, L, res, cal)
  local r = ctx.report
  local ebd = f_exp(ctx.results.data)
  r:section(L .. ": validity check")
  r:text(text.validation_intro(res, #ctx.results.data.mode1, cfg))
  local pdfs, cdfs, rows = {}, {}, {}
  for _, m in ipairs(MODES) do
    local v = res.modes[m]
    local data = ctx.results.data[m]
    local exp_curve = trial.pdf_curve(ebd[m], smi.vec(data), v.pdf.x[1], v.pdf.x[#v.pdf.x])
    pdfs[#pdfs + 1] = { figs.pdf_over_data(m, v, data, exp_curve), figs.title[m] .. ": calibrated PDF over the data." }
    cdfs[#cdfs + 1] = { figs.upool(m, v), figs.title[m] .. ": ECDF of the u-values against the uniform CDF." }
    local range = v.range and ("[%.4f, %.4f] over %d"):format(v.range.lower, v.range.upper, v.range.points) or "—"
    rows[#rows + 1] = { figs.title[m], v.used_in_calibration and "calibration" or "validation only", v.predicted_mean,
                        v.predicted_std, v.metric, range, v.threshold, { status = BADGE[v.verdict], text = v.verdict },
                        v.solver.metric, { status = v.solver.pass and "pass" or "fail",
                                           text = v.solver.pass and "valid" or "invalid" } }
    v.detail = v.range and text.range_detail(v, cal) or text.decisive_detail(v)
    r:verdict{ name = ("%s, %s"):format(L, figs.title[m]), status = BADGE[v.verdict], value = v.metric,
               threshold = v.threshold, detail = v.detail }
    if v.pass ~= v.solver.pass then r:callout(text.solver_disagrees(L, figs.title[m], v.solver.metric), "warn") end
  end
  r:figures(pdfs)
  r:figures(cdfs)
  r:table{ caption = "Validity check (frequencies in Hz). U range: over the near-optimal calibrations.", rows = rows,
           columns = { "Mode", "Role", "Pred. mean", "Pred. std", "U", "U range", "Threshold", "Verdict",
                       "U (solver check)", "Solver check" } }
  r:text(text.trial_verdict(L, res))
end

local function validation_step(k)
  return timed(function(ctx)
    local sur = ctx.results["trial" .. k .. "_surrogate"]
    if sur.skipped then return skipped(sur.reason) end
    local T = sur.model
    local cal = ctx.results["trial" .. k .. "_calibration"]
    local res = trial.validate{ name = "trial" .. k, model = T, kriging = trial.krigings(sur), calibration = cal,
                                data = vecs(ctx.results.data), n = cfg.val_n, n_solver = cfg.solver_check,
                                n_near = cfg.near_n, seed = seed + 100 * k + 30, solver = opt.solver }
    validation_report(ctx, label(T, k), res, cal)
    return res
  end)
end

-- ---------------------------------------------------------------------------------------------
-- Refinement: weighted decision matrix over the candidates' declared revisions
-- ---------------------------------------------------------------------------------------------
-- Ranks the candidates once (after the first invalid trial): each revised model runs at the
-- initial means; correctness is eq. (13) averaged over every response used in calibration.
local function rank_candidates(ctx)
  local observed = {}
  for _, m in ipairs(MODES) do observed[m] = smi.vec(ctx.results.data[m]):mean() end
  local runs = {}
  local crit = criteria.build{ observed = observed, responses = trial.calibration_modes, run = function(c)
    local rev = models.revised(c)
    local m = solver.command{ solver = opt.solver, airbag = rev.airbag, vary = { "column_frame_E" },
                              fixed = models.at_initial(rev), name = "refine-" .. c.short:gsub("%s", "-") }
    local Y, info = m:evaluate(smi.mat{ { inputs.nominal.column_frame_E } })
    runs[c.name] = { y = { mode1 = Y.mode1[1], mode2 = Y.mode2[1], mode4 = Y.mode4[1] }, seconds = info.duration[1] }
    return runs[c.name].y, info.duration[1]
  end }
  local dm = smi.refine.decision_matrix{ candidates = candidates, criteria = crit }
  local out = { responses = trial.calibration_modes, observed = observed, weights = criteria.weights,
                candidates = {}, overall = {} }
  for j, c in ipairs(candidates) do
    out.overall[j] = dm.overall[j]
    local mag, std = {}, {}
    for i = 1, 4 do mag[i], std[i] = dm.M:get(j, i), dm.S:get(j, i) end
    out.candidates[j] = { name = c.name, magnitudes = mag, standardized = std, prediction = runs[c.name].y,
                          new_inputs = c.new_inputs, implement_minutes = c.implement_minutes,
                          run_seconds = runs[c.name].seconds }
  end
  local order = {}
  for j = 1, #candidates do order[j] = j end
  table.sort(order, function(a, b) return dm.overall[a] > dm.overall[b] end)
  out.ranking = {}
  for i, j in ipairs(order) do out.ranking[i] = candidates[j].name end
  return out
end

-- The best-ranked candidate not tried yet (its index in the matrix), the runner-up among the
-- untried, and the set of tried ones; nil when every candidate has been tried.
local function choose(dm, R, k)
  local tried = {}
  for i = 1, k do tried[R["trial" .. i .. "_surrogate"].model.candidate] = true end
  local chosen
  for _, name in ipairs(dm.ranking) do if not tried[name] then chosen = name; break end end
  if not chosen then return nil end
  local jc, jr
  for j, c in ipairs(dm.candidates) do
    if c.name == chosen then jc = j end
    if c.name ~= chosen and not tried[c.name] and (not jr or dm.overall[j] > dm.overall[jr]) then jr = j end
  end
  return chosen, jc, jr
end

local function refinement_report(r, k, out)
  local dm = out.matrix
  r:section(("Model refinement after trial %d"):format(k))
  local M_rows, pred = {}, {}
  for j, c in ipairs(dm.candidates) do
    local mg, st = c.magnitudes, c.standardized
    M_rows[j] = { c.name, mg[1], mg[2], mg[3], mg[4], st[1], st[2], st[3], st[4], dm.overall[j] }
    pred[j] = { c.name, c.prediction.mode1, c.prediction.mode2, c.prediction.mode4 }
  end
  pred[#pred + 1] = { "data mean", dm.observed.mode1, dm.observed.mode2, dm.observed.mode4 }
  r:text(text.refinement_intro(k, out))
  r:table{ caption = "Weighted decision matrix (Table 6 analog): magnitudes M, standardized S, overall rating.",
           rows = M_rows, columns = { "Candidate", "M correctness", "M robustness", "M comp. (min)", "M impl. (min)",
                                      "S corr.", "S rob.", "S comp.", "S impl.", "Rating" } }
  r:table{ caption = "Revised models at the initial means (Hz).", rows = pred,
           columns = { "Model", "Mode 1", "Mode 2", "Mode 4" } }
  local names = {}
  for j, c in ipairs(dm.candidates) do names[j] = c.name end
  r:figure(figs.decision{ candidates = names, overall = dm.overall, best_name = out.chosen },
           "Overall rating of the candidates.")
  r:callout(("Refinement after trial %d: %s (%s)."):format(k, out.chosen, out.why), "info")
end

local function refinement_step(k)
  return timed(function(ctx)
    local v = ctx.results["trial" .. k .. "_validation"]
    if v.skipped then return skipped(v.reason) end
    if v.verdict ~= "invalid" then return skipped(text.nothing_to_refine(k, v)) end
    if k > opt.max_refinements then
      return skipped(("trial %d is invalid and the analyst's limit of %d refinement(s) is reached"):format(
        k, opt.max_refinements))
    end
    local failed = {}
    for _, m in ipairs(MODES) do if v.modes[m].verdict == "invalid" then failed[#failed + 1] = m end end
    local dm = k == 1 and rank_candidates(ctx) or ctx.results.refinement1.matrix
    local chosen, jc, jr = choose(dm, ctx.results, k)
    if not chosen then return skipped(("trial %d is invalid and every candidate has been tried"):format(k)) end
    local cand
    for _, c in ipairs(candidates) do if c.name == chosen then cand = c end end
    local out = { failed_responses = failed, matrix = dm, chosen = chosen, model = models.revised(cand),
                  why = text.why_chosen(dm, jc, jr) }
    for i, name in ipairs(dm.ranking) do if name == chosen then out.rank = i end end
    refinement_report(ctx.report, k, out)
    return out
  end)
end

for k = 1, MAX_TRIALS do
  s:step("trial" .. k .. "_surrogate", surrogate_step(k))
  s:step("trial" .. k .. "_calibration", calibration_step(k))
  s:step("trial" .. k .. "_validation", validation_step(k))
  if k < MAX_TRIALS then s:step("refinement" .. k, refinement_step(k)) end
end

-- ---------------------------------------------------------------------------------------------
-- Summary: the conclusion, solver runs, provenance
-- ---------------------------------------------------------------------------------------------
-- The summary's tables: solver use and the wall-clock time per step.
local function summary_tables(r, R)
  local rows = {}
  for name, cnt in pairs(solver.counts) do rows[#rows + 1] = { name, cnt.points, cnt.launched, cnt.reused } end
  table.sort(rows, function(a, b) return a[1] < b[1] end)
  if #rows > 0 then
    r:table{ caption = text.solver_use_caption, rows = rows,
             columns = { "Model", { title = "Points", format = "%d" }, { title = "Launched", format = "%d" },
                         { title = "Reused", format = "%d" } } }
  end
  -- wall time and solver runs per step, in one pass over each step's own record (a step run
  -- alone keeps both); the summary, still running, has neither
  local steps, per, total = {}, {}, 0
  for _, st in ipairs(s.steps) do
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
  r:table{ caption = ("Solver runs per step (column-fe solutions; new: not found in the evaluation store)."
             .. " Screening: %s; Kriging test points %d; solver check %d points"
             .. " (issue 16's budget: at most 1,000)."):format(
             cfg.screening == "surrogate" and ("surrogate, " .. cfg.screen_runs .. " runs") or "full eq. 3",
             cfg.test_points, cfg.solver_check),
           columns = { "Step", { title = "Solutions", format = "%d" }, { title = "New", format = "%s" },
                       { title = "Processes", format = "%s" } }, rows = per }
  return total
end

s:step("summary", timed(function(ctx)
  local R = ctx.results
  local c = verdict.conclusion(R, MAX_TRIALS)
  local out = { conclusion = c, solver_runs = solver.counts, solver_totals = solver.totals(), quick = opt.quick,
                config = cfg, seed = seed, data_file = opt.data, solver_path = opt.solver, prior_file = opt.prior,
                priors = PRIOR.labels, lua = _VERSION, words = text.conclusion(c, R) }
  local r = ctx.report
  r:section("Summary")
  r:text(text.story(c, R, PRIOR.labels))
  r:verdict{ name = "Conclusion: the model is " .. c.verdict, status = BADGE[c.verdict],
             detail = text.conclusion_detail(c, R) }
  out.solver_runs_total = summary_tables(r, R)
  r:provenance{ seed = seed, quick = opt.quick, data = opt.data, solver = opt.solver, lua = _VERSION,
                prior = opt.prior or "none", solver_runs = out.solver_totals, sample_sizes = cfg }
  return out
end))

-- The cost plan before anything runs (--dry-run, or smi-lua's own --dry-run, which then goes on to
-- count the runs the store already holds).
if opt.dry_run or smi.dry_run then
  local probe = solver.command{ solver = opt.solver, airbag = "rigid", vary = { "column_frame_E" },
                               name = "cost-probe" }
  local minutes, source = cost.minutes_per_run(opt.minutes_per_run, probe)
  local plan = cost.plan{ cfg = cfg, max_trials = MAX_TRIALS, initial = models.initial(), candidates = candidates }
  local text = cost.plan_text(plan, minutes, source)
  io.stdout:write(text)
  if opt.dry_run then return end
end

local results = s:run(opt)

-- The conclusion at the top of results.json, where outside checks read it, and in words last.
local ok, summary = pcall(function() return results.summary end)
if ok and summary and summary.conclusion then
  local c = summary.conclusion
  s:annotate("conclusion", verdict.top_level(c))
  s:annotate("cost", { solver_runs = summary.solver_runs_total, screening = cfg.screening,
                       test_points = cfg.test_points, solver_check = cfg.solver_check })
  for i, t in ipairs(c.trials) do io.stdout:write(text.trial_line(i, t, c.refinements[i]), "\n") end
  io.stdout:write(summary.words or ("Conclusion: the model is " .. c.verdict), "\n")
end
