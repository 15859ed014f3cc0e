-- SPDX-License-Identifier: MIT
--- smi.improve.evidence: a trial's Bayesian calibration and log evidence (smi.calibrate_bayes):
-- the posterior of the unknowns' means and stds given every measured response of every specimen
-- (a specimen's responses are jointly distributed through its shared inputs; the kernel
-- estimates that likelihood from propagated samples), under the declared priors (an unknown's
-- `prior`, the --prior file's entries; without one a parameter is uniform on its range). The
-- evidence of each tried form, on the same data and priors, is what the study's Bayes factors
-- compare (forms.lua).
--
-- Where the likelihood runs: where the trial runs (surface.lua), on its Krigings or on the model
-- itself when a model pass is measured cheaper than the Krigings' fit and predict (M.costs times
-- both); a model that launches a solver process is never run directly.
local M = {}

--- The kernel's prior list from the declaration's unknowns (their `prior`) and the --prior file's
-- entries ({param, dist, mean, std}); a file entry with a function (`fn`) has no density and is
-- refused by name. unknowns: the trial's names; specs: their declarations.
function M.priors(unknowns, specs, file_entries)
  local list, have = {}, {}
  for _, n in ipairs(unknowns) do
    for _, part in ipairs{ "mean", "std" } do
      local p = specs[n].prior and specs[n].prior[part]
      if p then
        local param = n .. "." .. part
        list[#list + 1] = { param = param, dist = p.dist, mean = p.mean, std = p.std }
        have[param] = true
      end
    end
  end
  local known = {}
  for _, n in ipairs(unknowns) do known[n .. ".mean"], known[n .. ".std"] = true, true end
  for i, e in ipairs(file_entries or {}) do
    if e.fn then
      error(("--prior entry %d ('%s'): a prior given as a function has no density for the Bayesian calibration;"
        .. " give {param = \"input.mean\", dist = \"normal\"|\"lognormal\", mean =, std =}"):format(i, tostring(e.name)), 0)
    end
    -- an entry on a parameter this form does not have (a candidate's unknown) is not this form's
    if known[e.param] and not have[e.param] then
      list[#list + 1] = { param = e.param, dist = e.dist or "normal", mean = e.mean, std = e.std }
      have[e.param] = true
    end
  end
  return list
end

--- The posterior of the unknowns' means of an evidence record ({names, mean, std}):
-- {["x.mean"] = {mean, std}}, or nil when it has none.
function M.posterior_means(ev)
  local out = {}
  for _, n in ipairs(ev and ev.names or {}) do
    if n:match("%.mean$") then out[n] = { mean = ev.mean[n], std = ev.std[n] } end
  end
  return next(out) and out or nil
end

-- Whether value x lies within `k` standard deviations of the prior entry p ({dist, mean, std},
-- of the parameter itself; a lognormal is judged on the log scale).
local function within(p, x, k)
  if p.dist == "lognormal" then
    if not (x > 0) then return false end
    local s2 = math.log(1 + (p.std / p.mean) ^ 2)
    return math.abs(math.log(x) - (math.log(p.mean) - s2 / 2)) <= k * math.sqrt(s2)
  end
  return math.abs(x - p.mean) <= k * p.std
end

--- The near-optimal calibrations (the PR fits as good as the optimum) that the declared priors
-- allow: a point with a parameter beyond 3 standard deviations of its prior is one the analyst's
-- knowledge rules out, and a verdict over the near-optimal range must not rest on it. The PR fit
-- itself ignores the priors (the paper's calibration); this is where they count in the validity
-- check. cal: the trial's calibration (its evidence holds the priors). Returns cal, or a copy with
-- the allowed points (all of them when none is: the priors then disagree with every fit, which the
-- evidence already says) and `prior_dropped`.
function M.plausible_near_optimal(cal)
  local ev, no = cal.evidence, cal.near_optimal
  if not (ev and ev.priors and #ev.priors > 0 and no and no.points) then return cal end
  local kept = {}
  for _, pt in ipairs(no.points) do
    local ok = true
    for _, p in ipairs(ev.priors) do
      local x = pt[p.param]
      if x ~= nil and not within(p, x, 3) then ok = false end
    end
    if ok then kept[#kept + 1] = pt end
  end
  if #kept == #no.points or #kept == 0 then return cal end
  local near = {}
  for key, v in pairs(no) do near[key] = v end
  near.points = kept
  near.prior_dropped = #no.points - #kept
  near.source = ("%s; %d beyond 3 standard deviations of a declared prior left out"):format(no.source or "",
    near.prior_dropped)
  local out = {}
  for key, v in pairs(cal) do out[key] = v end
  out.near_optimal = near
  return out
end

-- Timings per side; the fastest counts. A single timing of a few milliseconds moves by its own
-- size when another process takes the core, and a choice that flips from run to run changes the
-- study's numbers; the fastest of three is what the code costs.
local REPEATS = 3

--- Seconds of one batch of n points through the model and through the Krigings' fit and
-- predict (X: the design the Krigings were fitted on, Y its outputs), each the fastest of
-- REPEATS. Returns model_s, kriging_s.
function M.costs(model, X, Y, responses, box, n, seed, trend)
  local P = smi.doe.lhs(n, box, { seed = seed, criterion = "none" })
  local model_s, kriging_s = math.huge, math.huge
  for _ = 1, REPEATS do
    local t0 = smi.now()
    model:evaluate(P)
    model_s = math.min(model_s, smi.now() - t0)
    t0 = smi.now()
    for _, m in ipairs(responses) do
      smi.kriging.fit(X, Y[m], { trend = trend, corr = "gauss", seed = seed }):predict(P)
    end
    kriging_s = math.min(kriging_s, smi.now() - t0)
  end
  return model_s, kriging_s
end

--- t: {unknowns, specs, responses (all measured), data ({response = vec}), kriging ({response =
-- kriging}), direct (the factory's in-process smi.model, else nil), cost (the trial's
-- {on = "model"|"surrogate", model_seconds, kriging_seconds}: surface.decide's, or nil), priors (M.priors' list), n, samples, seed}.
-- Returns the plain record: {log_evidence, log_evidence_error, loglik_error, mean, std,
-- interval, map, diagnostics, on ("surrogate"|"model"), cost, priors, evaluations, model_runs}.
function M.calibrate(t)
  local inputs = {}
  for i, n in ipairs(t.unknowns) do
    local u = t.specs[n]
    inputs[i] = { name = n, dist = u.dist, mean = { u.mean[1], u.mean[2], u.mean[3] },
                  std = { u.std[1], u.std[2], u.std[3] } }
  end
  local on_model = t.direct ~= nil and t.cost ~= nil and t.cost.on == "model"
  local model
  if on_model then
    model = t.direct
  else
    model = {}
    for _, m in ipairs(t.responses) do model[m] = t.kriging[m] end
  end
  local data = {}
  for _, m in ipairs(t.responses) do data[m] = t.data[m] end
  local r = smi.calibrate_bayes{ model = model, inputs = inputs, data = data, prior = #t.priors > 0 and t.priors or nil,
                                 n = t.n, samples = t.samples, seed = t.seed }
  -- the error of a log-evidence difference adds the likelihood estimate's own (docs/bayesian-calibration.md)
  local err = math.sqrt(r.log_evidence_error ^ 2 + (r.loglik_error or 0) ^ 2)
  local out = { log_evidence = r.log_evidence, log_evidence_error = err, sampler_error = r.log_evidence_error,
                loglik_error = r.loglik_error,
                mean = r.mean, std = r.std, interval = r.interval, interval_level = r.interval_level, map = r.map, names = r.names, converged = r.converged,
                diagnostics = r.diagnostics, on = on_model and "model" or "surrogate", cost = t.cost,
                priors = t.priors, evaluations = r.evaluations, model_runs = r.model_runs, n = t.n, samples = t.samples }
  return out
end

return M
