-- SPDX-License-Identifier: MIT
--- smi.report.xmlcheck: a strict little XML parser, to prove that generated SVG/HTML is
-- well-formed (balanced tags, quoted unique attributes, valid entities, no raw '<' or '&')
-- and to let tests look inside it.
--
--   local ok, err = xmlcheck.check(s)      -- err names the line and the problem
--   local root = xmlcheck.parse(s)         -- {name=, attrs={}, children={...}, text=...}; raises
--   xmlcheck.find_all(root, "path")        -- every element with that name, document order
local M = {}

local NAME = "^[%a_:][%w_:%.%-]*"
local ENTITY = { amp = "&", lt = "<", gt = ">", quot = '"', apos = "'" }

local function line_of(s, i)
  local line = 1
  for _ in s:sub(1, i - 1):gmatch("\n") do line = line + 1 end
  return line
end

local function fail(s, i, msg)
  error(("line %d: %s"):format(line_of(s, i), msg), 0)
end

-- Decodes entities of text between i and j, checking each one.
local function text_of(s, i, j)
  local raw = s:sub(i, j)
  local lt = raw:find("<", 1, true)
  if lt then fail(s, i + lt - 1, "raw '<' in text") end
  local cc = raw:find("[%z\1-\8\11\12\14-\31]")
  if cc then fail(s, i + cc - 1, ("control character %d (not allowed in XML 1.0)"):format(raw:byte(cc))) end
  if not utf8.len(raw) then fail(s, i, "invalid UTF-8") end
  return (raw:gsub("&([^;%s<&]*);?", function(name)
    local full = name
    if ENTITY[full] then return ENTITY[full] end
    local num = full:match("^#x(%x+)$") and tonumber(full:sub(3), 16) or (full:match("^#(%d+)$") and tonumber(full:sub(2)))
    if num and num > 0 and num <= 0x10FFFF then return utf8.char(num) end
    fail(s, i, "bad entity '&" .. full .. "' (escape '&' as &amp;)")
  end))
end

-- The start tag at s[i] ("<name attr='v' ...>" or ".../>"): the element (name, attrs, empty,
-- pos) and the index just past the tag.
local function start_tag(s, i)
  local name = s:match(NAME, i + 1) or fail(s, i, "bad start tag (a raw '<' in text?)")
  local el = { name = name, attrs = {}, children = {}, pos = i }
  local j = i + 1 + #name
  while true do
    local ws, after = s:match("^(%s*)()", j)
    j = after
    local c = s:sub(j, j)
    if c == ">" then j = j + 1 break end
    if s:sub(j, j + 1) == "/>" then el.empty = true j = j + 2 break end
    if c == "" then fail(s, i, "unterminated start tag <" .. name) end
    if ws == "" then fail(s, j, "attributes of <" .. name .. "> must be separated by spaces") end
    local an = s:match(NAME, j) or fail(s, j, "bad attribute in <" .. name .. ">")
    j = j + #an
    local q, vstart = s:match("^%s*=%s*([\"'])()", j)
    if not q then fail(s, j, ("attribute %s of <%s> needs a quoted value"):format(an, name)) end
    local vend = s:find(q, vstart, true) or fail(s, j, "unterminated attribute value")
    if el.attrs[an] ~= nil then fail(s, j, ("duplicate attribute %s in <%s>"):format(an, name)) end
    el.attrs[an] = text_of(s, vstart, vend - 1)
    j = vend + 1
  end
  return el, j
end

--- Parses `s` and returns the root element; raises "line N: problem" when not well-formed.
-- An HTML5 "<!DOCTYPE html>" prologue is accepted.
function M.parse(s)
  if type(s) ~= "string" then error("xmlcheck: expected a string, got " .. type(s), 0) end
  local i, n = 1, #s
  local stack, root = {}, nil
  local doc = { children = {} }
  local function top() return stack[#stack] or doc end
  while i <= n do
    local lt = s:find("<", i, true)
    local stop = (lt or n + 1) - 1
    if stop >= i then
      local t = text_of(s, i, stop)
      if #stack == 0 then
        if t:match("%S") then fail(s, i, "text outside the root element") end
      else
        local cur = top()
        cur.text = (cur.text or "") .. t
        cur.children[#cur.children + 1] = t
      end
    end
    if not lt then break end
    i = lt
    if s:sub(i, i + 3) == "<!--" then
      local e = s:find("-->", i + 4, true) or fail(s, i, "unterminated comment")
      i = e + 3
    elseif s:sub(i, i + 8) == "<![CDATA[" then
      local e = s:find("]]>", i + 9, true) or fail(s, i, "unterminated CDATA")
      if #stack == 0 then fail(s, i, "CDATA outside the root element") end
      local cur = top()
      cur.text = (cur.text or "") .. s:sub(i + 9, e - 1)
      i = e + 3
    elseif s:sub(i, i + 1) == "<?" then
      local e = s:find("?>", i + 2, true) or fail(s, i, "unterminated processing instruction")
      i = e + 2
    elseif s:sub(i, i + 1) == "<!" then
      if root then fail(s, i, "DOCTYPE after the root element") end
      local e = s:find(">", i + 2, true) or fail(s, i, "unterminated DOCTYPE")
      i = e + 1
    elseif s:sub(i, i + 1) == "</" then
      local name = s:match(NAME, i + 2) or fail(s, i, "bad end tag")
      local e = s:match("^%s*>()", i + 2 + #name) or fail(s, i, "bad end tag </" .. name)
      local open = stack[#stack]
      if not open then fail(s, i, "end tag </" .. name .. "> with no open element") end
      if open.name ~= name then fail(s, i, ("end tag </%s> does not match <%s> opened on line %d"):format(name, open.name, line_of(s, open.pos))) end
      stack[#stack] = nil
      i = e
    else
      local el, j = start_tag(s, i)
      local name = el.name
      if root and #stack == 0 then fail(s, i, "a second root element <" .. name .. ">") end
      local parent = top()
      parent.children[#parent.children + 1] = el
      if not root then root = el end
      if not el.empty then stack[#stack + 1] = el end
      i = j
    end
  end
  if #stack > 0 then
    local open = stack[#stack]
    fail(s, n, ("<%s> opened on line %d is never closed"):format(open.name, line_of(s, open.pos)))
  end
  if not root then error("line 1: no root element", 0) end
  return root
end

--- true, or false and the problem.
function M.check(s)
  local ok, err = pcall(M.parse, s)
  if ok then return true end
  return false, tostring(err)
end

--- Every element named `name` under `el` (itself included), in document order.
function M.find_all(el, name, out)
  out = out or {}
  if type(el) ~= "table" then return out end
  if el.name == name then out[#out + 1] = el end
  for _, c in ipairs(el.children) do M.find_all(c, name, out) end
  return out
end

--- Every element named `name` under `root` whose class attribute lists `class`.
function M.find_by_class(root, name, class)
  local out = {}
  for _, e in ipairs(M.find_all(root, name)) do
    if (" " .. (e.attrs.class or "") .. " "):find(" " .. class .. " ", 1, true) then out[#out + 1] = e end
  end
  return out
end

--- The text content of `el` and all its descendants.
function M.text(el)
  local parts = {}
  local function walk(e)
    for _, c in ipairs(e.children) do
      if type(c) == "string" then parts[#parts + 1] = c else walk(c) end
    end
  end
  walk(el)
  return table.concat(parts)
end

return M
