-- SPDX-License-Identifier: MIT
--- smi.improve.trial: one trial of statistical model improvement (Son et al. 2020 §4.1 and §4.2)
-- on any declared product: Kriging surrogates of every response on a Latin hypercube of the
-- unknowns (solver runs through the declaration's model factory and the evaluation store),
-- calibration (calibration.lua), and validation by u-pooling, a validation-only response judged
-- over the near-optimal calibrations. This file computes; the words are in text.lua.
-- `responses` below is the declaration's list of response names (calibrate ones first or not:
-- the roles come from `calibrate` / `validate` name lists).
local stream = require "smi.improve.stream"

local M = {}

--- Box of an unknown's Kriging design (spec {dist, mean, std}): every value its distribution
-- can take with a mean and std inside the calibration bounds, up to 3 std (the uniform's
-- half-width √3·std), kept > 0.
function M.design_box(u)
  local reach = (u.dist == "uniform" and math.sqrt(3) or 3) * u.std[2]
  local lo = u.mean[1] - reach
  if lo <= 0 then lo = 0.5 * u.mean[1] end
  return { lo, u.mean[2] + reach }
end

--- The model that predicts `names`: `direct`, the in-process smi.model the trial runs on
-- (surface.lua; one call gives every response), or else the table of their Krigings k.
function M.responses_model(k, direct, names)
  if direct then return direct end
  local model = {}
  for _, m in ipairs(names) do model[m] = k[m] end
  return model
end

--- predicted(th, names): the named responses of the common-random-number sample of n points
-- through the Krigings k ({response = kriging}) or the model `direct`, the unknowns distributed
-- as their specs say with the means and stds of th ({["input.mean"] = v, ["input.std"] = v}).
function M.predictor(k, unknowns, specs, n, seed, direct)
  return function(th, names)
    local dists = {}
    for i, name in ipairs(unknowns) do
      dists[i] = { name, smi.dist[specs[name].dist]{ mean = th[name .. ".mean"], std = th[name .. ".std"] } }
    end
    return smi.propagate{ model = M.responses_model(k, direct, names), inputs = dists, n = n, seed = seed }
  end
end

local function col_table(v)
  local t = {}
  for i = 1, #v do t[i] = v[i] end
  return t
end

