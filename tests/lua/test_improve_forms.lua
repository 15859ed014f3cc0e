-- SPDX-License-Identifier: MIT
-- smi.improve's verdict over the tried model forms (stdlib/smi/improve/forms.lua), on records
-- whose log evidences are given: the margin is a Bayes factor (Kass & Raftery's "positive"
-- evidence starts at 3, ln 3 = 1.0986), beaten only by two Monte Carlo standard errors of the
-- difference; a form invalid on a response is rejected whatever its evidence; an undetermined
-- response or a calibrated mean on its bound keeps a form from being called valid.
local T = require "smi.testing"
local forms = require "smi.improve.forms"

local function form(applied, verdict, logz, err, extra)
  local f = { applied = applied, verdict = verdict, log_evidence = logz, log_evidence_error = err,
              undetermined = {}, at_bounds = {} }
  for k, v in pairs(extra or {}) do f[k] = v end
  return f
end

T.case("the margin: a Bayes factor of 3 by two standard errors", function()
  -- log BF 1.5 - 2 * sqrt(2) * 0.1 = 1.217 >= ln 3: beaten
  T.eq(forms.beats(form({}, "valid", -10, 0.1), form({ "a" }, "valid", -11.5, 0.1), 3), true)
  -- log BF 1.2 - 0.283 = 0.917 < ln 3: not beaten, although 1.2 > ln 3 alone
  T.eq(forms.beats(form({}, "valid", -10, 0.1), form({ "a" }, "valid", -11.2, 0.1), 3), false)
  -- no evidence: never beaten
  T.eq(forms.beats(form({}, "valid", -10, 0.1), form({ "a" }, "valid", nil, nil), 3), false)
end)

T.case("valid: the chosen form valid everywhere and ahead of every form not rejected", function()
  local f = { form({}, "invalid", -3, 0.1), form({ "joint" }, "valid", -10, 0.1), form({ "joint", "mass" }, "valid", -12, 0.1) }
  local c = forms.compare(f, 3)
  T.eq(c.verdict, "valid")
  T.eq(c.chosen, 2, "the valid form, not the invalid one with the larger evidence")
  T.eq(f[1].supported, false, "an invalid form is not supported")
  T.eq(f[3].supported, false, "log BF 2 - 0.28 >= ln 3")
  T.eq(f[2].chosen and not f[1].chosen and not f[3].chosen, true, "one chosen form")
end)

T.case("undetermined: two valid forms within the margin, named", function()
  local f = { form({}, "valid", -10, 0.1), form({ "joint" }, "valid", -10.5, 0.1) }
  local c = forms.compare(f, 3)
  T.eq(c.verdict, "undetermined")
  T.eq(c.chosen, 1)
  T.eq(c.reasons[1].kind, "inseparable")
  T.eq(c.reasons[1].forms[1], 2)
  T.eq(f[1].supported and f[2].supported, true)
  -- a larger margin never turns an undetermined verdict valid; a smaller one can
  T.eq(forms.compare({ form({}, "valid", -10, 0.1), form({ "joint" }, "valid", -10.5, 0.1) }, 1.2).verdict, "valid")
end)

T.case("undetermined: a response left open, or a mean on its bound; invalid when all are", function()
  local c = forms.compare({ form({}, "valid", -10, 0.1, { undetermined = { "f3" } }) }, 3)
  T.eq(c.verdict, "undetermined")
  T.eq(c.reasons[1].kind, "response")
  c = forms.compare({ form({}, "valid", -10, 0.1, { at_bounds = { "a.mean" } }) }, 3)
  T.eq(c.verdict, "undetermined")
  T.eq(c.reasons[1].kind, "bounds")
  T.eq(c.reasons[1].params[1], "a.mean")
  c = forms.compare({ form({}, "invalid", -10, 0.1), form({ "joint" }, "invalid", -9, 0.1) }, 3)
  T.eq(c.verdict, "invalid")
  T.eq(c.chosen, 2, "the best evidence among the invalid forms")
  -- one form, valid everywhere, nothing else tried: valid (no evidence needed to beat nothing)
  T.eq(forms.compare({ form({}, "valid", nil, nil) }, 3).verdict, "valid")
end)

T.case("alternatives (evidence only): never chosen; one within the margin keeps the verdict from valid", function()
  local alt = { alternative = true }
  -- the trial valid everywhere, an alternative within the margin: undetermined, the trial chosen
  local f = { form({}, "valid", -10, 0.1), form({ "mass" }, "not validated", -9.8, 0.1, alt) }
  local c = forms.compare(f, 3)
  T.eq(c.verdict, "undetermined")
  T.eq(c.chosen, 1, "an alternative is never the chosen form")
  T.eq(c.reasons[1].kind, "inseparable")
  -- the alternative beaten by the margin (log BF 3 - 0.28 >= ln 3): valid
  T.eq(forms.compare({ form({}, "valid", -10, 0.1), form({ "mass" }, "not validated", -13, 0.1, alt) }, 3).verdict, "valid")
  -- an alternative that beats the trial: the trial is not supported, so not valid
  f = { form({}, "valid", -10, 0.1), form({ "mass" }, "not validated", -5, 0.1, alt) }
  c = forms.compare(f, 3)
  T.eq(c.verdict, "undetermined")
  T.eq(f[1].supported, false)
  T.eq(c.chosen, 1, "the best trial, though the data favour a form not yet validated")
end)

T.case("a form valid everywhere that a better trial beats is not chosen", function()
  -- trial 2 has a mean on its bound (not valid everywhere) but beats trial 1 by 5 nats
  local f = { form({}, "valid", -10, 0.1), form({ "joint" }, "valid", -5, 0.1, { at_bounds = { "k.mean" } }) }
  local c = forms.compare(f, 3)
  T.eq(c.verdict, "undetermined")
  T.eq(c.chosen, 2, "the best supported form")
  T.eq(c.reasons[1].kind, "bounds")
end)

T.case("better_alternative: the largest evidence among the alternatives that beat the trial", function()
  local own = form({}, "valid", -10, 0.1)
  local alts = { form({ "a" }, "x", -7, 0.1), form({ "b" }, "x", -6, 0.1), form({ "c" }, "x", -9.5, 0.1) }
  T.eq(forms.better_alternative(own, alts, 3), 2)
  T.eq(forms.better_alternative(own, { alts[3] }, 3), nil, "within the margin: none")
  T.eq(forms.same({ "a", "b" }, { "b", "a" }), true)
  T.eq(forms.same({ "a" }, { "a", "b" }), false)
end)

T.case("the report's opening states the conclusion in one short sentence; the reasons follow it", function()
  local text = require "smi.improve.text"
  local D = { names = { "f1", "f2", "d1" } }
  local c = { verdict = "undetermined", chosen = 2, undetermined = { "d1" },
              trials = { { applied = {}, responses = { f1 = "invalid" } },
                         { applied = { "tip mass" }, responses = { f1 = "valid", f2 = "valid", d1 = "inconclusive" } } } }
  T.eq(text.conclusion_short(D, c),
    "Conclusion: the model is undetermined in {tip mass}: valid on f1 and f2; d1 not determined by these data.")
  c.verdict, c.undetermined, c.trials[2].responses.d1 = "valid", {}, "valid"
  T.eq(text.conclusion_short(D, c), "Conclusion: the model is valid in {tip mass} on f1, f2 and d1.")
  c.verdict, c.chosen = "invalid", 1
  T.eq(text.conclusion_short(D, c), "Conclusion: the model is invalid in the initial model: invalid on f1.")
end)
T.finish()
