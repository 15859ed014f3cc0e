-- SPDX-License-Identifier: MIT
--- smi.improve.verdict: the verdicts above the single response: a trial's verdict from its
-- responses' verdicts and its calibration, and the study's conclusion (results.json's top-level
-- `conclusion`) from the trials as they ran. Pure functions of saved results, so a step running
-- alone, the summary and a harness all judge the same way.
--
-- A response used in calibration always has a decisive verdict (trial.validate). A
-- validation-only response is "inconclusive" when the calibration data leave it undetermined.
-- That is the honest verdict on the response, not on the model form: the trial is
--   invalid       when any response is invalid (the refinement loop acts on this alone);
--   inconclusive  when its calibration did not converge, or a calibrated response is undecided;
--   valid         otherwise, with the undecided validation-only responses listed as `undetermined`.
-- A trial that is not invalid ends the study: nothing is refined without an invalid verdict.
local forms = require "smi.improve.forms"
local evidence = require "smi.improve.evidence"

local M = {}

--- t: {names = {response, ...}, responses = {name = {verdict, used_in_calibration}}, converged, status}.
-- Returns verdict, undetermined (list of the validation-only responses left undecided), why (words
-- when the verdict is inconclusive, else nil).
function M.trial(t)
  local undetermined, undecided_calibrated = {}, {}
  for _, m in ipairs(t.names) do
    local v = t.responses[m]
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

--- Whether a trial's validation (its step result) calls for a refinement: an invalid trial, or
-- one that leaves a validation response undetermined (the data cannot say whether this form
-- predicts it; another form may).
function M.needs_refinement(v)
  return v.verdict == "invalid" or (v.undetermined ~= nil and #v.undetermined > 0)
end

--- The report's and console's badge of a verdict.
M.BADGE = { valid = "pass", invalid = "fail", inconclusive = "inconclusive", undetermined = "inconclusive" }

local function skipped(r) return r == nil or r.skipped end

-- The calibrated means on a bound of their range (smi.calibrate's at_bounds, the means only):
-- the range is the analyst's prior, and the data ask for more than it allows.
-- A mean with a declared prior is judged on its posterior instead (cal.evidence): the
-- probability-residual optimum ignores the prior, and a mean the data leave free (a new unknown
-- in series with an old one) lands on a bound there though its prior holds it well inside.
-- T: the trial's model (its specs' ranges); on a bound: the posterior mean within 2 % of the
-- range's width from it.
local function means_at_bounds(cal, T)
  local out = {}
  local ev = cal.evidence
  local with_prior = {}
  for _, p in ipairs(ev and ev.priors or {}) do with_prior[p.param] = true end
  for _, p in ipairs(cal.at_bounds or {}) do
    if p:match("%.mean$") then
      local n = p:gsub("%.mean$", "")
      local post = with_prior[p] and ev.mean and ev.mean[p]
      local range = T and T.specs[n] and T.specs[n].mean
      if not (post and range) then
        out[#out + 1] = p
      else
        local w = 0.02 * (range[2] - range[1])
        if post - range[1] <= w or range[2] - post <= w then out[#out + 1] = p end
      end
    end
  end
  return out
end

--- The conclusion from the saved step results R (trialk_surrogate, trialk_calibration,
-- trialk_validation, refinementk) for at most max_trials trials: {verdict, refinements,
-- undetermined, trials = {{candidate, applied, unknowns, responses, calibration = {converged,
-- status, means, stds, at_bounds}}}, forms = {{applied, log_evidence, log_evidence_error,
-- supported, chosen}}} plus, kept in the summary step, `chosen` (the index of the chosen form's
-- trial), `comparison` (forms.lua's reasons), `ended` (why the loop stopped) and `why`. The
-- verdict is forms.lua's over the tried forms; the margin is the declaration's
-- evidence.margin. extra(model, responses) -> more keys of a trial.
function M.conclusion(R, D, max_trials, extra)
  local c = { trials = {}, refinements = {}, undetermined = {}, forms = {} }
  local records = {}
  for k = 1, max_trials do
    local sur = R["trial" .. k .. "_surrogate"]
    if skipped(sur) then break end
    local cal, val = R["trial" .. k .. "_calibration"], R["trial" .. k .. "_validation"]
    local means, stds = {}, {}
    for _, p in ipairs(cal.params or {}) do means[p.input], stds[p.input] = p.mean, p.std end
    local responses = {}
    if not skipped(val) then for _, m in ipairs(D.names) do responses[m] = val.responses[m].verdict end end
    local T = sur.model
    local t = { candidate = T.candidate, applied = T.applied, unknowns = T.unknowns, responses = responses,
                calibration = { converged = cal.converged == true, status = cal.status, means = means, stds = stds,
                                at_bounds = means_at_bounds(cal, sur.model) } }
    for key, v in pairs(extra and extra(T, responses) or {}) do t[key] = v end
    c.trials[#c.trials + 1] = t
    local ev = cal.evidence or {}
    local rec = { applied = T.applied, at_bounds = t.calibration.at_bounds, log_evidence = ev.log_evidence,
                  log_evidence_error = ev.log_evidence_error, posterior = evidence.posterior_means(ev) }
    records[#records + 1] = rec
    if skipped(val) then
      rec.verdict, rec.undetermined, rec.why = "inconclusive", {}, val and val.reason
      c.ended = val and val.reason
      break
    end
    rec.verdict, rec.undetermined, rec.why = M.trial{ names = D.names, responses = val.responses,
                                                      converged = cal.converged == true, status = cal.status }
    if k < max_trials then
      local ref = R["refinement" .. k]
      if ref and not ref.skipped then c.refinements[#c.refinements + 1] = ref.chosen
      elseif ref then c.ended = ref.reason end
    end
  end
  -- the alternatives' evidence (forms one candidate away from a trial that fits), after the trials
  local n_trials = #records
  for k = 1, n_trials do
    local alt = R["trial" .. k .. "_alternatives"]
    for _, f in ipairs(alt and not alt.skipped and alt.forms or {}) do
      local dup = false
      for _, r in ipairs(records) do dup = dup or forms.same(r.applied, f.applied) end
      if not dup then
        records[#records + 1] = { applied = f.applied, log_evidence = f.log_evidence, alternative = true,
                                  posterior = f.posterior,
                                  log_evidence_error = f.log_evidence_error, verdict = "not validated", undetermined = {} }
      end
    end
  end
  local cmp = forms.compare(records, D.evidence.margin)
  c.verdict, c.chosen, c.comparison = cmp.verdict, cmp.chosen, cmp.reasons
  local chosen = records[cmp.chosen]
  c.undetermined = chosen and chosen.undetermined or {}
  c.why = chosen and chosen.why
  for i, f in ipairs(records) do
    c.forms[i] = { applied = f.applied, log_evidence = f.log_evidence, log_evidence_error = f.log_evidence_error,
                   supported = f.supported, chosen = f.chosen, verdict = f.verdict, validated = not f.alternative,
                   posterior = f.posterior }
  end
  return c
end

--- The top-level entry of results.json: exactly the generic fields.
function M.top_level(c)
  return { verdict = c.verdict, refinements = c.refinements, trials = c.trials, undetermined = c.undetermined,
           forms = c.forms }
end

return M
