-- SPDX-License-Identifier: MIT
--- smi.report.html: turns a report's content (built by smi.report) into one self-contained
-- HTML page: inline CSS and SVG, no script, no network. The markup is also well-formed XML
-- (every element closed, every attribute quoted), so tests can check it with a plain parser.
local xml = require "smi.report.xml"
local fmt = require "smi.report.format"
local style = require "smi.report.style"
local summary = require "smi.report.summary"
local warnings = require "smi.report.warnings"

local M = {}
local esc = xml.escape

local STATUS_TEXT = { pass = "PASS", fail = "FAIL", warn = "WARNING", info = "INFO", inconclusive = "INCONCLUSIVE",
                      skip = "NOT RUN" }
M.STATUS_TEXT = STATUS_TEXT
-- Text callers wrote (paragraphs, details, captions): escaped, and numbers carrying binary noise
-- (1.4999999999999998e-09 from a "%s") shown with the digits they carry.
local function tesc(s) return esc(fmt.tidy(s)) end

function M.badge(status)
  return ('<span class="badge %s">%s</span>'):format(status, STATUS_TEXT[status])
end

-- Paragraphs: blank lines separate them; text is escaped (no markup from callers).
local function paragraphs(s)
  local out = {}
  s = tostring(s):gsub("\r\n", "\n")
  for para in (s .. "\n\n"):gmatch("(.-)\n%s*\n") do
    if para:match("%S") then out[#out + 1] = "<p>" .. tesc(para) .. "</p>" end
  end
  return table.concat(out, "\n")
end

local function cell_html(v, col, default_digits)
  if type(v) == "table" and v.status then
    return ('<td>%s%s</td>'):format(M.badge(v.status), tesc(v.text or ""))
  end
  if type(v) == "number" then
    local s
    if type(col.format) == "function" then s = col.format(v)
    elseif type(col.format) == "string" then s = col.format:format(v)
    elseif col.formatter then s = col.formatter(v)
    else s = fmt.num(v, col.digits or default_digits) end
    return ('<td class="num">%s</td>'):format(esc(s))
  end
  if type(v) == "boolean" then return ("<td>%s</td>"):format(v and "yes" or "no") end
  if v == nil then return "<td></td>" end
  -- a long unbroken name (column_frame_E_of_the_steering_column) may break anywhere; shorter
  -- words never do, so a squeezed column does not read "nor ma l"
  local long = tostring(v):find("[^%s]" .. ("[^%s]"):rep(15)) and ' class="long"' or ""
  return ("<td%s>%s</td>"):format(long, tesc(v))
end

local function table_html(t)
  -- a table of many columns is printed in smaller type (style.lua's table.wide)
  local wide = #t.columns >= 9 and " wide" or ""
  local out = { '<div class="table-wrap"><table class="data' .. wide .. '" id="' .. esc(t.id) .. '">' }
  out[#out + 1] = ("<caption>%s%s</caption>"):format(t.number and ("<b>Table %d.</b> "):format(t.number) or "", tesc(t.caption or ""))
  local head = {}
  for j, col in ipairs(t.columns) do
    local numeric = false
    for _, row in ipairs(t.rows) do
      local v = row[j] ~= nil and row[j] or (col.key and row[col.key])
      if type(v) == "number" then numeric = true break end
    end
    col.numeric = numeric
    if numeric and not col.format and col.align_decimals ~= false then
      local values = {}
      for _, row in ipairs(t.rows) do
        local v = row[j]
        if v == nil and col.key then v = row[col.key] end
        values[#values + 1] = v
      end
      col.formatter = fmt.column(values, col.digits or t.digits)
    end
    local title = col.unit and (col.title .. " (" .. col.unit .. ")") or col.title
    head[#head + 1] = ("<th%s>%s</th>"):format(numeric and ' class="num"' or "", esc(title))
  end
  out[#out + 1] = "<thead><tr>" .. table.concat(head) .. "</tr></thead><tbody>"
  for _, row in ipairs(t.rows) do
    local cells = {}
    for j, col in ipairs(t.columns) do
      local v = row[j]
      if v == nil and col.key then v = row[col.key] end
      cells[#cells + 1] = cell_html(v, col, t.digits)
    end
    out[#out + 1] = "<tr>" .. table.concat(cells) .. "</tr>"
  end
  out[#out + 1] = "</tbody></table></div>"
  return table.concat(out, "\n")
end

-- A verdict, its secondary checks (a solver check of a surrogate's verdict, say) and, when they
-- disagree, the sentence saying which one governs (smi.report:verdict fills in a default).
local function verdict_html(v)
  local out = { ('<div class="verdict %s" id="%s">'):format(v.status, esc(v.id)) }
  out[#out + 1] = M.badge(v.status) .. '<span class="name">' .. tesc(v.name) .. "</span>"
  if v.detail then out[#out + 1] = '<div class="detail">' .. tesc(v.detail) .. "</div>" end
  if v.checks and #v.checks > 0 then
    local li = {}
    for i, c in ipairs(v.checks) do
      li[i] = "<li>" .. esc(c.name) .. ": " .. STATUS_TEXT[c.status]:lower() .. (c.detail and (" (" .. tesc(c.detail) .. ")") or "") .. "</li>"
    end
    out[#out + 1] = '<ul class="checks">' .. table.concat(li) .. "</ul>"
  end
  if v.governs then out[#out + 1] = '<div class="governs">' .. tesc(v.governs) .. "</div>" end
  out[#out + 1] = "</div>"
  return table.concat(out)
end

local function figure_html(f)
  return ('<figure id="%s"><div class="chart">%s</div><figcaption><b>Figure %d.</b> %s</figcaption></figure>')
    :format(esc(f.id), f.svg, f.number, tesc(f.caption or ""))
end

local function item_html(it)
  if it.kind == "section" then
    local tag = it.level == 1 and "h2" or "h3"
    local head = ('<%s id="%s"><span class="num">%s</span>%s</%s>'):format(tag, esc(it.id), esc(it.number), esc(it.title), tag)
    if it.superseded then
      head = head .. ('<div class="callout superseded">%s<span>Superseded: %s. Its verdicts are not counted.</span></div>')
        :format('<span class="badge skip">SUPERSEDED</span>', tesc(it.superseded))
    end
    return head
  elseif it.kind == "text" then return paragraphs(it.text)
  elseif it.kind == "table" then return table_html(it)
  elseif it.kind == "figure" then return figure_html(it)
  elseif it.kind == "figrow" then
    local parts = {}
    for _, f in ipairs(it.figures) do parts[#parts + 1] = figure_html(f) end
    return '<div class="figrow">' .. table.concat(parts) .. "</div>"
  elseif it.kind == "verdict" then return verdict_html(it)
  elseif it.kind == "callout" then
    return ('<div class="callout %s"%s>%s<span>%s</span></div>'):format(it.status,
      it.id and (' id="' .. esc(it.id) .. '"') or "", M.badge(it.status), tesc(it.text))
  end
  error("smi.report.html: unknown item kind " .. tostring(it.kind))
end

local function toc_html(items, has_warnings)
  -- two levels: sections, and their subsections (a subsection before any section is a section)
  local top = {}
  for _, it in ipairs(items) do
    if it.kind == "section" then
      if it.level == 1 or #top == 0 then top[#top + 1] = { it = it, subs = {} }
      else table.insert(top[#top].subs, it) end
    end
  end
  local function link(it) return ('<a href="#%s">%s</a>'):format(esc(it.id), esc(it.title)) end
  local out = { '<nav class="toc"><h2>Contents</h2><ol>' }
  local warned = false
  for _, e in ipairs(top) do
    -- the warnings stand before the study's Provenance section, as on the page
    if has_warnings and not warned and e.it.title == "Provenance" then
      out[#out + 1] = '<li><a href="#warnings">Warnings</a></li>'
      warned = true
    end
    local subs = ""
    if #e.subs > 0 then
      local li = {}
      for i, sub in ipairs(e.subs) do li[i] = "<li>" .. link(sub) .. "</li>" end
      subs = "<ol>" .. table.concat(li) .. "</ol>"
    end
    out[#out + 1] = "<li>" .. link(e.it) .. subs .. "</li>"
  end
  if has_warnings and not warned then out[#out + 1] = '<li><a href="#warnings">Warnings</a></li>' end
  out[#out + 1] = '<li><a href="#run-details">Run details</a></li></ol></nav>'
  return table.concat(out, "\n")
end

-- The one verdict list: every verdict once, with its one status (its checks and the sentence on
-- which governs beside it), the counts by status, then the warnings raised along the way.
local function summary_html(items, counts, gone)
  local out, warns, old = {}, {}, 0
  for i, it in ipairs(items) do
    if it.kind == "verdict" and gone[i] then old = old + 1
    elseif it.kind == "verdict" then
      local sub = ""
      if it.checks and #it.checks > 0 then
        local c = {}
        for i, ch in ipairs(it.checks) do c[i] = esc(ch.name) .. ": " .. STATUS_TEXT[ch.status]:lower() end
        sub = ' <span class="sub">(' .. table.concat(c, "; ") .. (it.disagrees and "; see which governs" or "") .. ")</span>"
      end
      out[#out + 1] = ('<li>%s<a href="#%s">%s</a>%s</li>'):format(M.badge(it.status), esc(it.id), tesc(it.name), sub)
    end
  end
  if #out == 0 and not counts then return "" end
  local html = { '<section class="summary"><h2>Verdicts</h2>' }
  if counts then
    html[#html + 1] = '<p class="counts">' .. esc(counts) .. (counts:find("warning") and ' (<a href="#warnings">listed at the end</a>)' or "")
      .. (old > 0 and ("; " .. old .. " verdict" .. (old == 1 and "" or "s") .. " of superseded sections not counted") or "") .. "</p>"
  end
  if #out > 0 then html[#html + 1] = "<ul>" .. table.concat(out) .. "</ul>" end
  html[#html + 1] = "</section>"
  return table.concat(html)
end

-- The opening (smi.report:summary): the conclusion, the chosen form, each response's verdict,
-- the calibrated parameters, what is open and what would settle it.
local function answer_html(s, digits)
  if not s then return "" end
  local out = { '<section class="answer" id="summary"><h2>Summary</h2>', '<p class="conclusion">' .. tesc(s.conclusion) .. "</p>" }
  if s.detail then out[#out + 1] = '<p class="detail">' .. tesc(s.detail) .. "</p>" end
  if s.form then out[#out + 1] = '<p class="form"><b>Chosen form:</b> ' .. tesc(s.form) .. "</p>" end
  if #s.verdicts > 0 then
    local li = {}
    for i, v in ipairs(s.verdicts) do
      li[i] = "<li>" .. M.badge(v.status) .. '<span class="name">' .. tesc(v.name) .. "</span>"
        .. (v.detail and (' <span class="sub">' .. tesc(v.detail) .. "</span>") or "") .. "</li>"
    end
    out[#out + 1] = '<ul class="verdicts">' .. table.concat(li) .. "</ul>"
  end
  local t = summary.parameter_table(s, digits)
  if t then
    out[#out + 1] = table_html{ columns = t.columns, rows = t.rows, digits = digits, number = nil, id = "summary-parameters",
                                caption = "Calibrated parameters: mean and standard deviation with their interval (and the point estimate, where it is apart from them), and the prior where one was declared." }
  end
  if #s.open > 0 then
    local li = {}
    for i, o in ipairs(s.open) do
      li[i] = "<li>" .. tesc(o.question) .. (o.settle and (' <span class="settle">What would settle it: ' .. tesc(o.settle) .. "</span>") or "") .. "</li>"
    end
    out[#out + 1] = '<h3>Open</h3><ul class="open">' .. table.concat(li) .. "</ul>"
  end
  if s.notes then out[#out + 1] = paragraphs(s.notes) end
  out[#out + 1] = "</section>"
  return table.concat(out, "\n")
end

-- Warnings, grouped and counted (smi.report:warning_groups), with the sections they concern.
local function warnings_html(groups)
  if not groups or #groups == 0 then return "" end
  local total = 0
  for _, g in ipairs(groups) do total = total + g.count end
  local out = { '<h2 id="warnings">Warnings</h2>',
    ("<p>%d distinct warning%s (%d in all), each once with how often it came and where.</p>"):format(#groups,
      #groups == 1 and "" or "s", total), '<ul class="warnings">' }
  for _, g in ipairs(groups) do
    local where = #g.where > 0 and (' <span class="sub">(' .. esc(table.concat(g.where, "; ")) .. ")</span>") or ""
    local times = g.count > 1 and ('<span class="count">' .. g.count .. "&#215;</span> ") or ""
    out[#out + 1] = "<li>" .. M.badge("warn") .. times .. tesc(g.text) .. esc(warnings.similar(g)) .. where .. "</li>"
  end
  out[#out + 1] = "</ul>"
  return table.concat(out, "\n")
end

-- Run details (report:provenance): ordered groups of key/value pairs; nested tables are flattened
-- "a.b". Not titled "Provenance": smi.study's first section is the run's provenance, every file
-- and program with its hash; this is what the study itself chose to note (seed, run counts).
local function prov_html(groups)
  local out = { '<h2 id="run-details">Run details</h2>' }
  if #groups == 0 then
    out[#out + 1] = "<p>No provenance was recorded.</p>"
    return table.concat(out)
  end
  out[#out + 1] = '<dl class="prov">'
  for _, kv in ipairs(groups) do
    local v = kv[2]
    if type(v) == "number" then v = fmt.exact(v) else v = fmt.tidy(v) end
    out[#out + 1] = ("<dt>%s</dt><dd>%s</dd>"):format(esc(kv[1]), esc(v))
  end
  out[#out + 1] = "</dl>"
  return table.concat(out)
end

--- The page for `doc` = {title, subtitle, meta = {lines}, items = {...}, provenance = {{key, value}}}.
function M.render(doc)
  local out = {
    "<!DOCTYPE html>",
    '<html lang="en" xmlns="http://www.w3.org/1999/xhtml">',
    '<head><meta charset="utf-8"/><meta name="viewport" content="width=device-width, initial-scale=1"/>',
    "<title>" .. esc(doc.title) .. "</title>",
    "<style>" .. style .. "</style></head>",
    "<body>",
    '<header class="title-block"><h1>' .. esc(doc.title) .. "</h1>",
  }
  if doc.subtitle then out[#out + 1] = '<p class="subtitle">' .. esc(doc.subtitle) .. "</p>" end
  if doc.meta and #doc.meta > 0 then
    local m = {}
    for i, s in ipairs(doc.meta) do m[i] = esc(s) end
    out[#out + 1] = '<p class="meta">' .. table.concat(m, " · ") .. "</p>"
  end
  out[#out + 1] = "</header>"
  out[#out + 1] = answer_html(doc.summary, doc.digits)
  out[#out + 1] = summary_html(doc.items, doc.counts, doc.superseded or {})
  out[#out + 1] = toc_html(doc.items, doc.warnings and #doc.warnings > 0)
  out[#out + 1] = "<main>"
  -- the story; then the warnings; the study's Provenance section is its last item
  local prov_at
  for i, it in ipairs(doc.items) do
    if it.kind == "section" and it.title == "Provenance" and it.level == 1 then prov_at = i end
  end
  for i, it in ipairs(doc.items) do
    if i == prov_at then out[#out + 1] = warnings_html(doc.warnings) end
    out[#out + 1] = item_html(it)
  end
  if not prov_at then out[#out + 1] = warnings_html(doc.warnings) end
  out[#out + 1] = "</main>"
  out[#out + 1] = prov_html(doc.provenance or {})
  out[#out + 1] = "<footer>" .. esc(doc.footer or "Generated by smi-lua. Self-contained: no scripts, no network resources.") .. "</footer>"
  out[#out + 1] = "</body></html>\n"
  return table.concat(out, "\n")
end

return M
