-- SPDX-License-Identifier: MIT
--- The report's summary section: the loop as it ran, the conclusion's badge, solver use and wall
-- time per step (the summary step's result `out`; R: the steps' results; walls and per: the
-- rows of wall time and of solver runs per step).
local text = require "smi.improve.text"
local cost = require "smi.improve.cost"
local verdict = require "smi.improve.verdict"

return function(run, r, out, R, walls, per)
  local D, cfg, c = run.D, run.cfg, out.conclusion
  r:section("Summary")
  r:text(text.story(D, c, R, run.prior.labels))
  r:verdict{ name = "Conclusion: the model is " .. c.verdict, status = verdict.BADGE[c.verdict],
             detail = text.conclusion_detail(D, c, R) }
  -- the forms tried, side by side: the paper's u-pooling verdict and the Bayes factors
  local forms = {}
  for i, f in ipairs(c.forms) do
    forms[i] = { text.form_name(f.applied), f.validated == false and "evidence only" or f.verdict,
                 type(f.log_evidence) == "number" and ("%.2f ± %.2f"):format(f.log_evidence, f.log_evidence_error or 0)
                   or "not computed",
                 f.supported and "yes" or "no", f.chosen and "yes" or "", text.posterior_words(f.posterior) }
  end
  r:table{ caption = ("The model forms tried: each trial's verdict (u-pooling of its calibration; \"evidence only\":"
             .. " a form one candidate away from a trial that fits, compared by its evidence alone), its log evidence"
             .. " under the declared priors, whether the data support it (within a Bayes factor of %g of the best),"
             .. " and the posterior mean ± std of each unknown's mean."):format(D.evidence.margin),
           columns = { "Form", "Trial verdict", "log evidence", "Supported", "Chosen", "Posterior of the means" },
           rows = forms }
  local rows = {}
  for name, cnt in pairs(cost.counts) do rows[#rows + 1] = { name, cnt.points, cnt.launched, cnt.reused } end
  table.sort(rows, function(a, b) return a[1] < b[1] end)
  if #rows > 0 then
    r:table{ caption = text.solver_use_caption, rows = rows,
             columns = { "Model", { title = "Points", format = "%d" }, { title = "Launched", format = "%d" },
                         { title = "Reused", format = "%d" } } }
  end
  r:table{ caption = "Wall-clock time per step (s, 1 s resolution).", rows = walls,
           columns = { "Step", { title = "Wall (s)", format = "%d" } } }
  local all = {}
  for i, row in ipairs(per) do all[i] = row end
  all[#all + 1] = { "total", out.solver_runs_total, "", "" }
  r:table{ caption = ("Solver runs per step (new: not found in the evaluation store). Screening: %s; Kriging test"
             .. " points %d; solver check %d points."):format(D.screening and (cfg.screening == "surrogate"
             and ("surrogate, " .. cfg.screen_runs .. " runs") or "full eq. 3") or "none", cfg.test_points,
             cfg.solver_check),
           columns = { "Step", { title = "Solutions", format = "%d" }, { title = "New", format = "%s" },
                       { title = "Processes", format = "%s" } }, rows = all }
end
