-- SPDX-License-Identifier: MIT
--- smi.report.xml: text escaping and attribute formatting shared by the SVG and HTML writers.
-- Everything a caller gives us (titles, labels, table cells) goes through escape(), so a
-- label like "a<b & c" can never break the document.
local M = {}

local entities = { ["&"] = "&amp;", ["<"] = "&lt;", [">"] = "&gt;", ['"'] = "&quot;", ["'"] = "&#39;" }

--- Escapes &<>"' and replaces what XML 1.0 forbids: control characters (except tab and
-- newline) and invalid UTF-8 (each bad byte becomes "?"), so the output always parses.
function M.escape(s)
  s = tostring(s)
  if not utf8.len(s) then
    -- keep the valid UTF-8 sequences, replace each stray byte
    local out, i, n = {}, 1, #s
    while i <= n do
      local ok, len = pcall(utf8.len, s, i, i)
      local code = ok and len == 1 and utf8.codepoint(s, i) or nil
      if code then
        local nb = #utf8.char(code)
        out[#out + 1] = s:sub(i, i + nb - 1)
        i = i + nb
      else
        out[#out + 1] = "?"
        i = i + 1
      end
    end
    s = table.concat(out)
  end
  s = s:gsub("[%z\1-\8\11\12\14-\31\127]", "?")
  return (s:gsub("[&<>\"']", entities))
end

--- ' k="v"' for each pair of `attrs`, keys sorted so the output is stable; nil/false skipped.
function M.attrs(attrs)
  if not attrs then return "" end
  local keys = {}
  for k, v in pairs(attrs) do
    if v ~= nil and v ~= false then keys[#keys + 1] = k end
  end
  table.sort(keys)
  local parts = {}
  for _, k in ipairs(keys) do
    parts[#parts + 1] = (' %s="%s"'):format(k, M.escape(attrs[k]))
  end
  return table.concat(parts)
end

--- <name attrs>escaped text</name>; `text` nil gives a self-closed element.
function M.el(name, attrs, text)
  if text == nil then return ("<%s%s/>"):format(name, M.attrs(attrs)) end
  return ("<%s%s>%s</%s>"):format(name, M.attrs(attrs), M.escape(text), name)
end

--- Same, with `inner` already markup (not escaped).
function M.wrap(name, attrs, inner)
  return ("<%s%s>%s</%s>"):format(name, M.attrs(attrs), inner or "", name)
end

return M
