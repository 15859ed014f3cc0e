-- SPDX-License-Identifier: MIT
-- smi.report: one verdict list (every check once, one status), "not run" and
-- "inconclusive" statuses, the header's counts, a verdict contradicting its solver check says
-- which governs, numbers in text without binary noise, units beside numbers, tables that wrap.
local T = require "smi.testing"
local report = require "smi.report"
local X = require "smi.report.xmlcheck"
local fmt = require "smi.report.format"
local by_class = X.find_by_class

local function page()
  local r = report.new{ title = "Verdicts", date = "2026-01-01 00:00 UTC" }
  r:section("Validation")
  r:verdict{ name = "Mode 1", pass = true, detail = "U = 0.05 <= 0.19" }
  r:verdict{ name = "Mode 2", status = "inconclusive", detail = "U in [0.1, 0.3]",
             checks = { { name = "Solver check", pass = false, detail = "U = 0.31" } } }
  r:verdict{ name = "Mode 4", status = "fail", detail = "U = 0.4",
             checks = { { name = "Solver check", pass = true } },
             governs = "The solver check governs: it runs the model itself." }
  r:verdict{ name = "Trial 3", status = "skip", detail = "trial 2 is valid" }
  r:verdict{ name = "Mode 1", pass = true, detail = "U = 0.051 <= 0.19 (rerun)" } -- replaces the first
  r:callout("Data: a spread of 1.4999999999999998e-09 s", "warn")
  r:table{ caption = "Frequencies with 7790.000000000005 in the caption", columns = { "Mode", { title = "Mean", unit = "Hz" } },
           rows = { { "mode 1", 31.840000000000003 }, { "mode 2", 7790.000000000005 } } }
  r:provenance{ step = 1.4999999999999998e-09, density = 7790.000000000005, seed = 20200214 }
  return r
end

