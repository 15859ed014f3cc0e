-- SPDX-License-Identifier: MIT
--- smi.doc: the reference texts of every public function, method and options table, and what
-- reads them: help() in the REPL, `smi-lua doc [NAME]`, `smi-lua doc --html DIR` and the test
-- that runs every example and fails on a public function without a text.
--
-- Texts live beside the code they document: stdlib modules call doc.add[[...]] next to each
-- function; C++ bindings keep theirs in a *_doc.cpp beside the registration, with defaults
-- taken from the kernels' option structs, handed over by smi._docs(). One format for both:
--
--   @ smi.kde(data [, opts]) -> dist            the signature; its first word is the name
--   One-line summary.                           (more lines of description may follow)
--   options:
--     bandwidth = "silverman"  -- a number, or a rule: silverman, scott, ...
--                              -- (a continuation of the meaning)
--   returns: what comes back (indented lines continue it)
--   errors: what it raises, and when
--   example:
--     local k = smi.kde(smi.vec{1, 2, 4})       -- runs as a test; print() output is shown
--     print(k.bandwidth)
--
-- A module's own line: "@ module smi.dist" then its summary.
local M = {}

local raw = {}         -- texts added by Lua modules, parsed on first use
local entries = nil    -- name -> entry
local order = nil      -- names, sorted

