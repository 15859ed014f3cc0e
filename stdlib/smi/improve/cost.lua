-- SPDX-License-Identifier: MIT
--- smi.improve.cost: what a study costs in solver runs: the solutions each step makes (counted
-- by the wrapper every factory model gets, M.wrap) and, before anything runs (--dry-run), the
-- plan: runs per step × minutes per run ÷ concurrency. A "run" is one solution (one point), as
-- the analyst with a per-point solver pays for it; batch mode runs many points per process,
-- which the plan does not count as cheaper.
local trial = require "smi.improve.trial"

local M = { counts = {} }

M.CONCURRENCY = 2 -- the solver concurrency the plan assumes

local function count(name, info, n)
  local c = M.counts[name] or { points = 0, launched = 0, reused = 0, failed = 0 }
  M.counts[name] = c
  c.points = c.points + n
  c.launched = c.launched + (info.launched or 0)
  c.failed = c.failed + (info.failed or 0)
  local r = 0
  if info.reused then for i = 1, #info.reused do r = r + info.reused[i] end end
  c.reused = c.reused + r
end

--- Total launched processes and points over all models.
function M.totals()
  local t = { points = 0, launched = 0, reused = 0, failed = 0 }
  for _, c in pairs(M.counts) do
    for k in pairs(t) do t[k] = t[k] + c[k] end
  end
  return t
end

