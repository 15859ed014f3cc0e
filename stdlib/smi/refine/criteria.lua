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
local M = {}

local function weight_of(opts)
  return opts and opts.weight
end

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

--- Robustness: number of new input variables the revision introduces (field new_inputs).
function M.robustness(opts) return field_criterion("robustness", "new_inputs", opts) end

--- Computational cost: run time of the revised model (field run_minutes), or measured by
-- opts.measure(candidate); M.timed(f) builds such a measure from a function that runs the model.
function M.computational_cost(opts) return field_criterion("computational cost", "run_minutes", opts) end

--- Implementation cost: time to implement the revision (field implement_minutes).
function M.implementation_cost(opts) return field_criterion("implementation cost", "implement_minutes", opts) end

--- A measure(candidate) returning the CPU minutes taken by run(candidate).
function M.timed(run)
  return function(c)
    local t0 = os.clock()
    run(c)
    return (os.clock() - t0) / 60
  end
end

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
