-- SPDX-License-Identifier: MIT
--- The report's before/after figure of each response: the data, the initial model as declared
-- (trial 1 at the unknowns' start values, before any calibration) and the model the conclusion
-- names (its trial at its calibrated values). out: the summary step's
-- result; R: the steps' results.
local trial = require "smi.improve.trial"
local surface = require "smi.improve.surface"
local stream = require "smi.improve.stream"
local svg = require "smi.report.svg"

local N = 2000

-- The propagated samples of trial k at th ({"x.mean" =, "x.std" =}) where the trial ran (its
-- Krigings, or the in-process model itself: surface.lua), or nil.
local function samples(run, R, k, th, seed)
  local sur = R["trial" .. k .. "_surrogate"]
  if not sur or sur.skipped then return nil end
  local ok, Y = pcall(function()
    local T = sur.model
    local direct = surface.direct(sur, function(c) return run.model(T, c) end, "validation", "trial" .. k .. "-before-after")
    return trial.predictor(trial.krigings(sur), T.unknowns, T.specs, N, seed, direct)(th, run.D.names)
  end)
  return ok and Y or nil
end

return function(run, r, out, R)
  local D, c = run.D, out.conclusion
  local k = c.chosen or #c.trials
  local T1 = R.trial1_surrogate and not R.trial1_surrogate.skipped and R.trial1_surrogate.model
  local cal = R["trial" .. k .. "_calibration"]
  if not (T1 and cal and cal.params) then return end
  local start, calibrated = {}, {}
  for _, n in ipairs(T1.unknowns) do
    start[n .. ".mean"], start[n .. ".std"] = T1.specs[n].mean[3], T1.specs[n].std[3]
  end
  for _, p in ipairs(cal.params) do calibrated[p.input .. ".mean"], calibrated[p.input .. ".std"] = p.mean, p.std end
  local seed = stream(run.seed, "before after")
  local before, after = samples(run, R, 1, start, seed), samples(run, R, k, calibrated, seed)
  if not (before and after) then return end
  for _, m in ipairs(D.names) do
    local resp = D.by_name[m]
    local title = resp.title or m
    r:figure(svg.before_after{ title = title, xlabel = ("%s (%s)"):format(title, resp.unit or ""),
               data = R.data[m], initial = before[m], final = after[m],
               labels = { final = ("trial %d, calibrated"):format(k), initial = "initial model, start values" } },
             ("Before and after, %s: the data, the initial model at its start values and the model of trial %d"
               .. " at its calibrated values (empirical CDFs of %d propagated samples each)."):format(title, k, N))
  end
end
