-- SPDX-License-Identifier: MIT
--- The report's surrogate section of trial k: Kriging accuracy per response and the design box
-- (the surrogate step's result `res`; units: {response = likely-units words or nil}).
local text = require "smi.improve.text"
local figs = require "smi.improve.figures"

local function assignments(t)
  local parts = {}
  for k, v in pairs(t) do parts[#parts + 1] = ("%s = %.6g"):format(k, v) end
  table.sort(parts)
  return table.concat(parts, ", ")
end

return function(run, r, res, k, units)
  local D, T = run.D, res.model
  r:section(text.trial_label(T, k) .. ": surrogate model")
  if #T.dropped > 0 then r:callout("Revisions dropped before this trial: " .. text.dropped(T.dropped) .. ".", "info") end
  r:text(text.surrogate_intro(D, T, res, next(T.fixed) and (", fixed " .. assignments(T.fixed)) or "",
    run.cfg.test_points))
  r:callout(text.surface_note(res), "info")
  local figures, rows = {}, {}
  for _, name in ipairs(D.names) do
    local d, title = res.diagnostics[name], D.by_name[name].title
    figures[#figures + 1] = { figs.loo(D.by_name[name], d), title .. ": leave-one-out predictions." }
    rows[#rows + 1] = { title, d.loo_q2, d.loo_rmse, d.test_rmse }
    for _, w in ipairs(d.warnings or {}) do r:callout(title .. ": " .. w, "warn") end
    if units[name] then r:callout(units[name], "warn") end
  end
  r:figures(figures)
  r:table{ caption = "Kriging accuracy.", columns = { "Response", "LOO Q²", "LOO RMSE", "Test RMSE" }, rows = rows }
  local box = {}
  for _, n in ipairs(T.unknowns) do box[#box + 1] = { n, res.design_bounds[n][1], res.design_bounds[n][2] } end
  r:table{ caption = "Design box of the unknowns.", columns = { "Input", "Lower", "Upper" }, rows = box }
end
