--- smi.improve.criteria: the paper's four criteria of the weighted decision matrix (Son et al.
-- 2020, §4.1.5, Table 6; Oh et al. 2016), the default of a declaration without `criteria`:
-- magnitude functions, smaller = better.
--   correctness      eq. (13): |E[y_exp] − y_pre(x̄)| / E[y_exp] of the revised model run at the
--                    start means x̄ of the unknowns, averaged over every response used in
--                    calibration, so the score does not depend on which of them the
--                    calibration happened to give up
--   robustness       number of new input variables of the revision
--   computational    measured wall time of one run of the revised model (minutes), counted in
--                    whole seconds (M.cost_resolution_s): below that a single timing is
--                    noise (process start, machine load), and eq. (14) normalises by the
--                    largest magnitude, so 0.012 s against 0.029 s would otherwise weigh like
--                    a model twice as expensive and flip the choice from run to run
--   implementation   the analyst's estimate of the time to implement the revision (minutes)
-- Default weights (declaration `weights`): correctness 0.4, the three others 0.2 each. The weights of Oh et al. (2016) could not
-- be recovered (shared/spec/algorithms.md §6); correctness counts double because a revision that
-- does not move the failed response cannot make the model valid.
local M = {}

M.weights = { correctness = 0.4, robustness = 0.2, computational = 0.2, implementation = 0.2 }
M.cost_resolution_s = 1

--- A run time as the criterion counts it: whole resolution steps, at least one (minutes).
function M.cost_minutes(seconds)
  local r = M.cost_resolution_s
  return math.max(1, math.ceil(seconds / r - 1e-9)) * r / 60
end

--- Criteria for smi.refine.decision_matrix. opts.observed = {response = E[y_exp]};
-- opts.responses = the responses used in calibration; opts.run(candidate) -> {response = value}, seconds;
-- opts.weights (default M.weights).
-- Runs are cached per candidate so each is run once.
function M.build(opts)
  local cache = {}
  local function run(c)
    if not cache[c] then
      local y, seconds = opts.run(c)
      cache[c] = { y = y, seconds = seconds }
    end
    return cache[c]
  end
  local W = opts.weights or M.weights
  return {
    { name = "correctness", weight = W.correctness, magnitude = function(c)
        local r, s = run(c), 0
        for _, resp in ipairs(opts.responses) do
          local obs = opts.observed[resp]
          s = s + math.abs(obs - r.y[resp]) / math.abs(obs)
        end
        return s / #opts.responses
      end },
    { name = "robustness", weight = W.robustness, magnitude = function(c) return c.new_inputs end },
    { name = "computational cost", weight = W.computational,
      magnitude = function(c) return M.cost_minutes(run(c).seconds) end },
    { name = "implementation cost", weight = W.implementation,
      magnitude = function(c) return c.implement_minutes end },
  }, function(c) return run(c) end
end

return M
