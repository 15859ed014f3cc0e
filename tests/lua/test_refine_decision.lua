-- SPDX-License-Identifier: MIT
-- smi.refine.decision_matrix: spec §8.5 values, and a refinement of a different model with its
-- own criteria written in Lua.
local T = require "smi.testing"

local M = {{0.08, 5, 12, 120}, {0.05, 0, 10, 30}, {0.02, 1, 11, 60}}
local function spec_criteria(w)
  local names = {"correctness", "robustness", "computational cost", "implementation cost"}
  local c = {}
  for i = 1, 4 do
    c[i] = {name = names[i], weight = w and w[i], magnitude = {M[1][i], M[2][i], M[3][i]}}
  end
  return c
end

T.case("spec 8.5: w = (0.4, 0.2, 0.2, 0.2) picks candidate 3", function()
  local r = smi.refine.decision_matrix{candidates = {"c1", "c2", "c3"}, criteria = spec_criteria{0.4, 0.2, 0.2, 0.2}}
  T.near(r.S:get(2, 1), 0.375, 1e-12, "S[2,1]")
  T.near(r.S:get(3, 2), 0.8, 1e-12, "S[3,2]")
  T.near(r.S:get(2, 3), 1 / 6, 1e-12, "S[2,3]")
  T.near(r.S:get(1, 4), 0, 0, "worst candidate scores 0")
  T.near(r.overall[1], 0, 1e-15, "O1")
  T.near(r.overall[2], 0.53333333333, 1e-10, "O2")
  T.near(r.overall[3], 0.57666666667, 1e-10, "O3")
  T.eq(r.best, 3)
  T.eq(r.best_name, "c3")
  T.eq(#r.ties, 1)
  T.eq(r.ranking[1], 3)
  T.eq(r.ranking[3], 1)
  T.truthy(tostring(r):find("<- best", 1, true), "printable table")
end)

T.case("spec 8.5: equal weights (the default when none given) pick candidate 2", function()
  local r = smi.refine.decision_matrix{candidates = {"c1", "c2", "c3"}, criteria = spec_criteria()}
  T.near(r.overall[2], 0.572917, 1e-6, "O2")
  T.near(r.overall[3], 0.533333, 1e-6, "O3")
  T.eq(r.best, 2)
  T.near(r.weights[1], 0.25, 0, "equal weights")
end)

T.case("a different model: choosing how to refine a cantilever-beam model", function()
  -- Candidates are revisions of a beam model, described by tables; magnitude functions compute
  -- each criterion from the candidate itself. The measured tip deflection is 12.0 mm.
  local measured = 12.0
  local candidates = {
    {name = "shear deformation", predict = function() return 11.1 end, new_inputs = 1, run_s = 0.2, effort_h = 2},
    {name = "support compliance", predict = function() return 11.8 end, new_inputs = 2, run_s = 0.3, effort_h = 6},
    {name = "3-D solid mesh", predict = function() return 11.95 end, new_inputs = 4, run_s = 90, effort_h = 40},
  }
  local seen = 0
  local r = smi.refine.decision_matrix{
    candidates = candidates,
    criteria = {
      {name = "error", weight = 0.5,
       magnitude = function(c, j) seen = seen + 1; return math.abs(measured - c.predict()) / measured end},
      {name = "new inputs", weight = 0.2, magnitude = function(c) return c.new_inputs end},
      {name = "run time", weight = 0.2, magnitude = function(c) return c.run_s end},
      {name = "effort", weight = 0.1, magnitude = {["shear deformation"] = 2, ["support compliance"] = 6, ["3-D solid mesh"] = 40}},
    },
  }
  T.eq(seen, 3, "one call per candidate")
  -- Hand computation: errors (0.075, 0.016667, 0.0041667) -> S = (0, 0.77778, 0.94444);
  -- inputs (1, 2, 4) -> (0.75, 0.5, 0); run (0.2, 0.3, 90) -> (0.99778, 0.99667, 0); effort -> (0.95, 0.85, 0).
  T.near(r.overall[1], 0.5 * 0 + 0.2 * 0.75 + 0.2 * (1 - 0.2 / 90) + 0.1 * 0.95, 1e-12, "O1")
  T.near(r.overall[2], 0.5 * (1 - (0.2 / 12) / (0.9 / 12)) + 0.2 * 0.5 + 0.2 * (1 - 0.3 / 90) + 0.1 * (1 - 6 / 40), 1e-12, "O2")
  T.near(r.overall[3], 0.5 * (1 - (0.05 / 12) / (0.9 / 12)), 1e-12, "O3")
  T.eq(r.best_name, "support compliance")
  T.eq(r.best_candidate, candidates[2], "the candidate itself comes back")
end)

T.case("ties and non-discriminating criteria are reported", function()
  local r = smi.refine.decision_matrix{
    candidates = {"a", "b"},
    criteria = {{name = "x", weight = 0.5, magnitude = {1, 2}}, {name = "y", weight = 0.5, magnitude = {2, 1}},
                {name = "z", weight = 0, magnitude = {0, 0}}},
  }
  T.eq(#r.ties, 2, "tie")
  T.near(r.S:get(1, 3), 1, 0, "max M = 0 gives S = 1")
  T.truthy(#r.warnings >= 2, "warnings")
end)

T.case("bad input is refused with the culprit named", function()
  T.raises(function()
    smi.refine.decision_matrix{candidates = {"a", "b"}, criteria = {{name = "x", weight = 0.7, magnitude = {1, 2}},
                                                                      {name = "y", weight = 0.7, magnitude = {2, 1}}}}
  end, "sum to 1")
  T.raises(function()
    smi.refine.decision_matrix{candidates = {"a", "b"}, criteria = {{name = "x", weight = 1, magnitude = {1, -2}}}}
  end, "candidate 'b'")
  T.raises(function()
    smi.refine.decision_matrix{candidates = {"a", "b"}, criteria = {{name = "cost", magnitude = function() return "cheap" end}}}
  end, "criterion 'cost', candidate 'a'")
  T.raises(function()
    smi.refine.decision_matrix{candidates = {"a", "b"}, criteria = {{name = "x", weight = 1, magnitude = {1}}}}
  end, "1 magnitudes for 2 candidates")
  T.raises(function()
    smi.refine.decision_matrix{candidates = {"a"}, criteria = {{name = "x", weight = 1, magnitude = {1}}, {name = "y", magnitude = {1}}}}
  end, "give every criterion a weight")
  T.raises(function()
    smi.refine.decision_matrix{candidates = {"a"}, criteria = {{name = "x", magnitude = function() error("no run time known") end}}}
  end, "no run time known")
end)

T.finish()
