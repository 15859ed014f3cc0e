-- SPDX-License-Identifier: MIT
--- smi.report.format: numbers as people read them in tables and on charts.
local doc = require "smi.doc"
doc.add[==[
@ module smi.report.format
Numbers as people read them in tables and on charts.
]==]
local M = {}

local floor, abs = math.floor, math.abs

doc.add[==[
@ smi.report.format.num(x [, digits [, unit]]) -> string
x with digits significant digits (default 4), trailing zeros dropped; whole numbers as integers;
scientific notation below 1e-3 and from 1e6 on; NaN as "NaN", infinities as "inf"/"-inf"; with
a unit, the unit follows after a space ("246.3 Hz").
returns: a string
errors: none
example:
  local f = require("smi.report").format
  print(f.num(246312.7), f.num(0.000123456), f.num(3.14159, 3), f.num(12), f.num(31.84, 4, "Hz"))
]==]
--- `x` with `digits` significant digits (default 4), trailing zeros dropped; integers
-- (Lua integers, or floats that are whole and below 1e15 when `digits` covers them) as integers;
-- scientific notation below 1e-3 and from 1e6 on; NaN as "NaN", infinities as "inf"/"-inf".
function M.num(x, digits, unit)
  if unit ~= nil and unit ~= "" then return M.num(x, digits) .. " " .. unit end
  digits = digits or 4
  if type(x) ~= "number" then return tostring(x) end
  if x ~= x then return "NaN" end
  if x == math.huge then return "inf" end
  if x == -math.huge then return "-inf" end
  if math.type(x) == "integer" then return ("%d"):format(x) end
  if x == 0 then return "0" end
  local ax = abs(x)
  local e = floor(math.log(ax, 10))
  if ax >= 1e6 or ax < 1e-3 then
    local s = ("%." .. (digits - 1) .. "e"):format(x)
    local mant, exp = s:match("^(.-)e(.*)$")
    if mant:find("%.") then mant = mant:gsub("0+$", ""):gsub("%.$", "") end
    return mant .. "e" .. tonumber(exp)
  end
  local dec = math.max(0, digits - 1 - e)
  local s = ("%." .. dec .. "f"):format(x)
  if s:find("%.") then s = s:gsub("0+$", ""):gsub("%.$", "") end
  if s == "-0" then s = "0" end
  return s
end

doc.add[==[
@ smi.report.format.column(values [, digits]) -> formatter
A formatter for a table column: one number of decimals for the whole column so that the decimal
points line up (falls back to format.num for columns spanning more than a factor 100).
returns: a function(x) returning a string
errors: none
example:
  local f = require("smi.report").format
  local g = f.column({1.5, 22.25, 3}, 4)
  print(g(1.5), g(22.25))
]==]
--- A formatter for a table column: one number of decimals for the whole column, so that the
-- decimal points line up, chosen to give the largest magnitude `digits` significant digits.
-- Columns spanning below 1e-3 or from 1e6 on, or over more than a factor 100, fall back to
-- M.num for each value.
function M.column(values, digits)
  digits = digits or 4
  local big, small, all_int = 0, math.huge, true
  for _, x in ipairs(values) do
    if type(x) == "number" and x == x and x ~= math.huge and x ~= -math.huge then
      local ax = abs(x)
      if ax > big then big = ax end
      if ax > 0 and ax < small then small = ax end
      if math.type(x) ~= "integer" then all_int = false end
    end
  end
  if all_int then return function(x) return M.num(x, digits) end end
  -- columns mixing magnitudes (rows in different units) read better value by value
  if big >= 1e6 or (small < 1e-3 and small ~= math.huge) or big == 0 or big / small > 100 then
    return function(x) return M.num(x, digits) end
  end
  local dec = math.max(0, digits - 1 - floor(math.log(big, 10)))
  -- the smallest value keeps at least two significant digits
  dec = math.max(dec, math.min(6, 1 - floor(math.log(small, 10))))
  local pattern = "%." .. dec .. "f"
  return function(x)
    if type(x) ~= "number" or x ~= x or x == math.huge or x == -math.huge then return M.num(x, digits) end
    local s = pattern:format(x)
    if s:match("^%-0%.?0*$") then s = s:sub(2) end
    return s
  end
