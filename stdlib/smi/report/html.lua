--- smi.report.html: turns a report's content (built by smi.report) into one self-contained
-- HTML page: inline CSS and SVG, no script, no network. The markup is also well-formed XML
-- (every element closed, every attribute quoted), so tests can check it with a plain parser.
local xml = require "smi.report.xml"
local fmt = require "smi.report.format"
local style = require "smi.report.style"

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
  out[#out + 1] = ("<caption><b>Table %d.</b> %s</caption>"):format(t.number, tesc(t.caption or ""))
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
    return ('<%s id="%s"><span class="num">%s</span>%s</%s>'):format(tag, esc(it.id), esc(it.number), esc(it.title), tag)
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

local function toc_html(items)
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
  for _, e in ipairs(top) do
    local subs = ""
    if #e.subs > 0 then
      local li = {}
      for i, sub in ipairs(e.subs) do li[i] = "<li>" .. link(sub) .. "</li>" end
      subs = "<ol>" .. table.concat(li) .. "</ol>"
    end
    out[#out + 1] = "<li>" .. link(e.it) .. subs .. "</li>"
  end
  out[#out + 1] = '<li><a href="#run-details">Run details</a></li></ol></nav>'
  return table.concat(out, "\n")
end

-- The one verdict list: every verdict once, with its one status (its checks and the sentence on
-- which governs beside it), the counts by status, then the warnings raised along the way.
local function summary_html(items, counts)
  local out, warns = {}, {}
  for _, it in ipairs(items) do
    if it.kind == "verdict" then
      local sub = ""
      if it.checks and #it.checks > 0 then
        local c = {}
        for i, ch in ipairs(it.checks) do c[i] = esc(ch.name) .. ": " .. STATUS_TEXT[ch.status]:lower() end
        sub = ' <span class="sub">(' .. table.concat(c, "; ") .. (it.disagrees and "; see which governs" or "") .. ")</span>"
      end
      out[#out + 1] = ('<li>%s<a href="#%s">%s</a>%s</li>'):format(M.badge(it.status), esc(it.id), tesc(it.name), sub)
    elseif it.kind == "callout" and it.status == "warn" then
      -- the list names each warning in a line; the whole text stays where it was raised
      local text = fmt.tidy(it.text)
      if #text > 110 then text = text:sub(1, 100):gsub("[%s,;:]+%S*$", "") .. " ..." end
      warns[#warns + 1] = ('<li>%s<a href="#%s">%s</a></li>'):format(M.badge("warn"), esc(it.id), esc(text))
    end
  end
  if #out == 0 and #warns == 0 then return "" end
  local html = { '<section class="summary"><h2>Verdicts</h2>' }
  if counts then html[#html + 1] = '<p class="counts">' .. esc(counts) .. "</p>" end
  if #out > 0 then html[#html + 1] = "<ul>" .. table.concat(out) .. "</ul>" end
  if #warns > 0 then html[#html + 1] = '<h2>Warnings</h2><ul>' .. table.concat(warns) .. "</ul>" end
  html[#html + 1] = "</section>"
  return table.concat(html)
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
  out[#out + 1] = summary_html(doc.items, doc.counts)
  out[#out + 1] = toc_html(doc.items)
  out[#out + 1] = "<main>"
  for _, it in ipairs(doc.items) do out[#out + 1] = item_html(it) end
  out[#out + 1] = "</main>"
  out[#out + 1] = prov_html(doc.provenance or {})
  out[#out + 1] = "<footer>" .. esc(doc.footer or "Generated by smi-lua. Self-contained: no scripts, no network resources.") .. "</footer>"
  out[#out + 1] = "</body></html>\n"
  return table.concat(out, "\n")
end

return M
