-- SPDX-License-Identifier: MIT
--- smi.improve.step.alternatives: after a trial that fits, the evidence of each untried
-- candidate's form on top of it. A fit alone says nothing about forms the data cannot tell apart
-- (nine specimens and free means absorb most revisions), so a form is called valid only against
-- the forms it beat.
local trial = require "smi.improve.trial"
local evidence = require "smi.improve.evidence"
local verdict = require "smi.improve.verdict"
local forms = require "smi.improve.forms"
local alternatives = require "smi.improve.alternatives"
local stream = require "smi.improve.stream"
local trial_run = require "smi.improve.step.trial_run"
local trial_evidence = trial_run.evidence
local common = require "smi.improve.step.common"
local view, timed, skipped = common.view, common.timed, common.skipped

local M = {}

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

M.run = alternatives_step

return M
