-- SPDX-License-Identifier: MIT
--- smi.refine.criteria: the four refinement criteria of Oh et al. (2016) as used by Son et al.
-- (2020, eq. 13), written as builders of criterion tables for smi.refine.decision_matrix.
-- A candidate is a table describing one model revision; each builder reads what it needs from
-- it, so an analyst can mix these with criteria of their own.
--
--   local C = require "smi.refine.criteria"
--   local r = smi.refine.decision_matrix{
--     candidates = {{name = "airbag", predict = f, new_inputs = 1, run_minutes = 11, implement_minutes = 60}, ...},
--     criteria = C.paper{observed = {mode1 = 45.9, mode4 = 61.2}, weights = {0.4, 0.2, 0.2, 0.2}},
--   }
local doc = require "smi.doc"
doc.add[==[
@ module smi.refine.criteria
The four refinement criteria of Oh et al. (2016) as used by Son et al. (2020, eq. 13), as
builders of criterion tables for smi.refine.decision_matrix.
]==]
local M = {}

local function weight_of(opts)
  return opts and opts.weight
end

doc.add[==[
@ smi.refine.criteria.correctness(opts) -> criterion
Relative error of the revised model at the mean inputs, |E[y_exp] - y_pre| / |E[y_exp]| (smaller
is better); several responses are combined.
options:
  observed = (required)  -- a number, or {response = mean of the experimental data}
  predict = nil          -- function(candidate) returning a number or {response = value}
                         -- (default: candidate.predict(candidate))
  combine = "mean"       -- "mean", "max" or "sum" over responses
  weight = nil           -- the criterion's weight
  name = "correctness"   -- the criterion's name
returns: a criterion table {name =, weight =, magnitude = function(candidate)}
errors: no observed; combine unknown; at rating time a prediction that is not a number, or an
  observed mean of 0
example:
  local C = require "smi.refine.criteria"
  local c = C.correctness{observed = 50, predict = function(cand) return cand.f end, weight = 1}
  print(c.name, c.magnitude({f = 45}, 1))
]==]
--- Relative error of the revised model at the mean inputs (smaller is better):
--   |E[y_exp] - y_pre(x̄)| / |E[y_exp]| for one response; for several (tables keyed by response)
--   combined by opts.combine = "mean" (default), "max" or "sum".
-- opts.observed: number or {response = mean of the experimental data}.
-- opts.predict(candidate): number or {response = prediction}; default candidate.predict(candidate).
function M.correctness(opts)
  assert(type(opts) == "table" and opts.observed ~= nil, "criteria.correctness: give observed = number or {response = mean}")
  local combine = opts.combine or "mean"
  assert(combine == "mean" or combine == "max" or combine == "sum",
    "criteria.correctness: combine must be \"mean\", \"max\" or \"sum\", got " .. tostring(combine))
  local function rel(obs, pred, what)
    assert(type(pred) == "number", ("criteria.correctness: prediction for %s must be a number, got %s"):format(what, type(pred)))
    assert(obs ~= 0, ("criteria.correctness: observed mean of %s is 0; the relative error is undefined"):format(what))
    return math.abs(obs - pred) / math.abs(obs)
  end
  return {
    name = opts.name or "correctness",
    weight = weight_of(opts),
    magnitude = function(c, j)
      local predict = opts.predict or c.predict
      assert(type(predict) == "function", ("criteria.correctness: candidate %d has no predict function"):format(j))
      local y = predict(c)
      if type(opts.observed) == "number" then return rel(opts.observed, y, "the response") end
      assert(type(y) == "table", "criteria.correctness: observed is a table, so predict must return {response = value}")
      local keys = {}
      for k in pairs(opts.observed) do keys[#keys + 1] = k end
      table.sort(keys)
      local acc = combine == "max" and -math.huge or 0
      for _, k in ipairs(keys) do
        local e = rel(opts.observed[k], y[k], "'" .. k .. "'")
        if combine == "max" then acc = math.max(acc, e) else acc = acc + e end
      end
      return combine == "mean" and acc / #keys or acc
    end,
  }
end

--- Reads a non-negative number field of the candidate, or asks opts.measure(candidate).
local function field_criterion(default_name, default_field, opts)
  opts = opts or {}
  local field = opts.field or default_field
  return {
    name = opts.name or default_name,
    weight = weight_of(opts),
    magnitude = function(c, j)
      local v = c[field]
      if v == nil and opts.measure then v = opts.measure(c) end
      assert(type(v) == "number", ("criteria.%s: candidate %d needs a number field '%s'%s"):format(
        default_name:gsub(" ", "_"), j, field, opts.measure and " or a measure() result" or ""))
      return v
    end,
  }
end

doc.add[==[
@ smi.refine.criteria.robustness([opts]) -> criterion
The number of new input variables a revision introduces (candidate.new_inputs).
options:
  weight = nil      -- the criterion's weight
  measure = nil     -- function(candidate) returning the number when the field is absent
  field = "new_inputs"  -- the candidate's field
  name = "robustness"   -- the criterion's name
returns: a criterion table
errors: at rating time a candidate without the number ("candidate 2 needs a number field 'new_inputs'")
example:
  local C = require "smi.refine.criteria"
  print(C.robustness{weight = 1}.magnitude({name = "airbag", new_inputs = 1}, 1))
]==]
--- Robustness: number of new input variables the revision introduces (field new_inputs).
function M.robustness(opts) return field_criterion("robustness", "new_inputs", opts) end

doc.add[==[
@ smi.refine.criteria.computational_cost([opts]) -> criterion
The run time of the revised model (candidate.run_minutes, or measured by opts.measure).
options:
  weight = nil      -- the criterion's weight
  measure = nil     -- function(candidate) returning minutes (see smi.refine.criteria.timed)
  field = "run_minutes"  -- the candidate's field
  name = "computational cost"  -- the criterion's name
returns: a criterion table
errors: at rating time a candidate with neither the field nor a measure
example:
  local C = require "smi.refine.criteria"
  print(C.computational_cost{}.magnitude({run_minutes = 11}, 1))
]==]
--- Computational cost: run time of the revised model (field run_minutes), or measured by
-- opts.measure(candidate); M.timed(f) builds such a measure from a function that runs the model.
function M.computational_cost(opts) return field_criterion("computational cost", "run_minutes", opts) end

doc.add[==[
@ smi.refine.criteria.implementation_cost([opts]) -> criterion
The time to implement a revision (candidate.implement_minutes).
options:
  weight = nil      -- the criterion's weight
  measure = nil     -- function(candidate) returning minutes
  field = "implement_minutes"  -- the candidate's field
  name = "implementation cost"  -- the criterion's name
returns: a criterion table
errors: at rating time a candidate without the number
example:
  local C = require "smi.refine.criteria"
  print(C.implementation_cost{}.magnitude({implement_minutes = 60}, 1))
]==]
--- Implementation cost: time to implement the revision (field implement_minutes).
function M.implementation_cost(opts) return field_criterion("implementation cost", "implement_minutes", opts) end

doc.add[==[
@ smi.refine.criteria.timed(run) -> measure
A measure(candidate) returning the CPU minutes taken by run(candidate), for computational_cost.
returns: a function(candidate) returning minutes
errors: none (run's own errors propagate when the measure is called)
example:
  local C = require "smi.refine.criteria"
  local m = C.timed(function(cand) local s = 0 for i = 1, 1000 do s = s + i end end)
  print(m({}) >= 0)
]==]
--- A measure(candidate) returning the CPU minutes taken by run(candidate).
function M.timed(run)
  return function(c)
    local t0 = os.clock()
    run(c)
    return (os.clock() - t0) / 60
  end
end

doc.add[==[
@ smi.refine.criteria.paper(opts) -> criteria
The paper's four criteria in order: correctness, robustness, computational cost, implementation cost.
options:
  observed = (required)     -- as smi.refine.criteria.correctness
  weights = nil             -- {w1, w2, w3, w4} (default: equal weights)
  predict = nil             -- as smi.refine.criteria.correctness
  combine = "mean"          -- as smi.refine.criteria.correctness
  measure = nil             -- the computational cost's measure
returns: a list of four criterion tables for smi.refine.decision_matrix
errors: as the four builders
example:
  local C = require "smi.refine.criteria"
  local r = smi.refine.decision_matrix{
    candidates = {{name = "airbag", f = 48, new_inputs = 1, run_minutes = 11, implement_minutes = 60},
                  {name = "material", f = 45, new_inputs = 0, run_minutes = 10, implement_minutes = 20}},
    criteria = C.paper{observed = 50, predict = function(c) return c.f end}}
  print(r.best_name)
]==]
--- The paper's four criteria in order (correctness, robustness, computational and implementation
-- cost). opts.observed as for correctness; opts.weights = {w1, w2, w3, w4} (default equal).
function M.paper(opts)
  assert(type(opts) == "table", "criteria.paper: give {observed = ..., weights = {...}}")
  local w = opts.weights or {}
  return {
    M.correctness{observed = opts.observed, predict = opts.predict, combine = opts.combine, weight = w[1]},
    M.robustness{weight = w[2]},
    M.computational_cost{weight = w[3], measure = opts.measure},
    M.implementation_cost{weight = w[4]},
  }
end

return M
