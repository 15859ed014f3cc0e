--- The steering-column study's words: the report's paragraphs and the console's closing lines,
-- each a function of the run's results (thresholds, sample sizes and ranges are the numbers the
-- run computed, never retyped). steering_column.lua computes and places; this file says.
local M = {}

local MODES = { "mode1", "mode2", "mode4" }

local function join(list, last)
  if #list <= 1 then return list[1] or "" end
  return table.concat(list, ", ", 1, #list - 1) .. (last or " and ") .. list[#list]
end

--- "mode 1" for "mode1" (the conclusion's keys in words).
function M.mode_name(m) return (m:gsub("^mode", "mode ")) end

local function mode_list(list)
  local w = {}
  for i, m in ipairs(list) do w[i] = M.mode_name(m) end
  return join(w)
end

-- ---------------------------------------------------------------------------------------------
-- Verdicts and conclusion
-- ---------------------------------------------------------------------------------------------

--- The largest moves of the means along the strongest near-optimal push, in words (what a
-- measurement would have to pin down), or nil.
function M.weak_inputs(no)
  local d = no and no.directions and no.directions[1]
  if not d then return nil end
  local l = {}
  for name, w in pairs(d.loadings) do if name:match("%.mean$") then l[#l + 1] = { name:gsub("%.mean$", ""), w } end end
  table.sort(l, function(a, b) return math.abs(a[2]) > math.abs(b[2]) end)
  local parts = {}
  for i = 1, math.min(3, #l) do parts[i] = ("%s %+.2f"):format(l[i][1], l[i][2]) end
  return table.concat(parts, ", ")
end

--- What would settle an undetermined validation response.
function M.settle(mode, cal)
  local w = M.weak_inputs(cal and cal.near_optimal)
  return ("calibrate on %s as well, or measure an input that moves it%s and give it as --prior"):format(
    M.mode_name(mode), w and (" (the means move most along: " .. w .. "; e.g. weigh the wheel cover)") or " (e.g. weigh the wheel cover)")
end

--- One validation-only mode's verdict detail (the report's verdict list).
function M.range_detail(v, cal)
  local d = ("U = %.4f at the optimum; over %d near-optimal calibrations U in [%.4f, %.4f] against %.4f;"
    .. " not used by the calibration"):format(v.metric, v.range.points, v.range.lower, v.range.upper, v.threshold)
  if v.verdict ~= "inconclusive" then return d end
  return d .. (". Modes 1 and 4 fit equally well across calibrations that predict it on both sides of the"
    .. " threshold. What would settle it: %s"):format(M.settle("mode2", cal))
end

--- A calibrated mode's verdict detail.
function M.decisive_detail(v)
  return ("U = %.4f %s %.4f (p = %.3f); used by the calibration"):format(v.metric, v.pass and "≤" or ">", v.threshold, v.p)
end

--- An undetermined mode of the last trial in words, with its evidence (the U range over the
-- near-optimal set and the threshold the run computed) and what would settle it.
function M.undetermined_words(m, val, cal)
  local v = val.modes[m]
  local r = v.range
  local evidence = r and ("U over %d near-optimal calibrations in [%.4f, %.4f] against threshold %.4f"):format(
    r.points, r.lower, r.upper, r.threshold) or "no near-optimal range"
  return ("%s not determined by these data: %s; to settle it: %s"):format(M.mode_name(m), evidence, M.settle(m, cal))
end

--- The conclusion in words: one sentence starting "Conclusion: the model is <verdict>" (the
-- report's verdict name and the console's last line). c: verdict.conclusion's table; R: results.
function M.conclusion(c, R)
  local k = #c.trials
  local last = c.trials[k]
  local path = #c.refinements > 0 and (" after refinement by " .. table.concat(c.refinements, ", then ")) or ", no refinement"
  local val, cal = R["trial" .. k .. "_validation"], R["trial" .. k .. "_calibration"]
  if c.verdict == "valid" then
    local decided = {}
    for _, m in ipairs(MODES) do if last.modes[m] == "valid" then decided[#decided + 1] = m end end
    local s = ("Conclusion: the model is valid on %s%s (trial %d, %s airbag)"):format(mode_list(decided), path, k, last.airbag)
    for _, m in ipairs(c.undetermined) do s = s .. "; " .. M.undetermined_words(m, val, cal) end
    return s .. "."
  end
  if c.verdict == "inconclusive" then
    return ("Conclusion: the model is inconclusive%s (trial %d, %s airbag): %s."):format(path, k, last.airbag, c.why or "")
  end
  local failed = {}
  for _, m in ipairs(MODES) do if last.modes[m] == "invalid" then failed[#failed + 1] = m end end
  return ("Conclusion: the model is invalid%s (trial %d, %s airbag, invalid on %s)%s."):format(
    path, k, last.airbag, mode_list(failed), c.ended and ("; " .. c.ended) or "")
end

--- A trial's verdict in one sentence (the end of its validity-check section).
function M.trial_verdict(label, res)
  local s = ("%s is %s"):format(label, res.verdict)
  if res.why then s = s .. ": " .. res.why end
  if res.undetermined and #res.undetermined > 0 then
    s = s .. ("; %s not determined by the calibration data"):format(mode_list(res.undetermined))
  end
  return s .. "."
end

--- One line per trial for the console (what the conclusion says, in words).
function M.trial_line(i, t, refinement)
  local modes = {}
  for _, m in ipairs(MODES) do modes[#modes + 1] = m .. " " .. t.modes[m] end
  return ("Trial %d: %s, %s airbag, unknowns %s: %s%s"):format(i, t.candidate, t.airbag, table.concat(t.unknowns, ", "),
    table.concat(modes, ", "), refinement and ("; refined by " .. refinement) or "")
end

return M
