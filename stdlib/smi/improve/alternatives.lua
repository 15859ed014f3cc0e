-- SPDX-License-Identifier: MIT
--- smi.improve.alternatives: which forms a study compares besides the trials the decision matrix
-- picks. A fit alone does not single out a form (nine specimens and free means absorb most
-- revisions), so a trial that fits is compared with the forms one untried candidate away (its
-- alternatives, by their evidence); and when every candidate has been tried without a fit, the
-- form without the earliest revision is tried (a step back). Pure functions of the saved step
-- results R (trialk_surrogate, trialk_alternatives) and the checked declaration D.
local revise = require "smi.improve.revise"
local forms = require "smi.improve.forms"

local M = {}

-- The forms tried up to trial k: the trials' and, before trial k, the alternatives'.
local function tried(R, k)
  local seen = {}
  for i = 1, k do
    seen[forms.key(R["trial" .. i .. "_surrogate"].model.applied)] = true
    local alt = i < k and R["trial" .. i .. "_alternatives"]
    for _, f in ipairs(alt and not alt.skipped and alt.forms or {}) do seen[forms.key(f.applied)] = true end
  end
  return seen
end

--- The forms one candidate away from `base` (trial k's model) that no trial and no earlier
-- alternative has tried, and that differ from it as a model (a revision that changes nothing is
-- no alternative): revise.apply's models, in the candidates' declared order.
function M.untried_forms(D, R, k, base)
  local seen, out = tried(R, k), {}
  for _, c in ipairs(D.candidates) do
    local applied = false
    for _, a in ipairs(base.applied) do applied = applied or a == c.name end
    if not applied then
      local A = revise.apply(D, base, c.name)
      if not seen[forms.key(A.applied)] and not revise.same_model(A, base) then
        seen[forms.key(A.applied)] = true
        out[#out + 1] = A
      end
    end
  end
  return out
end

--- The step back after trial k (`state`: its verdict in words): the model without the earliest of
-- its revisions whose removal no trial has had (the decision matrix's first pick may have been
-- kept only because it absorbed part of what a later revision explains), and why; nil when trial
-- k has fewer than two revisions or every such form was tried.
function M.step_back(D, R, k, state)
  local T = R["trial" .. k .. "_surrogate"].model
  if #T.applied < 2 then return nil end
  local seen = {}
  for i = 1, k do seen[forms.key(R["trial" .. i .. "_surrogate"].model.applied)] = true end
  for _, name in ipairs(T.applied) do
    local why = ("trial %d is %s with every candidate applied or tried: %s was applied first and may only have"
      .. " absorbed part of what a later revision explains"):format(k, state, name)
    local m = revise.without(D, T, name, why)
    if not seen[forms.key(m.applied)] then return m, why end
  end
  return nil
end

return M
