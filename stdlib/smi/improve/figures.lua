-- SPDX-License-Identifier: MIT
--- smi.improve.figures: the report's figures of a study (inline SVG through smi.report.svg),
-- labelled from the declaration: `resp` below is the checked declaration's response record
-- (its title and unit).
local svg = require "smi.report.svg"

local M = {}

local function axis(resp) return resp.unit ~= "" and ("Value (%s)"):format(resp.unit) or "Value" end

function M.kde_vs_ebd(resp, c)
  local ch = svg.chart{ title = resp.title, xlabel = axis(resp), ylabel = "Density", width = 420, height = 300 }
  ch:line(c.kde.x, c.kde.y, { label = "KDE" }):line(c.ebd.x, c.ebd.y, { label = "KDE-ebd" })
  ch:rug(c.data, { label = ("%d data"):format(#c.data) })
  return ch:render()
end

function M.screening(resp, rows, chosen)
  local labels, values = {}, {}
  for i = 1, math.min(10, #rows) do labels[i], values[i] = rows[i].input, rows[i].ne end
  return svg.bars{ labels = labels, values = values, sort = true, highlight = chosen,
                   title = "Normalized area metric, " .. resp.title, xlabel = "N_e (eq. 7)", width = 420 }
end

function M.loo(resp, d)
  local u = resp.unit ~= "" and (" (" .. resp.unit .. ")") or ""
  local ch = svg.chart{ title = "Leave-one-out, " .. resp.title, xlabel = "Solver" .. u, ylabel = "Kriging LOO" .. u,
                        equal = true, width = 360, height = 330, legend = "top-left" }
  ch:scatter(d.observed, d.loo_predicted, { label = "design points" }):diagonal{ label = "y = x" }
  ch:note(("Q² %.4f, LOO RMSE %.3g%s, test RMSE %.3g%s"):format(d.loo_q2, d.loo_rmse, u, d.test_rmse or 0 / 0, u))
  return ch:render()
end

function M.history(cal, name)
  local it, obj = {}, {}
  for i, h in ipairs(cal.history) do it[i], obj[i] = i, h[2] end
  local parts = {}
  for i, m in ipairs(cal.calibrate or {}) do parts[i] = (cal.metric == "loglik" and "-logL(%s)" or "PR(%s)"):format(m) end
  local objective = table.concat(parts, cal.metric == "loglik" and " " or " + ")
  local ch = svg.chart{ title = name .. ": " .. objective, xlabel = "Optimizer step", ylabel = "Objective",
                        width = 420, height = 300, legend = "none" }
  ch:line(it, obj, { label = "objective" })
  return ch:render()
end

function M.pdf_over_data(resp, v, data, ebd)
  local ch = svg.chart{ title = resp.title, xlabel = axis(resp), ylabel = "Density", width = 420, height = 300 }
  ch:line(v.pdf.x, v.pdf.y, { label = "calibrated model" })
  if ebd then ch:line(ebd.x, ebd.y, { label = "data, KDE-ebd" }) end
  ch:rug(data, { label = ("%d data"):format(#data) })
  return ch:render()
end

function M.upool(resp, v)
  local ch = svg.chart{ title = ("u-pooling, %s: U = %.4f"):format(resp.title, v.metric), xlabel = "u", ylabel = "CDF",
                        width = 420, height = 300, xlim = { 0, 1 }, ylim = { 0, 1 }, legend = "top-left" }
  ch:step(v.curve.x, v.curve.y, { label = "ECDF of u (data)" }):diagonal{ label = "uniform" }
  ch:note(("threshold %.4f at 95 %%: %s"):format(v.threshold, v.pass and "valid" or "NOT valid"))
  return ch:render()
end

function M.decision(dm)
  return svg.bars{ labels = dm.candidates, values = dm.overall, title = "Weighted decision matrix: overall rating",
                   xlabel = "Σ w·S", highlight = { [dm.best_name] = true }, width = 520 }
end

return M
