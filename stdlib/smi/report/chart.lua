-- SPDX-License-Identifier: MIT
--- smi.report.chart: x/y charts (lines, steps, ECDF, scatter, rug, bands, reference lines)
-- as SVG strings. Used through smi.report.svg.chart{...}; see smi.report.svg for an example.
local xml = require "smi.report.xml"
local axis = require "smi.report.axis"
local draw = require "smi.report.draw"

local finite = axis.finite
local n2, text, text_width, check_series = draw.n2, draw.text, draw.text_width, draw.check_series
local marker_svg = draw.marker

local doc = require "smi.doc"
local M = {}
local dashes, markers = draw.dashes, draw.markers
local chart_count = 0 -- unique ids when several charts share one HTML page

-- ---------------------------------------------------------------------------------------------
-- Chart with x/y axes
-- ---------------------------------------------------------------------------------------------
local Chart = {}
Chart.__index = Chart

--- opts: width (640), height (400), title, xlabel, ylabel, xlim={lo,hi}, ylim={lo,hi},
-- xlog, ylog (log10 axes), equal (same range on both axes, for predicted vs observed),
-- legend ("auto" default: the corner with the fewest points under it; "top-right", "top-left",
-- "bottom-right", "bottom-left", "none").
function M.new(opts)
  opts = opts or {}
  local c = setmetatable({ opts = opts, series = {}, marks = {}, notes = {} }, Chart)
  c.width, c.height = opts.width or 640, opts.height or 400
  return c
end

