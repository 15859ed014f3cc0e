-- SPDX-License-Identifier: MIT
-- smi.doc: the parser of the reference texts, lookup by value and by name, search, and the
-- coverage walk (a function added at run time without a text is reported).
local T = require "smi.testing"
local doc = require "smi.doc"

T.case("an entry holds signature, summary, options with defaults, returns, errors, example", function()
  local e = doc.get("smi.kde_bd")
  T.eq(e.signature, "smi.kde_bd(data, opts) -> dist, info")
  T.eq(e.kind, "function")
  local by = {}
  for _, o in ipairs(e.options) do by[o.name] = o end
  T.eq(by.critical_area.default, "0.95", "critical_area default (BoundedKdeOptions)")
  T.eq(by.compare.default, '"previous"')
  T.truthy(by.lower.meaning:find("lower bound", 1, true), "meaning of lower")
  T.truthy(e.returns and e.errors and e.example, "sections")
  -- a continuation line joins the previous option's meaning
  local k = doc.get("smi.kde")
  for _, o in ipairs(k.options) do
    if o.name == "method" then T.truthy(o.meaning:find("for large data", 1, true), o.meaning) end
  end
end)

T.case("lookup by value: functions, methods, stdlib functions, modules", function()
  T.eq(doc.get(smi.kde).name, "smi.kde")
  T.eq(doc.get(smi.vec{1}.mean).name, "smi.vec:mean")
  T.eq(doc.get(require("smi.report").new).name, "smi.report.new")
  T.eq(doc.get(smi.dist).name, "smi.dist")
  T.eq(doc.get(print), nil)
end)

T.case("help text: by value, by name, by expression, search, overview", function()
  T.truthy(doc.help_text(smi.kde):find("^smi%.kde%(data"), "help(smi.kde)")
  T.truthy(doc.help_text("smi.rng"):find("^smi%.rng%(seed"), "help 'smi.rng'")
  _G.doc_test_vec = smi.vec{1, 2}
  T.truthy(doc.help_text("doc_test_vec:quantile"):find("^smi%.vec:quantile"), "an expression the user holds")
  _G.doc_test_vec = nil
  local s = doc.help_text("bandwidth")
  T.truthy(s:find("entries mention 'bandwidth'", 1, true), s)
  T.truthy(s:find("smi.bandwidth", 1, true) < s:find("smi.kde_ebd", 1, true), "exact name match ranks first")
  T.truthy(doc.help_text(require("smi.report").new{title = "t"}):find("^smi%.report\n"), "a report object")
  T.truthy(doc.help_text(smi.vec{1}):find("^smi%.vec%("), "a vec")
  T.truthy(doc.help_text(42):find("no doc text for this number", 1, true), "a number")
  T.truthy(doc.help_text("zzzunknownword"):find("nothing documented mentions", 1, true), "no hit")
  local o = doc.help_text()
  T.truthy(o:find("smi.calibrate", 1, true) and o:find("smi.study", 1, true), "overview lists modules")
end)

T.case("the walk finds a function added without a text, and a text without a function", function()
  local missing, stale = doc.missing()
  T.eq(#missing, 0, "missing: " .. table.concat(missing, ", "))
  T.eq(#stale, 0, "stale: " .. table.concat(stale, ", "))
  smi.metric.brand_new = function() end
  missing = doc.missing()
  smi.metric.brand_new = nil
  T.eq(missing[1], "smi.metric.brand_new")
  doc.add("@ smi.nothing_here(x)\nA text whose function does not exist.\nreturns: x\nerrors: none\nexample:\n  print(1)\n")
  local _, st = doc.missing()
  T.eq(st[1], "smi.nothing_here")
end)

T.case("a malformed text is refused with its source and entry named", function()
  doc.add("@ smi.bad_entry(x)\nSummary.\noptions:\n  this line is not an option\n")
  local ok, err = pcall(doc.list)
  T.truthy(not ok and err:find("smi.bad_entry", 1, true) and err:find("name = default  -- meaning", 1, true), tostring(err))
end)

T.finish()
