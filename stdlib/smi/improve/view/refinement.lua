-- SPDX-License-Identifier: MIT
--- The report's refinement section after trial k: the weighted decision matrix, the revised
-- models at their start means and the choice (the refinement step's result `out`); a refinement
-- without a matrix (on evidence, or a step back) gets its reason only.
local text = require "smi.improve.text"
local figs = require "smi.improve.figures"

return function(run, r, out, k)
  local D, dm = run.D, out.matrix
  r:section(("Model refinement after trial %d"):format(k))
  -- a refinement on evidence (an alternative beats the trial) or a step back has no matrix
  if not dm then
    r:callout(("Refinement after trial %d: %s (%s)."):format(k, out.chosen, out.why), "info")
    return
  end
  local M_rows, pred, cols = {}, {}, { "Candidate" }
  for _, n in ipairs(dm.criteria) do cols[#cols + 1] = "M " .. n end
  for _, n in ipairs(dm.criteria) do cols[#cols + 1] = "S " .. n end
  cols[#cols + 1] = "Rating"
  for j, c in ipairs(dm.candidates) do
    M_rows[j] = { c.name }
    for i = 1, #dm.criteria do M_rows[j][#M_rows[j] + 1] = c.magnitudes[i] end
    for i = 1, #dm.criteria do M_rows[j][#M_rows[j] + 1] = c.standardized[i] end
    M_rows[j][#M_rows[j] + 1] = dm.overall[j]
    pred[j] = { c.name }
    for _, m in ipairs(D.names) do pred[j][#pred[j] + 1] = c.prediction[m] end
  end
  pred[#pred + 1] = { "data mean" }
  for _, m in ipairs(D.names) do pred[#pred][#pred[#pred] + 1] = dm.observed[m] end
  local pcols = { "Model" }
  for _, m in ipairs(D.names) do pcols[#pcols + 1] = D.by_name[m].title end
  r:text(text.refinement_intro(k, out))
  r:table{ caption = "Weighted decision matrix: magnitudes M, standardized S, overall rating.", rows = M_rows,
           columns = cols }
  r:table{ caption = "Revised models at the start means.", rows = pred, columns = pcols }
  local names = {}
  for j, c in ipairs(dm.candidates) do names[j] = c.name end
  r:figure(figs.decision{ candidates = names, overall = dm.overall, best_name = out.chosen },
           "Overall rating of the candidates.")
  r:callout(("Refinement after trial %d: %s (%s)."):format(k, out.chosen, out.why), "info")
end
