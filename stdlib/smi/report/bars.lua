-- SPDX-License-Identifier: MIT
--- smi.report.bars: horizontal bar charts (screening indices, decision-matrix scores) as SVG
-- strings. Used through smi.report.svg.bars{...}.
local xml = require "smi.report.xml"
local axis = require "smi.report.axis"
local draw = require "smi.report.draw"

local finite = axis.finite
local esc = xml.escape
local n2, text, text_width, check_series = draw.n2, draw.text, draw.text_width, draw.check_series
local marker_svg = draw.marker
local fmt = require "smi.report.format"

local M = {}

-- ---------------------------------------------------------------------------------------------
-- Horizontal bar chart
-- ---------------------------------------------------------------------------------------------

-- Row order: as given, or by the first series (largest on top; non-finite last; ties as given).
local function row_order(values, n, sort)
  local order = {}
  for i = 1, n do order[i] = i end
  if sort then
    local function key(i) local x = values[i]; return finite(x) and x or -math.huge end
    table.sort(order, function(a, b) if key(a) ~= key(b) then return key(a) > key(b) end return a < b end)
  end
  return order
end

-- The value range (always including 0, the bars' base, and the threshold) and how many values
-- are not finite.
local function value_range(series, n, threshold)
  local lo, hi, bad = 0, 0, 0
  for _, s in ipairs(series) do
    for i = 1, n do
      local x = s.values[i]
      if finite(x) then lo, hi = math.min(lo, x), math.max(hi, x) else bad = bad + 1 end
    end
  end
  if finite(threshold) then lo, hi = math.min(lo, threshold), math.max(hi, threshold) end
  if lo == hi then hi = 1 end
  return lo, hi, bad
end

-- The frame: axis, row heights, margins (L, T; pw, ph the plot area), notes and the x scale.
local function bars_frame(opts, labels, series)
  local n, ns = #labels, #series
  local lo, hi, bad = value_range(series, n, opts.threshold)
  local f = { opts = opts, labels = labels, series = series, n = n, ns = ns }
  f.ax = axis.linear(lo, hi)
  f.W = opts.width or 640
  f.bh = ns == 1 and 14 or 9
  f.rowh = opts.row or (f.bh * ns + 8)
  local lw = 0
  for i = 1, n do lw = math.max(lw, text_width(labels[i], 11)) end
  f.maxlw = f.W * 0.4
  f.L = math.min(lw, f.maxlw) + 16
  f.T = (opts.title and 34 or 12) + (finite(opts.threshold) and opts.threshold_label and 10 or 0)
  f.notes = {}
  if bad > 0 then f.notes[#f.notes + 1] = ("%d value(s) not finite: shown as n/a"):format(bad) end
  for _, s in ipairs(opts.notes or {}) do f.notes[#f.notes + 1] = s end
  f.legend_h = ns > 1 and 20 or 0
  local B = 40 + (opts.xlabel and 16 or 0) + f.legend_h + 14 * #f.notes
  f.ph = f.rowh * n
  f.H = opts.height or (f.T + f.ph + B)
  local R = 60 -- room for the value labels
  f.pw = f.W - f.L - R
  f.X = axis.scale(f.ax, f.L, f.L + f.pw)
  return f
end

-- One row: its label (shortened with … beyond 40 % of the width, the full text as a tooltip)
-- and a bar with its value per series ("n/a" where not finite).
local function bar_row_svg(f, r, i, highlighted, rows)
  local opts, series, X, bh = f.opts, f.series, f.X, f.bh
  local y0 = f.T + (r - 1) * f.rowh + 4
  local label = tostring(f.labels[i])
  local shown = label
  if text_width(label, 11) > f.maxlw then
    local keep = math.max(1, math.floor(f.maxlw / (11 * 0.6)) - 1)
    shown = label:sub(1, utf8.offset(label, keep + 1) and utf8.offset(label, keep + 1) - 1 or #label) .. "…"
  end
  rows[#rows + 1] = ('<text x="%s" y="%s" text-anchor="end" fill="#1f2933" class="bar-label"%s>%s<title>%s</title></text>')
    :format(n2(f.L - 6), n2(y0 + (f.rowh - 8) / 2 + 4), highlighted(i) and ' font-weight="bold"' or "", esc(shown), esc(label))
  for k, s in ipairs(series) do
    local v = s.values[i]
    local yb = y0 + (k - 1) * bh
    if finite(v) then
      local x0, x1 = X(math.min(0, v)), X(math.max(0, v))
      local color = s.color or (f.ns == 1 and highlighted(i) and (opts.highlight_color or "#D55E00")) or draw.palette[k]
      rows[#rows + 1] = xml.el("rect", { class = "bar", x = n2(x0), y = n2(yb), width = n2(math.max(x1 - x0, 0.5)), height = n2(bh - 1), fill = color })
      rows[#rows + 1] = text(x1 + 4, yb + bh - 3, fmt.num(v, opts.digits or 3), { fill = "#52606d", ["font-size"] = 10, class = "bar-value",
        stroke = "#ffffff", ["stroke-width"] = 3, ["paint-order"] = "stroke" })
    else
      rows[#rows + 1] = text(X(0) + 4, yb + bh - 3, "n/a", { fill = "#b42318", ["font-size"] = 10, ["font-style"] = "italic", class = "bar-value" })
    end
  end
end

-- The zero line, the x axis with its ticks and label, and the threshold marker.
local function bars_axis_svg(f, out)
  local opts, ax, L, T, pw, ph, X = f.opts, f.ax, f.L, f.T, f.pw, f.ph, f.X
  out[#out + 1] = xml.el("line", { x1 = n2(X(0)), y1 = n2(T), x2 = n2(X(0)), y2 = n2(T + ph), stroke = "#52606d" })
  local tk = { '<g class="xticks" text-anchor="middle" fill="#333333">' }
  tk[#tk + 1] = xml.el("line", { x1 = n2(L), y1 = n2(T + ph), x2 = n2(L + pw), y2 = n2(T + ph), stroke = "#9aa3ad" })
  for _, t in ipairs(ax.ticks) do
    tk[#tk + 1] = ('<line x1="%s" y1="%s" x2="%s" y2="%s" stroke="#9aa3ad"/>'):format(n2(X(t)), n2(T + ph), n2(X(t)), n2(T + ph + 4))
    tk[#tk + 1] = text(X(t), T + ph + 17, axis.label(t, ax), { class = "tick" })
  end
  tk[#tk + 1] = "</g>"
  out[#out + 1] = table.concat(tk)
  if opts.xlabel then out[#out + 1] = text(L + pw / 2, T + ph + 36, opts.xlabel, { ["text-anchor"] = "middle", ["font-size"] = 12, fill = "#1f2933", class = "xlabel" }) end
  if finite(opts.threshold) then
    local x = X(opts.threshold)
    out[#out + 1] = xml.el("line", { x1 = n2(x), y1 = n2(T - 4), x2 = n2(x), y2 = n2(T + ph), stroke = "#b42318", ["stroke-width"] = 1.5, ["stroke-dasharray"] = "5 4", class = "mark-vline" })
    if opts.threshold_label then out[#out + 1] = text(x + 4, T - 6, opts.threshold_label, { fill = "#b42318", class = "mark-label", stroke = "#ffffff", ["stroke-width"] = 3, ["paint-order"] = "stroke" }) end
  end
end

-- The legend of grouped bars (more than one series).
local function bars_legend_svg(f, out)
  local lx = f.L
  local lg = { '<g class="legend">' }
  for k, s in ipairs(f.series) do
    local ly = f.T + f.ph + 34 + (f.opts.xlabel and 16 or 0)
    lg[#lg + 1] = xml.el("rect", { x = n2(lx), y = n2(ly - 9), width = 12, height = 10, fill = s.color or draw.palette[k] })
    lg[#lg + 1] = text(lx + 16, ly, s.label or ("series " .. k), { fill = "#1f2933" })
    lx = lx + 16 + text_width(s.label or ("series " .. k), 11) + 18
  end
  lg[#lg + 1] = "</g>"
  out[#out + 1] = table.concat(lg)
end

--- Horizontal bars, one row per label, returned as an SVG string.
-- opts: labels (strings), values (numbers) or series = {{label=, values=}, ...} for grouped bars,
-- title, xlabel, sort (true: by the first series, largest on top), highlight (set of labels or
-- function(label, value) -> bool: drawn in the accent colour), threshold (vertical marker) and
-- threshold_label, digits (value labels, 3), width (640), row (px per row, auto).
function M.render(opts)
  opts = opts or {}
  local labels = opts.labels or error("svg.bars: 'labels' is required (a list of strings)", 2)
  local series = opts.series or { { values = opts.values or error("svg.bars: 'values' or 'series' is required", 2) } }
  local n = #labels
  for k, s in ipairs(series) do
    local m = check_series(s.values, "svg.bars series " .. k)
    if m ~= n then error(("svg.bars: series %d has %d values for %d labels"):format(k, m, n), 2) end
  end
  local hl = opts.highlight
  local function highlighted(i)
    if type(hl) == "function" then return hl(labels[i], series[1].values[i]) end
    return hl ~= nil and hl[labels[i]] == true
  end
  local f = bars_frame(opts, labels, series)

  local out = {}
  out[#out + 1] = draw.open(f.W, f.H, opts.title or "bar chart")
  if opts.title then out[#out + 1] = draw.title(f.W, opts.title) end
  local g = { '<g class="grid" stroke="#e3e6ea">' }
  for _, t in ipairs(f.ax.ticks) do g[#g + 1] = ('<line x1="%s" y1="%s" x2="%s" y2="%s"/>'):format(n2(f.X(t)), n2(f.T), n2(f.X(t)), n2(f.T + f.ph)) end
  g[#g + 1] = "</g>"
  out[#out + 1] = table.concat(g)
  local rows = { '<g class="bars">' }
  for r, i in ipairs(row_order(series[1].values, n, opts.sort)) do bar_row_svg(f, r, i, highlighted, rows) end
  rows[#rows + 1] = "</g>"
  out[#out + 1] = table.concat(rows)
  bars_axis_svg(f, out)
  if f.ns > 1 then bars_legend_svg(f, out) end
  for i, s in ipairs(f.notes) do
    out[#out + 1] = draw.note(8, f.T + f.ph + 40 + (opts.xlabel and 16 or 0) + f.legend_h + 14 * (i - 1), s)
  end
  out[#out + 1] = "</svg>"
  return table.concat(out, "\n")
end

return M
