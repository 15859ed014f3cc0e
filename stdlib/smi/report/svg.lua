--- smi.report.svg: small, dependable SVG charts as strings (inline them in HTML or write .svg).
--
--   local svg = require "smi.report.svg"
--   local c = svg.chart{title = "Mode 1", xlabel = "Frequency (Hz)", ylabel = "Density"}
--   c:line(x, pdf, {label = "KDE"})          -- x, y: smi.vec or Lua tables (#v, v[i])
--   c:step(xs, ys, {label = "ECDF"})         -- post steps: y[i] holds from x[i] to x[i+1]
--   c:ecdf(data, {label = "data"})           -- the empirical CDF of a sample
--   c:scatter(obs, pred, {label = "LOO"})
--   c:rug(data, {label = "data"})            -- ticks at the foot of the plot
--   c:band(x, lower, upper, {label = "95 % band"})
--   c:diagonal() ; c:hline(0.5, {label = "threshold"}) ; c:vline(x0)
--   local s = c:render()
--   local b = svg.bars{labels = names, values = s_tot, title = "Total-effect indices", sort = true}
--
-- Non-finite values are never drawn: a line breaks at them, a point or bar is left out, and a
-- note under the chart says how many were skipped. All text is escaped. Sizes are fixed (px).
local draw = require "smi.report.draw"
local chart = require "smi.report.chart"
local bars = require "smi.report.bars"

local M = {}

M.palette = draw.palette
--- A chart with x/y axes (see smi.report.chart for the options and methods).
M.chart = chart.new
--- Horizontal bars (see smi.report.bars for the options).
M.bars = bars.render

--- Writes an SVG string (or a chart) to `path` as a standalone .svg file; returns the path.
function M.write(path, s)
  if type(s) == "table" and type(s.render) == "function" then s = s:render() end
  local f, err = io.open(path, "wb")
  if not f then error(("svg.write: cannot write '%s': %s"):format(path, tostring(err)), 2) end
  f:write('<?xml version="1.0" encoding="UTF-8"?>\n', s, "\n")
  f:close()
  return path
end

return M
