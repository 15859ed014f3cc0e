-- SPDX-License-Identifier: MIT
--- smi.improve.step.refinement: after a trial that is not valid, the decision matrix over the
-- untried candidates, each on top of the kept revisions (or a step back when every candidate is
-- in); after a valid one, the alternative form the evidence favours, if any.
local verdict = require "smi.improve.verdict"
local alternatives = require "smi.improve.alternatives"
local text = require "smi.improve.text"
local revise = require "smi.improve.revise"
local criteria = require "smi.refine.criteria"
local common = require "smi.improve.step.common"
local view, timed, skipped = common.view, common.timed, common.skipped

local M = {}

-- The candidates no trial up to k applied (R: the steps' results), in declared order.
local function untried_candidates(run, R, k)
  local tried = {}
  for i = 1, k do tried[R["trial" .. i .. "_surrogate"].model.candidate] = true end
  local untried = {}
  for _, c in ipairs(run.D.candidates) do if not tried[c.name] then untried[#untried + 1] = c end end
  return untried
end

-- A run time as the computational-cost criterion counts it: whole seconds, at least one
-- (minutes). Below a second a single timing is noise (process start, machine load), and eq. (14)
-- normalises by the largest magnitude, so 0.012 s against 0.029 s would otherwise weigh like a
-- model twice as expensive and flip the choice from run to run.
local function cost_minutes(seconds)
  return math.max(1, math.ceil(seconds - 1e-9)) / 60
end

-- The criteria of the decision matrix: the declaration's, or the paper's four
-- (smi.refine.criteria.paper: correctness eq. (13) averaged over every response used in
-- calibration, so the score does not depend on which of them the calibration gave up; robustness,
-- computational and implementation cost). Each revised model runs once, at its start means.
local function decision_criteria(run, observed, runner)
  local D, w = run.D, run.D.weights
  local cache = {}
  local function result(c)
    if not cache[c.name] then cache[c.name] = runner(c) end
    return cache[c.name]
  end
  local run_fn = function(c) local r = result(c) return r.y, r.seconds end
  if D.criteria then
    return D.criteria{ observed = observed, responses = D.calibrate, run = run_fn, weights = w }
  end
  local obs = {}
  for _, m in ipairs(D.calibrate) do obs[m] = observed[m] end
  return criteria.paper{ observed = obs, weights = { w.correctness, w.robustness, w.computational, w.implementation },
                         predict = function(c) return result(c).y end,
                         measure = function(c) return cost_minutes(result(c).seconds) end }
end

local function rank_candidates(run, R, base, untried)
  local D = run.D
  local observed = {}
  for _, m in ipairs(D.names) do observed[m] = smi.vec(R.data[m]):mean() end
  local revised = {}
  for _, c in ipairs(untried) do revised[c.name] = revise.apply(D, base, c.name) end
  local runs = {}
  local crit = decision_criteria(run, observed, function(c)
    local T = revised[c.name]
    local m = run.model(T, { purpose = "correctness", name = "refine-" .. c.short:gsub("%s", "-") })
    local Y, info = m:evaluate(revise.start_point(T))
    local y = {}
    for _, n in ipairs(D.names) do y[n] = Y[n][1] end
    runs[c.name] = { y = y, seconds = info and info.duration and info.duration[1] or 0 }
    return runs[c.name]
  end)
  local dm = smi.refine.decision_matrix{ candidates = untried, criteria = crit }
  local out = { responses = D.calibrate, observed = observed, weights = D.weights, candidates = {}, overall = {},
                criteria = {} }
  for i, c in ipairs(crit) do out.criteria[i] = c.name end
  for j, c in ipairs(untried) do
    out.overall[j] = dm.overall[j]
    local mag, std = {}, {}
    for i = 1, #crit do mag[i], std[i] = dm.M:get(j, i), dm.S:get(j, i) end
    out.candidates[j] = { name = c.name, magnitudes = mag, standardized = std, prediction = runs[c.name].y,
                          new_inputs = c.new_inputs, implement_minutes = c.implement_minutes,
                          run_seconds = runs[c.name].seconds }
  end
  local order = {}
  for j = 1, #untried do order[j] = j end
  table.sort(order, function(a, b) return dm.overall[a] > dm.overall[b] end)
  out.ranking = {}
  for i, j in ipairs(order) do out.ranking[i] = untried[j].name end
  return out
end

-- After a trial that is not valid with every candidate tried: a step back (alternatives.lua),
-- as the refinement step's result, or nil.
local function step_back(run, R, k, state)
  local m, why = alternatives.step_back(run.D, R, k, state)
  if not m then return nil end
  return { failed_responses = {}, chosen = "without " .. m.without, model = m, rank = 1, why = why, step_back = true }
end

-- After a trial valid on every response: the next trial is the alternative form whose evidence
-- beats it by the margin (alternatives_step), if any and if the limit allows.
local function refine_on_evidence(run, ctx, k, v)
  local alt = ctx.results["trial" .. k .. "_alternatives"]
  local better = alt and not alt.skipped and alt.better and alt.forms[alt.better]
  if not better then return skipped(text.nothing_to_refine(k, v)) end
  local why = text.favoured_alternative(better, ctx.results["trial" .. k .. "_calibration"].evidence, run.D.evidence.margin)
  if k > run.opt.max_refinements then
    return skipped(("%s, but the analyst's limit of %d refinement(s) is reached"):format(why, run.opt.max_refinements))
  end
  local base = revise.copy(ctx.results["trial" .. k .. "_surrogate"].model)
  local out = { failed_responses = {}, chosen = better.candidate, model = revise.apply(run.D, base, better.candidate),
                rank = 1, why = why, on_evidence = true }
  view("refinement")(run, ctx.report, out, k)
  return out
end

local function refinement_step(run, k)
  local D, opt = run.D, run.opt
  return timed(function(ctx)
    local R = ctx.results
    local v = R["trial" .. k .. "_validation"]
    if v.skipped then return skipped(v.reason) end
    if not verdict.needs_refinement(v) then return refine_on_evidence(run, ctx, k, v) end
    local state = v.verdict == "invalid" and "invalid" or ("undetermined on " .. table.concat(v.undetermined, ", "))
    if k > opt.max_refinements then
      return skipped(("trial %d is %s and the analyst's limit of %d refinement(s) is reached"):format(
        k, state, opt.max_refinements))
    end
    -- the responses that call for it: the invalid ones, else the undetermined ones
    local failed, undetermined = {}, {}
    for _, m in ipairs(D.names) do
      local rv = v.responses[m].verdict
      if rv == "invalid" then failed[#failed + 1] = m elseif rv == "inconclusive" then undetermined[#undetermined + 1] = m end
    end
    local undetermined_only = #failed == 0
    if undetermined_only then failed = undetermined end
    local untried = untried_candidates(run, R, k)
    if #untried == 0 then
      -- every candidate is in: take back the earliest revision whose removal no trial has tried
      local back = step_back(run, R, k, state)
      if back then
        view("refinement")(run, ctx.report, back, k)
        return back
      end
      return skipped(("trial %d is %s, every candidate has been tried and every step back too"):format(k, state))
    end
    -- the base of the next trial: this trial's revisions, minus the last one if it made the fit worse
    local base = revise.copy(R["trial" .. k .. "_surrogate"].model)
    local drop = revise.keep(R, k)
    if drop then
      local names = {}
      for _, a in ipairs(base.applied) do if not drop[a] then names[#names + 1] = a end end
      base.applied = names
    end
    local dm = rank_candidates(run, R, base, untried)
    local chosen = dm.ranking[1]
    local jc, jr
    for j, c in ipairs(dm.candidates) do
      if c.name == chosen then jc = j elseif not jr or dm.overall[j] > dm.overall[jr] then jr = j end
    end
    local next_model = revise.apply(D, base, chosen)
    if drop then
      local names = {}
      for name in pairs(drop) do names[#names + 1] = name end
      table.sort(names, function(a, b) return a > b end) -- each goes first: the list ends in name order, every run
      for _, name in ipairs(names) do table.insert(next_model.dropped, 1, { name = name, why = drop[name] }) end
    end
    local out = { failed_responses = failed, matrix = dm, chosen = chosen, model = next_model, rank = 1,
                  why = text.why_chosen(dm, jc, jr), undetermined_only = undetermined_only }
    view("refinement")(run, ctx.report, out, k)
    return out
  end)
end

M.run = refinement_step

return M
