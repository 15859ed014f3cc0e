-- SPDX-License-Identifier: MIT
--- smi.report: a study's report as one self-contained report.html, plus its numbers as JSON.
--
--   local report = require "smi.report"
--   local r = report.new{title = "Steering column: trial 1", subtitle = "Calibration and validation"}
--   r:section("Data") ; r:text("Nine wheel/column combinations ...")
--   r:table{caption = "Calibrated inputs", columns = {"Input", "Mean", {title = "Std", digits = 3}},
--           rows = {{"E", 2.07e11, 3.1e9}, ...}}
--   r:figure(svg_string, "KDE of mode 1")          -- from smi.report.svg
--   r:verdict{name = "Mode 4 validation", pass = false, detail = "area metric 0.031 > 0.02"}
--   r:provenance{seed = 42, versions = {["smi-lua"] = "0.1.0"}, solver_runs = {["smi-column-fe"] = 1200}}
--   r:result("calibration.mean_E", 2.07e11)        -- collected into r:json()
--   r:write("smi-out/study/report.html") ; r:write_json("smi-out/study/report.json")
local html = require "smi.report.html"
local json = require "smi.report.json"
local xmlcheck = require "smi.report.xmlcheck"
local warnings = require "smi.report.warnings"
local summary = require "smi.report.summary"

local doc = require "smi.doc"
doc.add[==[
@ module smi.report
A study's report as one self-contained report.html (inline SVG charts, tables, verdicts,
provenance) plus its numbers as JSON. smi.report.svg draws the charts; smi.study makes one for you
with report = {title = ...}.
]==]
local M = {}
M.svg = require "smi.report.svg"
M.format = require "smi.report.format"
M.json = json

local Report = {}
Report.__index = Report

