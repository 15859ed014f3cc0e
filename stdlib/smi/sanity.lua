-- SPDX-License-Identifier: MIT
--- smi.sanity: warnings about data that a study would otherwise use without a word.
--
--   local sanity = require "smi.sanity"
--   local w = sanity.units("mode 1 (Hz)", data, model_lo, model_hi)   -- nil or a warning text
--
-- units(): measured values an order of magnitude or more away from everything the model gives
-- over its input bounds are most often a units mistake (kHz for Hz, mm for m, rad/s for Hz,
-- rpm for Hz): every later verdict would fail or pass for that reason alone. Data somewhat
-- outside the model's range are normal (that is what calibration corrects) and pass quietly:
-- the warning needs the median of the data at least `factor` (default 3) times away from the
-- model's range and outside it.
local M = {}

local KNOWN = { { 1000, "a factor of 1000 (kHz vs Hz, mm vs m, MPa vs kPa?)" }, { 1e6, "a factor of 10^6 (MHz vs Hz, mm² vs m²?)" },
                { 2 * math.pi, "a factor of 2π (rad/s vs Hz?)" }, { 60, "a factor of 60 (rpm vs Hz, minutes vs seconds?)" },
                { 25.4, "a factor of 25.4 (inches vs mm?)" } }

local function median(t)
  local s = {}
  for i = 1, #t do s[i] = t[i] end
  table.sort(s)
  local n = #s
  if n == 0 then return nil end
  return n % 2 == 1 and s[(n + 1) / 2] or 0.5 * (s[n / 2] + s[n / 2 + 1])
end

function M.units(label, data, model_lo, model_hi, factor)
  factor = factor or 3
  local vals = {}
  for i = 1, #data do vals[i] = data[i] end
  local med = median(vals)
  if not med or not (model_lo <= model_hi) or model_lo <= 0 or med <= 0 then return nil end
  local ratio
  if med > model_hi then ratio = med / model_hi elseif med < model_lo then ratio = model_lo / med else return nil end
  if ratio < factor then return nil end
  -- the likely factor, from the middle of the model's range (a wide design box makes the
  -- distance to its nearest bound a poor estimate)
  local mid = math.sqrt(model_lo * model_hi)
  local r_mid = med > mid and med / mid or mid / med
  local guess = ""
  for _, k in ipairs(KNOWN) do
    if math.abs(math.log(r_mid / k[1])) < 0.4 then guess = "; that is close to " .. k[2] break end
  end
  return ("%s: the data (median %.6g) lie %.3g times %s everything the model gives over its input bounds (%.6g … %.6g)%s. Likely a units mistake: check the data file's units before reading any verdict."):format(
    label, med, ratio, med > model_hi and "above" or "below", model_lo, model_hi, guess)
end

return M