end

doc.add[==[
@ smi.report.format.exact(x) -> string
x with the digits it carries and no binary noise: at most 10 significant digits, trailing zeros
dropped (1.4999999999999998e-09 -> "1.5e-09", 7790.000000000005 -> "7790"); integers whole.
For values recorded as they are (provenance, settings) rather than measured.
returns: a string
errors: none
example:
  local f = require("smi.report").format
  print(f.exact(1.4999999999999998e-09), f.exact(7790.000000000005), f.exact(20200214))
]==]
--- At most 10 significant digits: enough for any value typed by a person or a setting, and
-- short of the 15-17 digits where a float's binary rounding shows.
function M.exact(x)
  if type(x) ~= "number" then return tostring(x) end
  if math.type(x) == "integer" then return ("%d"):format(x) end
  if x ~= x then return "NaN" end
  if x == math.huge then return "inf" end
  if x == -math.huge then return "-inf" end
  local s = ("%.10g"):format(x)
  local mant, exp = s:match("^(.-)(e.*)$")
  mant = mant or s
  if mant:find("%.") then mant = mant:gsub("0+$", ""):gsub("%.$", "") end
  return mant .. (exp or "")
end

doc.add[==[
@ smi.report.format.tidy(text) -> string
The text with every decimal number that carries more than 10 significant digits (binary noise
such as 1.4999999999999998e-09 or 7790.000000000005 from a string.format("%s", x)) rewritten
as smi.report.format.exact would write it; other text, integers and short numbers are kept.
The report passes its text, details, captions and text cells through it.
returns: a string
errors: none
example:
  local f = require("smi.report").format
  print(f.tidy("E = 7790.000000000005 kg/m3, t = 1.4999999999999998e-09 s, n = 12"))
]==]
--- Rewrites decimal numbers with more than 10 significant digits (see the doc above).
function M.tidy(text)
  text = tostring(text)
  if not text:find("%d%.%d") then return text end
  -- a number: digits with a decimal point (and an optional exponent), not part of a word or a
  -- dotted version/address (a.b.c)
  local out, pos = {}, 1
  while true do
    local i, j = text:find("%d+%.%d+", pos)
    if not i then break end
    local k = j
    local e = text:match("^[eE][-+]?%d+", j + 1)
    if e then k = j + #e end
    local num = text:sub(i, k)
    local before, after = text:sub(i - 1, i - 1), text:sub(k + 1, k + 1)
    local sig = num:match("^[%d.]+"):gsub("%.", ""):gsub("^0+", "")
    -- not part of a word, a hash or a dotted version/address (a.b.c)
    if #sig > 10 and not before:match("[%w_.]") and not after:match("[%w_]")
       and not (after == "." and text:sub(k + 2, k + 2):match("%d")) then
      out[#out + 1] = text:sub(pos, i - 1) .. M.exact(tonumber(num))
    else
      out[#out + 1] = text:sub(pos, k)
    end
    pos = k + 1
  end
  out[#out + 1] = text:sub(pos)
  return table.concat(out)
end

doc.add[==[
@ smi.report.format.seconds(t) -> string
A duration in seconds as "0.8 ms", "0.42 s", "31.2 s", "2 min 05 s".
returns: a string
errors: none
example:
  local f = require("smi.report").format
  print(f.seconds(0.0008), f.seconds(125))
]==]
--- A duration in seconds as "0.8 ms", "0.42 s", "31.2 s", "2 min 05 s".
function M.seconds(t)
  if t < 0.1 then return ("%.1f ms"):format(t * 1000) end
  if t < 60 then return ("%.2f s"):format(t) end
  return ("%d min %02d s"):format(floor(t / 60), floor(t % 60))
end

return M