doc.add[==[
@ smi.report.new(opts) -> report
A new, empty report; add sections, text, tables, figures and verdicts, then r:write().
options:
  title = (required)   -- the page title
  subtitle = nil       -- a line under the title
  author = nil         -- shown under the title
  date = now           -- the date shown (default: now, UTC)
  digits = 4           -- significant digits of numbers in tables
  out = nil            -- the folder r:write() uses when given no path (default smi.out_dir)
returns: a report with the methods smi.report:*
errors: no title
example:
  local r = require("smi.report").new{title = "Bracket study"}
  r:section("Data"):text("Nine measured frequencies.")
  print(#r:html() > 1000)
]==]
--- opts: title (required), subtitle, author, date (default: now, UTC), digits (tables, 4), out (folder).
function M.new(opts)
  opts = opts or {}
  if type(opts.title) ~= "string" or opts.title == "" then
    error("smi.report.new: 'title' is required (a non-empty string), e.g. smi.report.new{title = \"My study\"}", 2)
  end
  local r = setmetatable({ opts = opts, items = {}, prov = {}, results = {}, ids = {},
                           -- the run's warnings from here on are this report's too
                           warnings_from = type(smi) == "table" and type(smi.warnings) == "function" and #smi.warnings() or 0,
                           counts = { section = 0, sub = 0, table = 0, figure = 0, verdict = 0 } }, Report)
  return r
end

-- A unique, readable anchor from a title.
function Report:_id(prefix, title)
  local base = (prefix .. "-" .. tostring(title or "")):lower():gsub("[^%w]+", "-"):gsub("%-+$", ""):sub(1, 48)
  local id, n = base, 1
  while self.ids[id] do n = n + 1; id = base .. "-" .. n end
  self.ids[id] = true
  return id
end

doc.add[==[
@ smi.report:section(title [, opts]) -> report
A numbered section (1, 2, ...), or a subsection with opts.level = 2.
options:
  level = 1     -- 1 (section) or 2 (subsection)
returns: the report (calls chain)
errors: none
example:
  local r = require("smi.report").new{title = "t"}
  print(r:section("Calibration") == r)
]==]
--- A numbered section (level 1) or subsection (opts.level = 2; or use r:subsection).
function Report:section(title, opts)
  local level = opts and opts.level or 1
  local c = self.counts
  local number
  if level == 1 then
    c.section, c.sub = c.section + 1, 0
    number = tostring(c.section)
  else
    c.sub = c.sub + 1
    number = ("%d.%d"):format(c.section, c.sub)
  end
  self.items[#self.items + 1] = { kind = "section", title = tostring(title), level = level, number = number, id = self:_id("s", title) }
  return self
end

doc.add[==[
@ smi.report:subsection(title) -> report
A numbered subsection (2.1, 2.2, ...) of the current section.
returns: the report
errors: none
example:
  local r = require("smi.report").new{title = "t"}
  r:section("Trial 1"):subsection("Surrogate")
  print("ok")
]==]
function Report:subsection(title) return self:section(title, { level = 2 }) end

doc.add[==[
@ smi.report:text(s) -> report
Paragraphs of plain text (blank lines separate paragraphs; the text is escaped, no markup).
returns: the report
errors: none
example:
  local r = require("smi.report").new{title = "t"}
  r:text("Modes 1 and 4 calibrate the model.\n\nMode 2 validates it.")
  print("ok")
]==]
--- Paragraphs of plain text (blank lines separate paragraphs; no markup, it is escaped).
function Report:text(s)
  self.items[#self.items + 1] = { kind = "text", text = tostring(s) }
  return self
end

doc.add[==[
@ smi.report:table(t) -> report
A numbered table. Cells are numbers (formatted with the column's digits, 4 significant by
default, or its format), strings, booleans, or {status = "pass" | "fail" | "warn" | "info" |
"inconclusive" | "skip", text = ...} badges. The table wraps its cells and, when still wider than
the page, scrolls in its own box on screen; printed, it takes the page width.
options:
  columns = (required)  -- {"Name" | {title =, key =, digits =, unit =, format = "%.3f" | function(v)}, ...};
                        -- unit ("Hz") is shown beside the title: "Mode 1 (Hz)"
  rows = (required)     -- {{...} by position | {key = value} by column key, ...}
  caption = nil         -- the caption under "Table N."
  digits = 4            -- significant digits (default: the report's)
returns: the report
errors: no columns or rows; a column that is neither a string nor {title | key}; a row that is not a table
example:
  local r = require("smi.report").new{title = "t"}
  r:table{caption = "Calibrated inputs", columns = {"Input", {title = "Mean", digits = 3}},
          rows = {{"E (MPa)", 246300}, {"t (mm)", 3.83}}}
  print(r:data().tables[1].rows[1][2])
]==]
--- A table. t: columns = {"Name" | {title=, key=, digits=, format="%.3f" | function}},
-- rows = {{...} (by position) | {key = value} (by column key)}, caption, digits (default 4).
-- Cells: numbers (formatted), strings, booleans, {status = "pass"|"fail"|"warn"|"info", text = ...}.
function Report:table(t)
  if type(t) ~= "table" or type(t.columns) ~= "table" or type(t.rows) ~= "table" then
    error("report:table: expects {columns = {...}, rows = {{...}, ...}, caption = ...}", 2)
  end
  local cols = {}
  for j, c in ipairs(t.columns) do
    if type(c) == "string" then c = { title = c } end
    if type(c) ~= "table" or not (c.title or c.key) then
      error(("report:table: column %d must be a string or {title = ..., key = ...}"):format(j), 2)
    end
    c.title = c.title or c.key
    cols[j] = c
  end
  for i, row in ipairs(t.rows) do
    if type(row) ~= "table" then error(("report:table: row %d is a %s, expected a table"):format(i, type(row)), 2) end
  end
  self.counts.table = self.counts.table + 1
  self.items[#self.items + 1] = { kind = "table", columns = cols, rows = t.rows, caption = t.caption,
    digits = t.digits or self.opts.digits or 4, number = self.counts.table, id = self:_id("table", self.counts.table) }
  return self
end

local function check_svg(svg, where)
  if type(svg) == "table" and type(svg.render) == "function" then svg = svg:render() end
  if type(svg) ~= "string" or not svg:match("^%s*<svg") then
    error(where .. ": expects an SVG string (from smi.report.svg), got " .. (type(svg) == "string" and ("'" .. svg:sub(1, 30) .. "'") or type(svg)), 3)
  end
  local ok, err = xmlcheck.check(svg)
  if not ok then error(where .. ": the SVG is not well-formed XML: " .. err, 3) end
  -- The page promises no scripts and no network: an allow-list of static SVG (svgsafe.lua).
  local safe, why = require("smi.report.svgsafe").check(svg)
  if not safe then error(where .. ": " .. why, 3) end
  return svg
end

doc.add[==[
@ smi.report:figure(svg, caption) -> report
A numbered figure: an SVG string (or a chart of smi.report.svg, rendered) and its caption.
returns: the report
errors: not an SVG string; SVG that is not well-formed XML; SVG beyond static graphics (scripts, handlers, links, images, external references)
example:
  local report = require "smi.report"
  local c = report.svg.chart{title = "Line"}
  c:line({0, 1, 2}, {0, 1, 4})
  local r = report.new{title = "t"}
  r:figure(c, "y = x^2")
  print("ok")
]==]
--- A figure: an SVG string (or a chart of smi.report.svg) and its caption; numbered "Figure N.".
function Report:figure(svg, caption)
  svg = check_svg(svg, "report:figure")
  self.counts.figure = self.counts.figure + 1
  self.items[#self.items + 1] = { kind = "figure", svg = svg, caption = caption, number = self.counts.figure,
    id = self:_id("fig", self.counts.figure) }
  return self
end

doc.add[==[
@ smi.report:figures(list) -> report
Several figures side by side (wrapping on narrow pages): {{svg, caption}, ...}.
returns: the report
errors: as smi.report:figure, naming the entry
example:
  local report = require "smi.report"
  local a, b = report.svg.chart{}, report.svg.chart{}
  a:line({0, 1}, {0, 1}); b:line({0, 1}, {1, 0})
  report.new{title = "t"}:figures{{a, "up"}, {b, "down"}}
  print("ok")
]==]
--- Several figures side by side (wrapping on narrow pages): {{svg, caption}, ...}.
function Report:figures(list)
  local figs = {}
  for i, f in ipairs(list) do
    local svg = check_svg(f[1], "report:figures[" .. i .. "]")
    self.counts.figure = self.counts.figure + 1
    figs[i] = { svg = svg, caption = f[2], number = self.counts.figure, id = self:_id("fig", self.counts.figure) }
  end
  self.items[#self.items + 1] = { kind = "figrow", figures = figs }
  return self
end

-- Statuses: pass, fail, warn, info; inconclusive (the check ran and could not decide) and skip
-- (the check did not run; shown "NOT RUN", with its reason as the detail).
local STATUSES = { pass = true, fail = true, warn = true, info = true, inconclusive = true, skip = true }
M.STATUSES = STATUSES
local function status_of(v, where)
  if v.status ~= nil then
    if v.status == "not run" or v.status == "not_run" then return "skip" end
    if not STATUSES[v.status] then
      error(where .. ": status must be \"pass\", \"fail\", \"warn\", \"info\", \"inconclusive\" or \"skip\" (not run), got "
        .. tostring(v.status), 3)
    end
    return v.status
  end
  if type(v.pass) ~= "boolean" then error(where .. ": give pass = true/false (or status = \"warn\"/\"inconclusive\"/...)", 3) end
  return v.pass and "pass" or "fail"
end

-- Two statuses that give opposite answers to the same question (info and not-run answer nothing).
local function disagree(a, b)
  local silent = { info = true, skip = true }
  return a ~= b and not silent[a] and not silent[b]
end

doc.add[==[
@ smi.report:verdict(v) -> report
A verdict with its status badge, also listed once in the verdict list at the top of the page (whose
header counts passes, failures, warnings, inconclusives and checks not run) and printed by
smi.study at the end of a run. A second verdict with the same name replaces the first (in its
place): every check appears once, with one status.
A verdict may carry secondary checks of the same question (a solver check of a surrogate's
verdict): when a check's status disagrees with the verdict's, `governs` says which one governs
and why; without it the report says that nobody did, so the contradiction is never silent.
options:
  name = (required)   -- what was checked
  pass = nil          -- true or false (or give status)
  status = nil        -- "pass", "fail", "warn", "info", "inconclusive" or "skip" (not run)
  detail = nil        -- a sentence with the numbers (for "skip": why it did not run)
  checks = nil        -- {{name =, status = | pass =, detail =}, ...}: secondary checks
  governs = nil       -- the sentence saying which of verdict and checks governs, and why
returns: the report (any other numeric fields go to the JSON)
errors: neither pass nor a known status (of the verdict or of a check); a check without a name
example:
  local r = require("smi.report").new{title = "t"}
  r:verdict{name = "Mode 1 validation", pass = true, detail = "U = 0.057 <= 0.193", value = 0.057}
  r:verdict{name = "Mode 2 validation", status = "inconclusive", detail = "U in [0.1, 0.3]",
            checks = {{name = "solver check", pass = false, detail = "U = 0.31"}},
            governs = "The surrogate's verdict governs: the solver check has 40 points, too few to decide."}
  print(r:data().verdicts[1].status, r:data().verdicts[2].disagrees)
]==]
--- A verdict with a badge, also listed once in the verdict list at the top of the page (see above).
function Report:verdict(v)
  if type(v) ~= "table" or type(v.name) ~= "string" then error("report:verdict: expects {name = \"...\", pass = true/false, detail = ...}", 2) end
  local item = {}
  for k, x in pairs(v) do item[k] = x end
  item.kind, item.status = "verdict", status_of(v, "report:verdict")
  if v.checks ~= nil then
    if type(v.checks) ~= "table" then error("report:verdict '" .. v.name .. "': checks must be a list {{name =, status =}, ...}", 2) end
    local checks = {}
    for i, c in ipairs(v.checks) do
      if type(c) ~= "table" or type(c.name) ~= "string" then
        error(("report:verdict '%s': checks[%d] needs a name, e.g. {name = \"solver check\", pass = false}"):format(v.name, i), 2)
      end
      checks[i] = { name = c.name, status = status_of(c, ("report:verdict '%s': checks[%d]"):format(v.name, i)),
                    detail = c.detail, value = c.value }
      if disagree(item.status, checks[i].status) then item.disagrees = true end
    end
    item.checks = checks
  end
  if item.disagrees and (type(v.governs) ~= "string" or v.governs == "") then
    local names = {}
    for _, c in ipairs(item.checks) do
      if disagree(item.status, c.status) then names[#names + 1] = ("%s (%s)"):format(c.name, c.status) end
    end
    item.governs = ("The verdict (%s) and its %s disagree, and the study does not say which governs:"
      .. " neither settles the question alone."):format(item.status, table.concat(names, ", "))
  end
  -- one entry per check: a verdict given again replaces the earlier one where it stood
  for _, old in ipairs(self.items) do
    if old.kind == "verdict" and old.name == v.name then
      item.id = old.id
      for k in pairs(old) do old[k] = nil end
      for k, x in pairs(item) do old[k] = x end
      return self
    end
  end
  item.id = self:_id("verdict", v.name)
  self.items[#self.items + 1] = item
  return self
end

doc.add[==[
@ smi.report:tally() -> table, string
The verdicts counted by status, and the header's sentence ("4 passed, 1 failed, 2 warnings,
1 inconclusive, 2 not run"). Warnings are the verdicts with status "warn" plus the distinct warning
callouts (smi.report:warning_groups). What lies in a superseded section (smi.report:supersede) is
not counted: the header counts what the study declares final.
returns: {pass =, fail =, warn =, inconclusive =, skip =, info =}, a string
errors: none
example:
  local r = require("smi.report").new{title = "t"}
  r:verdict{name = "a", pass = true}:verdict{name = "b", status = "inconclusive"}:callout("low data", "warn")
  print(select(2, r:tally()))
]==]
function Report:tally()
  local n = { pass = 0, fail = 0, warn = 0, inconclusive = 0, skip = 0, info = 0 }
  local gone = self:_superseded()
  for i, it in ipairs(self.items) do
    if it.kind == "verdict" and not gone[i] then n[it.status] = n[it.status] + 1 end
  end
  n.warn = n.warn + #self:warning_groups(true)
  local function plural(k, one, many) return ("%d %s"):format(n[k], n[k] == 1 and one or many) end
  local parts = { ("%d passed"):format(n.pass), ("%d failed"):format(n.fail), plural("warn", "warning", "warnings"),
                  ("%d inconclusive"):format(n.inconclusive) }
  if n.skip > 0 then parts[#parts + 1] = ("%d not run"):format(n.skip) end
  return n, table.concat(parts, ", ")
end

doc.add[==[
@ smi.report:callout(text [, status]) -> report
A highlighted remark ("the optimum lies on a bound").
returns: the report
errors: an unknown status (pass, fail, warn, info)
example:
  local r = require("smi.report").new{title = "t"}
  r:callout("The optimum lies on a bound.", "warn")
  print("ok")
]==]
--- A highlighted remark: r:callout("the optimum lies on a bound", "warn").
function Report:callout(text, status)
  status = status or "info"
  status_of({ status = status }, "report:callout")
  self.items[#self.items + 1] = { kind = "callout", text = tostring(text), status = status, id = self:_id("note", #self.items) }
  return self
end

doc.add[==[
@ smi.report:supersede(section, reason) -> report
Marks a section (by its title or number, "Trial 1" or "3") and its subsections as superseded:
replaced by a later one (a revised trial). It stays in the page, headed by the reason, but its
verdicts and warnings are not counted in the header nor printed as the study's answer.
returns: the report
errors: no section with that title or number
example:
  local r = require("smi.report").new{title = "t"}
  r:section("Trial 1"):verdict{name = "Mode 1", pass = false}
  r:section("Trial 2"):verdict{name = "Mode 1 (revised)", pass = true}
  r:supersede("Trial 1", "revised in trial 2: the boundary stiffness is calibrated")
  print(select(2, r:tally()))
]==]
function Report:supersede(which, reason)
  for _, it in ipairs(self.items) do
    if it.kind == "section" and it.level == 1 and (it.title == tostring(which) or it.number == tostring(which)) then
      it.superseded = tostring(reason or "superseded by a later section")
      return self
    end
  end
  local titles = {}
  for _, it in ipairs(self.items) do if it.kind == "section" and it.level == 1 then titles[#titles + 1] = it.title end end
  error(("report:supersede: no section '%s' (sections: %s)"):format(tostring(which), table.concat(titles, ", ")), 2)
end

-- {[item index] = reason} for the items inside a superseded section.
function Report:_superseded()
  local out, reason = {}, nil
  for i, it in ipairs(self.items) do
    if it.kind == "section" and it.level == 1 then reason = it.superseded end
    if reason then out[i] = reason end
  end
  return out
end

-- The title of the level-1 section each item lies in.
function Report:_section_of()
  local out, title = {}, nil
  for i, it in ipairs(self.items) do
    if it.kind == "section" and it.level == 1 then title = it.number .. " " .. it.title end
    out[i] = title
  end
  return out
end

doc.add[==[
@ smi.report:warning_groups([final]) -> list
The report's warnings (callouts with status "warn", and the run's smi.warnings() raised since the
report was made), grouped: the same warning raised per trial or per parameter is one group, with
how often it came and the sections it concerns. The page lists them in its Warnings section, and
smi.study prints them at the end of a run.
final = false   -- true: leave out those in superseded sections
returns: {{text =, count =, where = {section titles}, texts = {each distinct text}}, ...}
errors: none
example:
  local r = require("smi.report").new{title = "t"}
  r:section("Trial 1"):callout("input 'E' at its bound 2.1", "warn")
  r:section("Trial 2"):callout("input 'E' at its bound 2.3", "warn")
  local g = r:warning_groups()
  print(#g, g[1].count, g[1].where[2])
]==]
function Report:warning_groups(final)
  local gone, where = self:_superseded(), self:_section_of()
  local entries = {}
  for i, it in ipairs(self.items) do
    if it.kind == "callout" and it.status == "warn" and not (final and gone[i]) then
      entries[#entries + 1] = { text = it.text, where = where[i] }
    end
  end
  if type(smi) == "table" and type(smi.warnings) == "function" then
    local all = smi.warnings()
    for k = (self.warnings_from or 0) + 1, #all do entries[#entries + 1] = { text = all[k], where = "run" } end
  end
  return warnings.group(entries)
end

doc.add[==[
@ smi.report:summary(s) -> report
The report's opening: the answer before the story. Rendered first, under the title, whenever it
is given (a study gives it at its end); given again, it replaces the first.
options:
  conclusion = (required) -- one sentence: what the study found
  detail = nil            -- the conclusion's reasons, under it in plain type
  form = nil              -- the chosen form of the model (the final trial's unknowns, revisions)
  verdicts = nil          -- {{name =, status = | pass =, detail =}, ...}: each response in the final trial
  parameters = nil        -- {{name =, unit =, mean =, std =, interval = {lo, hi}, level = 0.95, prior =,
                          -- estimate =}, ...}: the calibrated parameters (prior: text such as
                          -- "normal(2.1e11, 1e10)"; estimate: a point estimate apart from the mean,
                          -- std and interval, shown in a column of its own and marked † outside the interval)
  open = nil              -- {{question =, settle =}, ...} (or strings): what is open and what would settle it
  notes = nil             -- a paragraph under the rest
returns: the report
errors: no conclusion; a verdict without a name or status; a parameter without a name
example:
  local r = require("smi.report").new{title = "t"}
  r:summary{conclusion = "The model is valid for modes 1 to 4 after one revision.",
            form = "trial 2: E and t calibrated",
            verdicts = {{name = "Mode 1", status = "pass", detail = "U = 0.05 <= 0.19"}},
            parameters = {{name = "E", unit = "GPa", mean = 207, std = 3.1, interval = {201, 213}, prior = "normal(210, 10)"}},
            open = {{question = "Mode 4 rests on 9 tests", settle = "nine more tests of mode 4"}}}
  print(r:data().summary.parameters[1].mean)
]==]
function Report:summary(s)
  self.summary_data = summary.check(s, 2)
  return self
end

local function flatten(prefix, v, out)
  if type(v) == "table" then
    local keys = {}
    for k in pairs(v) do keys[#keys + 1] = k end
    table.sort(keys, function(a, b) return tostring(a) < tostring(b) end)
    local is_list = #v > 0
    if is_list then
      local parts = {}
      for i = 1, #v do
        if type(v[i]) == "table" then flatten(("%s[%d]"):format(prefix, i), v[i], out) else parts[#parts + 1] = tostring(v[i]) end
      end
      if #parts > 0 then out[#out + 1] = { prefix, table.concat(parts, ", ") } end
    else
      for _, k in ipairs(keys) do flatten(prefix == "" and tostring(k) or (prefix .. "." .. tostring(k)), v[k], out) end
    end
  else
    out[#out + 1] = { prefix, v }
  end
end

doc.add[==[
@ smi.report:provenance(p) -> report
Run details shown at the end of the page (under "Run details") and stored in the JSON as
`provenance`: any key/value table (seed, versions, solver runs); several calls add up. smi.study's
own first section, Provenance, lists every file and program the run used with its hash.
returns: the report
errors: p not a table
example:
  local r = require("smi.report").new{title = "t"}
  r:provenance{seed = smi.seed, solver_runs = {["smi-column-fe"] = 1200}}
  print(r:data().provenance.seed == smi.seed)
]==]
--- Provenance, shown at the end of the page and stored in the JSON: any key/value table, e.g.
-- {seed = 20200214, versions = {...}, solver_runs = {["smi-column-fe"] = 1200},
--  inputs = {["data/column.csv"] = "sha256:..."}}. Several calls add up.
function Report:provenance(p)
  if type(p) ~= "table" then error("report:provenance: expects a table of key = value", 2) end
  for k, v in pairs(p) do self.prov[k] = v end
  return self
end

doc.add[==[
@ smi.report:result(key, value) -> report
Records a number (or any JSON value) under a dotted key ("calibration.E.mean") for r:json().
returns: the report
errors: none (a value JSON cannot hold fails later, in r:json())
example:
  local r = require("smi.report").new{title = "t"}
  r:result("calibration.E.mean", 246300)
  print(r:data().results.calibration.E.mean)
]==]
--- Records a number (or any JSON value) under a dotted key for r:json().
function Report:result(key, value)
  local t = self.results
  local parts = {}
  for part in tostring(key):gmatch("[^%.]+") do parts[#parts + 1] = part end
  for i = 1, #parts - 1 do
    t[parts[i]] = t[parts[i]] or {}
    t = t[parts[i]]
  end
  t[parts[#parts]] = value
  return self
end

doc.add[==[
@ smi.report:html() -> string
The page as one self-contained HTML string (styles and SVG inline; no script, nothing fetched).
returns: a string
errors: none
example:
  local r = require("smi.report").new{title = "Demo"}
  print(r:html():match("<title>(.-)</title>"))
]==]
--- The page as a string.
function Report:html()
  local o = self.opts
  local meta = {}
  if o.author then meta[#meta + 1] = o.author end
  meta[#meta + 1] = "Generated " .. (o.date or os.date("!%Y-%m-%d %H:%M UTC"))
  local n, counted = self:tally()
  local any = false
  for _, c in pairs(n) do any = any or c > 0 end
  if any then meta[#meta + 1] = counted end
  local prov = {}
  flatten("", self.prov, prov)
  return html.render{ title = o.title, subtitle = o.subtitle, meta = meta, items = self.items, provenance = prov,
                      footer = o.footer, counts = any and counted or nil, summary = self.summary_data,
                      superseded = self:_superseded(), warnings = self:warning_groups(), digits = o.digits or 4 }
end

-- Where to write: an explicit path, else <out>/<name> with out from the options or the host.
local function target(self, path, name)
  if path then return path end
  local dir = self.opts.out or (type(smi) == "table" and smi.out_dir) or "."
  return (tostring(dir):gsub("/+$", "")) .. "/" .. name
end

-- Whole file or nothing: a full disk never leaves a torn report (smi.file).
local function write_file(path, content, what)
  return require("smi.file").write(path, content, what)
end

doc.add[==[
@ smi.report:write([path]) -> path
Writes report.html (to path, or <out>/report.html).
returns: the path written
errors: the sandbox refuses the path; the file cannot be written
example:
  local r = require("smi.report").new{title = "Demo"}
  local p = r:write(smi.out("doc_report.html"))
  print(p:match("doc_report%.html$") ~= nil)
]==]
--- Writes report.html (to `path`, or <out>/report.html) and returns the path.
function Report:write(path)
  return write_file(target(self, path, "report.html"), self:html(), "report:write")
end

doc.add[==[
@ smi.report:data() -> table
Everything the report holds as numbers: tables, verdicts, provenance and recorded results.
returns: {title =, tables = {...}, verdicts = {...}, provenance = {...}, results = {...}, ...}
errors: none
example:
  local r = require("smi.report").new{title = "Demo"}
  r:result("n", 9)
  print(r:data().results.n)
]==]
--- Everything the report holds as numbers: tables, verdicts, provenance, recorded results.
function Report:data()
  local d = { title = self.opts.title, tables = {}, verdicts = {}, figures = {}, provenance = self.prov, results = self.results,
              counts = (self:tally()), summary = self.summary_data, warnings = self:warning_groups() }
  local gone = self:_superseded()
  local section = nil
  for i, it in ipairs(self.items) do
    if it.kind == "section" then section = it.number .. " " .. it.title
    elseif it.kind == "table" then
      local cols, rows = {}, {}
      for j, c in ipairs(it.columns) do cols[j] = c.title end
      for i, row in ipairs(it.rows) do
        local r = {}
        for j, c in ipairs(it.columns) do
          local v = row[j]
          if v == nil and c.key then v = row[c.key] end
          if type(v) == "table" then v = v.text or v.status end
          r[j] = v == nil and "" or v
        end
        rows[i] = r
      end
      d.tables[#d.tables + 1] = { number = it.number, caption = it.caption, section = section, columns = cols, rows = rows }
    elseif it.kind == "verdict" then
      local v = { section = section, superseded = gone[i] }
      for k, x in pairs(it) do if k ~= "kind" and k ~= "id" then v[k] = x end end
      d.verdicts[#d.verdicts + 1] = v
    elseif it.kind == "figure" or it.kind == "figrow" then
      for _, f in ipairs(it.figures or { it }) do d.figures[#d.figures + 1] = { number = f.number, caption = f.caption, section = section } end
    end
  end
  return d
end

doc.add[==[
@ smi.report:json() -> string
JSON text of r:data() (NaN written as null, infinities as 1e999).
returns: a string
errors: a value JSON cannot hold (its path is named)
example:
  local r = require("smi.report").new{title = "Demo"}
  r:result("n", 9)
  print(#r:json() > 10)
]==]
--- JSON text of r:data() (non-finite numbers: NaN -> null, inf -> 1e999).
function Report:json()
  return json.encode(self:data(), { indent = "  ", root = "report", skip = true })
end

doc.add[==[
@ smi.report:write_json([path]) -> path
Writes r:json() (to path, or <out>/report.json).
returns: the path written
errors: the sandbox refuses the path
example:
  local r = require("smi.report").new{title = "Demo"}
  print(r:write_json(smi.out("doc_report.json")):match("json$"))
]==]
function Report:write_json(path)
  return write_file(target(self, path, "report.json"), self:json() .. "\n", "report:write_json")
end

if type(smi) == "table" and smi.report == nil then smi.report = M end
return M
