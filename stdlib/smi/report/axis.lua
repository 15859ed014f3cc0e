-- SPDX-License-Identifier: MIT
--- smi.report.axis: "nice" axis ranges and ticks, linear and log10 scales, tick labels.
-- Ticks are multiples of 1, 2 or 5 x 10^k (Heckbert's "nice numbers"), and the axis range is
-- widened to whole ticks so that every data point lies inside it.
local M = {}

local floor, ceil, log10, abs = math.floor, math.ceil, math.log10 or function(x) return math.log(x, 10) end, math.abs

local LIMIT, LOG_LO, LOG_HI = 1e307, 1e-300, 1e300

local function finite(x) return type(x) == "number" and x == x and x ~= math.huge and x ~= -math.huge end
M.finite = finite

--- The nice number closest to x (round=true) or not below it (round=false): 1, 2, 5 x 10^k.
local function nice(x, round)
  local e = floor(log10(x))
  local f = x / 10 ^ e
  local nf
  if round then
    nf = (f < 1.5 and 1) or (f < 3 and 2) or (f < 7 and 5) or 10
  else
    nf = (f <= 1 and 1) or (f <= 2 and 2) or (f <= 5 and 5) or 10
  end
  return nf * 10 ^ e
end

--- Ticks for data in [lo, hi] aiming at about `target` ticks (default 6).
-- Returns {lo=, hi=, step=, ticks={...}} with lo <= min, hi >= max, ticks from lo to hi.
function M.linear(lo, hi, target)
  target = target or 6
  assert(finite(lo) and finite(hi), "axis.linear: the range must be finite")
  if lo > hi then lo, hi = hi, lo end
  -- beyond +/-1e307 the arithmetic below would overflow; such values sit at the edge
  lo, hi = math.max(math.min(lo, LIMIT), -LIMIT), math.max(math.min(hi, LIMIT), -LIMIT)
  if hi - lo <= 1e-9 * math.max(abs(lo), abs(hi)) or hi - lo < 1e-290 then
    -- a single value: a range around it (or around 0 for 0 and subnormal values)
    local pad = abs(lo) > 1e-280 and abs(lo) * 0.1 or 1
    lo, hi = lo - pad, hi + pad
  end
  -- halves keep the width finite even for data near +/-1.8e308
  local step = nice((hi / 2 - lo / 2) / (target - 1) * 2, true)
  local k0, k1 = floor(lo / step + 1e-9), ceil(hi / step - 1e-9)
  -- the tolerance absorbs rounding in lo/step, but the range must still cover the data
  if k0 * step > lo then k0 = k0 - 1 end
  if k1 * step < hi then k1 = k1 + 1 end
  local a, b = k0 * step, k1 * step
  local ticks = {}
  for k = k0, k1 do
    local t = k * step
    if abs(t) < step * 1e-9 then t = 0 end
    ticks[#ticks + 1] = t
  end
  return { lo = a, hi = b, step = step, ticks = ticks, log = false }
end

--- Log10 ticks: whole decades covering [lo, hi] (both > 0).
function M.log(lo, hi)
  assert(finite(lo) and finite(hi) and lo > 0 and hi > 0, "axis.log: the range must be finite and > 0")
  if lo > hi then lo, hi = hi, lo end
  lo, hi = math.min(math.max(lo, LOG_LO), LOG_HI), math.min(math.max(hi, LOG_LO), LOG_HI)
  local a, b = floor(log10(lo) + 1e-9), ceil(log10(hi) - 1e-9)
  if a == b then a, b = a - 1, b + 1 end
  local every = math.max(1, ceil((b - a) / 8))
  local ticks = {}
  for e = a, b, every do ticks[#ticks + 1] = 10.0 ^ e end
  return { lo = 10.0 ^ a, hi = 10.0 ^ b, step = every, ticks = ticks, log = true }
end

--- A function mapping data x to pixel p, for an axis from `ax` onto [p0, p1].
function M.scale(ax, p0, p1)
  if ax.log then
    local a, b = log10(ax.lo), log10(ax.hi)
    return function(x) return p0 + (log10(x) - a) / (b - a) * (p1 - p0) end
  end
  local a, b = ax.lo / 2, ax.hi / 2
  return function(x) return p0 + (x / 2 - a) / (b - a) * (p1 - p0) end
end

--- Tick label: as many decimals as the step needs, scientific for very large/small magnitudes.
function M.label(x, ax)
  if x == 0 then return "0" end
  if ax and ax.log then
    local e = floor(log10(x) + 0.5)
    if e >= -3 and e <= 4 then return M.label(10.0 ^ e, { step = 10.0 ^ math.min(e, 0) }) end
    return ("1e%d"):format(e)
  end
  local step = ax and ax.step or abs(x)
  local big = math.max(abs(x), step)
  if big >= 1e6 or step < 1e-4 then
    local s = ("%.3g"):format(x):gsub("e%+?(%-?)0*(%d)", "e%1%2")
    return s
  end
  local decimals = math.max(0, -floor(log10(step) + 1e-9))
  -- a step of 2.5 (never produced, but allowed for callers) needs one more digit
  if abs(step / 10 ^ -decimals - floor(step / 10 ^ -decimals + 0.5)) > 1e-6 then decimals = decimals + 1 end
  local s = ("%." .. decimals .. "f"):format(x)
  if s:match("^%-0%.?0*$") then s = s:sub(2) end
  return s
end

return M