function Chart:_add(kind, x, y, o, what)
  o = o or {}
  local nx = check_series(x, what .. " x")
  local ny = check_series(y, what .. " y")
  if nx ~= ny then error(("%s: x has %d values but y has %d"):format(what, nx, ny), 3) end
  local k = #self.series + 1
  self.series[k] = { kind = kind, x = x, y = y, n = nx, label = o.label, opts = o,
                     color = o.color or draw.palette[(k - 1) % #draw.palette + 1],
                     dash = o.dash or (kind ~= "scatter" and dashes[((k - 1) // #draw.palette) % #dashes + 1]) or nil,
                     marker = o.marker or markers[(k - 1) % #markers + 1] }
  return self
end

doc.add[==[
@ smi.report.chart:line(x, y [, opts]) -> chart
A polyline through (x[i], y[i]); x and y are vecs or tables of one length (a line breaks at
non-finite values).
options:
  label = nil     -- the legend entry
  color = nil     -- a CSS colour (default: the next of the palette)
  dash = nil      -- an SVG dash pattern such as "6 3"
  width = 2       -- line width, pixels
returns: the chart (calls chain)
errors: x and y of different lengths or not numbers
example:
  local c = require("smi.report").svg.chart{}
  c:line({0, 1, 2}, {0, 1, 4}, {label = "y", dash = "6 3"})
  print("ok")
]==]
--- A polyline through (x[i], y[i]); opts: label, color, dash ("6 3"), width (px, 2).
function Chart:line(x, y, o) return self:_add("line", x, y, o, "chart:line") end
doc.add[==[
@ smi.report.chart:step(x, y [, opts]) -> chart
A step curve: y[i] holds from x[i] to x[i+1] (x ascending).
options:
  label = nil     -- as chart:line
  color = nil     -- as chart:line
  dash = nil      -- as chart:line
  width = 2       -- as chart:line
  tails = false   -- extend the first value left and the last value right to the axes
returns: the chart
errors: as chart:line
example:
  local c = require("smi.report").svg.chart{}
  c:step({0, 1, 2}, {0.2, 0.6, 1}, {tails = true})
  print("ok")
]==]
--- A step curve: y[i] holds from x[i] to x[i+1] (x ascending); opts as line, plus tails=true
-- to extend the first value left to the axis and the last value right to the axis.
function Chart:step(x, y, o) return self:_add("step", x, y, o, "chart:step") end
doc.add[==[
@ smi.report.chart:scatter(x, y [, opts]) -> chart
Points (non-finite ones are left out and noted).
options:
  label = nil       -- the legend entry
  color = nil       -- a CSS colour
  marker = "circle" -- "circle", "square", "triangle" or "diamond"
  size = 3.5        -- marker size, pixels
returns: the chart
errors: as chart:line
example:
  local c = require("smi.report").svg.chart{equal = true}
  c:scatter({1, 2, 3}, {1.1, 1.9, 3.2}, {label = "LOO", marker = "square"}):diagonal()
  print("ok")
]==]
--- Points; opts: label, color, marker ("circle", "square", "triangle", "diamond"), size (px, 3.5).
function Chart:scatter(x, y, o) return self:_add("scatter", x, y, o, "chart:scatter") end

doc.add[==[
@ smi.report.chart:band(x, lo, hi [, opts]) -> chart
A shaded band between two curves over the same x (a confidence band).
options:
  label = nil      -- the legend entry
  color = nil      -- a CSS colour
  opacity = 0.18   -- fill opacity
returns: the chart
errors: x, lo and hi of different lengths
example:
  local c = require("smi.report").svg.chart{}
  c:band({0, 1, 2}, {0, 0.5, 1}, {1, 1.5, 2}, {label = "90 % band"})
  print("ok")
]==]
--- A shaded band between two curves over the same x (a confidence band, or the area between
-- an ECDF and a reference CDF); opts: label, color, opacity (0.18).
function Chart:band(x, lo, hi, o)
  local nx = check_series(x, "chart:band x")
  local nl, nh = check_series(lo, "chart:band lower"), check_series(hi, "chart:band upper")
  if nl ~= nx or nh ~= nx then error(("chart:band: x has %d values, lower %d, upper %d"):format(nx, nl, nh), 2) end
  o = o or {}
  local k = #self.series + 1
  self.series[k] = { kind = "band", x = x, y = lo, y2 = hi, n = nx, label = o.label, opts = o,
                     color = o.color or draw.palette[(k - 1) % #draw.palette + 1] }
  return self
end

doc.add[==[
@ smi.report.chart:rug(data [, opts]) -> chart
A short tick at the foot of the plot for each value of data (raw data under a density curve).
options:
  label = nil     -- the legend entry
  color = nil     -- a CSS colour
returns: the chart
errors: data not numbers
example:
  local c = require("smi.report").svg.chart{}
  c:rug(smi.vec{1, 1.5, 2.2})
  print("ok")
]==]
--- A rug: a short tick at the foot of the plot for each value of `data` (raw data under a
-- density curve); opts: label, color.
function Chart:rug(data, o)
  local n = check_series(data, "chart:rug data")
  local k = #self.series + 1
  o = o or {}
  self.series[k] = { kind = "rug", x = data, n = n, label = o.label, opts = o, color = o.color or "#1f2933" }
  return self
end

doc.add[==[
@ smi.report.chart:ecdf(data [, opts]) -> chart
The empirical CDF of data as steps of 1/n, from 0 at the left edge to 1 at the right.
options:
  label = nil     -- as chart:line
  color = nil     -- as chart:line
  dash = nil      -- as chart:line
  width = 2       -- as chart:line
returns: the chart
errors: data not numbers
example:
  local c = require("smi.report").svg.chart{ylabel = "F"}
  c:ecdf(smi.vec{3, 1, 2}, {label = "data"})
  print("ok")
]==]
--- The empirical CDF of `data` (non-finite values are skipped and noted): steps of 1/n at
-- the sorted values, from 0 at the left edge to 1 at the right edge.
function Chart:ecdf(data, o)
  check_series(data, "chart:ecdf data")
  local xs, bad = {}, 0
  for i = 1, #data do
    local v = data[i]
    if finite(v) then xs[#xs + 1] = v else bad = bad + 1 end
  end
  table.sort(xs)
  local ys = {}
  for i = 1, #xs do ys[i] = i / #xs end
  o = setmetatable({ tails = true }, { __index = o or {} })
  self:_add("step", xs, ys, o, "chart:ecdf")
  if bad > 0 then
    self.notes[#self.notes + 1] = ("%d non-finite value(s) of '%s' left out of the ECDF"):format(bad, o.label or "data")
  end
  self.series[#self.series].ecdf_zero = true
  return self
end

doc.add[==[
@ smi.report.chart:diagonal([opts]) -> chart
The line y = x across the plot (predicted vs observed).
options:
  label = nil     -- the legend entry
  color = nil     -- a CSS colour
returns: the chart
errors: none
example:
  local c = require("smi.report").svg.chart{equal = true}
  c:scatter({1, 2}, {1, 2}):diagonal{label = "y = x"}
  print("ok")
]==]
--- The line y = x across the plot (predicted vs observed); opts: label, color.
function Chart:diagonal(o)
  self.marks[#self.marks + 1] = { kind = "diagonal", opts = o or {} }
  return self
end
doc.add[==[
@ smi.report.chart:hline(y [, opts]) -> chart
A horizontal marker at y (a threshold).
options:
  label = nil       -- the marker's label
  color = "darkred" -- a CSS colour
  dash = nil        -- a dash pattern
returns: the chart
errors: y not a number
example:
  local c = require("smi.report").svg.chart{}
  c:line({0, 1}, {0, 1}):hline(0.5, {label = "threshold"})
  print("ok")
]==]
--- A horizontal marker at y; opts: label, color (default dark red), dash.
function Chart:hline(y, o)
  if not finite(y) then error("chart:hline: the value must be a finite number, got " .. tostring(y), 2) end
  self.marks[#self.marks + 1] = { kind = "hline", value = y, opts = o or {} }
  return self
end
doc.add[==[
@ smi.report.chart:vline(x [, opts]) -> chart
A vertical marker at x.
options:
  label = nil       -- the marker's label
  color = "darkred" -- a CSS colour
  dash = nil        -- a dash pattern
returns: the chart
errors: x not a number
example:
  local c = require("smi.report").svg.chart{}
  c:line({0, 1}, {0, 1}):vline(0.3, {label = "measured"})
  print("ok")
]==]
--- A vertical marker at x; opts as hline.
function Chart:vline(x, o)
  if not finite(x) then error("chart:vline: the value must be a finite number, got " .. tostring(x), 2) end
  self.marks[#self.marks + 1] = { kind = "vline", value = x, opts = o or {} }
  return self
end
doc.add[==[
@ smi.report.chart:note(s) -> chart
A line of small text under the chart ("bandwidth 0.31 Hz").
returns: the chart
errors: none
example:
  local c = require("smi.report").svg.chart{}
  c:line({0, 1}, {0, 1}):note("bandwidth 0.31 Hz")
  print("ok")
]==]
--- A line of small text under the chart (e.g. "bandwidth 0.31 Hz").
function Chart:note(s)
  self.notes[#self.notes + 1] = tostring(s)
  return self
end

local function usable(v, log) return finite(v) and (not log or v > 0) end

-- Data ranges over the plottable points of every series and marker.
function Chart:_ranges()
  local o = self.opts
  local xr, yr = { math.huge, -math.huge }, { math.huge, -math.huge }
  local function grow(r, v) if v < r[1] then r[1] = v end if v > r[2] then r[2] = v end end
  for _, s in ipairs(self.series) do
    for i = 1, s.n do
      local x, y = s.x[i], s.kind == "rug" and 1 or s.y[i]
      if s.kind == "rug" then
        if usable(x, o.xlog) then grow(xr, x) end
      elseif usable(x, o.xlog) and usable(y, o.ylog) then grow(xr, x); grow(yr, y) end
      if s.kind == "band" and usable(x, o.xlog) and usable(s.y2[i], o.ylog) then grow(yr, s.y2[i]) end
    end
    if s.ecdf_zero and s.n > 0 and not o.ylog then grow(yr, 0) end
  end
  for _, m in ipairs(self.marks) do
    if m.kind == "hline" and usable(m.value, o.ylog) then grow(yr, m.value) end
    if m.kind == "vline" and usable(m.value, o.xlog) then grow(xr, m.value) end
  end
  if o.equal and xr[1] <= xr[2] and yr[1] <= yr[2] then
    local lo, hi = math.min(xr[1], yr[1]), math.max(xr[2], yr[2])
    xr, yr = { lo, hi }, { lo, hi }
  end
  local only_points = #self.series > 0
  for _, s in ipairs(self.series) do if s.kind ~= "scatter" then only_points = false end end
  if only_points and xr[1] <= xr[2] then
    -- keep markers off the frame: 4 % of the range on each side (linear axes)
    local function pad(r, log)
      if log then return r end
      local d = (r[2] - r[1]) * 0.04
      return { r[1] - d, r[2] + d }
    end
    xr, yr = pad(xr, o.xlog), pad(yr, o.ylog)
  end
  if xr[1] <= xr[2] and yr[1] > yr[2] then yr = { o.ylog and 1 or 0, o.ylog and 10 or 1 } end -- rugs alone
  local empty = xr[1] > xr[2]
  if empty then xr, yr = { o.xlog and 1 or 0, o.xlog and 10 or 1 }, { o.ylog and 1 or 0, o.ylog and 10 or 1 } end
  if o.xlim then xr = { o.xlim[1], o.xlim[2] } end
  if o.ylim then yr = { o.ylim[1], o.ylim[2] } end
  return xr, yr, empty
end

local function make_axis(r, log, fixed)
  local ax = log and axis.log(r[1], r[2]) or axis.linear(r[1], r[2])
  if fixed then
    -- keep the caller's limits exactly; ticks only inside them
    local t = {}
    for _, v in ipairs(ax.ticks) do if v >= r[1] - 1e-12 * math.abs(r[1]) and v <= r[2] + 1e-12 * math.abs(r[2]) then t[#t + 1] = v end end
    ax.lo, ax.hi, ax.ticks = r[1], r[2], t
  end
  return ax
end


-- The path of one line or step series, and the number of points left out.
local function series_path(s, X, Y, o, ax)
  local parts, skipped, pen_down = {}, 0, false
  local function pt(px, py)
    parts[#parts + 1] = (pen_down and "L" or "M") .. n2(px) .. "," .. n2(py)
    pen_down = true
  end
  local prev_y
  if s.kind == "step" and s.opts.tails and s.n > 0 and usable(s.y[1], o.ylog) then
    prev_y = s.ecdf_zero and 0 or s.y[1]
    pt(X(ax.x.lo), Y(prev_y))
  end
  for i = 1, s.n do
    local x, y = s.x[i], s.y[i]
    if usable(x, o.xlog) and usable(y, o.ylog) then
      if s.kind == "step" and pen_down and prev_y then pt(X(x), Y(prev_y)) end
      pt(X(x), Y(y))
      prev_y = y
    else
      skipped = skipped + 1
      pen_down, prev_y = false, nil
    end
  end
  if s.kind == "step" and s.opts.tails and prev_y then pt(X(ax.x.hi), Y(prev_y)) end
  return table.concat(parts), skipped
end

-- The legend box, placed in the corner that hides the fewest data points unless told where.
local function legend(self, o, L, T, pw, ph, X, Y, ax)
  local out = {}
  local entries = {}
  for _, s in ipairs(self.series) do if s.label then entries[#entries + 1] = { s = s } end end
  for _, m in ipairs(self.marks) do if m.kind == "diagonal" and m.opts.label then entries[#entries + 1] = { m = m } end end
  local where = o.legend or "auto"
  if #entries > 0 and where ~= "none" then
    local lw = 0
    for _, e in ipairs(entries) do lw = math.max(lw, text_width((e.s or e.m.opts).label, 11)) end
    lw = lw + 40
    local lh = 8 + 17 * #entries
    if where == "auto" then
      -- the corner whose legend box covers the fewest data points
      local best, best_n = "top-right", math.huge
      for _, corner in ipairs{ "top-right", "top-left", "bottom-right", "bottom-left" } do
        local bx = corner:find("left") and L + 8 or L + pw - lw - 8
        local by = corner:find("bottom") and T + ph - lh - 8 or T + 8
        local count = 0
        for _, s in ipairs(self.series) do
          for i = 1, s.n do
            local x = s.x[i]
            local y = s.kind == "rug" and ax.y.lo or s.y[i]
            if usable(x, o.xlog) and usable(y, o.ylog) then
              local px, py = X(x), Y(y)
              if px >= bx - 4 and px <= bx + lw + 4 and py >= by - 4 and py <= by + lh + 4 then count = count + 1 end
            end
          end
        end
        if count < best_n then best, best_n = corner, count end
      end
      where = best
    end
    local lx = where:find("left") and L + 8 or L + pw - lw - 8
    local ly = where:find("bottom") and T + ph - lh - 8 or T + 8
    local lg = { '<g class="legend">', xml.el("rect", { x = n2(lx), y = n2(ly), width = n2(lw), height = n2(lh), fill = "#ffffff", ["fill-opacity"] = 0.9, stroke = "#cbd2d9", rx = 3 }) }
    for i, e in ipairs(entries) do
      local cy = ly + 4 + 17 * (i - 1) + 8.5
      if e.s and e.s.kind == "scatter" then
        lg[#lg + 1] = marker_svg(e.s.marker, lx + 18, cy, 3.5, e.s.color)
      elseif e.s and e.s.kind == "band" then
        lg[#lg + 1] = xml.el("rect", { x = n2(lx + 8), y = n2(cy - 5), width = 20, height = 10, fill = e.s.color, ["fill-opacity"] = e.s.opts.opacity or 0.18 })
      elseif e.s and e.s.kind == "rug" then
        lg[#lg + 1] = xml.el("line", { x1 = n2(lx + 18), y1 = n2(cy - 5), x2 = n2(lx + 18), y2 = n2(cy + 5), stroke = e.s.color, ["stroke-width"] = 1.5 })
      else
        local color, dash
        if e.s then color, dash = e.s.color, e.s.dash else color, dash = e.m.opts.color or "#7b8794", e.m.opts.dash or "5 4" end
        lg[#lg + 1] = xml.el("line", { x1 = n2(lx + 8), y1 = n2(cy), x2 = n2(lx + 28), y2 = n2(cy), stroke = color, ["stroke-width"] = 2, ["stroke-dasharray"] = dash })
      end
      lg[#lg + 1] = text(lx + 34, cy + 4, (e.s or e.m.opts).label, { fill = "#1f2933" })
    end
    lg[#lg + 1] = "</g>"
    out[#out + 1] = table.concat(lg)
  end
  return table.concat(out)
end

-- Notes on what a chart leaves out: points a series cannot show (non-finite, or not positive
-- on a log axis) and scatter points beyond the axis limits.
local function dropped_notes(self, ax)
  local o, notes = self.opts, {}
  for k, s in ipairs(self.series) do
    local skipped = 0
    for i = 1, s.n do
      if not (usable(s.x[i], o.xlog) and (s.kind == "rug" or usable(s.y[i], o.ylog))
              and (s.kind ~= "band" or usable(s.y2[i], o.ylog))) then skipped = skipped + 1 end
    end
    if skipped > 0 then
      notes[#notes + 1] = ("%d of %d point(s) of '%s' not drawn (non-finite%s)"):format(skipped, s.n, s.label or ("series " .. k),
        (o.xlog or o.ylog) and " or not positive on a log axis" or "")
    end
    if s.kind == "scatter" then
      local outside = 0
      for i = 1, s.n do
        local x, y = s.x[i], s.y[i]
        if usable(x, o.xlog) and usable(y, o.ylog) and (x < ax.x.lo or x > ax.x.hi or y < ax.y.lo or y > ax.y.hi) then outside = outside + 1 end
      end
      if outside > 0 then
        notes[#notes + 1] = ("%d point(s) of '%s' outside the axis limits not drawn"):format(outside, s.label or ("series " .. k))
      end
    end
  end
  return notes
end

-- The frame of a chart: axes, tick labels, notes, margins (L, T: left and top; pw, ph: the plot
-- area's size) and the scales X, Y from data to pixels.
local function chart_frame(self)
  local o = self.opts
  local W, H = self.width, self.height
  local xr, yr, empty = self:_ranges()
  local ax = { x = make_axis(xr, o.xlog, o.xlim ~= nil), y = make_axis(yr, o.ylog, o.ylim ~= nil) }
  -- left margin from the widest y tick label
  local ylabels, wmax = {}, 0
  for i, t in ipairs(ax.y.ticks) do
    ylabels[i] = axis.label(t, ax.y)
    wmax = math.max(wmax, text_width(ylabels[i], 11))
  end
  local L = math.floor(wmax + 14 + (o.ylabel and 22 or 0) + 0.5)
  local T = o.title and 34 or 14
  local R = 18
  local pw = W - L - R
  -- the notes (skipped points first) decide the bottom margin
  local notes = dropped_notes(self, ax)
  if empty then notes[#notes + 1] = "no finite data to plot" end
  for _, n in ipairs(self.notes) do notes[#notes + 1] = n end
  local B = 44 + 14 * #notes
  local ph = H - T - B
  return { o = o, W = W, H = H, ax = ax, ylabels = ylabels, notes = notes, L = L, T = T, pw = pw, ph = ph,
           X = axis.scale(ax.x, L, L + pw), Y = axis.scale(ax.y, T + ph, T) }
end

-- Grid lines, the plot frame, the ticks with their labels, the title and the axis labels.
local function axes_svg(f, out)
  local o, ax, L, T, pw, ph, X, Y = f.o, f.ax, f.L, f.T, f.pw, f.ph, f.X, f.Y
  local g = { '<g class="grid" stroke="#e3e6ea" stroke-width="1">' }
  for _, t in ipairs(ax.x.ticks) do g[#g + 1] = ('<line x1="%s" y1="%s" x2="%s" y2="%s"/>'):format(n2(X(t)), n2(T), n2(X(t)), n2(T + ph)) end
  for _, t in ipairs(ax.y.ticks) do g[#g + 1] = ('<line x1="%s" y1="%s" x2="%s" y2="%s"/>'):format(n2(L), n2(Y(t)), n2(L + pw), n2(Y(t))) end
  g[#g + 1] = "</g>"
  out[#out + 1] = table.concat(g)
  out[#out + 1] = xml.el("rect", { x = n2(L), y = n2(T), width = n2(pw), height = n2(ph), fill = "none", stroke = "#9aa3ad" })
  local tk = { '<g class="xticks" text-anchor="middle" fill="#333333">' }
  for _, t in ipairs(ax.x.ticks) do
    tk[#tk + 1] = ('<line x1="%s" y1="%s" x2="%s" y2="%s" stroke="#9aa3ad"/>'):format(n2(X(t)), n2(T + ph), n2(X(t)), n2(T + ph + 4))
    tk[#tk + 1] = text(X(t), T + ph + 17, axis.label(t, ax.x), { class = "tick" })
  end
  tk[#tk + 1] = "</g>"
  out[#out + 1] = table.concat(tk)
  tk = { '<g class="yticks" text-anchor="end" fill="#333333">' }
  for i, t in ipairs(ax.y.ticks) do
    tk[#tk + 1] = ('<line x1="%s" y1="%s" x2="%s" y2="%s" stroke="#9aa3ad"/>'):format(n2(L - 4), n2(Y(t)), n2(L), n2(Y(t)))
    tk[#tk + 1] = text(L - 7, Y(t) + 4, f.ylabels[i], { class = "tick" })
  end
  tk[#tk + 1] = "</g>"
  out[#out + 1] = table.concat(tk)
  -- titles and axis labels
  if o.title then out[#out + 1] = draw.title(f.W, o.title) end
  if o.xlabel then out[#out + 1] = text(L + pw / 2, T + ph + 36, o.xlabel, { ["text-anchor"] = "middle", ["font-size"] = 12, fill = "#1f2933", class = "xlabel" }) end
  if o.ylabel then
    out[#out + 1] = text(0, 0, o.ylabel, { ["text-anchor"] = "middle", ["font-size"] = 12, fill = "#1f2933", class = "ylabel",
      transform = ("translate(%s,%s) rotate(-90)"):format(n2(15), n2(T + ph / 2)) })
  end
end

-- A band series: one closed polygon per run of finite points, along the lower curve and back
-- along the upper.
local function band_svg(f, k, s, out)
  local o, X, Y = f.o, f.X, f.Y
  local polys, run = {}, {}
  local function flush()
    if #run >= 2 then
      local d = {}
      for j, i in ipairs(run) do d[#d + 1] = (j == 1 and "M" or "L") .. n2(X(s.x[i])) .. "," .. n2(Y(s.y[i])) end
      for j = #run, 1, -1 do d[#d + 1] = "L" .. n2(X(s.x[run[j]])) .. "," .. n2(Y(s.y2[run[j]])) end
      polys[#polys + 1] = table.concat(d) .. "Z"
    end
    run = {}
  end
  for i = 1, s.n do
    if usable(s.x[i], o.xlog) and usable(s.y[i], o.ylog) and usable(s.y2[i], o.ylog) then run[#run + 1] = i else flush() end
  end
  flush()
  if #polys > 0 then
    out[#out + 1] = xml.el("path", { class = "series band", ["data-series"] = k, d = table.concat(polys), fill = s.color,
      ["fill-opacity"] = s.opts.opacity or 0.18, stroke = "none" })
  end
end

-- The marks: the diagonal y = x, horizontal and vertical lines with their labels.
local function marks_svg(self, f, out)
  local ax, L, T, pw, ph, X, Y = f.ax, f.L, f.T, f.pw, f.ph, f.X, f.Y
  for _, m in ipairs(self.marks) do
    local mo = m.opts
    local color = mo.color or (m.kind == "diagonal" and "#7b8794" or "#b42318")
    local attrs = { stroke = color, ["stroke-width"] = mo.width or 1.5, ["stroke-dasharray"] = mo.dash or "5 4", class = "mark-" .. m.kind }
    if m.kind == "diagonal" then
      local lo, hi = math.max(ax.x.lo, ax.y.lo), math.min(ax.x.hi, ax.y.hi)
      if lo < hi then
        attrs.x1, attrs.y1, attrs.x2, attrs.y2 = n2(X(lo)), n2(Y(lo)), n2(X(hi)), n2(Y(hi))
        out[#out + 1] = xml.el("line", attrs)
      end
    elseif m.kind == "hline" then
      attrs.x1, attrs.y1, attrs.x2, attrs.y2 = n2(L), n2(Y(m.value)), n2(L + pw), n2(Y(m.value))
      out[#out + 1] = xml.el("line", attrs)
      if mo.label then out[#out + 1] = text(L + pw - 4, Y(m.value) - 5, mo.label, { ["text-anchor"] = "end", fill = color, class = "mark-label", stroke = "#ffffff", ["stroke-width"] = 3, ["paint-order"] = "stroke" }) end
    elseif m.kind == "vline" then
      attrs.x1, attrs.y1, attrs.x2, attrs.y2 = n2(X(m.value)), n2(T), n2(X(m.value)), n2(T + ph)
      out[#out + 1] = xml.el("line", attrs)
      if mo.label then out[#out + 1] = text(X(m.value) + 4, T + 14, mo.label, { fill = color, class = "mark-label", stroke = "#ffffff", ["stroke-width"] = 3, ["paint-order"] = "stroke" }) end
    end
  end
end

-- A rug series: one short tick per point on the x axis.
local function rug_svg(f, k, s, out)
  local ticks = { ('<g class="series rug" data-series="%d" stroke="%s" stroke-width="1.5">'):format(k, s.color) }
  for i = 1, s.n do
    local x = s.x[i]
    if usable(x, f.o.xlog) then
      ticks[#ticks + 1] = ('<line x1="%s" y1="%s" x2="%s" y2="%s"/>'):format(n2(f.X(x)), n2(f.T + f.ph), n2(f.X(x)), n2(f.T + f.ph - 10))
    end
  end
  ticks[#ticks + 1] = "</g>"
  out[#out + 1] = table.concat(ticks)
end

-- The data drawn inside the plot area, clipped to it: bands below the marks, lines and rugs above.
local function clipped_data_svg(self, f, id, out)
  out[#out + 1] = ('<g clip-path="url(#%s-clip)">'):format(id)
  for k, s in ipairs(self.series) do
    if s.kind == "band" then band_svg(f, k, s, out) end
  end
  marks_svg(self, f, out)
  for k, s in ipairs(self.series) do
    if s.kind == "rug" then
      rug_svg(f, k, s, out)
    elseif s.kind ~= "scatter" and s.kind ~= "band" then
      local d = series_path(s, f.X, f.Y, f.o, f.ax)
      if d ~= "" then
        out[#out + 1] = xml.el("path", { class = "series " .. s.kind, ["data-series"] = k, d = d, fill = "none", stroke = s.color,
          ["stroke-width"] = s.opts.width or 2, ["stroke-dasharray"] = s.dash, ["stroke-linejoin"] = "round" })
      end
    end
  end
  out[#out + 1] = "</g>"
end

-- Scatter markers are not clipped (a point on the frame stays whole); points beyond limits set
-- by the caller are left out (chart_frame's notes count them).
local function scatter_svg(self, f, out)
  local o, ax = f.o, f.ax
  for k, s in ipairs(self.series) do
    if s.kind == "scatter" then
      local pts = { ('<g class="series scatter" data-series="%d" fill-opacity="0.85">'):format(k) }
      for i = 1, s.n do
        local x, y = s.x[i], s.y[i]
        if usable(x, o.xlog) and usable(y, o.ylog) and not (x < ax.x.lo or x > ax.x.hi or y < ax.y.lo or y > ax.y.hi) then
          pts[#pts + 1] = marker_svg(s.marker, f.X(x), f.Y(y), s.opts.size or 3.5, s.color)
        end
      end
      pts[#pts + 1] = "</g>"
      out[#out + 1] = table.concat(pts)
    end
  end
end

doc.add[==[
@ smi.report.chart:render() -> svg
The chart as an SVG string (axes with readable ticks, legend, notes).
returns: a string starting with <svg
errors: none (values a log axis cannot show are skipped, and a note says how many)
example:
  local c = require("smi.report").svg.chart{title = "t"}
  c:line({1, 2}, {3, 4})
  print(c:render():sub(1, 4))
]==]
function Chart:render()
  chart_count = chart_count + 1
  local id = "smi-chart-" .. chart_count
  local f = chart_frame(self)
  local out = {}
  out[#out + 1] = draw.open(f.W, f.H, self.opts.title or "chart")
  out[#out + 1] = ('<defs><clipPath id="%s-clip"><rect x="%s" y="%s" width="%s" height="%s"/></clipPath></defs>')
    :format(id, n2(f.L), n2(f.T), n2(f.pw), n2(f.ph))
  axes_svg(f, out)
  clipped_data_svg(self, f, id, out)
  scatter_svg(self, f, out)
  out[#out + 1] = legend(self, f.o, f.L, f.T, f.pw, f.ph, f.X, f.Y, f.ax)
  for i, n in ipairs(f.notes) do
    out[#out + 1] = draw.note(8, f.T + f.ph + 52 + 14 * (i - 1), n)
  end
  out[#out + 1] = "</svg>"
  return table.concat(out, "\n")
end

doc.add[==[
@ smi.report.svg.before_after(opts) -> chart
The before/after figure of one response: the measured data, the initial model and the final
(calibrated, revised) model as empirical CDFs on one axis, so that a reader sees at a glance
what the study changed. The data are drawn solid in black, the initial model dashed in grey, the
final model solid in the accent colour.
options:
  data = (required)    -- the measurements (vec or table)
  initial = (required) -- samples of the initial model's response (its propagated prior)
  final = (required)   -- samples of the final model's response
  title = nil          -- the chart title (the response's name)
  xlabel = nil         -- the response with its unit ("Mode 1 (Hz)")
  labels = nil         -- {data =, initial =, final =}: the legend entries (defaults: "data (n = 9)",
                       -- "initial model", "final model")
  width = 640          -- pixels
  height = 360         -- pixels
returns: a chart (render it, or pass it to r:figure)
errors: data, initial or final missing or not numbers
example:
  local c = require("smi.report").svg.before_after{title = "Mode 1", xlabel = "Hz", data = {29.6, 30.1, 30.4},
    initial = {27, 28, 29, 30, 31}, final = {29.5, 29.9, 30.2, 30.5}}
  print(#c.series, c:render():find("final model") ~= nil)
]==]
function M.before_after(o)
  if type(o) ~= "table" then error("chart.before_after: expects {data =, initial =, final =, title =, xlabel =}", 2) end
  for _, k in ipairs({ "data", "initial", "final" }) do
    if o[k] == nil then error(("chart.before_after: '%s' is missing (the %s)"):format(k,
      ({ data = "measurements", initial = "initial model's samples", final = "final model's samples" })[k]), 2) end
  end
  local labels = o.labels or {}
  local c = M.new{ title = o.title, xlabel = o.xlabel, ylabel = "cumulative probability", width = o.width or 640,
                   height = o.height or 360, ylim = { 0, 1 }, legend = "auto" }
  c:ecdf(o.initial, { label = labels.initial or "initial model", color = "#8a94a0", dash = "6 4" })
  c:ecdf(o.final, { label = labels.final or "final model", color = draw.palette[1], width = 2.5 })
  c:ecdf(o.data, { label = labels.data or ("data (n = %d)"):format(#o.data), color = "#1f2933", width = 1.5 })
  c:rug(o.data, { color = "#1f2933" })
  return c
end

return M
