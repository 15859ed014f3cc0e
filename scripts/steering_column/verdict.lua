--- The study's verdicts above the single mode: a trial's verdict from its modes' verdicts and its
-- calibration, and the study's conclusion (results.json's top-level `conclusion`, issue 12 item 5)
-- from the trials as they ran. Pure functions of saved results, so a step running alone, the
-- summary and the harness all judge the same way.
--
-- A mode used in calibration always has a decisive verdict (trial.validate). A validation-only
-- mode is "inconclusive" when the calibration data leave it undetermined. That is the honest
-- verdict on the mode, not on the model form: the trial is
--   invalid       when any mode is invalid (the refinement loop acts on this alone);
--   inconclusive  when its calibration did not converge, or a calibrated mode is undecided;
--   valid         otherwise, with the undecided validation-only modes listed as `undetermined`.
-- A trial that is not invalid ends the study: nothing is refined without an invalid verdict.
local M = {}

M.modes = { "mode1", "mode2", "mode4" }

--- t: {modes = {mode = {verdict, used_in_calibration}}, converged = bool}.
-- Returns verdict, undetermined (list of the validation-only modes left undecided), why (words
-- when the verdict is inconclusive, else nil).
function M.trial(t)
  local undetermined, undecided_calibrated = {}, {}
  for _, m in ipairs(M.modes) do
    local v = t.modes[m]
    if v.verdict == "invalid" then return "invalid", {}, nil end
    if v.verdict == "inconclusive" then
      if v.used_in_calibration then undecided_calibrated[#undecided_calibrated + 1] = m
      else undetermined[#undetermined + 1] = m end
    end
  end
  if not t.converged then
    return "inconclusive", undetermined, "its calibration did not converge (" .. tostring(t.status) .. ")"
  end
  if #undecided_calibrated > 0 then
    return "inconclusive", undetermined,
      "no decisive verdict on calibrated " .. table.concat(undecided_calibrated, ", ")
  end
  return "valid", undetermined, nil
end

local function skipped(r) return r == nil or r.skipped end

--- The conclusion from the saved step results R (trialk_surrogate, trialk_calibration,
-- trialk_validation, refinementk) for at most max_trials trials. The schema of issue 12 item 5
-- ({verdict, refinements, trials = {{candidate, airbag, unknowns, modes, calibration = {converged,
-- status, means, stds}}}}) plus `undetermined` (the last trial's validation-only modes the data
-- leave undecided). `ended` (why the loop stopped) and `why` (of an inconclusive verdict) stay in
-- the summary step, not in the top-level conclusion.
function M.conclusion(R, max_trials)
  local c = { trials = {}, refinements = {}, undetermined = {} }
  for k = 1, max_trials do
    local sur = R["trial" .. k .. "_surrogate"]
    if skipped(sur) then break end
    local cal, val = R["trial" .. k .. "_calibration"], R["trial" .. k .. "_validation"]
    local means, stds = {}, {}
    for _, p in ipairs(cal.params) do means[p.input], stds[p.input] = p.mean, p.std end
    local modes = {}
    for _, m in ipairs(M.modes) do modes[m] = val.modes[m].verdict end
    c.trials[#c.trials + 1] = { candidate = sur.model.candidate, airbag = sur.model.airbag,
                                unknowns = sur.model.unknowns,
                                modes = modes, calibration = { converged = cal.converged == true, status = cal.status,
                                                               means = means, stds = stds } }
    c.verdict, c.undetermined, c.why = M.trial{ modes = val.modes, converged = cal.converged == true,
                                                status = cal.status }
    if k < max_trials then
      local ref = R["refinement" .. k]
      if ref and not ref.skipped then c.refinements[#c.refinements + 1] = ref.chosen
      elseif ref then c.ended = ref.reason end
    end
  end
  return c
end

--- The top-level entry of results.json: exactly the issue's fields and `undetermined`.
function M.top_level(c)
  return { verdict = c.verdict, refinements = c.refinements, trials = c.trials, undetermined = c.undetermined }
end

return M
