-- SPDX-License-Identifier: MIT
-- smi.refine.criteria: the paper's four criteria as Lua builders, used on a model that is not
-- the steering column (a 2-DOF spring-mass system with three candidate revisions).
local T = require "smi.testing"
local C = require "smi.refine.criteria"

-- Measured natural frequencies (Hz) of the rig, and three candidate revisions of the model.
local observed = {f1 = 10.0, f2 = 25.0}
local candidates = {
  {name = "add damping", predict = function() return {f1 = 9.7, f2 = 24.0} end, new_inputs = 2, run_minutes = 1, implement_minutes = 30},
  {name = "flexible base", predict = function() return {f1 = 9.9, f2 = 25.5} end, new_inputs = 3, run_minutes = 2, implement_minutes = 90},
  {name = "mass correction", predict = function() return {f1 = 10.4, f2 = 24.5} end, new_inputs = 0, run_minutes = 1, implement_minutes = 10},
}

T.case("paper criteria with equal weights, mean relative error over both responses", function()
  local r = smi.refine.decision_matrix{candidates = candidates, criteria = C.paper{observed = observed}}
  -- Correctness magnitudes: mean(|10 - f1|/10, |25 - f2|/25).
  local e = {(0.03 + 0.04) / 2, (0.01 + 0.02) / 2, (0.04 + 0.02) / 2}
  T.near(r.M:get(1, 1), e[1], 1e-12, "M[1,1]")
  T.near(r.M:get(2, 1), e[2], 1e-12, "M[2,1]")
  -- By hand: S columns: correctness 1 - e/0.035; robustness 1 - n/3; run 1 - t/2; implementation 1 - m/90.
  local function O(j, n, t, m) return 0.25 * ((1 - e[j] / 0.035) + (1 - n / 3) + (1 - t / 2) + (1 - m / 90)) end
  T.near(r.overall[1], O(1, 2, 1, 30), 1e-12, "O1")
  T.near(r.overall[2], O(2, 3, 2, 90), 1e-12, "O2")
  T.near(r.overall[3], O(3, 0, 1, 10), 1e-12, "O3")
  T.eq(r.best_name, "mass correction")
end)

T.case("correctness-heavy weights and max combination change the pick", function()
  local r = smi.refine.decision_matrix{
    candidates = candidates,
    criteria = C.paper{observed = observed, combine = "max", weights = {0.85, 0.05, 0.05, 0.05}},
  }
  T.near(r.M:get(2, 1), 0.02, 1e-12, "max relative error of candidate 2")
  T.eq(r.best_name, "flexible base")
end)

T.case("measured run time and clear errors", function()
  local crit = C.computational_cost{measure = C.timed(function(c) local s = 0 for i = 1, c.loops do s = s + i end return s end)}
  local r = smi.refine.decision_matrix{candidates = {{name = "a", loops = 10}, {name = "b", loops = 2000000}}, criteria = {crit}}
  T.truthy(r.M:get(2, 1) > r.M:get(1, 1), "longer loop costs more")
  T.raises(function()
    smi.refine.decision_matrix{candidates = {{name = "x"}}, criteria = {C.robustness()}}
  end, "needs a number field 'new_inputs'")
  T.raises(function()
    smi.refine.decision_matrix{candidates = {{name = "x", predict = function() return 1 end}},
                               criteria = {C.correctness{observed = 0}}}
  end, "undefined")
end)

T.finish()
