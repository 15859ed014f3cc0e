-- SPDX-License-Identifier: MIT
--- smi.improve.step.summary: the conclusion, the solver runs per step and the provenance.
local verdict = require "smi.improve.verdict"
local cost = require "smi.improve.cost"
local text = require "smi.improve.text"
local common = require "smi.improve.step.common"
local view, hook = common.view, common.hook

local M = {}

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

M.run = summary_step

return M
