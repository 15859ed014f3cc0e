-- SPDX-License-Identifier: MIT
-- smi.report: the page is well-formed, self-contained, escapes what callers give it, numbers and
-- links its parts, formats table numbers, and its JSON holds the numbers.
local T = require "smi.testing"
local report = require "smi.report"
local X = require "smi.report.xmlcheck"
local json = require "smi.report.json"

local function sample()
  local r = report.new{ title = "Beam <study> & co", subtitle = "trial 1", date = "2026-01-01 00:00 UTC" }
  r:section("Data"):text("First paragraph.\n\n<script>alert(1)</script> second & last.")
  r:table{ caption = "Inputs", columns = { "Name", "Mean", { title = "Std", digits = 2 }, "Count" },
           rows = { { "E", 1.5, 0.123, 3 }, { "t<1>", 22.25, 0 / 0, 12 }, { "rho", 3, 1 / 0, 7 } } }
  r:subsection("Plots")
  local c = report.svg.chart{ title = "c" }
  c:line({ 1, 2, 3 }, { 1, 4, 9 })
  r:figure(c:render(), "Squares & cubes")
  r:figures{ { c:render(), "left" }, { c:render(), "right" } }
  r:section("Validation")
  r:verdict{ name = "Mode 1", pass = true, value = 0.012, threshold = 0.05, detail = "area 0.012 <= 0.05" }
  r:verdict{ name = "Mode 4", pass = false, value = 0.09, threshold = 0.05 }
  r:verdict{ name = "Bounds", status = "warn", detail = "optimum on a bound" }
  r:callout("check <this>", "warn")
  r:provenance{ seed = 42, versions = { ["smi-lua"] = "0.1.0" }, solver_runs = { fe = 120 }, inputs = { ["data.csv"] = "sha256:ab12" } }
  r:result("calibration.mean", 2.07e11)
  r:result("calibration.std", 3.1e9)
  return r
end

local by_class = X.find_by_class