--- Design, solver runs, Kriging per response, leave-one-out and an independent test set.
-- t: {name, model (the factory's smi.model over the unknowns), responses, unknowns, specs, trend,
-- n_design (the fixed design's size, the sequential one's limit), design = "sequential"|"fixed",
-- n_test, seed, added (a fixed design's further points: a second maximin hypercube of that many
-- over the same box, its own seed, so the first n_design points and their runs are kept)}
function M.surrogate(t)
  local box = {}
  for i, n in ipairs(t.unknowns) do box[i] = M.design_box(t.specs[n]) end
  local model = t.model
  -- sequential (design.lua: start small, add batches, stop on the leave-one-out target) or the
  -- fixed maximin hypercube of n_design points
  local X, Y, seq
  if t.design == "sequential" then
    X, Y, seq = require("smi.improve.design").sequential{
      box = box, unknowns = t.unknowns, specs = t.specs, model = model,
      max = t.n_design, seed = t.seed, trend = t.trend, responses = t.responses }
  else
    X = smi.doe.lhs(t.n_design, box, { seed = t.seed, criterion = "maximin" })
    if (t.added or 0) > 0 then
      local rows = {}
      for i = 1, X:rows() do rows[i] = col_table(X[i]) end
      local X2 = smi.doe.lhs(t.added, box, { seed = stream(t.seed, "added design points"), criterion = "maximin" })
      for i = 1, X2:rows() do rows[#rows + 1] = col_table(X2[i]) end
      X = smi.mat(rows)
    end
    Y = model:evaluate(X)
  end
  local Xt = t.n_test > 0 and smi.doe.lhs(t.n_test, box, { seed = stream(t.seed, "test points"), criterion = "maximin" }) or nil
  local Yt = Xt and model:evaluate(Xt) or nil
  local k, diag = {}, {}
  for _, m in ipairs(t.responses) do
    k[m] = smi.kriging.fit(X, Y[m], { trend = t.trend, corr = "gauss", inputs = t.unknowns, output = m, seed = t.seed })
    -- saved beside the report: smi.kriging.load(file) gives the analyst this very surrogate
    local file = smi.out(("%s_%s.kriging"):format(t.name, m))
    k[m]:save(file)
    local loo = k[m]:loo()
    local pred = Yt and k[m]:predict(Xt) or {}
    local se, ymin, ymax = 0, math.huge, -math.huge
    for i = 1, #pred do
      se = se + (pred[i] - Yt[m][i]) ^ 2
      ymin, ymax = math.min(ymin, Yt[m][i]), math.max(ymax, Yt[m][i])
    end
    local loo_pred = {}
    for i = 1, #loo.residuals do loo_pred[i] = Y[m][i] - loo.residuals[i] end
    diag[m] = { loo_q2 = loo.q2, loo_rmse = loo.rmse, test_rmse = #pred > 0 and math.sqrt(se / #pred) or nil,
                test_range = { ymin, ymax },
                theta = col_table(k[m].theta), observed = col_table(Y[m]), loo_predicted = loo_pred, model_file = file,
                warnings = k[m].warnings }
  end
  local design = {}
  for i = 1, X:rows() do design[i] = col_table(X[i]) end
  local bounds = {}
  for i, n in ipairs(t.unknowns) do bounds[n] = box[i] end
  return { kriging = k, design = design, diagnostics = diag, design_bounds = bounds, n_design = X:rows(),
           n_test = t.n_test,
           trend = t.trend, unknowns = t.unknowns, responses = t.responses, sequential = seq }
end

--- The Kriging models of a surrogate step's results: the live objects or, when the step ran in
-- an earlier process, its saved model files; a results.json without them (or whose files were
-- removed) gets them refitted from the saved design and solver outputs at the saved
-- hyperparameters (no search, no solver run: the same model).
function M.krigings(s)
  if s.kriging and type(s.kriging[s.responses[1]]) == "userdata" then return s.kriging end
  local k, X = {}, nil
  for _, m in ipairs(s.responses) do
    local file = s.diagnostics[m].model_file
    local ok, loaded = false, nil
    if file then ok, loaded = pcall(smi.kriging.load, file) end
    if ok then
      k[m] = loaded
    else
      X = X or smi.mat(s.design)
      k[m] = smi.kriging.fit(X, smi.vec(s.diagnostics[m].observed),
                             { trend = s.trend, corr = "gauss", theta = smi.vec(s.diagnostics[m].theta),
                               inputs = s.unknowns, output = m })
    end
  end
  return k
end

--- What the calibrated responses can determine (beyond the paper): the relative sensitivities
-- d ln y / d ln x of each response's Kriging (or of the model, t.direct, when the trial runs on
-- it) at the calibrated means (central differences of
-- ±1 %), for each validation-only response the share of its sensitivity vector outside the span
-- of the calibrated ones' (0: the calibration fixes it; 1: it leaves it free), and the number of
-- mean combinations the calibrated responses leave undetermined. t: {calibrate, validate}.
function M.sensitivity(k, cal, t)
  local names, x0 = {}, {}
  for i, p in ipairs(cal.params) do names[i], x0[i] = p.input, p.mean end
  local all = {}
  for _, m in ipairs(t.calibrate) do all[#all + 1] = m end
  for _, m in ipairs(t.validate) do all[#all + 1] = m end
  -- the point and its 2 d steps, in one call per Kriging (or one model call)
  local rows = { x0 }
  for j = 1, #x0 do
    local up, dn = {}, {}
    for i = 1, #x0 do up[i], dn[i] = x0[i], x0[i] end
    up[j], dn[j] = x0[j] * 1.01, x0[j] * 0.99
    rows[#rows + 1], rows[#rows + 2] = up, dn
  end
  local P, Y = smi.mat(rows), nil
  if t.direct then
    Y = t.direct:evaluate(P)
  else
    Y = {}
    for _, m in ipairs(all) do Y[m] = k[m]:predict(P) end
  end
  local J = {}
  for _, m in ipairs(all) do
    J[m] = {}
    for j = 1, #x0 do J[m][j] = (Y[m][2 * j] - Y[m][2 * j + 1]) / (0.02 * Y[m][1]) end
  end
  -- Gram-Schmidt on the calibrated rows, then each validation-only row's residual.
  local function dot(a, b) local s = 0 for i = 1, #a do s = s + a[i] * b[i] end return s end
  local basis = {}
  for _, m in ipairs(t.calibrate) do
    local v = {}
    for i = 1, #x0 do v[i] = J[m][i] end
    for _, b in ipairs(basis) do local c = dot(v, b) for i = 1, #v do v[i] = v[i] - c * b[i] end end
    local n = math.sqrt(dot(v, v))
    if n > 1e-12 then for i = 1, #v do v[i] = v[i] / n end basis[#basis + 1] = v end
  end
  local share, most = {}, 0
  for _, m in ipairs(t.validate) do
    local r = {}
    for i = 1, #x0 do r[i] = J[m][i] end
    for _, b in ipairs(basis) do local c = dot(r, b) for i = 1, #r do r[i] = r[i] - c * b[i] end end
    local jj = dot(J[m], J[m])
    share[m] = jj > 0 and math.sqrt(dot(r, r) / jj) or 0
    most = math.max(most, share[m])
  end
  local sens = {}
  for _, m in ipairs(all) do
    sens[m] = {}
    for j, n in ipairs(names) do sens[m][n] = J[m][j] end
  end
  return { inputs = names, responses = all, sensitivity = sens, undetermined = #x0 - #basis,
           constrained = #basis, unconstrained_share = share, most_unconstrained_share = most }
end

--- The calibrated input distributions of a calibration result (numbers only, so that a step
-- running alone can rebuild them).
function M.distributions(cal)
  local d = {}
  for _, p in ipairs(cal.params) do d[#d + 1] = { p.input, smi.dist[p.dist]{ mean = p.mean, std = p.std } } end
  return d
end

--- The u-pooling metric of the data of `response` over the calibration's near-optimal points (each
-- propagated through the Kriging, n samples), and the verdict it allows: "valid" when every
-- point's metric is at most the threshold, "invalid" when every one is above it, else
-- "inconclusive".
function M.metric_range(t, response)
  local cal, specs = t.calibration, t.model.specs
  local names = {}
  for i, p in ipairs(cal.params) do names[i] = p.input end
  local predicted = M.predictor(t.kriging, names, specs, t.n_near, stream(t.seed, "near-optimal predictions"), t.direct)
  local lo, hi, threshold, metrics = math.huge, -math.huge, nil, {}
  for i, th in ipairs(cal.near_optimal.points) do
    local Y = predicted(th, { response })
    local v = smi.metric.upool{ data = { t.data[response] }, predicted = { smi.kde(Y[response]) }, confidence = 0.95,
                                seed = stream(t.seed, "u-pooling") }
    metrics[i], threshold = v.metric, v.threshold
    lo, hi = math.min(lo, v.metric), math.max(hi, v.metric)
  end
  local verdict = hi <= threshold and "valid" or (lo > threshold and "invalid" or "inconclusive")
  return { lower = lo, upper = hi, threshold = threshold, metrics = metrics, points = #metrics, verdict = verdict,
           tolerance = cal.near_optimal.tolerance, source = cal.near_optimal.source, n = t.n_near }
end

--- Validation: propagate the calibrated distributions through the Krigings (n samples) and,
-- as a check of the surrogate, through the solver itself (n_solver points, stratified:
-- check_points.lua); u-pooling of the data of each response against the predicted KDE, at 95 %.
-- A response used by the calibration gets the verdict at the optimum; a validation-only one
-- gets the verdict over the near-optimal calibrations (metric_range). t: {name, model (trial
-- model record), check_model (the factory's smi.model over the unknowns, or nil: no solver
-- check), kriging, direct (the in-process smi.model when the trial runs on it, surface.lua: then
-- it replaces the Krigings), calibration, data, responses, calibrate, n, n_solver, n_near, seed}.
function M.validate(t)
  local dists = M.distributions(t.calibration)
  local Ys = smi.propagate{ model = M.responses_model(t.kriging, t.direct, t.responses), inputs = dists, n = t.n,
                            seed = t.seed }
  local out = { n = t.n, n_solver = t.n_solver, responses = {}, on = t.direct and "model" or "surrogate" }
  local Ysol
  if t.check_model and t.n_solver > 0 then
    local Xs = require("smi.improve.check_points")(dists, t.n_solver, stream(t.seed, "solver check points"))
    Ysol = t.check_model:evaluate(Xs)
  end
  local used = {}
  for _, m in ipairs(t.calibrate) do used[m] = true end
  for _, m in ipairs(t.responses) do
    local pred = smi.kde(Ys[m])
    local v = smi.metric.upool{ data = { t.data[m] }, predicted = { pred }, confidence = 0.95, seed = stream(t.seed, "u-pooling") }
    local c = v:curve()
    local o = { metric = v.metric, threshold = v.threshold, p = v.p, pass = v.pass, u = col_table(v.u),
      predicted_mean = Ys[m]:mean(), predicted_std = Ys[m]:std(),
      curve = { x = col_table(c.x), y = col_table(c.y) }, used_in_calibration = used[m] == true, name = m }
    if Ysol then
      local vs = smi.metric.upool{ data = { t.data[m] }, predicted = { smi.kde(Ysol[m]) }, confidence = 0.95,
                                   seed = stream(t.seed, "u-pooling") }
      o.solver = { metric = vs.metric, pass = vs.pass, p = vs.p, mean = Ysol[m]:mean(), std = Ysol[m]:std() }
    end
    if used[m] then
      o.verdict = v.pass and "valid" or "invalid"
    else
      o.range = M.metric_range(t, m)
      o.verdict = o.range.verdict
    end
    o.pdf = M.pdf_curve(pred, t.data[m])
    out.responses[m] = o
  end
  -- the trial's verdict (verdict.lua): invalid if any response is; valid when every calibrated
  -- one is and the calibration converged, the undecided validation-only ones listed apart
  out.verdict, out.undetermined, out.why = require("smi.improve.verdict").trial{ names = t.responses,
    responses = out.responses, converged = t.calibration.converged == true, status = t.calibration.status }
  return out
end

--- (x, pdf) of a distribution on a grid covering the data and the distribution's bulk.
function M.pdf_curve(d, data, lo, hi)
  local mu, sd = d:mean(), d:std()
  lo = lo or math.min(mu - 4 * sd, data:min() - sd)
  hi = hi or math.max(mu + 4 * sd, data:max() + sd)
  local x = {}
  for i = 1, 201 do x[i] = lo + (hi - lo) * (i - 1) / 200 end
  return { x = x, y = col_table(d:pdf(smi.vec(x))) }
end

return M
