-- SPDX-License-Identifier: MIT
--- smi.doc.markdown: the guides (docs/*.md) as HTML for `smi-lua doc --html`. The subset they
-- use: headings, paragraphs, fenced code blocks, lists (- and 1.), tables, block quotes,
-- `code`, **bold**, *emphasis*, [links](target). Every character of the text is escaped: no
-- HTML passes through, and a link target is kept only when it is a relative path or an
-- http(s) address (a link to another guide, name.md, becomes name.html).
local M = {}

local function esc(s)
  return (tostring(s):gsub("[&<>\"']", { ["&"] = "&amp;", ["<"] = "&lt;", [">"] = "&gt;", ['"'] = "&quot;", ["'"] = "&#39;" }))
end
M.escape = esc

-- A link target allowed in the page: relative (no scheme) or http(s); anything else (javascript:,
-- data:) is dropped. A guide's .md becomes its .html.
local function target(t)
  t = t:gsub("^%s+", ""):gsub("%s+$", "")
  local scheme = t:match("^([%a][%w+.-]*):")
  if scheme and scheme:lower() ~= "http" and scheme:lower() ~= "https" then return nil end
  if not scheme then t = t:gsub("%.md$", ".html"):gsub("%.md#", ".html#") end
  return t
end

--- Inline markup of one line of text: code spans first (their contents are literal), then links,
-- bold and emphasis over the escaped rest.
function M.inline(s)
  local out, i = {}, 1
  while i <= #s do
    local a, b, ticks = s:find("(`+)", i)
    if not a then out[#out + 1] = M.spans(s:sub(i)) break end
    local c, d = s:find(ticks, b + 1, true)
    if not c then out[#out + 1] = M.spans(s:sub(i)) break end
    out[#out + 1] = M.spans(s:sub(i, a - 1))
    out[#out + 1] = "<code>" .. esc(s:sub(b + 1, c - 1)) .. "</code>"
    i = d + 1
  end
  return table.concat(out)
end

-- Links, bold and emphasis in text without code spans.
function M.spans(s)
  local out, i = {}, 1
  while i <= #s do
    local a, b, text, url = s:find("%[([^%]]+)%]%(([^)%s]+)%)", i)
    if not a then out[#out + 1] = M.emphasis(esc(s:sub(i))) break end
    out[#out + 1] = M.emphasis(esc(s:sub(i, a - 1)))
    local t = target(url)
    if t then
      out[#out + 1] = ('<a href="%s">%s</a>'):format(esc(t), M.emphasis(esc(text)))
    else
      out[#out + 1] = M.emphasis(esc(text))
    end
    i = b + 1
  end
  return table.concat(out)
end

-- **bold** and *emphasis* over escaped text (asterisks are not escaped: safe to match).
function M.emphasis(s)
  s = s:gsub("%*%*(%S.-%S?)%*%*", "<strong>%1</strong>")
  s = s:gsub("%f[%w*]%*(%S[^*]-)%*%f[^%w*]", "<em>%1</em>")
  return s
end

local function cells(line)
  line = line:gsub("^%s*|", ""):gsub("|%s*$", "")
  local out = {}
  -- a pipe inside a code span (`a|b`) stays in its cell
  local buf, code = {}, false
  for ch in line:gmatch(".") do
    if ch == "`" then code = not code end
    if ch == "|" and not code then
      out[#out + 1] = table.concat(buf):gsub("^%s+", ""):gsub("%s+$", "")
      buf = {}
    else
      buf[#buf + 1] = ch
    end
  end
  out[#out + 1] = table.concat(buf):gsub("^%s+", ""):gsub("%s+$", "")
  return out
end

local function heading_id(text, used)
  local id = text:lower():gsub("`", ""):gsub("[^%w]+", "-"):gsub("^%-+", ""):gsub("%-+$", "")
  if id == "" then id = "section" end
  local base, n = id, 1
  while used[id] do n = n + 1; id = base .. "-" .. n end
  used[id] = true
  return id
end

--- The HTML of a Markdown text (the body of a page: no <html> around it).
function M.render(text)
  local lines = {}
  for line in (tostring(text):gsub("\r\n", "\n") .. "\n"):gmatch("(.-)\n") do lines[#lines + 1] = line end
  local out, used, i = {}, {}, 1
  local para = {}
  local function flush()
    if #para > 0 then out[#out + 1] = "<p>" .. M.inline(table.concat(para, " ")) .. "</p>" end
    para = {}
  end
  while i <= #lines do
    local line = lines[i]
    local fence = line:match("^%s*(```+)")
    if fence then
      flush()
      local lang = line:match("^%s*```+%s*([%w_+-]*)")
      local code = {}
      i = i + 1
      while i <= #lines and not lines[i]:match("^%s*" .. fence .. "%s*$") do code[#code + 1] = lines[i]; i = i + 1 end
      out[#out + 1] = "<pre><code" .. (lang ~= "" and (' class="language-' .. esc(lang) .. '"') or "") .. ">"
        .. esc(table.concat(code, "\n")) .. "</code></pre>"
      i = i + 1
    elseif line:match("^#+%s") then
      flush()
      local hashes, text = line:match("^(#+)%s+(.-)%s*#*%s*$")
      local n = math.min(#hashes, 6)
      out[#out + 1] = ('<h%d id="%s">%s</h%d>'):format(n, heading_id(text, used), M.inline(text), n)
      i = i + 1
    elseif line:match("^%s*|") and lines[i + 1] and lines[i + 1]:match("^%s*|?%s*:?%-%-+") then
      flush()
      local head = cells(line)
      local t = { '<div class="table-wrap"><table><thead><tr>' }
      for _, c in ipairs(head) do t[#t + 1] = "<th>" .. M.inline(c) .. "</th>" end
      t[#t + 1] = "</tr></thead><tbody>"
      i = i + 2
      while i <= #lines and lines[i]:match("^%s*|") do
        t[#t + 1] = "<tr>"
        for _, c in ipairs(cells(lines[i])) do t[#t + 1] = "<td>" .. M.inline(c) .. "</td>" end
        t[#t + 1] = "</tr>"
        i = i + 1
      end
      t[#t + 1] = "</tbody></table></div>"
      out[#out + 1] = table.concat(t)
    elseif line:match("^%s*[-*+]%s") or line:match("^%s*%d+[.)]%s") then
      flush()
      local ordered = line:match("^%s*%d+[.)]%s") ~= nil
      local items = {}
      while i <= #lines do
        local l = lines[i]
        local item = ordered and l:match("^%s*%d+[.)]%s+(.*)$") or (not ordered and l:match("^%s*[-*+]%s+(.*)$"))
        if item then
          items[#items + 1] = { item }
        elseif l:match("^%s+%S") and #items > 0 then
          table.insert(items[#items], (l:gsub("^%s+", "")))  -- a continuation line
        else
          break
        end
        i = i + 1
      end
      local tag = ordered and "ol" or "ul"
      local li = {}
      for k, it in ipairs(items) do li[k] = "<li>" .. M.inline(table.concat(it, " ")) .. "</li>" end
      out[#out + 1] = "<" .. tag .. ">" .. table.concat(li) .. "</" .. tag .. ">"
    elseif line:match("^%s*>") then
      flush()
      local q = {}
      while i <= #lines and lines[i]:match("^%s*>") do q[#q + 1] = lines[i]:gsub("^%s*>%s?", ""); i = i + 1 end
      out[#out + 1] = "<blockquote>" .. M.render(table.concat(q, "\n")) .. "</blockquote>"
    elseif line:match("^%s*$") then
      flush()
      i = i + 1
    else
      para[#para + 1] = (line:gsub("^%s+", ""))
      i = i + 1
    end
  end
  flush()
  return table.concat(out, "\n")
end

--- The first heading of a Markdown text (a guide's title), or nil.
function M.title(text)
  return tostring(text):match("^#%s+([^\n]-)%s*\n") or tostring(text):match("\n#%s+([^\n]-)%s*\n")
end

return M
