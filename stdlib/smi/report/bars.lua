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
  local order = {}
  for i = 1, n do order[i] = i end
  if opts.sort then
    local v = series[1].values
    local function key(i) local x = v[i]; return finite(x) and x or -math.huge end
    table.sort(order, function(a, b) if key(a) ~= key(b) then return key(a) > key(b) end return a < b end)
  end
  local hl = opts.highlight
  local function highlighted(i)
    if type(hl) == "function" then return hl(labels[i], series[1].values[i]) end
    return hl ~= nil and hl[labels[i]] == true
  end
  -- value range (always includes 0, the bars' base)
  local lo, hi, bad = 0, 0, 0
  for _, s in ipairs(series) do
    for i = 1, n do
      local x = s.values[i]
      if finite(x) then lo, hi = math.min(lo, x), math.max(hi, x) else bad = bad + 1 end
    end
  end
  if finite(opts.threshold) then lo, hi = math.min(lo, opts.threshold), math.max(hi, opts.threshold) end
  if lo == hi then hi = 1 end
  local ax = axis.linear(lo, hi)
  local W = opts.width or 640
  local ns = #series
  local bh = ns == 1 and 14 or 9
  local rowh = opts.row or (bh * ns + 8)
  local lw = 0
  for i = 1, n do lw = math.max(lw, text_width(labels[i], 11)) end
  local maxlw = W * 0.4
  local L = math.min(lw, maxlw) + 16
  local T = (opts.title and 34 or 12) + (finite(opts.threshold) and opts.threshold_label and 10 or 0)
  local notes = {}
  if bad > 0 then notes[#notes + 1] = ("%d value(s) not finite: shown as n/a"):format(bad) end
  for _, s in ipairs(opts.notes or {}) do notes[#notes + 1] = s end
  local legend_h = ns > 1 and 20 or 0
  local B = 40 + (opts.xlabel and 16 or 0) + legend_h + 14 * #notes
  local ph = rowh * n
  local H = opts.height or (T + ph + B)
  local R = 60 -- room for the value labels
  local pw = W - L - R
  local X = axis.scale(ax, L, L + pw)
  local digits = opts.digits or 3
  local chosen_color = opts.highlight_color or "#D55E00"

  local out = {}
  out[#out + 1] = draw.open(W, H, opts.title or "bar chart")
  if opts.title then out[#out + 1] = draw.title(W, opts.title) end
  local g = { '<g class="grid" stroke="#e3e6ea">' }
  for _, t in ipairs(ax.ticks) do g[#g + 1] = ('<line x1="%s" y1="%s" x2="%s" y2="%s"/>'):format(n2(X(t)), n2(T), n2(X(t)), n2(T + ph)) end
  g[#g + 1] = "</g>"
  out[#out + 1] = table.concat(g)
  local rows = { '<g class="bars">' }
  for r, i in ipairs(order) do
    local y0 = T + (r - 1) * rowh + 4
    local label = tostring(labels[i])
    local shown = label
    if text_width(label, 11) > maxlw then
      local keep = math.max(1, math.floor(maxlw / (11 * 0.6)) - 1)
      shown = label:sub(1, utf8.offset(label, keep + 1) and utf8.offset(label, keep + 1) - 1 or #label) .. "…"
    end
    rows[#rows + 1] = ('<text x="%s" y="%s" text-anchor="end" fill="#1f2933" class="bar-label"%s>%s<title>%s</title></text>')
      :format(n2(L - 6), n2(y0 + (rowh - 8) / 2 + 4), highlighted(i) and ' font-weight="bold"' or "", esc(shown), esc(label))
    for k, s in ipairs(series) do
      local v = s.values[i]
      local yb = y0 + (k - 1) * bh
      if finite(v) then
        local x0, x1 = X(math.min(0, v)), X(math.max(0, v))
        local color = s.color or (ns == 1 and highlighted(i) and chosen_color) or draw.palette[k]
        rows[#rows + 1] = xml.el("rect", { class = "bar", x = n2(x0), y = n2(yb), width = n2(math.max(x1 - x0, 0.5)), height = n2(bh - 1), fill = color })
        rows[#rows + 1] = text(x1 + 4, yb + bh - 3, fmt.num(v, digits), { fill = "#52606d", ["font-size"] = 10, class = "bar-value",
          stroke = "#ffffff", ["stroke-width"] = 3, ["paint-order"] = "stroke" })
      else
        rows[#rows + 1] = text(X(0) + 4, yb + bh - 3, "n/a", { fill = "#b42318", ["font-size"] = 10, ["font-style"] = "italic", class = "bar-value" })
      end
    end
  end
  rows[#rows + 1] = "</g>"
  out[#out + 1] = table.concat(rows)
  -- zero line and axis
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
  if ns > 1 then
    local lx = L
    local lg = { '<g class="legend">' }
    for k, s in ipairs(series) do
      local ly = T + ph + 34 + (opts.xlabel and 16 or 0)
      lg[#lg + 1] = xml.el("rect", { x = n2(lx), y = n2(ly - 9), width = 12, height = 10, fill = s.color or draw.palette[k] })
      lg[#lg + 1] = text(lx + 16, ly, s.label or ("series " .. k), { fill = "#1f2933" })
      lx = lx + 16 + text_width(s.label or ("series " .. k), 11) + 18
    end
    lg[#lg + 1] = "</g>"
    out[#out + 1] = table.concat(lg)
  end
  for i, s in ipairs(notes) do
    out[#out + 1] = draw.note(8, T + ph + 40 + (opts.xlabel and 16 or 0) + legend_h + 14 * (i - 1), s)
  end
  out[#out + 1] = "</svg>"
  return table.concat(out, "\n")
end

return M
