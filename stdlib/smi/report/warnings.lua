-- SPDX-License-Identifier: MIT
--- smi.report.warnings: a report's warnings grouped and counted. The same warning raised per
-- trial or per parameter reads once, with how often it came and the sections it concerns; two
-- warnings that differ only in their numbers or quoted names ("input 'E': ... [1.2, 3.4]" and
-- "input 'nu': ... [0.2, 0.4]") are one group, shown by its first text.
local fmt = require "smi.report.format"

local M = {}

--- The grouping key of a warning's text: numbers and quoted names masked.
function M.key(text)
  return (fmt.tidy(tostring(text)):gsub("'[^']*'", "'_'"):gsub("[-+]?%d[%d.,eE+-]*", "#"))
end

--- Groups {text =, where = section title | nil} entries, in the order they were first raised:
-- {{text = first text, count = n, where = {titles, in order, once each}, texts = {distinct texts}}}.
function M.group(entries)
  local groups, by = {}, {}
  for _, e in ipairs(entries) do
    local k = M.key(e.text)
    local g = by[k]
    if not g then
      g = { text = fmt.tidy(tostring(e.text)), count = 0, where = {}, seen = {}, texts = {}, seen_text = {} }
      by[k] = g
      groups[#groups + 1] = g
    end
    g.count = g.count + 1
    if e.where and not g.seen[e.where] then
      g.seen[e.where] = true
      g.where[#g.where + 1] = e.where
    end
    if not g.seen_text[e.text] then
      g.seen_text[e.text] = true
      g.texts[#g.texts + 1] = e.text
    end
  end
  for _, g in ipairs(groups) do g.seen, g.seen_text = nil, nil end
  return groups
end

--- " (and 2 more like it)" when a group holds several distinct texts, else "".
function M.similar(g)
  local more = #g.texts - 1
  if more <= 0 then return "" end
  return (" (and %d more like it)"):format(more)
end

--- Console lines for the groups: "  3x  <text>  (in: Trial 1, Trial 2)".
function M.lines(groups)
  local out = {}
  for _, g in ipairs(groups) do
    local where = #g.where > 0 and ("  [" .. table.concat(g.where, "; ") .. "]") or ""
    out[#out + 1] = ("  %s%s%s%s"):format(g.count > 1 and (g.count .. "x ") or "", g.text, M.similar(g), where)
  end
  return out
end

return M