T.case("every verdict once, with one status; the header counts all statuses", function()
  local r = page()
  local root = X.parse(r:html())
  local summary = by_class(root, "section", "summary")[1]
  local items = X.find_all(X.find_all(summary, "ul")[1], "li")
  T.eq(#items, 4, "Mode 1 given twice is listed once")
  local badges = {}
  for i, li in ipairs(items) do badges[i] = X.text(by_class(li, "span", "badge")[1]) end
  T.eq(table.concat(badges, ","), "PASS,INCONCLUSIVE,FAIL,NOT RUN", "one status each")
  T.eq(#by_class(root, "div", "verdict"), 4, "four verdict blocks in the body")
  local header = X.text(X.find_all(root, "header")[1])
  T.truthy(header:find("1 passed, 1 failed, 1 warning, 1 inconclusive, 1 not run", 1, true), "counts: " .. header)
  local n = r:tally()
  T.eq(n.pass + n.fail + n.warn + n.inconclusive + n.skip, 5, "counts")
  T.eq(r:data().verdicts[1].detail, "U = 0.051 <= 0.19 (rerun)", "the later verdict replaced the earlier")
end)

T.case("a verdict that contradicts its check says which governs", function()
  local d = page():data()
  T.truthy(d.verdicts[2].disagrees, "inconclusive vs solver FAIL disagree")
  T.truthy(d.verdicts[2].governs:find("does not say which governs", 1, true), "default sentence: " .. tostring(d.verdicts[2].governs))
  T.eq(d.verdicts[3].governs, "The solver check governs: it runs the model itself.", "the study's sentence kept")
  T.eq(d.verdicts[1].governs, nil, "no contradiction, no sentence")
  local root = X.parse(page():html())
  T.eq(#by_class(root, "div", "governs"), 2, "both sentences on the page")
  T.raises(function() report.new{ title = "x" }:verdict{ name = "a", pass = true, checks = { { pass = true } } } end, "needs a name")
  T.raises(function() report.new{ title = "x" }:verdict{ name = "a", status = "maybe" } end, "inconclusive")
end)

T.case("numbers: no binary noise in text, units beside them", function()
  T.eq(fmt.exact(1.4999999999999998e-09), "1.5e-09", "exact")
  T.eq(fmt.exact(7790.000000000005), "7790", "exact whole")
  T.eq(fmt.tidy("a 7790.000000000005 b 0.30000000000000004, v1.2.3 sha 12345678901.5x 3.25"),
       "a 7790 b 0.3, v1.2.3 sha 12345678901.5x 3.25", "tidy keeps words, versions and short numbers")
  T.eq(fmt.num(31.84, 4, "Hz"), "31.84 Hz", "unit")
  local html = page():html()
  for num in html:gmatch("%d[%d.]*%d") do
    local sig = num:gsub("%.", ""):gsub("^0+", "")
    if num:find("%.") and not num:find("%..*%.") then T.truthy(#sig <= 10, "a number with more than 10 digits: " .. num) end
  end
  T.truthy(html:find("<th class=\"num\">Mean (Hz)</th>", 1, true), "unit in the header")
  T.truthy(html:find('<div class="table-wrap"><table', 1, true), "tables sit in a wrapping box")
end)

T.case("a step that did not run says 'not run' and why", function()
  local study = require "smi.study"
  os.remove(smi.out("notrun.json"))  -- a rerun of this file on the same build would reuse step a
  local s = study.new{ name = "notrun", out = smi.out(), results = smi.out("notrun.json"), quiet = true,
                       report = { title = "not run" } }
  s:step("a", function() return { x = 1 } end)
  s:step("b", function(ctx) return ctx:skip("trial 2 is valid") end)
  s:step("c", function() return { skipped = true, reason = "nothing to refine" } end)
  s:run()
  local saved = s:load()
  T.eq(saved.steps.b.not_run, "trial 2 is valid", "recorded")
  T.eq(saved.steps.c.not_run, "nothing to refine", "the plain record too")
  T.eq(saved.steps.a.not_run, nil, "a ran")
  local root = X.parse(s.report:html())
  local steps  -- the study's step table (the Provenance table comes after it)
  for _, t in ipairs(X.find_all(root, "table")) do
    if X.text(X.find_all(t, "caption")[1]):find("Steps of this run", 1, true) then steps = t end
  end
  local rows = X.find_all(X.find_all(steps, "tbody")[1], "tr")
  local function status(tr) return X.text(X.find_all(tr, "td")[2]) end
  T.eq(status(rows[1]), "PASSran", "a")
  T.eq(status(rows[2]), "NOT RUNtrial 2 is valid", "b")
  T.eq(status(rows[3]), "NOT RUNnothing to refine", "c")
end)
T.case("superseded sections: kept, headed, not counted; the header counts the final trial", function()
  local r = require("smi.report").new{ title = "trials" }
  r:section("Trial 1"):verdict{ name = "Mode 1, trial 1", pass = false }:verdict{ name = "Mode 2, trial 1", pass = false }
  r:callout("input 'E' at its bound 1.5", "warn")
  r:section("Trial 2"):verdict{ name = "Mode 1, trial 2", pass = true }:verdict{ name = "Mode 2, trial 2", pass = true }
  r:callout("input 'E' at its bound 2.5", "warn")
  r:callout("input 'nu' at its bound 0.3", "warn")
  T.eq(select(2, r:tally()), "2 passed, 2 failed, 1 warning, 0 inconclusive", "before: every trial counts")
  r:supersede("Trial 1", "revised in trial 2")
  T.eq(select(2, r:tally()), "2 passed, 0 failed, 1 warning, 0 inconclusive", "after: the final trial only")
  local g = r:warning_groups()
  T.eq(#g, 1, "one warning, given per trial and per input")
  T.eq(g[1].count, 3) T.eq(#g[1].texts, 3) T.eq(table.concat(g[1].where, "; "), "1 Trial 1; 2 Trial 2")
  local root = X.parse(r:html())
  local note = X.text(by_class(root, "div", "superseded")[1])
  T.truthy(note:find("revised in trial 2", 1, true), note)
  T.raises(function() r:supersede("Trial 9") end, "no section 'Trial 9' (sections: Trial 1, Trial 2)")
end)

T.case("the summary opens the page: conclusion, form, verdicts, parameters with intervals and priors, what is open", function()
  local r = require("smi.report").new{ title = "answer" }
  r:section("Data"):text("...")
  r:summary{ conclusion = "The model is valid after one revision.", form = "trial 2: E and t calibrated",
             verdicts = { { name = "Mode 1", status = "pass", detail = "U = 0.05" } },
             parameters = { { name = "E", unit = "GPa", mean = 207.25, std = 3.125, interval = { 201, 213.5 }, prior = "normal(210, 10)" },
                            { name = "t", unit = "mm", mean = 3.8, std = 0.02, interval = { 3.76, 3.84 } } },
             open = { { question = "Mode 4 rests on 9 tests", settle = "nine more tests of mode 4" } } }
  local html = r:html()
  local at_summary, at_data = html:find('id="summary"', 1, true), html:find(">Data</h2>", 1, true)
  T.truthy(at_summary and at_data and at_summary < at_data, "the summary comes before the story")
  local root = X.parse(html)
  local t = X.find_all(by_class(root, "section", "answer")[1], "table")[1]
  local cells = {}
  for _, td in ipairs(X.find_all(X.find_all(t, "tbody")[1], "td")) do cells[#cells + 1] = X.text(td) end
  T.eq(table.concat(cells, "|"), "E (GPa)|207.2|3.125|[201, 213.5]|normal(210, 10)|t (mm)|3.8|0.02|[3.76, 3.84]|not declared")
  T.raises(function() r:summary{ form = "x" } end, "'conclusion' is missing")
end)

T.case("a point estimate apart from the interval's distribution: its own column, marked where it lies outside", function()
  local r = require("smi.report").new{ title = "estimate" }
  r:summary{ conclusion = "The model is undetermined.", detail = "mode 2 is not determined by these data",
             parameters = { { name = "E", estimate = 199.5, mean = 207.25, std = 3.125, interval = { 201, 213.5 } },
                            { name = "t", estimate = 3.81, mean = 3.8, std = 0.02, interval = { 3.76, 3.84 } },
                            { name = "k", mean = 1.5, std = 0.1, interval = { 1.3, 1.7 } } } }
  local root = X.parse(r:html())
  local answer = by_class(root, "section", "answer")[1]
  T.eq(X.text(by_class(answer, "p", "detail")[1]), "mode 2 is not determined by these data")
  local t = X.find_all(answer, "table")[1]
  local heads, cells = {}, {}
  for _, th in ipairs(X.find_all(X.find_all(t, "thead")[1], "th")) do heads[#heads + 1] = X.text(th) end
  for _, td in ipairs(X.find_all(X.find_all(t, "tbody")[1], "td")) do cells[#cells + 1] = X.text(td) end
  T.eq(table.concat(heads, "|"), "Parameter|Estimate|Mean|Std|95 % interval")
  -- 199.5 < 201: outside its interval, marked; 3.81 inside, not marked; k has no estimate
  T.eq(table.concat(cells, "|"), "E|199.5 †|207.2|3.125|[201, 213.5]|t|3.81|3.8|0.02|[3.76, 3.84]|k||1.5|0.1|[1.3, 1.7]")
  T.raises(function() r:summary{ conclusion = "x", parameters = { { name = "E", estimate = "high" } } } end,
    "parameters[1] ('E'): estimate must be a number")
end)

T.finish()
