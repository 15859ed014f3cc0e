-- SPDX-License-Identifier: MIT
--- smi.improve.text: a study's words: the report's paragraphs and the console's closing lines,
-- each a function of the run's results and the declaration (response names and units, candidate
-- names; thresholds, sample sizes and ranges are the numbers the run computed, never retyped).
-- The steps compute and the views place; this file says. D: the checked declaration, passed to
-- every function that names responses.
local M = {}

local function join(list, last)
  if #list <= 1 then return list[1] or "" end
  return table.concat(list, ", ", 1, #list - 1) .. (last or " and ") .. list[#list]
end

local function listed(list, last) return join(list, last) end

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
  table.sort(l, function(a, b) -- equal moves in name order (l comes in pairs() order, which varies)
    if math.abs(a[2]) ~= math.abs(b[2]) then return math.abs(a[2]) > math.abs(b[2]) end
    return a[1] < b[1]
  end)
  local parts = {}
  for i = 1, math.min(3, #l) do parts[i] = ("%s %+.2f"):format(l[i][1], l[i][2]) end
  return table.concat(parts, ", ")
end

--- What would settle an undetermined validation response.
function M.settle(response, cal)
  local w = M.weak_inputs(cal and cal.near_optimal)
  return ("calibrate on %s as well, or measure an input that moves it%s and give it as --prior"):format(
    response, w and (" (the means move most along: " .. w .. ")") or "")
end

--- One validation-only response's verdict detail (the report's verdict list).
function M.range_detail(D, v, cal)
  local d = ("U = %.4f at the optimum; over %d near-optimal calibrations U in [%.4f, %.4f] against %.4f;"
    .. " not used by the calibration"):format(v.metric, v.range.points, v.range.lower, v.range.upper, v.threshold)
  if v.verdict ~= "inconclusive" then return d end
  return d .. (". %s fit equally well across calibrations that predict it on both sides of the"
    .. " threshold. What would settle it: %s"):format(listed(D.calibrate), M.settle(v.name, cal))
end

--- A calibrated response's verdict detail.
function M.decisive_detail(v)
  return ("U = %.4f %s %.4f (p = %.3f); used by the calibration"):format(v.metric, v.pass and "≤" or ">",
    v.threshold, v.p)
end

--- An undetermined response of the last trial in words, with its evidence (the U range over the
-- near-optimal set and the threshold the run computed) and what would settle it.
function M.undetermined_words(m, val, cal)
  local v = val.responses[m]
  local r = v.range
  local evidence = r and ("U over %d near-optimal calibrations in [%.4f, %.4f] against threshold %.4f"):format(
    r.points, r.lower, r.upper, r.threshold) or "no near-optimal range"
  return ("%s not determined by these data: %s; to settle it: %s"):format(m, evidence, M.settle(m, cal))
end

-- A form in words: "the initial model" or "the form with a, b applied".
local function form_name(applied)
  return #applied > 0 and ("{" .. table.concat(applied, " + ") .. "}") or "the initial model"
end
M.form_name = form_name

-- The Bayes factor of form a over form b in words, or why there is none.
local function factor_words(a, b)
  if type(a.log_evidence) ~= "number" or type(b.log_evidence) ~= "number" then return "no evidence computed" end
  return ("Bayes factor %.3g (log %.2f ± %.2f)"):format(math.exp(a.log_evidence - b.log_evidence),
    a.log_evidence - b.log_evidence,
    math.sqrt((a.log_evidence_error or 0) ^ 2 + (b.log_evidence_error or 0) ^ 2))
end

--- What would separate forms the data leave together: a prior on the parameters that move most
-- among the calibrations that fit (the chosen trial's strongest near-optimal push), a response
-- (the undetermined ones, calibrated on), more specimens.
function M.separate(D, c, R)
  local k = c.chosen
  local cal = R["trial" .. k .. "_calibration"]
  local parts = {}
  local w = M.weak_inputs(cal and cal.near_optimal)
  local priors, tighter, has = {}, {}, {}
  for _, p in ipairs(cal and cal.evidence and cal.evidence.priors or {}) do has[p.param] = true end
  for _, n in ipairs(c.trials[k].unknowns) do
    local list = has[n .. ".mean"] and tighter or priors
    list[#list + 1] = n .. ".mean"
  end
  local moves = w and (" (the means move most along: " .. w .. ")") or ""
  if #priors > 0 then parts[#parts + 1] = ("a prior (--prior) on %s%s"):format(listed(priors, " or "), moves) end
  if #tighter > 0 then
    parts[#parts + 1] = ("a tighter prior on %s%s"):format(listed(tighter, " or "), #priors > 0 and "" or moves)
  end
  if #c.undetermined > 0 then parts[#parts + 1] = ("calibrating on %s as well"):format(listed(c.undetermined)) end
  parts[#parts + 1] = "more specimens"
  return listed(parts, ", or ")
end

--- The conclusion in words after "Conclusion: the model is <verdict>": the form it names, the
-- responses it rests on, the path, the forms the data cannot separate, and each undetermined
-- response with its evidence. c: verdict.conclusion's table; R: the step results.
function M.conclusion_detail(D, c, R)
  local k = c.chosen or #c.trials
  local chosen = c.trials[k]
  local refined = #c.refinements > 0
  local path = refined and ("after refinement by " .. table.concat(c.refinements, ", then ") .. " ") or ""
  local where = ("(trial %d, %s%s)"):format(k, #chosen.applied > 0 and ("applied: " .. table.concat(chosen.applied, ", "))
    or "initial model", refined and "" or ", no refinement")
  local val, cal = R["trial" .. k .. "_validation"], R["trial" .. k .. "_calibration"]
  if c.verdict == "invalid" then
    local failed = {}
    for _, m in ipairs(D.names) do if chosen.responses[m] == "invalid" then failed[#failed + 1] = m end end
    return ("%s%s: invalid on %s%s"):format(path, where, listed(failed), c.ended and ("; " .. c.ended) or "")
  end
  if next(chosen.responses) == nil then return ("%s%s: %s"):format(path, where, c.why or c.ended or "not validated") end
  local decided = {}
  for _, m in ipairs(D.names) do if chosen.responses[m] == "valid" then decided[#decided + 1] = m end end
  local s = ("in %s, valid on %s %s%s"):format(form_name(chosen.applied), #decided > 0 and listed(decided) or "no response",
    path, where)
  local others = {}
  for i, f in ipairs(c.forms) do
    if i ~= k then
      others[#others + 1] = f.verdict == "invalid" and ("%s is invalid"):format(form_name(f.applied))
        or ("%s%s: %s%s"):format(form_name(f.applied), f.validated == false and " (evidence only)" or "",
          factor_words(c.forms[k], f),
          f.supported and (", within the margin " .. ("%g"):format(D.evidence.margin)) or "")
    end
  end
  if #others > 0 then s = s .. "; against the other forms tried: " .. table.concat(others, "; ") end
  if c.verdict == "valid" then return s end
  local open = false -- whether more knowledge or data could decide (else: the trial's own reason)
  for _, r in ipairs(c.comparison or {}) do
    open = open or r.kind ~= "trial"
    if r.kind == "inseparable" then
      local names = {}
      for i, j in ipairs(r.forms) do names[i] = form_name(c.forms[j].applied) end
      s = s .. ("; the data cannot separate it from %s (Bayes factor under %g)"):format(listed(names), D.evidence.margin)
    elseif r.kind == "bounds" then
      s = s .. ("; the calibrated %s on its range's bound: the data ask for more than the declared range, which"
        .. " counts against this form"):format(listed(r.params))
    elseif r.kind == "trial" and r.why then
      s = s .. "; " .. r.why
    end
  end
  for _, m in ipairs(c.undetermined) do
    if val and val.responses then s = s .. "; " .. M.undetermined_words(m, val, cal) end
  end
  return open and (s .. "; what would separate the forms: " .. M.separate(D, c, R)) or s
end

--- The conclusion in one sentence starting "Conclusion: the model is <verdict>" (the console's
-- last line; the report's verdict name and detail).
function M.conclusion(D, c, R)
  return ("Conclusion: the model is %s %s."):format(c.verdict, (M.conclusion_detail(D, c, R):gsub("%.$", "")))
end

--- The conclusion as the report's opening states it, in one short sentence: the verdict, the form
-- it names, the responses that are valid and those the data leave undetermined. The reasons
-- (the other forms, the bounds, what would settle it) follow it in M.conclusion's words.
function M.conclusion_short(D, c)
  local k = c.chosen or #c.trials
  local chosen = c.trials[k]
  local by = { valid = {}, invalid = {} }
  for _, m in ipairs(D.names) do
    local v = chosen.responses[m]
    if by[v] then by[v][#by[v] + 1] = m end
  end
  local s = ("Conclusion: the model is %s in %s"):format(c.verdict, form_name(chosen.applied))
  if c.verdict == "valid" then return ("%s on %s."):format(s, listed(by.valid)) end
  local parts = {}
  if #by.valid > 0 then parts[#parts + 1] = "valid on " .. listed(by.valid) end
  if #by.invalid > 0 then parts[#parts + 1] = "invalid on " .. listed(by.invalid) end
  if #c.undetermined > 0 then parts[#parts + 1] = listed(c.undetermined) .. " not determined by these data" end
  return s .. (#parts > 0 and (": " .. table.concat(parts, "; ")) or "") .. "."
end

--- A trial's label in the report and the log: "Trial k (candidate)".
function M.trial_label(model, k)
  return ("Trial %d (%s)"):format(k, model.candidate == "initial" and "initial model" or model.candidate)
end

--- A trial's verdict in one sentence (the end of its validity-check section).
function M.trial_verdict(label, res)
  local s = ("%s is %s"):format(label, res.verdict)
  if res.why then s = s .. ": " .. res.why end
  if res.undetermined and #res.undetermined > 0 then
    s = s .. ("; %s not determined by the calibration data"):format(listed(res.undetermined))
  end
  return s .. "."
end

--- One line per trial for the console (what the conclusion says, in words).
function M.trial_line(D, i, t, refinement)
  local parts = {}
  for _, m in ipairs(D.names) do parts[#parts + 1] = m .. " " .. (t.responses[m] or "not validated") end
  return ("Trial %d: %s, applied {%s}, unknowns %s: %s%s"):format(i, t.candidate, table.concat(t.applied, ", "),
    table.concat(t.unknowns, ", "),
    table.concat(parts, ", "), refinement and ("; refined by " .. refinement) or "")
end

-- ---------------------------------------------------------------------------------------------
-- Data and characterization
-- ---------------------------------------------------------------------------------------------

function M.data_intro(D, n, file)
  return ("%d measurements from %s. %s calibrate the model%s."):format(n, file, listed(D.calibrate),
    #D.validate > 0 and ("; " .. listed(D.validate) .. (#D.validate > 1 and " are" or " is") .. " kept for validation") or "")
end

--- The data step's units check: the nominal run against the data, per response.
function M.units_intro(rows)
  return ("Before any solver budget is spent: one run of the initial model with every unknown at its start mean"
    .. " gives %s. Data an order of magnitude or more away from it (or outside a declared plausible range) are"
    .. " most often a units mistake, and the study stops on them unless --accept-units is given."):format(
    table.concat(rows, ", "))
end

function M.characterize_intro(n)
  return ("With %d data the plain KDE is bumpy; KDE-ebd (Kang et al. 2018) adds points drawn uniformly in bounds"
    .. " estimated from the data (significance 0.1) until the PDF changes by less than a critical intersection area"
    .. " of 0.95, smoothing it. The KDE-ebd PDFs are the experimental PDFs of the calibration."):format(n)
end

-- ---------------------------------------------------------------------------------------------
-- Screening
-- ---------------------------------------------------------------------------------------------

--- The screening's paragraph: out is the screening step's record (method, n, inputs,
-- solver_solutions, the surrogate's leave-one-out Q² per response).
function M.screening_intro(D, out)
  if out.method == "surrogate" then
    local q = {}
    for _, m in ipairs(D.names) do q[#q + 1] = ("%s %.4f"):format(m, out.responses[m].q2 or 0 / 0) end
    return ("Area-metric screening (eq. 3 and 7) at the solver's cost: the initial model ran %d times on a Latin"
      .. " hypercube of the %d inputs through their declared distributions; a ridge quadratic per response"
      .. " (leave-one-out Q² %s) stands in for the model, and each input is fixed at its mean in turn on one"
      .. " common-random-number sample of %d points of it (--screening full: on the model itself)."):format(
      out.solver_solutions, out.inputs, table.concat(q, ", "), out.n)
  end
  return ("Area-metric screening (eq. 3 and 7): each of the %d inputs is fixed at its mean in turn on one"
    .. " common-random-number sample of %d points of their declared distributions, initial model, %d solutions."
    ):format(out.inputs, out.n, out.solver_solutions)
end

-- ---------------------------------------------------------------------------------------------
-- Surrogate
-- ---------------------------------------------------------------------------------------------

--- A trial's surrogate paragraph: T the trial's model, res its surrogate step's record, fixed the
-- words for its fixed inputs ("" or ", fixed a = 1, ..."), test_points the independent test points.
function M.surrogate_intro(D, T, res, fixed, test_points)
  local form = {}
  for k, v in pairs(T.form) do form[#form + 1] = ("%s = %s"):format(k, tostring(v)) end
  table.sort(form)
  local sq = res.sequential
  local how = sq and ("a sequential design of %d points (a %d-point maximin Latin hypercube, then batches of %d"
    .. " where the Kriging variance, weighted by where the calibration can put the unknowns' mass, is largest;"
    .. " %s; the fixed design it replaces has %d)"):format(
    res.n_design, sq.initial, sq.batch,
    sq.reached and ("stopped at leave-one-out Q² ≥ " .. sq.q2_target .. " in every response")
      or ("stopped at its limit: " .. sq.stop), T.n_design)
    or ("a %d-point maximin Latin hypercube"):format(res.n_design)
  return ("Kriging (Gauss correlation, %s trend, hyperparameters by maximum likelihood) of %s on"
    .. " %s of the unknowns %s over the design box (mean bounds widened by 3 std bounds; uniform: √3), model"
    .. " form {%s}%s. Every solution is a solver run of the declared model, kept in the evaluation store."
    .. " An independent %d-point hypercube measures the test RMSE (the paper's Tables 3 and 7)."):format(
    T.trend, listed(D.names), how, table.concat(T.unknowns, ", "), table.concat(form, ", "), fixed, test_points)
end

--- Where the trial's calibration, validation and evidence ran (the surrogate step's decision,
-- surface.lua), for the surrogate section.
function M.surface_note(res)
  if res.on == "model" then
    return ("The calibration, the validation and the evidence of this trial ran on the model itself, not on these"
      .. " Krigings: it runs in-process and is cheaper (%s). The Krigings are shown for their accuracy only."):format(
      res.cost.why)
  end
  return ("The calibration, the validation and the evidence of this trial run on these Krigings (%s)."):format(
    res.cost and res.cost.why or "where they ran was not recorded")
end

-- ---------------------------------------------------------------------------------------------
-- Calibration
-- ---------------------------------------------------------------------------------------------

local function priors_sentence(prior_file, labels)
  if #labels == 0 then return "No prior knowledge: the objective is the data's alone (no --prior given)." end
  return ("Prior knowledge declared by the analyst (%s): %s."):format(prior_file, table.concat(labels, "; "))
end

local STAGE1_ENDS = { tolerance_reached = "matched to its tolerance (tolerance_reached)",
  ftol_reached = "matched as well as a start needs: the last step lowered it by less than 1e-3 of itself + 1e-4"
    .. " (ftol_reached)",
  stationary = "the closest match within the bounds: no step there lowers it (stationary)",
  max_iterations = "stopped on its iteration budget (max_iterations)" }

--- How stage 1 (calibration.lua's moments_record) ended, in words.
function M.stage1_outcome(m)
  return ("moment mismatch %.3g -> %.3g, %s%s"):format(m.objective_start or 0 / 0, m.objective or 0 / 0,
    STAGE1_ENDS[m.status] or m.status, m.moved and "" or "; the start values kept: PR was no lower at the moved point")
end

--- The calibration section's paragraph. T: the trial model; res: calibration.calibrate's result;
-- cfg: the run's sample sizes.
function M.calibration_intro(D, T, res, cfg, prior_file, labels)
  local pr = res.metric == "pr"
  local parts = {}
  for _, m in ipairs(D.calibrate) do parts[#parts + 1] = ("%s %.4f"):format(m, res.metrics[m]) end
  local direct = res.on == "model"
  return ("Means and standard deviations of the %d unknowns (types, bounds and start values as declared: the"
    .. " study's unknowns, and each applied candidate's new ones) minimize %s over the KDEs of %d"
    .. " common-random-number samples propagated through %s; SLSQP (NLopt), in"
    .. " smi.calibrate's model form (%s). PR saturates when the PDFs"
    .. " do not overlap, so a first stage moves the start values to match the means and stds of %s"
    .. " (smi.calibrate's moment start: Levenberg-Marquardt on the %s, %d model runs; %s); the"
    .. " PR stage starts from there. %s Objective at the optimum %.4f (%s %s), %d"
    .. " evaluations from %d start(s), %s (converged: %s)."):format(
    #T.unknowns, (pr and "the summed PR between the KDE-ebd PDFs of the data and the predicted ones, over %s"
      or "minus the log-likelihood of the data points of %s"):format(listed(D.calibrate)), cfg.cal_n,
    direct and ("the model itself (it runs in-process, cheaper than the Krigings: %s)"):format(res.cost.why)
      or "the Kriging models",
    direct and "the model, its differences for the gradient" or "the Krigings as the model: analytic gradients",
    listed(D.calibrate), direct and "model's differences" or "Krigings' Jacobian", res.moments_stage.evaluations,
    M.stage1_outcome(res.moments_stage), priors_sentence(prior_file, labels),
    res.objective, pr and "PR" or "-logL", table.concat(parts, ", "), res.evaluations,
    res.starts and #res.starts or 1, res.status, tostring(res.converged))
end

--- The bootstrap interval of one input (mean / std), or why there is none.
function M.bootstrap_cell(res, input)
  local b = res.bootstrap
  if not b then return "not computed (--quick or --bootstrap 0)" end
  if b.replicates == 0 then return ("all %d replicates failed"):format(b.failed) end
  return ("[%.4g, %.4g] / [%.4g, %.4g]"):format(b.lower[input .. ".mean"], b.upper[input .. ".mean"],
    b.lower[input .. ".std"], b.upper[input .. ".std"])
end

function M.parameters_caption(res)
  local b = res.bootstrap
  -- the sd of B replicates is known to about 1/sqrt(2(B - 1)) of itself; the percentiles need
  -- more replicates (the kernel's replicates_needed: their Monte Carlo error under a tenth of the
  -- half-width), said with the option that asks for them
  local ci = b and b.replicates > 1 and ("90 %% bootstrap over the data (mean / std), estimate ± 1.645 sd of %d replicates that restart"
    .. " SLSQP at the optimum with %d evaluations each (the sd's Monte Carlo error about %.0f %%)%s%s: the local pull"
    .. " of the data, which understates the spread along the directions the calibrated responses leave undetermined"):format(
      b.replicates, b.maxeval, 100 / math.sqrt(2 * (b.replicates - 1)),
      b.failed > 0 and ("; %d failed, see the warnings"):format(b.failed) or "",
      (b.replicates_needed or 0) > b.replicates and ("; the 90 %% percentile interval would need about %d replicates"
        .. " (--bootstrap %d)"):format(b.replicates_needed, b.replicates_needed) or "")
    or b and ("none: all %d replicates failed"):format(b.failed) or "none (--quick or --bootstrap 0)"
  return ("Calibrated statistical parameters. CI: %s."):format(ci)
end


--- Each mean's range over the near-optimal set, in words.
local function mean_ranges(no)
  local r = {}
  for name, rg in pairs(no.mean_ranges or {}) do r[#r + 1] = ("%s [%.4g, %.4g]"):format(name, rg[1], rg[2]) end
  table.sort(r)
  return table.concat(r, ", ")
end

--- The identifiability callout: what the calibrated responses fix and the near-optimal set.
function M.identifiability(D, res)
  local sv, no = res.sensitivity, res.near_optimal
  local shares = {}
  for _, m in ipairs(D.validate) do
    shares[#shares + 1] = ("%.0f %% of %s's sensitivity lies outside what they constrain"):format(
      100 * (sv.unconstrained_share[m] or 0), m)
  end
  return ("Identifiability (beyond the paper): %s fix %d combinations of the %d means and leave %d"
    .. " undetermined%s. Near-optimal calibrations (objective within %.3g of the optimum, the %s; %s): %d points;"
    .. " the means over them: %s."):format(listed(D.calibrate), sv.constrained, #sv.inputs, sv.undetermined,
    #shares > 0 and ("; " .. table.concat(shares, "; ")) or "", no.tolerance,
    no.tolerance_basis and no.tolerance_basis.basis or "tolerance", no.source, #no.points, mean_ranges(no))
end

function M.weak_parameters(D, weak)
  return ("Identifiability: the objective hardly changes with %s over its whole range; these parameters are not"
    .. " determined by %s."):format(table.concat(weak, ", "), listed(D.calibrate))
end

-- ---------------------------------------------------------------------------------------------
-- Validity check
-- ---------------------------------------------------------------------------------------------

--- The validity check's paragraph; the threshold is the run's (res.responses.*.threshold).
function M.validation_intro(D, res, n, cfg)
  local val = #D.validate == 0 and "" or (" %s %s not: the calibration data may leave combinations of the means"
    .. " undetermined, so the metric is computed over every near-optimal calibration (%d samples each) and the"
    .. " verdict is valid or invalid only when that whole range lies on one side of the threshold, else"
    .. " inconclusive; an undecided one in a trial that is otherwise valid is listed as undetermined, not hidden."):format(
    listed(D.validate), #D.validate > 1 and "were" or "was", cfg.near_n)
  local direct = res.on == "model"
  local check = direct and " The samples ran through the model itself (in-process), so there is no surrogate to check."
    or (" As a check of the surrogate, %d points of the calibrated distributions, stratified (a Latin hypercube in"
      .. " probability space), were also run through the solver itself."):format(res.n_solver)
  return ("u-pooling area metric (eq. 11 and 12) of the data of each response against the KDE of %d samples of"
    .. " the calibrated model (%s), with the exact 95 %% threshold for the number of data (%.4f for n = %d,"
    .. " docs/spec/algorithms.md §5). %s were used by the calibration: their verdict is the optimum's.%s The"
    .. " trial is valid when every calibrated response is valid and its calibration converged.%s"):format(
    res.n, direct and "the model itself" or "Kriging", res.responses[D.calibrate[1]].threshold, n,
    listed(D.calibrate), val, check)
end

--- The sentence that says which of the Kriging verdict and the solver check governs when they
-- disagree: the verdict, because it is the u-pooling of the calibrated distributions sampled
-- val_n times, where the check runs the solver at solver_check stratified points only; the
-- disagreement says the surrogate's error matters near this optimum.
function M.solver_disagrees(label, title, v, cfg)
  local sv = v.solver
  if v.verdict == "inconclusive" then
    return ("%s, %s: the verdict (inconclusive) governs. The solver check (U = %.4f, %s) runs the solver at the"
      .. " optimum's distributions only, one of the calibrations that fit the calibrated responses as well; over"
      .. " them U spans both sides of the threshold, which one calibration cannot settle. The response is"
      .. " undetermined by these data, so the study refines or concludes undetermined, never valid on it."):format(
      label, title, sv.metric, sv.pass and "valid" or "invalid")
  end
  return ("%s, %s: the verdict governs. It is the u-pooling of the calibrated distributions on %d Kriging"
    .. " samples; the solver check (U = %.4f) runs the solver at %d points only, so it flags the surrogate's error"
    .. " near this optimum rather than overrules the verdict. More points (--solver-check N) or a larger design"
    .. " would settle the disagreement."):format(label, title, cfg.val_n, sv.metric, cfg.solver_check)
end

-- ---------------------------------------------------------------------------------------------
-- Refinement
-- ---------------------------------------------------------------------------------------------

--- Why the chosen candidate (index jc of the matrix dm) won against the runner-up (jr, or
-- none): its rating and the weighted differences of its standardized criteria.
function M.why_chosen(dm, jc, jr)
  local w = { dm.weights.correctness, dm.weights.robustness, dm.weights.computational, dm.weights.implementation }
  local why = {}
  for i, name in ipairs(dm.criteria) do
    local d = (w[i] or 1) * (dm.candidates[jc].standardized[i] - (jr and dm.candidates[jr].standardized[i] or 0))
    why[#why + 1] = ("%s %+.3f"):format(name, d)
  end
  return ("rating %.3f%s; weighted difference by criterion: %s"):format(dm.overall[jc],
    jr and (" against %.3f for %s"):format(dm.overall[jr], dm.candidates[jr].name) or "", table.concat(why, ", "))
end

--- Why the study refines a trial that fits: an alternative form the data favour. alt: the
-- alternative's record; own: the trial's evidence; margin: the declared Bayes factor.
function M.favoured_alternative(alt, own, margin)
  return ("the data favour %s over it by a %s, the margin %g"):format(form_name(alt.applied), factor_words(alt, own), margin)
end

--- A form's posterior of the unknowns' means ({["x.mean"] = {mean, std}}) in words, by name.
function M.posterior_words(posterior)
  local names, out = {}, {}
  for n in pairs(posterior or {}) do names[#names + 1] = n end
  table.sort(names)
  for _, n in ipairs(names) do
    out[#out + 1] = ("%s %.4g ± %.2g"):format(n:gsub("%.mean$", ""), posterior[n].mean, posterior[n].std)
  end
  return table.concat(out, "; ")
end

--- The alternatives section's paragraph after trial k.
function M.alternatives_intro(k, label)
  return ("%s fits the data; other forms may fit them as well. Each form one untried candidate away from it gets"
    .. " a design of its own and its log evidence under the declared priors (no calibration or validation: the"
    .. " evidence alone compares forms). The trial is called valid only if it beats each of them by the margin;"
    .. " an alternative that beats it becomes the next trial."):format(label)
end

--- Why a trial is not refined (its verdict is not invalid).
function M.nothing_to_refine(k, v)
  local und = v.undetermined and #v.undetermined > 0 and ("; %s undetermined"):format(listed(v.undetermined)) or ""
  return ("trial %d is %s%s%s: nothing is refined without an invalid or undetermined response"):format(k, v.verdict,
    v.why and (" (" .. v.why .. ")") or "", und)
end

--- The refinement section's paragraph. out: the refinement step's result (matrix, chosen, rank,
-- why, model, failed_responses).
function M.refinement_intro(k, out)
  local dm, model = out.matrix, out.model
  local names = {}
  for j, c in ipairs(dm.candidates) do names[j] = c.name end
  local w = dm.weights
  return ("Trial %d is %s on %s. Candidates (each declaring its revision): %s. Each revised model (on top"
    .. " of the revisions kept so far) is run at the start means; correctness is eq. (13)"
    .. " averaged over every response used in calibration (%s), whichever of them the calibration gave up;"
    .. " robustness the number of new unknowns, computational cost the measured run time (minutes, in whole"
    .. " seconds: shorter differences are timing noise), implementation cost the analyst's estimate (minutes)."
    .. " Weights: correctness %g, robustness %g, computational cost %g, implementation cost %g (the"
    .. " declaration's weights; by default correctness counts double: a revision that does not move the failed"
    .. " response cannot make the model valid). S = 1 − M / max M (eq. 14); rating = Σ w·S. Ranking: %s. Chosen: %s"
    .. " (rank %d; candidates"
    .. " already tried are passed over): %s. Trial %d applies %s; unknowns %s.%s"):format(
    k, out.undetermined_only and "undetermined" or "invalid", listed(out.failed_responses), table.concat(names, "; "), table.concat(dm.responses, ", "),
    w.correctness, w.robustness, w.computational, w.implementation, table.concat(dm.ranking, " > "), out.chosen,
    out.rank, out.why, k + 1, table.concat(model.applied, " + "), table.concat(model.unknowns, ", "),
    #(model.dropped or {}) > 0 and (" Dropped: " .. M.dropped(model.dropped) .. ".") or "")
end

--- The revisions a trial dropped, with why.
function M.dropped(list)
  local w = {}
  for i, d in ipairs(list) do w[i] = ("%s (%s)"):format(d.name, d.why) end
  return table.concat(w, "; ")
end

-- ---------------------------------------------------------------------------------------------
-- Summary
-- ---------------------------------------------------------------------------------------------

M.solver_use_caption = "Solver use in this run (steps run alone count only their own runs): points evaluated,"
  .. " processes launched, points reused from the store."

--- The loop as it ran, in words (the summary's paragraph).
function M.story(D, c, R, prior_labels)
  local story = {}
  for i, t in ipairs(c.trials) do
    local parts = {}
    for _, m in ipairs(D.names) do parts[#parts + 1] = m .. " " .. (t.responses[m] or "not validated") end
    story[#story + 1] = ("Trial %d (%s, applied {%s}, calibration %s): %s."):format(i, t.candidate,
      table.concat(t.applied, ", "),
      t.calibration.converged and "converged" or ("stopped: " .. tostring(t.calibration.status)),
      table.concat(parts, ", "))
    if c.refinements[i] then
      story[#story + 1] = ("The decision matrix chose %s (%s)."):format(c.refinements[i], R["refinement" .. i].why)
    end
  end
  if c.ended then story[#story + 1] = "The study ended: " .. c.ended .. "." end
  story[#story + 1] = ("Priors: %s."):format(#prior_labels > 0 and table.concat(prior_labels, "; ")
    or "none (the data file alone)")
  return table.concat(story, " ")
end

return M
