-- SPDX-License-Identifier: MIT
--- smi.improve.steps: the steps of the trial loop on one smi.study, in order. Each step
-- (smi/improve/step/<step>.lua) computes plain data with the kernels (trial.lua, calibration.lua,
-- evidence.lua, verdict.lua) and then hands it to its view (smi/improve/view/<section>.lua), which
-- writes the report section; the words are text.lua's. A step after the study has concluded
-- records why it did not run. Steps read earlier steps' results only from ctx.results, so
-- --only/--from work. `run` is the run context (run_context.lua): the checked declaration, the
-- options, the sample sizes, the seed, the study.
local common = require "smi.improve.step.common"
local data = require "smi.improve.step.data"
local characterize = require "smi.improve.step.characterize"
local screening = require "smi.improve.step.screening"
local trial_run = require "smi.improve.step.trial_run"
local alternatives = require "smi.improve.step.alternatives"
local refinement = require "smi.improve.step.refinement"
local summary = require "smi.improve.step.summary"

local M = {}

local timed = common.timed

--- Adds the study's steps to run.study.
function M.add(run)
  local s = run.study
  s:step("data", timed(function(ctx) return data.run(run, ctx) end))
  s:step("characterize", timed(function(ctx) return characterize.run(run, ctx) end))
  if run.D.screening then
    s:step("screening", timed(function(ctx) return screening.run(run, ctx) end))
  end
  for k = 1, run.max_trials do
    s:step("trial" .. k .. "_surrogate", trial_run.surrogate(run, k))
    s:step("trial" .. k .. "_calibration", trial_run.calibration(run, k))
    s:step("trial" .. k .. "_validation", trial_run.validation(run, k))
    s:step("trial" .. k .. "_alternatives", alternatives.run(run, k))
    if k < run.max_trials then s:step("refinement" .. k, refinement.run(run, k)) end
  end
  s:step("summary", timed(function(ctx) return summary.run(run, ctx) end))
end

return M