T.case("the page is well-formed and self-contained", function()
  local s = sample():html()
  T.truthy(s:sub(1, 15) == "<!DOCTYPE html>", "doctype")
  local ok, err = X.check(s)
  T.truthy(ok, "well-formed: " .. tostring(err))
  local root = X.parse(s)
  T.eq(#X.find_all(root, "script"), 0, "no script element")
  T.eq(#X.find_all(root, "link"), 0, "no link element")
  T.eq(#X.find_all(root, "img"), 0, "no img element")
  T.eq(#X.find_all(root, "svg"), 3, "inline SVGs")
  for _, e in ipairs(X.find_all(root, "a")) do T.eq(e.attrs.href:sub(1, 1), "#", "links stay in the page") end
  T.truthy(not s:find("url%(http") and not s:find('src="http'), "no remote resources")
end)

T.case("caller text is escaped", function()
  local root = X.parse(sample():html())
  T.eq(X.text(X.find_all(root, "h1")[1]), "Beam <study> & co", "title")
  local ps = X.find_all(root, "p")
  local found = false
  for _, p in ipairs(ps) do if X.text(p) == "<script>alert(1)</script> second & last." then found = true end end
  T.truthy(found, "second paragraph kept as text")
end)

T.case("contents link to every section, numbered", function()
  local root = X.parse(sample():html())
  local ids = {}
  for _, tag in ipairs{ "h2", "h3" } do for _, h in ipairs(X.find_all(root, tag)) do if h.attrs.id then ids[h.attrs.id] = X.text(h) end end end
  local nav = X.find_all(root, "nav")[1]
  local links = X.find_all(nav, "a")
  T.eq(#links, 5, "Data, Plots, Validation, Warnings and Run details")
  T.eq(links[4].attrs.href, "#warnings", "the warnings, listed at the end")
  for _, a in ipairs(links) do T.truthy(ids[a.attrs.href:sub(2)], "target exists: " .. a.attrs.href) end
  T.eq(ids[links[2].attrs.href:sub(2)], "1.1Plots", "subsection numbered 1.1")
end)

T.case("table numbers: aligned decimals, NaN and inf visible", function()
  local root = X.parse(sample():html())
  local tbl = X.find_all(root, "table")[1]
  local rows = X.find_all(X.find_all(tbl, "tbody")[1], "tr")
  T.eq(#rows, 3, "rows")
  local function cells(tr) local t = {} for i, td in ipairs(X.find_all(tr, "td")) do t[i] = X.text(td) end return t end
  T.eq(table.concat(cells(rows[1]), "|"), "E|1.50|0.12|3", "row 1 (Std: 2 digits)")
  T.eq(table.concat(cells(rows[2]), "|"), "t<1>|22.25|NaN|12", "row 2")
  T.eq(table.concat(cells(rows[3]), "|"), "rho|3.00|inf|7", "row 3")
  T.eq(X.find_all(rows[1], "td")[2].attrs.class, "num", "numeric cells right-aligned")
  T.truthy(X.text(X.find_all(tbl, "caption")[1]):find("Table 1.", 1, true), "numbered caption")
  -- a column mixing magnitudes (rows in different units) keeps significant digits per value
  local fmt = require "smi.report.format"
  local f = fmt.column({ 205.1, 2.02, 3.41 }, 4)
  T.eq(f(205.1) .. " " .. f(2.02), "205.1 2.02", "mixed magnitudes")
  f = fmt.column({ 31.36, 58.2, 55 }, 4)
  T.eq(f(58.2) .. " " .. f(55), "58.20 55.00", "aligned decimals")
end)

T.case("format.num: significant digits, scientific at the extremes", function()
  local fmt = require "smi.report.format"
  local got = {}
  for i, x in ipairs{ 3.14159265, 2.07e11, 1.5e-5, -0.00123456, 123456.7, 42, 0.1 + 0.2, 0 / 0, -math.huge, -0.0 } do got[i] = fmt.num(x) end
  T.eq(table.concat(got, " "), "3.142 2.07e11 1.5e-5 -0.001235 123457 42 0.3 NaN -inf 0", "formats")
  T.eq(fmt.num(2 / 3, 2), "0.67", "two digits")
end)

T.case("verdicts: badges and summary", function()
  local root = X.parse(sample():html())
  local summary = by_class(root, "section", "summary")[1]
  local items = X.find_all(X.find_all(summary, "ul")[1], "li")
  T.eq(#items, 3, "three verdicts listed")
  T.eq(X.text(by_class(items[1], "span", "badge")[1]), "PASS", "first passes")
  T.eq(X.text(by_class(items[2], "span", "badge")[1]), "FAIL", "second fails")
  T.eq(X.text(by_class(items[3], "span", "badge")[1]), "WARNING", "third warns")
  T.eq(#by_class(root, "div", "fail"), 1, "one failing verdict block")
  T.truthy(X.text(X.find_all(root, "header")[1]):find("1 passed, 1 failed", 1, true), "count in the title block")
end)

T.case("figures are numbered in order, captions escaped", function()
  local root = X.parse(sample():html())
  local caps = X.find_all(root, "figcaption")
  T.eq(#caps, 3, "three figures")
  T.eq(X.text(caps[1]), "Figure 1. Squares & cubes", "first")
  T.eq(X.text(caps[3]), "Figure 3. right", "third")
end)

T.case("provenance is listed", function()
  local root = X.parse(sample():html())
  local dl = by_class(root, "dl", "prov")[1]
  local kv = {}
  local dts, dds = X.find_all(dl, "dt"), X.find_all(dl, "dd")
  for i = 1, #dts do kv[X.text(dts[i])] = X.text(dds[i]) end
  T.eq(kv.seed, "42", "seed")
  T.eq(kv["versions.smi-lua"], "0.1.0", "version")
  T.eq(kv["solver_runs.fe"], "120", "runs")
  T.eq(kv["inputs.data.csv"], "sha256:ab12", "input hash")
end)

T.case("bad arguments name the problem", function()
  T.raises(function() report.new{} end, "'title' is required")
  local r = report.new{ title = "x" }
  T.raises(function() r:figure("<svg><g></svg>", "broken") end, "not well-formed")
  T.raises(function() r:figure("hello", "x") end, "expects an SVG string")
  r:figure(report.svg.chart{ title = "as object" }:line({ 1, 2 }, { 2, 1 }), "a chart object is rendered")
  T.truthy(r:html():find("as object", 1, true), "chart object accepted")
  T.raises(function() r:verdict{ name = "v" } end, "pass = true/false")
  T.raises(function() r:verdict{ name = "v", status = "ok" } end, "status must be")
  T.raises(function() r:table{ columns = { "a" }, rows = { 3 } } end, "row 1 is a number")
end)

T.case("write() and write_json(): files with the page and the numbers", function()
  local r = sample()
  local dir = smi.out_dir or "."
  local path = r:write(dir .. "/test_report_html.html")
  local f = assert(io.open(path, "rb"))
  local text = f:read("a")
  f:close()
  T.eq(text, r:html(), "file holds the page")
  local jpath = r:write_json(dir .. "/test_report_html.json")
  f = assert(io.open(jpath, "rb"))
  local d = json.decode(f:read("a"))
  f:close()
  T.eq(d.title, "Beam <study> & co", "title")
  T.eq(d.results.calibration.mean, 2.07e11, "recorded result")
  T.eq(d.verdicts[2].value, 0.09, "verdict value")
  T.eq(d.verdicts[2].status, "fail", "verdict status")
  T.eq(d.tables[1].rows[2][2], 22.25, "table number")
  T.truthy(d.tables[1].rows[2][3] ~= d.tables[1].rows[2][3], "NaN cell read back as NaN")
  T.eq(d.tables[1].rows[3][3], math.huge, "inf cell read back as inf")
  T.eq(d.provenance.solver_runs.fe, 120, "provenance")
  os.remove(path)
  os.remove(jpath)
end)

T.finish()
