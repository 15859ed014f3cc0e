-- SPDX-License-Identifier: MIT
--- smi.improve: the method of statistical model improvement (Son et al. 2020) as a library. A
-- study declares its responses, unknowns, model factory, refinement candidates, criteria and
-- limits (docs/new-product.md; the fields: declare.lua); smi.improve.run(declaration, arg) runs
-- the loop through smi.study (resume, --only/--from, --dry-run cost plan):
--   data (and a units check on one nominal run), characterize (KDE vs KDE-ebd), [screening],
--   then per trial k: trialk_surrogate, trialk_calibration, trialk_validation and, after a trial
--   that is not valid, refinementk (decision matrix; the chosen revision goes on top of the kept
--   ones); summary. It stops when a trial is valid, when the data cannot decide, or at the limit.
-- The numerics are the kernels' (smi.kriging, smi.calibrate, smi.propagate, smi.metric, ...);
-- smi/improve/*.lua hold one job each: steps.lua computes, view/*.lua write the report.
local doc = require "smi.doc"
doc.add[==[
@ module smi.improve
The trial loop of statistical model improvement for any declared product (responses, unknowns,
a model factory, refinement candidates, criteria and limits): smi.improve.run(declaration, arg).
See docs/new-product.md.
]==]
local study = require "smi.study"
local options = require "smi.options"
local declare = require "smi.improve.declare"
local verdict = require "smi.improve.verdict"
local cost = require "smi.improve.cost"
local text = require "smi.improve.text"
local revise = require "smi.improve.revise"
local factory = require "smi.improve.factory"
local run_context = require "smi.improve.run_context"

local M = {}

-- Whether the study's initial model runs in this process (smi.model.lua), asked of the factory
-- with every option at its default: only then does the usage line leave out --allow-exec. A
-- factory that fails on the defaults (a solver not found, not allowed) keeps the flag in.
local function in_process(D, s)
  -- the defaults as smi.options fills them in; with --help it opens no input file
  local opt = options.check({ "--help" }, s) or {}
  opt.help = nil
  local ok, m = pcall(factory.model, D, opt, revise.initial(D, D.unknowns), { purpose = "help", name = "help" })
  return ok and m.kind == "lua"
end

-- The options every study gets (a declaration adds its own with `options`).
local function spec(D, script)
  local s
  s = {
    name = D.name, summary = D.title or ("the statistical model improvement study " .. D.name),
    -- the script as it was run (its declaration's name may differ); a solver needs --allow-exec
    usage = function()
      local run = script or (D.name .. ".lua")
      if in_process(D, s) then return ("smi-lua %s [options]"):format(run) end
      return ("smi-lua [--allow-exec SOLVER] %s [options]"):format(run)
    end,
    { name = "data", type = "path", input = true, default = D.data, meaning = "measurements (CSV; give --allow-read for its folder)" },
    { name = "quick", type = "flag", default = false,
      meaning = D.screening and "CI form: a 40-point screening sample, no bootstrap, half the evidence's sample sizes"
        or "CI form: no bootstrap of the calibration, half the evidence's sample sizes" },
    { name = "bootstrap", type = "integer", min = 0,
      check = function(v) return v ~= 1, "0 (no bootstrap) or at least 2 replicates" end,
      meaning = "bootstrap replicates of the calibration (default 50; 0 with --quick; 0: none)" },
    { name = "metric", type = "string", default = "pr", allowed = { "pr", "loglik" },
      meaning = "calibration metric per response: the paper's probability residual, or minus the log-likelihood" },
    { name = "multistart", type = "integer", default = 1, min = 1,
      meaning = "the PR stage from its start plus N-1 seeded points in the bounds" },
    { name = "prior", type = "path", meaning = "a Lua file returning prior entries {param, mean, std[, dist]}: densities in the trials' evidence; none by default" },
    { name = "max-refinements", type = "integer", default = D.limits.refinements, min = 0,
      meaning = "how many refinements (revised trials) to try after a trial that is not valid or that an alternative beats" },
    { name = "screening", type = "string", default = "surrogate", allowed = { "surrogate", "full" }, applies = D.screening ~= nil,
      meaning = "eq.-3 screening on a ridge quadratic of --screening-runs runs, or on the model itself" },
    { name = "screening-runs", type = "integer", default = D.screening and D.screening.runs or 300, min = 50,
      applies = D.screening ~= nil, meaning = "solver runs of the surrogate screening" },
    { name = "design", type = "string", default = "fixed", allowed = { "fixed", "sequential" },
      meaning = "the trials' Kriging designs: a maximin hypercube, or sequential batches up to the same size" },
    { name = "test-points", type = "integer", min = 0,
      meaning = ("independent test points of each Kriging (default %d)"):format(D.design.test_points) },
    { name = "solver-check", type = "integer", min = 0,
      meaning = ("points of the validation's solver check (default %d)"):format(D.design.solver_check) },
    { name = "dry-run", type = "flag", default = false, meaning = "print the cost plan and stop before anything runs" },
    { name = "minutes-per-run", type = "number", min = 0,
      meaning = "the solver's minutes per run for the cost plan (default: the store's mean)" },
    { name = "accept-units", type = "flag", default = D.accept_units,
      meaning = "go on when the data's magnitudes look like a units mistake (the data step's check)" },
    options.study_steps,
    epilog = ("smi-lua's own --out DIR (default smi-out/%s/), --seed N and --quiet go before the script."):format(D.name),
  }
  for _, o in ipairs(D.options) do s[#s + 1] = o end
  return s
end

doc.add[==[
@ smi.improve.model(D, opt, trial, ctx) -> model
The declaration's model factory called for one trial model (smi.improve.revise's record): the
factory gets (trial.applied, trial.unknowns, ctx with form, fixed and opt added); the returned
model's outputs are checked against the responses; its runs are counted for the cost tables.
returns: the model, wrapped (evaluate and plan as the factory's model)
errors: the factory's error, re-raised naming the candidate (the last applied one, or the
  initial model); a response the model does not give, named
example:
  local improve = require "smi.improve"
  local D = require("smi.improve.declare").check{name = "doc_model", responses = {{name = "y"}},
    unknowns = {{name = "a", dist = "normal", mean = {1, 3, 2}, std = {0.1, 0.3, 0.2}}},
    model = function(applied, unknowns, ctx)
      return smi.model.lua{inputs = unknowns, outputs = {"y"}, fn = function(X) return {y = X:col(1) * 2} end}
    end}
  local trial = require("smi.improve.revise").initial(D, D.unknowns)
  local m = improve.model(D, {}, trial, {purpose = "nominal", name = "doc"})
  print(m:evaluate(smi.mat{{2}}).y[1])
]==]
M.model = factory.model

doc.add[==[
@ smi.improve.run(declaration, arg [, run_opts]) -> results, conclusion
Checks the declaration, parses the study's options from arg (--data, --quick, --metric,
--max-refinements, --dry-run, --accept-units, --only/--from, ... and the declaration's own) and
runs the trial loop through smi.study; results.json gets the top-level `conclusion`
{verdict, refinements, undetermined, trials = {{candidate, applied, unknowns, responses,
calibration}}}. docs/new-product.md describes every field.
options (run_opts, for tests and harnesses):
  results = nil   -- path of results.json (default <out>/results.json)
  out = nil       -- folder of the report (default smi-lua's --out)
returns: the steps' results and the conclusion (nil, nil with --dry-run)
errors: a missing or misspelt declaration field (named, with the likely one), a response the data
  or the model lack, a failing model factory (the candidate named), data whose magnitudes look
  like a units error (unless --accept-units), a plan over limits.runs, any step's error
example:
  local improve = require "smi.improve"
  local line = function(applied, unknowns, ctx)
    return smi.model.lua{inputs = unknowns, outputs = {"y"}, fn = function(X) return {y = X:col(1) * 2} end}
  end
  local data = smi.out("doc_improve_tests.csv")
  smi.csv.write(data, {y = {4.1, 3.8, 4.3, 3.9, 4.0}})
  improve.run({name = "doc_improve", data = data, responses = {{name = "y", unit = "mm"}},
               unknowns = {{name = "a", dist = "normal", mean = {1, 3, 2}, std = {0.1, 0.3, 0.2}}},
               model = line}, {"--dry-run", "--quick"})
]==]
--- Runs the declared study (see the module's comment). argv: the script's arg; run_opts
-- (optional, for tests and harnesses): {results = path of results.json, out = report folder}.
-- Returns the results and the conclusion, or nil with --dry-run.
function M.run(declaration, argv, run_opts)
  run_opts = run_opts or {}
  local D = declare.check(declaration)
  local script = type(argv) == "table" and type(argv[0]) == "string" and argv[0]:match("[^/]+$") or nil
  local opt = options.parse(argv or {}, spec(D, script))
  if not opt.data then error(("smi.improve: %s: no data: give --data FILE.csv or declare `data`"):format(D.name), 0) end
  local cfg = run_context.config(opt, D)
  local seed = smi.seed
  local MAX_TRIALS = 1 + opt.max_refinements
  local PRIOR = require("smi.improve.prior_file").load(opt.prior)
  -- the declared priors beside the file's, in the report's words
  for _, n in ipairs(D.unknowns) do
    for _, part in ipairs{ "mean", "std" } do
      local p = D.specs[n].prior and D.specs[n].prior[part]
      if p then PRIOR.labels[#PRIOR.labels + 1] = ("%s.%s ~ %s(%.6g, %.6g)"):format(n, part, p.dist, p.mean, p.std) end
    end
  end
  -- wall time and solver-run counts differ between identical runs (reused runs count 0), and so
  -- do a refinement candidate's run time and the timings that decide where a trial runs
  -- (surface.lua): left out of the steps' result hashes, so a rerun does not mark the later steps stale
  local s = study.new{ name = D.name, seed = seed, results = run_opts.results, out = run_opts.out,
    volatile = { "wall_seconds", "solver_runs", "run_seconds", "model_seconds", "kriging_seconds" },
    report = { title = D.title or D.name, subtitle = (D.subtitle or "") .. (opt.quick and " (quick run)" or ""),
               author = D.author or "smi.improve" } }
  local run = run_context.new{ D = D, opt = opt, cfg = cfg, seed = seed, study = s, prior = PRIOR,
                               max_trials = MAX_TRIALS }
  require("smi.improve.steps").add(run)

  -- the declared cap on solver runs holds for the plan's upper bound, before anything runs
  local plan_rows = cost.plan{ cfg = cfg, max_trials = MAX_TRIALS, D = D }
  local _, planned = cost.plan_text(plan_rows)
  if D.limits.runs and planned > D.limits.runs and not opt.dry_run then
    error(("smi.improve: %s: the plan needs up to %d solver runs, more than limits.runs = %d (--dry-run lists them);"
      .. " lower --max-refinements, the designs' sizes or --solver-check, or raise limits.runs"):format(
      D.name, planned, D.limits.runs), 0)
  end
  if opt.dry_run or smi.dry_run then
    local T0 = revise.initial(D, D.unknowns)
    local probe = M.model(D, opt, T0, { purpose = "nominal", name = "nominal" })
    local minutes, source = cost.minutes_per_run(opt.minutes_per_run, probe)
    local words, total = cost.plan_text(plan_rows, minutes, source)
    -- print, not io.stdout: what a reference example prints is captured with print
    print((words:gsub("\n$", "")))
    print(cost.calibration_text(probe, T0, D, cfg))
    if D.limits.runs and total > D.limits.runs then
      print(("the plan's %d runs exceed the declared limits.runs = %d"):format(total, D.limits.runs))
    end
    if opt.dry_run then return nil end
  end

  local results = s:run(opt)
  local ok, summary = pcall(function() return results.summary end)
  if ok and summary and summary.conclusion then
    local c = summary.conclusion
    s:annotate("conclusion", verdict.top_level(c))
    s:annotate("cost", { solver_runs = summary.solver_runs_total, screening = D.screening and cfg.screening or "none",
                         test_points = cfg.test_points, solver_check = cfg.solver_check })
    for i, t in ipairs(c.trials) do print(text.trial_line(D, i, t, c.refinements[i])) end
    print(summary.words or ("Conclusion: the model is " .. tostring(c.verdict)))
    return results, verdict.top_level(c)
  end
  return results, nil
end

--- The declaration's reference (declare.lua's schema), as `smi-lua doc smi.improve.declaration` shows it.
M.declaration = declare.reference
return M
