-- SPDX-License-Identifier: MIT
--- The report's validity-check section of trial k: per response the calibrated PDF over the data,
-- the u-pooling, the verdict with its solver check beside it and, when the two disagree, which
-- governs and why (the validation step's result `res`; cal: the trial's calibration; data: the
-- data step's result).
local text = require "smi.improve.text"
local figs = require "smi.improve.figures"
local trial = require "smi.improve.trial"
local verdict = require "smi.improve.verdict"

return function(run, r, res, cal, k, L, data)
  local D, cfg = run.D, run.cfg
  local BADGE = verdict.BADGE
  local ebd = run.f_exp(data)
  r:section(L .. ": validity check")
  r:text(text.validation_intro(D, res, #data[D.names[1]], cfg))
  local pdfs, cdfs, rows = {}, {}, {}
  for _, m in ipairs(D.names) do
    local v, resp = res.responses[m], D.by_name[m]
    local exp_curve = trial.pdf_curve(ebd[m], smi.vec(data[m]), v.pdf.x[1], v.pdf.x[#v.pdf.x])
    pdfs[#pdfs + 1] = { figs.pdf_over_data(resp, v, data[m], exp_curve), resp.title .. ": calibrated PDF over the data." }
    cdfs[#cdfs + 1] = { figs.upool(resp, v), resp.title .. ": ECDF of the u-values against the uniform CDF." }
    local range = v.range and ("[%.4f, %.4f] over %d"):format(v.range.lower, v.range.upper, v.range.points) or "—"
    local sv = v.solver or {}
    rows[#rows + 1] = { resp.title, v.used_in_calibration and "calibration" or "validation only", v.predicted_mean,
                        v.predicted_std, v.metric, range, v.threshold, { status = BADGE[v.verdict], text = v.verdict },
                        sv.metric or "—", v.solver and { status = sv.pass and "pass" or "fail",
                                                         text = sv.pass and "valid" or "invalid" } or "—" }
    -- one entry per response: the verdict with its solver check beside it, and when the two
    -- disagree the sentence saying which one governs and why
    local checks = v.solver and { { name = "Solver check", pass = sv.pass, value = sv.metric } } or nil
    local disagree = v.solver and BADGE[v.verdict] ~= (sv.pass and "pass" or "fail")
    r:verdict{ name = ("%s, %s"):format(L, resp.title), status = BADGE[v.verdict], value = v.metric,
               threshold = v.threshold, detail = v.detail, checks = checks,
               governs = disagree and text.solver_disagrees(L, resp.title, v, cfg) or nil }
  end
  r:figures(pdfs)
  r:figures(cdfs)
  r:table{ caption = "Validity check. U range: over the near-optimal calibrations.", rows = rows,
           columns = { "Response", "Role", "Pred. mean", "Pred. std", "U", "U range", "Threshold", "Verdict",
                       "U (solver check)", "Solver check" } }
  r:text(text.trial_verdict(L, res))
end