--- Adds doc texts (one or more "@ ..." blocks). Used by stdlib modules beside their functions.
function M.add(text)
  raw[#raw + 1] = text
  entries = nil
end

-- The public stdlib modules (the rest are their parts). Walked like the smi table.
M.stdlib = { "smi.options", "smi.study", "smi.report", "smi.testing", "smi.refine.criteria", "smi.improve", "smi.strict" }

-- Lua classes have no registry metatable: their methods are found on an instance.
local classes = {
  { "smi.study", function() return require("smi.study").new { name = "doc" } end },
  { "smi.report", function() return require("smi.report").new { title = "doc" } end },
  { "smi.report.chart", function() return require("smi.report").svg.chart {} end },
}

local function trim(s) return (s:gsub("^%s+", ""):gsub("%s+$", "")) end

local SECTIONS = { options = true, returns = true, errors = true, example = true, fields = true }

-- Parses one "@ ..." block into an entry.
local function parse_block(block, source)
  local lines = {}
  for line in (block .. "\n"):gmatch("(.-)\r?\n") do lines[#lines + 1] = line end
  local head = trim(lines[1] or "")
  local e = { source = source, options = {}, text = {} }
  local modname = head:match("^module%s+([%w_%.]+)$")
  if modname then
    e.name, e.kind, e.signature = modname, "module", modname
  else
    e.signature = head
    e.name = head:match("^([%w_%.:]+)")
    e.kind = e.name and e.name:find(":", 1, true) and "method" or "function"
  end
  if not e.name then error(("smi.doc: %s: a block must start with '@ name(...)', got '%s'"):format(source, head), 0) end
  local section, body = nil, {}
  local function flush()
    if section == nil then
      -- paragraphs (blank lines separate them) joined into single lines
      local paras, cur = {}, {}
      for _, l in ipairs(body) do
        if l:match("%S") then cur[#cur + 1] = trim(l)
        elseif #cur > 0 then paras[#paras + 1] = table.concat(cur, " "); cur = {} end
      end
      if #cur > 0 then paras[#paras + 1] = table.concat(cur, " ") end
      e.description = table.concat(paras, "\n")
      -- the summary: the first sentence
      local first = paras[1] or ""
      e.summary = first
      local abbrev = { eq = true, al = true, ["e.g"] = true, ["i.e"] = true, vs = true, cf = true, fig = true }
      for stop in first:gmatch("()%.%s") do
        local word = first:sub(1, stop - 1):match("([%w%.]+)$") or ""
        if not abbrev[word:lower()] and word:match("[%w%)%]\"]$") then e.summary = first:sub(1, stop) break end
      end
      if #e.summary > 110 then e.summary = e.summary:sub(1, 107):gsub("%s+%S*$", "") .. "..." end
    elseif section == "example" then
      local ind
      for _, l in ipairs(body) do
        if l:match("%S") then
          local w = #l:match("^(%s*)")
          ind = ind and math.min(ind, w) or w
        end
      end
      local out = {}
      for _, l in ipairs(body) do out[#out + 1] = l:sub((ind or 0) + 1) end
      e.example = trim(table.concat(out, "\n"))
    elseif section ~= "options" then
      e[section] = trim(table.concat(body, " "):gsub("%s+", " "))
    end
    body = {}
  end
  for i = 2, #lines do
    local l = lines[i]
    local key, rest = l:match("^(%a+):%s*(.*)$")
    if key and SECTIONS[key] then
      flush()
      section = key
      if rest ~= "" then body[#body + 1] = rest end
    elseif section == "options" then
      local name, def, meaning = l:match("^%s+([%w_%.%[%]\"]+)%s*=%s*(.-)%s+%-%-%s+(.*)$")
      if name then
        e.options[#e.options + 1] = { name = name, default = trim(def), meaning = trim(meaning) }
      else
        local more = l:match("^%s+%-%-%s+(.*)$")
        if more and #e.options > 0 then
          local o = e.options[#e.options]
          o.meaning = o.meaning .. " " .. trim(more)
        elseif l:match("%S") then
          error(("smi.doc: %s, %s: option line must read '  name = default  -- meaning', got '%s'"):format(source, e.name, l), 0)
        end
      end
    else
      body[#body + 1] = l
    end
  end
  flush()
  return e
end

local function parse_text(text, source, into)
  -- blocks start at a line beginning with "@ "
  local pos = 1
  text = "\n" .. text
  local starts = {}
  for s in text:gmatch("()\n@ ") do starts[#starts + 1] = s end
  for i, s in ipairs(starts) do
    local block = text:sub(s + 3, (starts[i + 1] or (#text + 1)) - 1)
    local e = parse_block(block, source)
    if into[e.name] then error(("smi.doc: '%s' is documented twice (%s and %s)"):format(e.name, into[e.name].source, source), 0) end
    into[e.name] = e
  end
  return pos
end

-- Loads every text: the C++ ones from smi._docs(), the stdlib ones by requiring the modules.
local function load_all()
  if entries then return entries end
  for _, m in ipairs(M.stdlib) do require(m) end
  local all = {}
  local native = type(smi) == "table" and type(smi._docs) == "function" and smi._docs() or { texts = {} }
  for _, t in ipairs(native.texts) do parse_text(t.text, t.source, all) end
  for i, t in ipairs(raw) do parse_text(t, "stdlib text " .. i, all) end
  entries = all
  order = {}
  for n in pairs(all) do order[#order + 1] = n end
  table.sort(order)
  return entries
end

--- Every public name found at run time, with its value: the smi table walked (fields starting
-- with "_" are private), the public stdlib modules, and the methods of every smi type and Lua
-- class. Returns a list of {name =, kind = "function"|"method"|"module", value =}, sorted.
function M.walk()
  for _, m in ipairs(M.stdlib) do require(m) end
  local out, seen = {}, {}
  local function add(name, kind, value)
    if seen[name] then return end
    seen[name] = true
    out[#out + 1] = { name = name, kind = kind, value = value }
  end
  local visited = {}
  local function walk(t, prefix, depth)
    if visited[t] or depth > 5 then return end
    visited[t] = true
    add(prefix, "module", t)
    local mt = getmetatable(t)
    if type(mt) == "table" and rawget(mt, "__call") then add(prefix, "function", t) end
    local keys = {}
    for k in pairs(t) do if type(k) == "string" then keys[#keys + 1] = k end end
    table.sort(keys)
    for _, k in ipairs(keys) do
      local v = t[k]
      if k:sub(1, 1) ~= "_" then
        local n = prefix .. "." .. k
        if type(v) == "function" then add(n, "function", v)
        elseif type(v) == "table" and (getmetatable(v) == nil or rawget(getmetatable(v), "__call")
                                       or rawget(getmetatable(v), "__smi_members")) then walk(v, n, depth + 1) end
      end
    end
  end
  -- stdlib modules first, so that a module installed into smi (smi.study) keeps its own name
  for _, m in ipairs(M.stdlib) do walk(require(m), m, 0) end
  walk(smi, "smi", 0)
  local native = type(smi._docs) == "function" and smi._docs() or { types = {} }
  local types = {}
  for tname, methods in pairs(native.types or {}) do types[#types + 1] = { tname, methods } end
  for _, c in ipairs(classes) do
    local ok, obj = pcall(c[2])
    local idx = ok and getmetatable(obj) and getmetatable(obj).__index
    if type(idx) == "table" then types[#types + 1] = { c[1], idx } end
  end
  table.sort(types, function(a, b) return a[1] < b[1] end)
  for _, t in ipairs(types) do
    local keys = {}
    for k, v in pairs(t[2]) do if type(k) == "string" and type(v) == "function" and k:sub(1, 1) ~= "_" then keys[#keys + 1] = k end end
    table.sort(keys)
    for _, k in ipairs(keys) do add(t[1] .. ":" .. k, "method", t[2][k]) end
  end
  -- a table counts as a module only when it holds functions (smi.options.study_steps and
  -- smi.report.svg.palette are data)
  local list = {}
  for _, e in ipairs(out) do
    local keep = true
    if e.kind == "module" then
      keep = false
      for _, f in ipairs(out) do
        if f.kind ~= "module" and f.name:sub(1, #e.name + 1) == e.name .. "." then keep = true break end
      end
    end
    if keep then list[#list + 1] = e end
  end
  table.sort(list, function(a, b) return a.name < b.name end)
  return list
end

--- The doc entry of a name (string) or a value (a function or module found by the walk).
function M.get(x)
  local all = load_all()
  if type(x) == "string" then
    if all[x] then return all[x] end
    if all["smi." .. x] then return all["smi." .. x] end
    return nil
  end
  for _, w in ipairs(M.walk()) do
    if rawequal(w.value, x) and all[w.name] then return all[w.name] end
  end
  return nil
end

--- Names of public functions, methods and modules without a doc text (the coverage test), and
-- texts whose function no longer exists.
function M.missing()
  local all = load_all()
  local missing, found = {}, {}
  for _, w in ipairs(M.walk()) do
    found[w.name] = true
    local e = all[w.name]
    if not e then
      missing[#missing + 1] = w.name
    elseif e.kind ~= "module" then
      local lacks = {}
      if (e.summary or "") == "" then lacks[#lacks + 1] = "summary" end
      if not e.returns then lacks[#lacks + 1] = "returns:" end
      if not e.errors then lacks[#lacks + 1] = "errors:" end
      if not e.example then lacks[#lacks + 1] = "example:" end
      if #lacks > 0 then missing[#missing + 1] = w.name .. " (no " .. table.concat(lacks, ", ") .. ")" end
    end
  end
  local stale = {}
  for _, n in ipairs(order) do if not found[n] then stale[#stale + 1] = n end end
  return missing, stale
end

--- All entries, sorted by name.
function M.list()
  local all = load_all()
  local out = {}
  for _, n in ipairs(order) do out[#out + 1] = all[n] end
  return out
end

-- How well entry e matches one lowercase word (0: not at all).
local function word_score(e, w)
  local score = 0
  if e.name:lower() == w or e.name:lower():match("[%.:]" .. w:gsub("%p", "%%%0") .. "$") then score = 100
  elseif e.name:lower():find(w, 1, true) then score = 50 end
  for _, o in ipairs(e.options) do
    if o.name:lower():find(w, 1, true) then score = score + 20 end
    if o.meaning:lower():find(w, 1, true) then score = score + 5 end
  end
  if (e.summary or ""):lower():find(w, 1, true) then score = score + 10 end
  if (e.description or ""):lower():find(w, 1, true) or (e.returns or ""):lower():find(w, 1, true) then score = score + 3 end
  return score
end

--- Entries whose name, summary, options or text mention every word of `query` (case-insensitive,
-- in any order: "prior weight" finds smi.calibrate, whose text has "weight" and "prior"), best first.
function M.search(query)
  local words = {}
  for w in tostring(query):lower():gmatch("%S+") do words[#words + 1] = w end
  local hits = {}
  if #words == 0 then return hits end
  for _, e in ipairs(M.list()) do
    local score = 0
    for _, w in ipairs(words) do
      local s = word_score(e, w)
      if s == 0 then score = 0 break end
      score = score + s
    end
    if score > 0 then hits[#hits + 1] = { e = e, score = score } end
  end
  table.sort(hits, function(a, b) if a.score ~= b.score then return a.score > b.score end return a.e.name < b.e.name end)
  local out = {}
  for i, h in ipairs(hits) do out[i] = h.e end
  return out
end

--- The documented names closest to a misspelt one ("smi.kdee" -> {"smi.kde", ...}), nearest first.
function M.suggest(name)
  load_all()
  if type(smi) ~= "table" or type(smi._closest) ~= "function" then return {} end
  return smi._closest(tostring(name), order, 5)
end

local function wrap(s, width, indent)
  local out, line = {}, ""
  for word in s:gmatch("%S+") do
    if #line + #word + 1 > width and line ~= "" then out[#out + 1] = indent .. line; line = word
    else line = line == "" and word or (line .. " " .. word) end
  end
  if line ~= "" then out[#out + 1] = indent .. line end
  return table.concat(out, "\n")
end

--- The plain-text page of one entry (what help() and `smi-lua doc NAME` print).
function M.text(e)
  local out = { e.signature }
  if e.description and e.description ~= "" then
    for para in (e.description .. "\n"):gmatch("(.-)\n") do out[#out + 1] = wrap(para, 96, "  ") end
  end
  if #e.options > 0 then
    out[#out + 1] = "options:"
    local w = 0
    for _, o in ipairs(e.options) do w = math.max(w, #o.name + #o.default + 3) end
    w = math.min(w, 36)
    for _, o in ipairs(e.options) do
      local head = ("  %s = %s"):format(o.name, o.default)
      local pad = math.max(1, w - #head + 3)
      out[#out + 1] = head .. (" "):rep(pad) .. "-- " .. o.meaning
    end
  end
  if e.returns then out[#out + 1] = wrap("returns: " .. e.returns, 96, "") end
  if e.errors then out[#out + 1] = wrap("errors: " .. e.errors, 96, "") end
  if e.example then
    out[#out + 1] = "example:"
    for l in (e.example .. "\n"):gmatch("(.-)\n") do out[#out + 1] = "  " .. l end
  end
  if e.kind == "module" then
    local members = {}
    for _, x in ipairs(M.list()) do
      if x.name ~= e.name and (x.name:sub(1, #e.name + 1) == e.name .. "." or x.name:sub(1, #e.name + 1) == e.name .. ":") then
        members[#members + 1] = ("  %-30s %s"):format(x.name, x.summary or "")
      end
    end
    if #members > 0 then out[#out + 1] = "members:"; for _, m in ipairs(members) do out[#out + 1] = m end end
  end
  return table.concat(out, "\n")
end

--- The overview: the top-level modules and functions, one line each.
function M.overview()
  local out = { "smi-lua reference. help(smi.kde) or ?smi.kde for one entry, help \"word\" to search, smi-lua doc --html DIR for a browsable copy." }
  local seen = {}
  for _, e in ipairs(M.list()) do
    local top = e.name:match("^smi%.[%w_]+") or e.name
    if e.name ~= "smi" and not seen[top] and (e.name == top or (e.kind == "module" and not e.name:match("^smi%.[%w_]+[%.:]"))) then
      seen[top] = true
      local t = load_all()[top] or e
      out[#out + 1] = ("  %-22s %s"):format(top, t.summary or "")
    end
  end
  local head = table.remove(out, 1)
  for _, m in ipairs(M.stdlib) do
    if not seen[m] then
      seen[m] = true
      local t = load_all()[m]
      out[#out + 1] = ("  %-22s %s"):format(m, t and t.summary or "")
    end
  end
  table.sort(out)
  table.insert(out, 1, head)
  return table.concat(out, "\n")
end

-- Resolves what the user typed in help(...): a value, a doc name, an expression ("v:mean"), or
-- a word to search for.
local function resolve(x)
  if x == nil then return nil, "overview" end
  if type(x) ~= "string" then
    local e = M.get(x)
    if e then return e end
    local mt = getmetatable(x)
    if mt and type(mt.__name) == "string" and load_all()[mt.__name] then return load_all()[mt.__name] end
    -- an instance of a Lua class (a study, a report, a chart): its class's module entry
    if type(mt) == "table" and type(mt.__index) == "table" then
      for _, c in ipairs(classes) do
        local ok, obj = pcall(c[2])
        if ok and getmetatable(obj) and getmetatable(obj).__index == mt.__index then
          local name = c[1]
          while name and not load_all()[name] do name = name:match("^(.*)%.[^%.]+$") end
          if name then return load_all()[name] end
        end
      end
    end
    return nil, "no doc text for this " .. type(x) .. " (help() lists the modules)"
  end
  local s = trim(x)
  local e = load_all()[s]  -- a full name: "smi.kde", "smi.vec:mean", "smi.report.new"
  if e then return e end
  -- an expression the user has at hand: "smi.kde", "v.mean", "v:mean", "k:pdf"
  if s:match("^[%a_][%w_%.:]*$") then
    local f = load("return " .. s:gsub(":", "."), "=help", "t")
    if f then
      local ok, v = pcall(f)
      if ok and v ~= nil and type(v) ~= "string" then
        local r = M.get(v)
        if r then return r end
        local mt = getmetatable(v)
        local tname = mt and type(mt.__name) == "string" and mt.__name
        local method = s:match(":([%w_]+)$") or s:match("%.([%w_]+)$")
        if tname and method and load_all()[tname .. ":" .. method] then return load_all()[tname .. ":" .. method] end
      end
      -- "obj:method" where obj is a value of a documented type
      local obj, method = s:match("^(.-)[:%.]([%w_]+)$")
      if obj then
        local g = load("return " .. obj:gsub(":", "."), "=help", "t")
        local ok2, o = pcall(g or function() end)
        local mt = ok2 and getmetatable(o)
        local tname = mt and (type(mt.__name) == "string" and mt.__name)
        if tname and load_all()[tname .. ":" .. method] then return load_all()[tname .. ":" .. method] end
        -- a Lua class instance: find the method among the walk
        if ok2 and o ~= nil then
          local fn = type(o) == "table" and o[method]
          if fn then local r = M.get(fn) if r then return r end end
        end
      end
    end
  end
  return nil, "search"
end

--- What help(x) prints, as a string.
function M.help_text(x)
  load_all()
  local e, why = resolve(x)
  if e then return M.text(e) end
  if why == "overview" then return M.overview() end
  if why ~= "search" then return why end
  local hits = M.search(x)
  if #hits == 0 then
    local near = M.suggest(x)
    return ("nothing documented mentions '%s'%s (help() lists the modules)"):format(tostring(x),
      #near > 0 and ("; did you mean " .. table.concat(near, ", ") .. "?") or ""), "none"
  end
  local out = { ("%d entr%s '%s' (help(\"name\") shows one):"):format(#hits, #hits == 1 and "y mentions" or "ies mention", x) }
  for i, h in ipairs(hits) do
    if i > 40 then out[#out + 1] = ("  ... and %d more"):format(#hits - 40) break end
    out[#out + 1] = ("  %-30s %s"):format(h.name, h.summary or "")
  end
  return table.concat(out, "\n")
end

--- help(x): prints the entry of x (a function, module, method or name), the entries a word
-- appears in (help "bandwidth"), or the list of modules (help()).
function M.help(...)
  local n = select("#", ...)
  io.stdout:write(M.help_text(n == 0 and nil or (...)), "\n")
end

--- Sorted doc names starting with prefix (REPL completion inside help(" ... ").
function M.names(prefix)
  load_all()
  local out = {}
  for _, n in ipairs(order) do if n:sub(1, #prefix) == prefix then out[#out + 1] = n end end
  return out
end

--- The documented option lists against the option names the code reads: for every function that
-- checked its options (its option schema in the bindings, recorded by smi._known_options)
-- and has a doc entry, the names only one side has. Run after check_examples, which calls them.
-- Returns a list of problems ("smi.kde: documented but not read: x"). `known` ({fname = {names}})
-- replaces the recorded lists (tests).
function M.check_options(known)
  local all = load_all()
  known = known or (type(smi) == "table" and type(smi._known_options) == "function" and smi._known_options()) or {}
  local problems = {}
  local fnames = {}
  for f in pairs(known) do fnames[#fnames + 1] = f end
  table.sort(fnames)
  for _, f in ipairs(fnames) do
    local e = all[f]
    if e then
      local documented, read = {}, {}
      for _, o in ipairs(e.options) do documented[o.name] = true end
      -- "Options as smi.model.command, without template/deck/constants, plus:" inherits that
      -- entry's list (less the names after "without")
      local base, rest = (e.description or ""):match("[Oo]ptions as (smi[%w_%.:]+)(.-)plus")
      if base and all[base] then
        local without = {}
        for n in (rest:match("without ([%w_/ ]+)") or ""):gmatch("[%w_]+") do without[n] = true end
        for _, o in ipairs(all[base].options) do if not without[o.name] then documented[o.name] = true end end
      end
      for _, k in ipairs(known[f]) do read[k] = true end
      local only_doc, only_code = {}, {}
      for k in pairs(documented) do if not read[k] then only_doc[#only_doc + 1] = k end end
      for k in pairs(read) do if not documented[k] then only_code[#only_code + 1] = k end end
      table.sort(only_doc); table.sort(only_code)
      if #only_doc > 0 then problems[#problems + 1] = ("%s: documented but not read by the code: %s"):format(f, table.concat(only_doc, ", ")) end
      if #only_code > 0 then problems[#problems + 1] = ("%s: read by the code but not documented: %s"):format(f, table.concat(only_code, ", ")) end
    end
  end
  return problems
end

--- Runs one entry's example in a fresh environment; returns ok, output (print lines) or error.
function M.run_example(e)
  local lines = {}
  local env = setmetatable({}, { __index = _G })
  env.print = function(...)
    local t = {}
    for i = 1, select("#", ...) do t[i] = tostring((select(i, ...))) end
    lines[#lines + 1] = table.concat(t, "\t")
  end
  local f, err = load(e.example, "=example of " .. e.name, "t", env)
  if not f then return false, err end
  -- modules called by the example print through the global print (T.finish): capture it too
  local global_print = _G.print
  _G.print = env.print
  local ok, perr = xpcall(f, function(m) return debug and debug.traceback and debug.traceback(tostring(m), 2) or tostring(m) end)
  _G.print = global_print
  if not ok then return false, tostring(perr) end
  return true, table.concat(lines, "\n")
end

--- Runs every example; returns the number that failed after printing each failure to stderr.
function M.check_examples(verbose)
  local failed, n = 0, 0
  for _, e in ipairs(M.list()) do
    if e.example then
      n = n + 1
      local ok, out = M.run_example(e)
      if not ok then
        failed = failed + 1
        io.stderr:write("example of ", e.name, " failed:\n", out, "\n")
      elseif verbose then
        io.stdout:write("ok ", e.name, "\n")
      end
    end
  end
  return failed, n
end

return M