--- The factory's model, counted under `name`; a failed point is an error naming the model.
function M.wrap(m, name)
  local w = { inputs = m.inputs, outputs = m.outputs, name = m.name, kind = m.kind, model = m }
  function w.evaluate(_, X)
    local Y, info = m:evaluate(X)
    info = info or {}
    count(name, info, info.status and #info.status or X:rows())
    if info.failed and info.failed > 0 then
      error(("the solver failed on %d point(s) of '%s': %s"):format(info.failed, name,
        info.failures and info.failures[1] and info.failures[1].reason or "?"), 0)
    end
    return Y, info
  end
  function w.plan(_, X) return m.plan and m:plan(X) end
  return w
end

--- A mark of the counts; M.since(mark) is what was run after it.
function M.mark() return M.totals() end

--- {solutions (points the step evaluated), new (of them, not found in the store), processes}.
function M.since(mark)
  local t = M.totals()
  return { solutions = t.points - mark.points, new = (t.points - t.reused) - (mark.points - mark.reused),
           processes = t.launched - mark.launched }
end

--- The per-point solver time: declared (--minutes-per-run) or the store's measured mean of the
-- probe model's runs; nil when neither is known. Returns minutes, source.
function M.minutes_per_run(declared, probe_model)
  if declared then return declared, "declared (--minutes-per-run)" end
  local ok, p = pcall(function() return probe_model:plan(smi.mat{ { -1 } }) end)
  if ok and p and p.mean_seconds then
    return p.mean_seconds / 60, ("measured: mean of the runs in the store (%.3g s)"):format(p.mean_seconds)
  end
  return nil, "unknown: no run in the store yet; give --minutes-per-run X"
end

--- The plan: a row per step {step, runs, why, conditional}. t: {cfg, max_trials, D (the checked
-- declaration)}. Trials after the first run only after an invalid trial; their design counts the
-- largest candidate's (an upper bound).
function M.plan(t)
  local cfg, D, rows = t.cfg, t.D, {}
  local function add(step, runs, why, cond)
    rows[#rows + 1] = { step = step, runs = runs, why = why, conditional = cond }
  end
  add("data", 1, "one nominal run (all unknowns at their start means): the data's units check")
  if D.screening then
    local n_in = #D.screening.inputs
    if cfg.screening == "surrogate" then
      add("screening", cfg.screen_runs, ("surrogate screening: %d runs on a Latin hypercube of the %d inputs"):format(
        cfg.screen_runs, n_in))
    else
      add("screening", (n_in + 1) * cfg.screen_n, ("full eq.-3 screening: (%d + 1) x %d"):format(n_in, cfg.screen_n))
    end
  end
  local largest = D.design.n
  for _, c in ipairs(D.candidates) do largest = math.max(largest, c.revision.n_design or D.design.n) end
  for k = 1, t.max_trials do
    local n = k == 1 and D.design.n or largest
    local cond = k > 1 and ("only if trial %d is invalid"):format(k - 1) or nil
    add(("trial%d_surrogate"):format(k), n + cfg.test_points, cfg.design == "sequential"
      and ("sequential Kriging design: at most %d points (stops on its leave-one-out target),"
           .. " + %d test points"):format(n, cfg.test_points)
      or ("%d-point Latin hypercube + %d test points"):format(n, cfg.test_points), cond)
    add(("trial%d_validation"):format(k), cfg.solver_check,
        ("solver check of the Kriging verdicts: %d points"):format(cfg.solver_check), cond)
    if D.evidence.alternatives ~= false and #D.candidates > 0 then
      local n_alt = 0
      for _, c in ipairs(D.candidates) do n_alt = n_alt + (c.revision.n_design or D.design.n) + cfg.test_points end
      add(("trial%d_alternatives"):format(k), n_alt,
          "the forms one untried candidate away: a design each, for their evidence (reused by the next trial)",
          ("only if trial %d fits"):format(k))
    end
    if k < t.max_trials and #D.candidates > 0 then
      local left = math.max(0, #D.candidates - (k - 1))
      add(("refinement%d"):format(k), left,
          ("decision matrix: each untried candidate (%d) once at the start means"):format(left),
          ("only if trial %d is invalid"):format(k))
    end
  end
  return rows
end

--- The calibration's cost per trial in words, measured here, for any model: an objective
-- evaluation propagates cal_n rows through the in-process model itself, or through one Kriging
-- per response for a solver (a stand-in fitted on a design of the declared size: the trial's own
-- are fitted on its runs, and a predict costs the same for any response values). A calibration
-- makes at most maxeval evaluations, each with a gradient of 2p more passes where it is taken by
-- differences (p unknowns, a mean and a std each). T: the initial model.
function M.calibration_text(probe, T, D, cfg)
  local b = {}
  for i, n in ipairs(T.unknowns) do b[i] = trial.design_box(T.specs[n]) end
  local P = smi.doe.lhs(cfg.cal_n, b, { seed = 1, criterion = "none" })
  local seconds, through
  if probe.kind == "lua" then
    local t0 = smi.now()
    probe.model:evaluate(P)
    seconds, through = smi.now() - t0, "the model itself (in-process)"
  else
    local X = smi.doe.lhs(D.design.n, b, { seed = 2, criterion = "none" })
    local k = smi.kriging.fit(X, X:col(1), { trend = D.design.trend, corr = "gauss", seed = 3 })
    local t0 = smi.now()
    for _ = 1, #D.names do k:predict(P) end
    seconds, through = smi.now() - t0, ("%d Krigings of %d points (a stand-in for the trial's)"):format(#D.names, D.design.n)
  end
  local passes = cfg.maxeval * (1 + 2 * 2 * #T.unknowns)
  return ("calibration per trial: at most %d evaluations of %d rows through %s; one pass takes %.3g s here,"
    .. " so at most %d passes (with gradients by differences) take %.3g s; the evidence and the validation add"
    .. " a few times one calibration's passes"):format(cfg.maxeval, cfg.cal_n, through, seconds, passes, passes * seconds)
end

--- The plan as text: runs per step, × minutes per run ÷ concurrency, total runs and wall time.
function M.plan_text(rows, minutes, source)
  local L = {}
  local function w(fmt, ...) L[#L + 1] = fmt:format(...) end
  local function wall(runs)
    if not minutes then return "?" end
    local m = runs * minutes / M.CONCURRENCY
    if m >= 2880 then return ("%.1f d"):format(m / 1440) end
    if m >= 120 then return ("%.1f h"):format(m / 60) end
    if m >= 1 then return ("%.1f min"):format(m) end
    return ("%.0f s"):format(60 * m)
  end
  w("cost plan (nothing has run): solver runs per step x minutes per run / concurrency %d", M.CONCURRENCY)
  w("minutes per run: %s", minutes and ("%.4g, %s"):format(minutes, source) or source)
  w("  %-20s %6s %10s  %s", "step", "runs", "wall", "what")
  local total, sure = 0, 0
  for _, r in ipairs(rows) do
    w("  %-20s %6d %10s  %s%s", r.step, r.runs, wall(r.runs), r.why,
      r.conditional and (" [" .. r.conditional .. "]") or "")
    total = total + r.runs
    if not r.conditional then sure = sure + r.runs end
  end
  w("total: at most %d solver runs, wall %s (%d runs, %s, if trial 1 is valid)", total, wall(total), sure, wall(sure))
  return table.concat(L, "\n") .. "\n", total
end

return M
