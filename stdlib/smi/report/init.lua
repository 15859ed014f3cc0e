--- smi.report: a study's report as one self-contained report.html, plus its numbers as JSON.
--
--   local report = require "smi.report"
--   local r = report.new{title = "Steering column: trial 1", subtitle = "Calibration and validation"}
--   r:section("Data") ; r:text("Nine wheel/column combinations ...")
--   r:table{caption = "Calibrated inputs", columns = {"Input", "Mean", {title = "Std", digits = 3}},
--           rows = {{"E", 2.07e11, 3.1e9}, ...}}
--   r:figure(svg_string, "KDE of mode 1")          -- from smi.report.svg
--   r:verdict{name = "Mode 4 validation", pass = false, detail = "area metric 0.031 > 0.02"}
--   r:provenance{seed = 42, versions = {["smi-lua"] = "0.1.0"}, solver_runs = {["column-fe"] = 1200}}
--   r:result("calibration.mean_E", 2.07e11)        -- collected into r:json()
--   r:write("smi-out/study/report.html") ; r:write_json("smi-out/study/report.json")
local html = require "smi.report.html"
local json = require "smi.report.json"
local xmlcheck = require "smi.report.xmlcheck"

local M = {}
M.svg = require "smi.report.svg"
M.format = require "smi.report.format"
M.json = json

local Report = {}
Report.__index = Report

--- opts: title (required), subtitle, author, date (default: now, UTC), digits (tables, 4), out (folder).
function M.new(opts)
  opts = opts or {}
  if type(opts.title) ~= "string" or opts.title == "" then
    error("smi.report.new: 'title' is required (a non-empty string), e.g. smi.report.new{title = \"My study\"}", 2)
  end
  local r = setmetatable({ opts = opts, items = {}, prov = {}, results = {}, ids = {},
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

function Report:subsection(title) return self:section(title, { level = 2 }) end

--- Paragraphs of plain text (blank lines separate paragraphs; no markup, it is escaped).
function Report:text(s)
  self.items[#self.items + 1] = { kind = "text", text = tostring(s) }
  return self
end

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
  return svg
end

--- A figure: an SVG string (or a chart of smi.report.svg) and its caption; numbered "Figure N.".
function Report:figure(svg, caption)
  svg = check_svg(svg, "report:figure")
  self.counts.figure = self.counts.figure + 1
  self.items[#self.items + 1] = { kind = "figure", svg = svg, caption = caption, number = self.counts.figure,
    id = self:_id("fig", self.counts.figure) }
  return self
end

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

local function status_of(v, where)
  if v.status ~= nil then
    if v.status ~= "pass" and v.status ~= "fail" and v.status ~= "warn" and v.status ~= "info" then
      error(where .. ": status must be \"pass\", \"fail\", \"warn\" or \"info\", got " .. tostring(v.status), 3)
    end
    return v.status
  end
  if type(v.pass) ~= "boolean" then error(where .. ": give pass = true/false (or status = \"warn\"/\"info\")", 3) end
  return v.pass and "pass" or "fail"
end

--- A verdict with a badge, also listed in the summary at the top of the page.
-- v: name, pass (boolean) or status ("pass"|"fail"|"warn"|"info"), detail, and any numbers
-- (value, threshold, ...) which go to the JSON.
function Report:verdict(v)
  if type(v) ~= "table" or type(v.name) ~= "string" then error("report:verdict: expects {name = \"...\", pass = true/false, detail = ...}", 2) end
  local item = {}
  for k, x in pairs(v) do item[k] = x end
  item.kind, item.status, item.id = "verdict", status_of(v, "report:verdict"), self:_id("verdict", v.name)
  self.items[#self.items + 1] = item
  return self
end

--- A highlighted remark: r:callout("the optimum lies on a bound", "warn").
function Report:callout(text, status)
  status = status or "info"
  status_of({ status = status }, "report:callout")
  self.items[#self.items + 1] = { kind = "callout", text = tostring(text), status = status }
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

--- Provenance, shown at the end of the page and stored in the JSON: any key/value table, e.g.
-- {seed = 20200214, versions = {...}, solver_runs = {["column-fe"] = 1200},
--  inputs = {["data/column.csv"] = "sha256:..."}}. Several calls add up.
function Report:provenance(p)
  if type(p) ~= "table" then error("report:provenance: expects a table of key = value", 2) end
  for k, v in pairs(p) do self.prov[k] = v end
  return self
end

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

--- The page as a string.
function Report:html()
  local o = self.opts
  local meta = {}
  if o.author then meta[#meta + 1] = o.author end
  meta[#meta + 1] = "Generated " .. (o.date or os.date("!%Y-%m-%d %H:%M UTC"))
  local verdicts = { pass = 0, fail = 0 }
  for _, it in ipairs(self.items) do if verdicts[it.status] then verdicts[it.status] = verdicts[it.status] + 1 end end
  if verdicts.pass + verdicts.fail > 0 then meta[#meta + 1] = ("%d passed, %d failed"):format(verdicts.pass, verdicts.fail) end
  local prov = {}
  flatten("", self.prov, prov)
  return html.render{ title = o.title, subtitle = o.subtitle, meta = meta, items = self.items, provenance = prov, footer = o.footer }
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

--- Writes report.html (to `path`, or <out>/report.html) and returns the path.
function Report:write(path)
  return write_file(target(self, path, "report.html"), self:html(), "report:write")
end

--- Everything the report holds as numbers: tables, verdicts, provenance, recorded results.
function Report:data()
  local d = { title = self.opts.title, tables = {}, verdicts = {}, figures = {}, provenance = self.prov, results = self.results }
  local section = nil
  for _, it in ipairs(self.items) do
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
      local v = { section = section }
      for k, x in pairs(it) do if k ~= "kind" and k ~= "id" then v[k] = x end end
      d.verdicts[#d.verdicts + 1] = v
    elseif it.kind == "figure" or it.kind == "figrow" then
      for _, f in ipairs(it.figures or { it }) do d.figures[#d.figures + 1] = { number = f.number, caption = f.caption, section = section } end
    end
  end
  return d
end

--- JSON text of r:data() (non-finite numbers: NaN -> null, inf -> 1e999).
function Report:json()
  return json.lua_encode(self:data(), { indent = "  ", root = "report", skip = true })
end

function Report:write_json(path)
  return write_file(target(self, path, "report.json"), self:json() .. "\n", "report:write_json")
end

if type(smi) == "table" and smi.report == nil then smi.report = M end
return M
