-- SPDX-License-Identifier: MIT
--- The report's calibration section of trial k: the objective's history, the calibrated
-- parameters, the kernel's warnings, the sensitivities and what the data leave open (the
-- calibration step's result `res`; T: the trial's model).
local text = require "smi.improve.text"
local figs = require "smi.improve.figures"
local calibration = require "smi.improve.calibration"

local function parameter_rows(res)
  local rows = {}
  for _, p in ipairs(res.params) do
    rows[#rows + 1] = { p.input, p.dist, p.unit, ("[%.4g, %.4g]"):format(p.mean_bounds[1], p.mean_bounds[2]),
                        ("[%.4g, %.4g]"):format(p.std_bounds[1], p.std_bounds[2]), p.mean_start, p.std_start,
                        p.stage1_mean, p.stage1_std, p.mean, p.std, text.bootstrap_cell(res, p.input) }
  end
  return rows
end

return function(run, r, res, T, k)
  local D, L = run.D, text.trial_label(T, k)
  r:section(L .. ": calibration")
  r:text(text.calibration_intro(D, T, res, run.cfg, run.opt.prior, run.prior.labels))
  r:figure(figs.history(res, L), L .. ": calibration history.")
  r:table{ caption = text.parameters_caption(res), rows = parameter_rows(res),
           columns = { "Input", "Type", "Unit", "Mean bounds", "Std bounds", "Initial mean", "Initial std",
                       "Stage-1 mean", "Stage-1 std", "Calibrated mean", "Calibrated std", "Bootstrap CI" } }
  for _, w in ipairs(res.warnings) do r:callout(L .. ": " .. w, "warn") end
  if calibration.units_stop(res) then return end
  local sv = res.sensitivity
  local srows, columns = {}, { "Input" }
  for _, m in ipairs(sv.responses) do columns[#columns + 1] = D.by_name[m].title end
  for _, n in ipairs(sv.inputs) do
    srows[#srows + 1] = { n }
    for _, m in ipairs(sv.responses) do srows[#srows][#srows[#srows] + 1] = sv.sensitivity[m][n] end
  end
  r:table{ caption = ("Relative sensitivities d ln y / d ln x of the %s at the calibrated means."):format(
             res.on == "model" and "model" or "Krigings"),
           rows = srows, columns = columns }
  r:callout(text.identifiability(D, res), sv.most_unconstrained_share > 0.2 and "warn" or "info")
  if #res.weak > 0 then r:callout(text.weak_parameters(D, res.weak), "warn") end
end
