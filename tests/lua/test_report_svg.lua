-- SPDX-License-Identifier: MIT
-- smi.report.svg and smi.report.axis: the charts parse as XML, draw every finite point where
-- the axes say it belongs, skip non-finite values with a note, and escape text.
local T = require "smi.testing"
local svg = require "smi.report.svg"
local axis = require "smi.report.axis"
local X = require "smi.report.xmlcheck"

local function parse(s)
  local ok, err = X.check(s)
  T.truthy(ok, "well-formed SVG (" .. tostring(err) .. ")")
  return X.parse(s)
end

-- Coordinate pairs of a path's d attribute, and the number of subpaths (M commands).
local function path_points(d)
  local pts = {}
  for cmd, x, y in d:gmatch("([ML])(%-?[%d%.]+),(%-?[%d%.]+)") do pts[#pts + 1] = { cmd = cmd, x = tonumber(x), y = tonumber(y) } end
  local m = 0
  for _ in d:gmatch("M") do m = m + 1 end
  return pts, m
end

local by_class = X.find_by_class

-- The plot frame: the rect with stroke and no fill after the background.
local function frame(root)
  for _, r in ipairs(X.find_all(root, "rect")) do
    if r.attrs.fill == "none" and r.attrs.stroke then
      return tonumber(r.attrs.x), tonumber(r.attrs.y), tonumber(r.attrs.width), tonumber(r.attrs.height)
    end
  end
  error("no plot frame")
end

T.case("xmlcheck rejects what is not well-formed (so the other checks mean something)", function()
  T.truthy(X.check('<a x="1"><b/>t &amp; &#60;</a>'), "a good document")
  for _, bad in ipairs{ "<a>\1</a>", "<a>\255</a>", "<a><b></a></b>", "<a x=1/>", "<a>&foo;</a>", "<a>1 < 2</a>", '<a x="1" x="2"/>', "<a>", "<a/><b/>", "<a>x & y</a>" } do
    local ok = X.check(bad)
    T.eq(ok, false, "rejects " .. bad)
  end
end)

T.case("nice ticks: steps of 1, 2 or 5 x 10^k that cover the data", function()
  local rng = smi.rng(7)
  local u = rng:uniform(400, -6, 6)
  for k = 1, 200 do
    local a = (u[2 * k - 1] > 0 and 1 or -1) * 10 ^ u[2 * k - 1]
    local b = a + 10 ^ u[2 * k] * (k % 3 == 0 and 0.001 or 1)
    local ax = axis.linear(a, b)
    local lo, hi = math.min(a, b), math.max(a, b)
    T.truthy(ax.lo <= lo and ax.hi >= hi, ("range [%g,%g] covers [%g,%g]"):format(ax.lo, ax.hi, lo, hi))
    local e = math.floor(math.log(ax.step, 10) + 1e-9)
    local mant = ax.step / 10 ^ e
    T.truthy(math.abs(mant - 1) < 1e-9 or math.abs(mant - 2) < 1e-9 or math.abs(mant - 5) < 1e-9, "mantissa " .. mant)
    T.truthy(#ax.ticks >= 4 and #ax.ticks <= 11, "tick count " .. #ax.ticks)
    for i, t in ipairs(ax.ticks) do
      local q = t / ax.step
      T.truthy(math.abs(q - math.floor(q + 0.5)) < 1e-6 + math.abs(q) * 1e-12, ("tick %g is a multiple of %g"):format(t, ax.step))
      if i > 1 then T.near(t - ax.ticks[i - 1], ax.step, ax.step * 1e-9 + math.abs(t) * 1e-14, "spacing") end
    end
  end
end)

T.case("tick labels: decimals follow the step, no '-0'", function()
  local ax = axis.linear(-0.93, 1.07)
  local labels = {}
  for i, t in ipairs(ax.ticks) do labels[i] = axis.label(t, ax) end
  T.eq(table.concat(labels, " "), "-1.0 -0.5 0 0.5 1.0 1.5", "labels")
  local lg = axis.log(0.003, 250)
  T.eq(lg.ticks[1], 0.001, "first decade")
  T.eq(lg.ticks[#lg.ticks], 1000.0, "last decade")
end)

T.case("a line has one path point per value, at the right pixels", function()
  local n = 50
  local x, y = {}, {}
  for i = 1, n do x[i] = (i - 1) / (n - 1); y[i] = x[i] ^ 2 end
  local c = svg.chart{ title = "parabola", xlabel = "x", ylabel = "y", xlim = { 0, 1 }, ylim = { 0, 1 } }
  c:line(x, y, { label = "x^2" })
  local root = parse(c:render())
  local paths = by_class(root, "path", "line")
  T.eq(#paths, 1, "one series path")
  local pts, m = path_points(paths[1].attrs.d)
  T.eq(#pts, n, "points")
  T.eq(m, 1, "one subpath")
  local fx, fy, fw, fh = frame(root)
  for i = 1, n do
    T.near(pts[i].x, fx + x[i] * fw, 0.01, "pixel x " .. i)
    T.near(pts[i].y, fy + fh - y[i] * fh, 0.01, "pixel y " .. i)
  end
end)

T.case("NaN and inf break the line and are reported, never written", function()
  local x, y = {}, {}
  for i = 1, 40 do x[i] = i; y[i] = math.sin(i / 5) end
  y[10], y[11], x[25] = 0 / 0, math.huge, -math.huge
  local c = svg.chart{ title = "gaps" }
  c:line(smi.vec(x), smi.vec(y), { label = "sine" })
  local s = c:render()
  T.truthy(not s:find("nan", 1, true) and not s:find("inf", 1, true), "no nan/inf text in the SVG")
  local root = parse(s)
  local pts, m = path_points(by_class(root, "path", "line")[1].attrs.d)
  T.eq(#pts, 37, "finite points drawn")
  T.eq(m, 3, "three runs")
  local notes = by_class(root, "text", "note")
  T.eq(#notes, 1, "one note")
  T.truthy(X.text(notes[1]):find("3 of 40 point(s) of 'sine'", 1, true), "note text: " .. X.text(notes[1]))
end)

T.case("a series with no finite value still gives a valid chart", function()
  local c = svg.chart{ title = "empty" }
  c:line({ 0 / 0, 0 / 0 }, { 1, 2 }):scatter({}, {})
  local root = parse(c:render())
  local text = X.text(root)
  T.truthy(text:find("no finite data", 1, true), "says so")
end)

T.case("step curve and ECDF", function()
  local c = svg.chart{ title = "steps" }
  c:step({ 1, 2, 3, 4 }, { 0.1, 0.5, 0.7, 1.0 }, { label = "s" })
  local root = parse(c:render())
  local pts = path_points(by_class(root, "path", "step")[1].attrs.d)
  T.eq(#pts, 7, "2n-1 points")
  for i = 2, #pts do T.truthy(pts[i].x == pts[i - 1].x or pts[i].y == pts[i - 1].y, "axis-parallel segment " .. i) end

  local data = { 3.2, -1, 0.5, 2.2, 0 / 0, 1.7 }
  local e = svg.chart{ title = "ecdf", ylim = { 0, 1 } }
  e:ecdf(data, { label = "sample" })
  root = parse(e:render())
  local fx, fy, fw, fh = frame(root)
  pts = path_points(by_class(root, "path", "step")[1].attrs.d)
  T.eq(#pts, 2 * 5 + 2, "2n+2 points for 5 finite values")
  T.near(pts[1].x, fx, 0.01, "starts at the left edge")
  T.near(pts[1].y, fy + fh, 0.01, "at F = 0")
  T.near(pts[#pts].x, fx + fw, 0.01, "ends at the right edge")
  T.near(pts[#pts].y, fy, 0.01, "at F = 1")
  for i = 2, #pts do T.truthy(pts[i].y <= pts[i - 1].y + 1e-9 and pts[i].x >= pts[i - 1].x - 1e-9, "monotone " .. i) end
  T.truthy(X.text(root):find("1 non-finite value(s) of 'sample'", 1, true), "NaN noted")
end)

T.case("scatter, diagonal, threshold markers", function()
  local obs, pred = { 1, 2, 3, 4, 5 }, { 1.1, 1.9, 3.2, 0 / 0, 5.1 }
  local c = svg.chart{ title = "LOO", equal = true }
  c:scatter(obs, pred, { label = "LOO" }):diagonal{ label = "y = x" }:hline(2.5, { label = "limit" }):vline(4)
  local root = parse(c:render())
  local g = by_class(root, "g", "scatter")[1]
  T.eq(#X.find_all(g, "circle"), 4, "finite points only")
  local d = by_class(root, "line", "mark-diagonal")[1]
  -- equal axes: the diagonal runs corner to corner of the plot frame
  local fx, fy, fw, fh = frame(root)
  T.near(tonumber(d.attrs.x1), fx, 0.01, "diagonal x1")
  T.near(tonumber(d.attrs.y1), fy + fh, 0.01, "diagonal y1")
  T.near(tonumber(d.attrs.x2), fx + fw, 0.01, "diagonal x2")
  T.near(tonumber(d.attrs.y2), fy, 0.01, "diagonal y2")
  local legend = by_class(root, "g", "legend")[1]
  local names = {}
  for _, t in ipairs(X.find_all(legend, "text")) do names[#names + 1] = X.text(t) end
  T.eq(table.concat(names, "|"), "LOO|y = x", "legend entries")
  local h = by_class(root, "line", "mark-hline")[1]
  T.eq(h.attrs.y1, h.attrs.y2, "horizontal")
  local v = by_class(root, "line", "mark-vline")[1]
  T.eq(v.attrs.x1, v.attrs.x2, "vertical")
end)

T.case("rug ticks and points beyond caller limits", function()
  local c = svg.chart{ title = "rug", xlim = { 0, 3 }, ylim = { 0, 1 } }
  c:line({ 0, 3 }, { 0, 1 }):rug({ 0.5, 1, 0 / 0, 2.5 }, { label = "data" }):scatter({ 1, 2, 5 }, { 0.5, 0.5, 0.5 }, { label = "pts" })
  local root = parse(c:render())
  local fx, fy, fw, fh = frame(root)
  local ticks = X.find_all(by_class(root, "g", "rug")[1], "line")
  T.eq(#ticks, 3, "finite rug values")
  T.near(tonumber(ticks[2].attrs.x1), fx + fw / 3, 0.01, "rug tick at x = 1")
  T.near(tonumber(ticks[2].attrs.y1), fy + fh, 0.01, "at the foot")
  local markers = 0
  for _, ch in ipairs(by_class(root, "g", "scatter")[1].children) do if type(ch) == "table" then markers = markers + 1 end end
  T.eq(markers, 2, "point at x = 5 left out")
  T.truthy(X.text(root):find("1 point(s) of 'pts' outside the axis limits", 1, true), "and noted")
  T.truthy(X.text(root):find("1 of 4 point(s) of 'data' not drawn", 1, true), "NaN in the rug noted")
end)

T.case("a band is one polygon per finite run", function()
  local x, lo, hi = {}, {}, {}
  for i = 1, 10 do x[i] = i; lo[i] = -i; hi[i] = i end
  hi[5] = 0 / 0
  local c = svg.chart{ title = "band" }
  c:band(x, lo, hi, { label = "band" })
  local root = parse(c:render())
  local d = by_class(root, "path", "band")[1].attrs.d
  local pts, m = path_points(d)
  T.eq(m, 2, "two polygons around the NaN")
  T.eq(#pts, 2 * 4 + 2 * 5, "lower and upper points of both runs")
  local closes = 0
  for _ in d:gmatch("Z") do closes = closes + 1 end
  T.eq(closes, 2, "closed")
  T.truthy(X.text(root):find("1 of 10 point(s) of 'band'", 1, true), "NaN noted")
end)

T.case("text is escaped and invalid bytes cannot break the document", function()
  local title = 'Q<sub> & "R" > 0'
  local c = svg.chart{ title = title, xlabel = "x \1\2 \255\254", ylabel = "<y>" }
  c:line({ 1, 2 }, { 3, 4 }, { label = "a&b" })
  local s = c:render()
  local root = parse(s)
  T.eq(X.text(by_class(root, "text", "title")[1]), title, "title round-trips")
  T.eq(X.text(by_class(root, "text", "ylabel")[1]), "<y>", "ylabel round-trips")
  T.truthy(s:find("a&amp;b", 1, true), "legend escaped")
end)

T.case("horizontal bars: sorted, proportional, labelled, n/a for NaN", function()
  local labels = { "b", "a<1>", "c", "d", "e" }
  local values = { 0.2, 0.8, 0 / 0, 0.4, -0.1 }
  local s = svg.bars{ labels = labels, values = values, sort = true, title = "S", highlight = { b = true }, threshold = 0.3, threshold_label = "cut" }
  local root = parse(s)
  local order = {}
  for i, t in ipairs(by_class(root, "text", "bar-label")) do order[i] = X.find_all(t, "title")[1] and X.text(X.find_all(t, "title")[1]) end
  T.eq(table.concat(order, ","), "a<1>,d,b,e,c", "sorted largest first, NaN last")
  local bars = by_class(root, "rect", "bar")
  T.eq(#bars, 4, "four finite bars")
  T.near(tonumber(bars[1].attrs.width) / tonumber(bars[2].attrs.width), 0.8 / 0.4, 0.01, "widths proportional")
  T.eq(bars[3].attrs.fill, "#D55E00", "highlighted bar")
  local zero = tonumber(bars[1].attrs.x)
  T.truthy(tonumber(bars[4].attrs.x) < zero, "negative bar left of zero")
  T.truthy(X.text(root):find("n/a", 1, true), "n/a shown")
  T.eq(#by_class(root, "line", "mark-vline"), 1, "threshold line")
end)

T.case("grouped bars need one value per label", function()
  T.raises(function() svg.bars{ labels = { "a", "b" }, series = { { values = { 1, 2 } }, { values = { 1 } } } } end, "series 2 has 1 values for 2 labels")
  T.raises(function() svg.chart{}:line({ 1, 2, 3 }, { 1, 2 }) end, "x has 3 values but y has 2")
  T.raises(function() svg.chart{}:hline(0 / 0) end, "finite")
  T.raises(function() svg.chart{}:line(3, { 1 }) end, "expected a smi.vec or a table")
end)

T.case("log axes drop values <= 0 with a note", function()
  local c = svg.chart{ title = "history", ylog = true }
  c:line({ 1, 2, 3, 4 }, { 10, 1, 0, 0.01 }, { label = "f" })
  local root = parse(c:render())
  local pts = path_points(by_class(root, "path", "line")[1].attrs.d)
  T.eq(#pts, 3, "three positive values")
  T.truthy(X.text(root):find("not positive on a log axis", 1, true), "note")
end)

T.case("fuzz: extreme and non-finite values never give invalid SVG", function()
  local rng = smi.rng(3)
  local pool = { 0 / 0, math.huge, -math.huge, 1.7e308, -1.7e308, 1e-308, 0, -0.0, 1, -1, 5e-324, 42, 1e15, 1e15 + 1 }
  for trial = 1, 150 do
    local n = 1 + trial % 7
    local pick = rng:integers(4 * n, 1, #pool)
    local x, y, y2 = {}, {}, {}
    for i = 1, n do x[i], y[i], y2[i] = pool[pick[i]], pool[pick[n + i]], pool[pick[2 * n + i]] end
    local c = svg.chart{ title = "fuzz", xlog = trial % 5 == 0, ylog = trial % 3 == 0 }
    c:line(x, y):scatter(y, x):step(x, y):band(x, y, y2):rug(y2)
    if trial % 2 == 0 then c:ecdf(y) end
    local s = c:render()
    local ok, err = X.check(s)
    T.truthy(ok, "trial " .. trial .. ": " .. tostring(err))
    local bad = s:lower():match("[^%a](nan)[^%a]") or s:lower():match("[^%a](inf)[^%a]")
    T.truthy(not bad, "trial " .. trial .. ": non-finite number written")
    local b = svg.bars{ labels = { "a", "b", "c" }, values = { pool[pick[1]], pool[pick[2]], pool[pick[3]] } }
    T.truthy(X.check(b), "bars trial " .. trial)
    T.truthy(not b:lower():match("[^%a]nan[^%a]") and not b:lower():match("[^%a]inf[^%a]"), "bars trial " .. trial .. ": non-finite")
  end
end)

T.case("several charts on one page get distinct clip ids", function()
  local a = svg.chart{}:line({ 1, 2 }, { 1, 2 }):render()
  local b = svg.chart{}:line({ 1, 2 }, { 1, 2 }):render()
  T.truthy(a:match('clipPath id="([^"]+)"') ~= b:match('clipPath id="([^"]+)"'), "ids differ")
end)

T.finish()
