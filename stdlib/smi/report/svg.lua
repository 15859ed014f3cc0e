-- SPDX-License-Identifier: MIT
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

local doc = require "smi.doc"
doc.add[==[
@ module smi.report.svg
Small, dependable SVG charts as strings (inline them in a report or write .svg files): x/y charts
(smi.report.svg.chart) and horizontal bars (smi.report.svg.bars). Non-finite values are never drawn;
a note says how many were skipped.
]==]
local M = {}

M.palette = draw.palette
doc.add[==[
@ smi.report.svg.chart([opts]) -> chart
A chart with x/y axes; add series with the methods smi.report.chart:* and render it (or pass it to
r:figure).
options:
  width = 640       -- pixels
  height = 400      -- pixels
  title = nil       -- the title
  xlabel = nil      -- the x axis label
  ylabel = nil      -- the y axis label
  xlim = nil        -- {lo, hi}: a fixed x range
  ylim = nil        -- {lo, hi}: a fixed y range
  xlog = false      -- a log10 x axis
  ylog = false      -- a log10 y axis
  equal = false     -- the same range on both axes (predicted vs observed)
  legend = "auto"   -- "auto" (the emptiest corner), "top-right", "top-left", "bottom-right",
                    -- "bottom-left" or "none"
returns: a chart
errors: none here (series are checked when added)
example:
  local svg = require("smi.report").svg
  local c = svg.chart{title = "Mode 1", xlabel = "Hz", ylabel = "density"}
  local k = smi.kde(smi.vec{30.1, 30.4, 29.9, 30.6})
  local cv = k:curve(101)
  c:line(cv.x, cv.pdf, {label = "KDE"})
  print(#c:render() > 500)
]==]
--- A chart with x/y axes (see smi.report.chart for the options and methods).
M.chart = chart.new
--- The before/after figure of a response: data, initial and final model (see its doc text).
M.before_after = chart.before_after
doc.add[==[
@ smi.report.svg.bars(opts) -> svg
Horizontal bars, one row per label (screening indices, decision-matrix ratings).
options:
  labels = (required)  -- the row labels
  values = nil         -- one number per label (or series)
  series = nil         -- {{label =, values =}, ...} for grouped bars
  title = nil          -- the title
  xlabel = nil         -- the value axis label
  sort = false         -- sort by the first series, largest on top
  highlight = nil      -- a set of labels, or function(label, value) returning true: accent colour
  threshold = nil      -- a vertical marker at this value
  threshold_label = nil  -- its label
  digits = 3           -- significant digits of the value labels
  width = 640          -- pixels
  row = nil            -- pixels per row (automatic)
returns: an SVG string
errors: no labels; neither values nor series; a series of another length than labels
example:
  local svg = require("smi.report").svg
  local s = svg.bars{labels = {"E", "t", "rho"}, values = {0.58, 0.30, 0.02}, sort = true, title = "N_e"}
  print(s:sub(1, 4))
]==]
--- Horizontal bars (see smi.report.bars for the options).
M.bars = bars.render

doc.add[==[
@ smi.report.svg.write(path, s) -> path
Writes an SVG string (or a chart, rendered) to path as a standalone .svg file.
returns: the path
errors: the sandbox refuses the path; not an SVG string or chart
example:
  local svg = require("smi.report").svg
  local c = svg.chart{}
  c:line({0, 1}, {1, 2})
  print(svg.write(smi.out("doc_chart.svg"), c):match("svg$"))
]==]
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
