--- The weighted decision matrix of the steering-column study (Son et al. 2020, §4.1.5, Table 6;
-- Oh et al. 2016): criteria, weights and magnitude functions, smaller magnitude = better.
--   correctness      eq. (13): |E[y_exp] − y_pre(x̄)| / E[y_exp] of the revised model run at the
--                    mean x̄ of the initial unknowns, averaged over every response used in
--                    calibration (modes 1 and 4), so the score does not depend on which of
--                    them the calibration happened to give up
--   robustness       number of new input variables of the revision
--   computational    measured wall time of one run of the revised model (minutes), counted in
--                    whole seconds (M.cost_resolution_s): below that a single timing is
--                    noise (process start, machine load), and eq. (14) normalises by the
--                    largest magnitude, so 0.012 s against 0.029 s would otherwise weigh like
--                    a model twice as expensive and flip the choice from run to run
--   implementation   the analyst's estimate of the time to implement the revision (minutes)
-- Weights: correctness 0.4, the three others 0.2 each. The weights of Oh et al. (2016) could not
-- be recovered (docs/spec/algorithms.md §6); correctness counts double because a revision that
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
-- opts.responses = the responses used in calibration; opts.run(candidate) -> {response = value}, seconds.
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
  return {
    { name = "correctness", weight = M.weights.correctness, magnitude = function(c)
        local r, s = run(c), 0
        for _, resp in ipairs(opts.responses) do
          local obs = opts.observed[resp]
          s = s + math.abs(obs - r.y[resp]) / math.abs(obs)
        end
        return s / #opts.responses
      end },
    { name = "robustness", weight = M.weights.robustness, magnitude = function(c) return c.new_inputs end },
    { name = "computational cost", weight = M.weights.computational,
      magnitude = function(c) return M.cost_minutes(run(c).seconds) end },
    { name = "implementation cost", weight = M.weights.implementation,
      magnitude = function(c) return c.implement_minutes end },
  }, function(c) return run(c) end
end

return M
