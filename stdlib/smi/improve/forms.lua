-- SPDX-License-Identifier: MIT
--- smi.improve.forms: the study's verdict over the model forms it tried. Each tried form (a
-- trial: the candidates applied) carries its trial verdict and its log evidence under the declared
-- priors (evidence.lua). The study concludes
--   valid         when the chosen form is valid on every response, no calibrated mean of it sits
--                 on its range's bound, and its Bayes factor over every other tried form that the
--                 data do not reject is at least the declared margin (default 3, "positive" in
--                 Kass & Raftery's sense); a form invalid on a response is rejected by the
--                 u-pooling of its own calibration, whatever its evidence;
--   invalid       when every tried form is invalid;
--   undetermined  otherwise: the data do not single out one form (the forms within the margin
--                 of the best are named), or a response is left undetermined, or the chosen form
--                 needs a mean at its range's bound (the range is the prior: the data ask for
--                 more than the analyst allowed).
-- A Bayes factor counts as beating the margin only when it does so by two Monte Carlo standard
-- errors of the log-evidence difference: the sampler's error decides nothing.
-- A form that fits is compared with the forms one candidate away from it (the alternatives,
-- evidence only): without them a fit says nothing of the forms the data cannot tell apart.
-- Pure functions of saved results, so the summary and a harness judge the same way.
local M = {}

--- One form's record from its trial: t {applied, verdict (the trial's), undetermined (response
-- names), at_bounds (calibrated means on a bound: names), log_evidence, log_evidence_error}.
local function valid_everywhere(f)
  return f.verdict == "valid" and #(f.undetermined or {}) == 0 and #(f.at_bounds or {}) == 0
end
M.valid_everywhere = valid_everywhere

-- The log Bayes factor of a over b and its standard error (nil when either has no evidence).
local function log_factor(a, b)
  if type(a.log_evidence) ~= "number" or type(b.log_evidence) ~= "number" then return nil end
  local d = a.log_evidence - b.log_evidence
  local e = math.sqrt((a.log_evidence_error or 0) ^ 2 + (b.log_evidence_error or 0) ^ 2)
  return d, e
end

--- Whether form a beats form b by the margin (a Bayes factor >= margin, by two standard errors).
function M.beats(a, b, margin)
  local d, e = log_factor(a, b)
  return d ~= nil and d - 2 * e >= math.log(margin)
end

--- The key of a form: its applied revisions in name order (the order they were applied in does
-- not make another form).
function M.key(applied)
  local a = {}
  for i, n in ipairs(applied) do a[i] = n end
  table.sort(a)
  return table.concat(a, "\n")
end

--- Whether two lists of applied revisions name the same form (order aside).
function M.same(a, b) return M.key(a) == M.key(b) end

--- The alternative (evidence-only) form that beats `own` (a trial's record) by the margin and has
-- the largest evidence of those that do: its index in `alternatives`, or nil.
function M.better_alternative(own, alternatives, margin)
  local best
  for i, f in ipairs(alternatives) do
    if M.beats(f, own, margin) and (not best or f.log_evidence > alternatives[best].log_evidence) then best = i end
  end
  return best
end

--- forms: the tried forms' records, in the order tried (a record with `alternative = true` was
-- only compared by its evidence, not calibrated and validated as a trial: it is never chosen,
-- and, unless it is beaten, it keeps the verdict from "valid"); margin: the Bayes factor (>= 1).
-- Returns {verdict, chosen (index), supported = {index = true}, best (index of the largest
-- evidence among the forms not rejected), reasons = {words}} and marks each form's `supported` and `chosen`.
function M.compare(forms, margin)
  -- the best: the largest evidence among the forms the data do not reject (all, if they all are)
  local best
  local any_kept = false
  for _, f in ipairs(forms) do any_kept = any_kept or f.verdict ~= "invalid" end
  for i, f in ipairs(forms) do
    if (f.verdict ~= "invalid" or not any_kept) and type(f.log_evidence) == "number"
       and (not best or f.log_evidence > forms[best].log_evidence) then best = i end
  end
  local out = { supported = {}, reasons = {}, best = best }
  for i, f in ipairs(forms) do
    -- within the margin of the best: the best does not beat it
    f.supported = f.verdict ~= "invalid" and (best == nil or i == best or not M.beats(forms[best], f, margin))
    if f.supported then out.supported[i] = true end
  end
  -- the chosen form: of the forms valid everywhere the one with the largest evidence (the first
  -- tried of equals); else, of the forms not invalid, the largest evidence; else the best
  local function pick(ok)
    local c
    for i, f in ipairs(forms) do
      if not f.alternative and ok(f) and (not c or (f.log_evidence or -math.huge) > (forms[c].log_evidence or -math.huge)) then c = i end
    end
    return c
  end
  -- (a form valid everywhere that a better form beats by the margin is not the data's answer)
  local chosen = pick(function(f) return valid_everywhere(f) and f.supported end)
  if chosen then
    local others = {}
    for i, f in ipairs(forms) do
      if i ~= chosen and f.verdict ~= "invalid" and not M.beats(forms[chosen], f, margin) then others[#others + 1] = i end
    end
    if #others == 0 then
      out.verdict = "valid"
    else
      out.verdict = "undetermined"
      out.reasons[#out.reasons + 1] = { kind = "inseparable", forms = others }
    end
  else
    chosen = pick(function(f) return f.verdict ~= "invalid" end)
    if chosen then
      out.verdict = "undetermined"
      local f = forms[chosen]
      if #(f.undetermined or {}) > 0 then out.reasons[#out.reasons + 1] = { kind = "response", responses = f.undetermined } end
      if #(f.at_bounds or {}) > 0 then out.reasons[#out.reasons + 1] = { kind = "bounds", params = f.at_bounds } end
      if f.verdict ~= "valid" and #(f.undetermined or {}) == 0 then
        out.reasons[#out.reasons + 1] = { kind = "trial", why = f.why }
      end
    else
      out.verdict = "invalid"
      chosen = best and not forms[best].alternative and best or nil
      for i, f in ipairs(forms) do if not chosen and not f.alternative then chosen = i end end
    end
  end
  out.chosen = chosen
  for i, f in ipairs(forms) do f.chosen = i == chosen end
  return out
end

return M
