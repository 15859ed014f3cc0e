-- SPDX-License-Identifier: MIT
--- The report's section on the alternative forms of trial k (the alternatives step's result
-- `out`; own: the trial's evidence): each form one candidate away, its log evidence, its Bayes
-- factor against the trial and its posterior means, and which (if any) the next trial takes.
local text = require "smi.improve.text"

return function(run, r, out, own, k)
  local D = run.D
  r:section(("Alternative forms after trial %d"):format(k))
  r:text(text.alternatives_intro(k, ("Trial %d"):format(k)))
  local rows = { { text.form_name(out.base_applied) .. " (trial " .. k .. ")",
                   ("%.2f ± %.2f"):format(own.log_evidence, own.log_evidence_error), "1", "" } }
  for _, f in ipairs(out.forms) do
    rows[#rows + 1] = { text.form_name(f.applied), ("%.2f ± %.2f"):format(f.log_evidence, f.log_evidence_error),
                        ("%.3g"):format(math.exp(f.log_evidence - own.log_evidence)), text.posterior_words(f.posterior) }
  end
  r:table{ caption = ("Log evidence of trial %d's form and of each alternative under the declared priors; Bayes"
             .. " factor against the trial (the margin: %g); posterior mean ± std of the unknowns' means."):format(
             k, D.evidence.margin),
           columns = { "Form", "log evidence", "Bayes factor", "Posterior" }, rows = rows }
  local better = out.better and out.forms[out.better]
  if better then
    r:callout(("%s: %s."):format(text.form_name(better.applied), text.favoured_alternative(better, own, D.evidence.margin)), "info")
  else
    r:callout(("No alternative beats trial %d by the margin %g."):format(k, D.evidence.margin), "info")
  end
end
