-- SPDX-License-Identifier: MIT
--- smi.improve.near_optimal: the study's pushes beside smi.calibrate's r.near_optimal (`smi-lua doc smi.calibrate`):
-- calibrations that fit the calibration responses as well as the optimum, within a tolerance,
-- chosen to show how far a validation response's prediction can move among them. calibration.lua
-- takes the union of both: the kernel's points follow the objective's weak directions and cannot
-- know which prediction matters.
--
-- How: for each summary of each validation response (its mean and std, in units of the data's
-- std) and each way (up, down), and once towards the data's mean and std of the validation
-- response, a calibration from the optimum (smi.calibrate, SLSQP) pushes the summaries while a
-- quadratic penalty holds the calibration responses' summaries (their means and stds)
-- at the optimum's; the penalty weight is raised tenfold if the end point does not fit. An end
-- point, and the points at 1/3 and 2/3 of the way
-- to it, are kept when the calibration objective (the study's PR or log-likelihood) there is
-- within `tolerance` of the optimum's. These are calibrations from several starts' worth of
-- directions, each checked against the real objective: the range of the validation metric over
-- them is what the calibration data leave open. Cost: propagations only (no KDE) in the pushes,
-- one objective evaluation per point checked.
local M = {}

-- The summaries of responses `all` predicted at th: each response's mean and std, in units of the data's
-- std (the pushes' penalty and targets compare them across responses on one scale).
local function summaries(t, all, th)
  local Y = t.predicted(th, all)
  local s = {}
  for _, m in ipairs(all) do
    local sd = t.data[m]:std()
    s[#s + 1] = Y[m]:mean() / sd
    s[#s + 1] = Y[m]:std() / sd
  end
  return s
end

-- The pushes: each validation summary up and down (sign = ±1, summary r), and one towards the
-- data (sign = 0): all validation summaries at the data's mean and std, i.e. is there a
-- calibration fitting the calibrated responses as well that predicts the validation ones as
-- measured? Also returns the
-- data's summaries (the sign = 0 push's target) by summary index.
local function push_plan(t, nc, n)
  local plan = {}
  for r = nc + 1, n do
    plan[#plan + 1] = { r, 1 }
    plan[#plan + 1] = { r, -1 }
  end
  plan[#plan + 1] = { nil, 0 }
  local target = {}
  for i, m in ipairs(t.validation_responses) do
    target[nc + 2 * i - 1] = t.data[m]:mean() / t.data[m]:std()
    target[nc + 2 * i] = 1
  end
  return plan, target
end

-- One push (summary r, sign) from the optimum: smi.calibrate on the push objective with the
-- calibration summaries held by a quadratic penalty, weight 100, then from its end point weight
-- 1000 when that end point does not fit (keep(th) checks the real objective and keeps fitting
-- points). Returns the end point, whether it was kept, the last status and the evaluations.
local function push_from_optimum(t, ctx, r, sign, keep)
  local nc, s0, target = ctx.nc, ctx.s0, ctx.target
  local start, reached, status, evals = t.optimum, nil, nil, 0
  for _, weight in ipairs{ 100, 1000 } do
    local params = {}
    for _, q in ipairs(t.params) do
      params[#params + 1] = { name = q.name, lower = q.lower, upper = q.upper, start = start[q.name] }
    end
    local res = smi.calibrate{
      parameters = params, method = "slsqp", maxeval = t.maxeval or 1000, identifiability = false,
      -- the analyst's prior holds too, weighted as the summaries are (smi.calibrate adds it)
      prior = t.prior, prior_weight = t.prior and weight or nil,
      objective = function(th)
        local s = summaries(t, ctx.all, th)
        local pen = 0
        for a = 1, nc do pen = pen + (s[a] - s0[a]) ^ 2 end
        if sign == 0 then
          local miss = 0
          for q = nc + 1, #s do miss = miss + (s[q] - target[q]) ^ 2 end
          return miss + weight * pen
        end
        return -sign * (s[r] - s0[r]) + weight * pen
      end,
    }
    reached, status, evals = res.params, res.status, evals + res.evaluations
    if keep(reached) then return reached, true, status, evals end
    start = reached
  end
  return reached, false, status, evals
end

-- The push in scaled parameters (0..1 over the bounds), as unit loadings and its length: what
-- moved, for the report.
local function push_loadings(t, reached)
  local loadings, norm = {}, 0
  for _, q in ipairs(t.params) do
    local d = (reached[q.name] - t.optimum[q.name]) / (q.upper - q.lower)
    loadings[q.name], norm = d, norm + d * d
  end
  norm = math.sqrt(norm)
  if norm > 0 then for k, v in pairs(loadings) do loadings[k] = v / norm end end
  return loadings, norm
end

--- t: params ({name, lower, upper} list), optimum ({name = value}), value (objective at the
-- optimum, with the analyst's prior terms if any), objective(th) -> value (the same),
-- predicted(th, responses) -> {response = vec},
-- tolerance, calibration_responses, validation_responses, data ({response = vec}), maxeval (per push),
-- prior: the analyst's smi.calibrate prior list (nil: none), held by the pushes like the summaries.
-- Returns {source, tolerance, points = {optimum, ...}, objectives = {...}, directions = {...}}.
function M.by_prediction_extremes(t)
  local all = {}
  for _, m in ipairs(t.calibration_responses) do all[#all + 1] = m end
  for _, m in ipairs(t.validation_responses) do all[#all + 1] = m end
  local ctx = { all = all, nc = 2 * #t.calibration_responses, s0 = summaries(t, all, t.optimum) }
  local nc = ctx.nc
  local points, objectives = { t.optimum }, { t.value }
  local function between(a, b, f)
    local th = {}
    for _, q in ipairs(t.params) do th[q.name] = a[q.name] + f * (b[q.name] - a[q.name]) end
    return th
  end
  local function keep(th)
    local f = t.objective(th)
    if f - t.value <= t.tolerance then
      points[#points + 1], objectives[#objectives + 1] = th, f
      return true
    end
    return false
  end
  local plan
  plan, ctx.target = push_plan(t, nc, #ctx.s0)
  local pushes = {}
  for _, step in ipairs(plan) do
    local r, sign = step[1], step[2]
    local reached, kept, status, evals = push_from_optimum(t, ctx, r, sign, keep)
    if kept then
      for _, f in ipairs{ 1 / 3, 2 / 3 } do keep(between(t.optimum, reached, f)) end
    end
    local loadings, norm = push_loadings(t, reached)
    pushes[#pushes + 1] = { response = sign == 0 and table.concat(t.validation_responses, ", ")
                                         or all[math.floor((r - 1) / 2) + 1],
                            summary = sign == 0 and "mean and std" or ((r - nc) % 2 == 1 and "mean" or "std"),
                            way = sign > 0 and "up" or (sign < 0 and "down" or "to the data"), kept = kept,
                            status = status, evaluations = evals, loadings = loadings, length = norm }
  end
  -- strongest first: the push that moved the parameters furthest while still fitting
  table.sort(pushes, function(a, b) return (a.kept and a.length or -1) > (b.kept and b.length or -1) end)
  return { source = ("pushes of %s's mean and std up and down with %s held, checked against the objective"):format(
             table.concat(t.validation_responses, ", "), table.concat(t.calibration_responses, ", ")),
           tolerance = t.tolerance, points = points, objectives = objectives, directions = pushes }
end

return M
