--- What the study costs in solver runs (issue 16): the column-fe solutions each step makes
-- (counted by solver.lua as they happen) and, before anything runs (--dry-run), the plan: runs
-- per step × minutes per run ÷ concurrency. A "run" is one column-fe solution (one point), as
-- the analyst with a per-point solver such as Nastran pays for it; batch mode runs many points
-- per process, which the plan does not count as cheaper.
local solver = require "steering_column.solver"
local inputs = require "steering_column.inputs"

local M = {}

M.CONCURRENCY = 2 -- the study's solver concurrency (solver.command / solver.batch)

--- A mark of the solver counts; M.since(mark) is what was run after it.
function M.mark() return solver.totals() end

--- {solutions (points the step evaluated), new (of them, not found in the store), processes}.
function M.since(mark)
  local t = solver.totals()
  return { solutions = t.points - mark.points, new = (t.points - t.reused) - (mark.points - mark.reused),
           processes = t.launched - mark.launched }
end

--- The per-point solver time: opt.minutes_per_run (declared) or the store's measured mean of
-- column-fe runs (one point per process); nil when neither is known. Returns minutes, source.
function M.minutes_per_run(declared, probe_model)
  if declared then return declared, "declared (--minutes-per-run)" end
  local ok, p = pcall(function() return probe_model:plan(smi.mat{ { -1 } }) end)
  if ok and p and p.mean_seconds then
    return p.mean_seconds / 60, ("measured: mean of the column-fe runs in the store (%.3g s)"):format(p.mean_seconds)
  end
  return nil, "unknown: no run in the store yet; give --minutes-per-run X"
end

--- The plan: a row per step {step, runs, why, conditional}. t: {cfg, max_trials, initial (model),
-- candidates}. Trials after the first run only after an invalid trial; their model is the
-- refinement's choice, so their design counts the largest candidate's (an upper bound).
function M.plan(t)
  local cfg, rows = t.cfg, {}
  local function add(step, runs, why, cond)
    rows[#rows + 1] = { step = step, runs = runs, why = why, conditional = cond }
  end
  if cfg.screening == "surrogate" then
    add("screening", cfg.screen_runs,
        ("surrogate screening: %d runs on a Latin hypercube of the 46 inputs"):format(cfg.screen_runs))
  else
    add("screening", (#inputs.names + 1) * cfg.screen_n, ("full eq.-3 screening: (46 + 1) x %d"):format(cfg.screen_n))
  end
  local largest = 0
  for _, c in ipairs(t.candidates) do largest = math.max(largest, c.revision.n_design or t.initial.n_design) end
  for k = 1, t.max_trials do
    local n = k == 1 and t.initial.n_design or largest
    local cond = k > 1 and ("only if trial %d is invalid"):format(k - 1) or nil
    add(("trial%d_surrogate"):format(k), n + cfg.test_points, cfg.design == "sequential"
      and ("sequential Kriging design: at most %d points (stops on its leave-one-out target),"
           .. " + %d test points"):format(n, cfg.test_points)
      or ("%d-point Latin hypercube + %d test points"):format(n, cfg.test_points), cond)
    add(("trial%d_validation"):format(k), cfg.solver_check,
        ("solver check of the Kriging verdicts: %d points"):format(cfg.solver_check), cond)
    if k == 1 and t.max_trials > 1 then
      add("refinement1", #t.candidates,
          ("decision matrix: each of the %d candidates once at the initial means"):format(#t.candidates),
          "only if trial 1 is invalid")
    end
  end
  return rows
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
