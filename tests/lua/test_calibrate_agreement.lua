-- SPDX-License-Identifier: MIT
-- smi.calibrate: whether several starts reached the same optimum where the data can tell
-- (r.agreement), and basin hopping (hops, hop_step).
local T = require "smi.testing"

T.case("y = x1 + 2 x2: four starts end at different points of the valley and agree where the data can tell", function()
  local g = smi.rng(3)
  local x1, x2 = g:normal(200, 1, 0.5), g:normal(200, 2, 0.3)
  local r = smi.calibrate{
    model = function(M) return {y = M:col(1) + M:col(2) * 2} end,
    inputs = {x1 = {mean = {0, 4, 1.5}, std = {0.1, 1, 0.4}}, x2 = {mean = {0, 4, 1.5}, std = {0.1, 1, 0.4}}},
    data = {y = x1 + x2 * 2}, n = 1000, grid_nodes = 2001, seed = 4, multistart = 4,
  }
  local a = r.agreement
  T.eq(a.starts, 4)
  -- PR's tolerance measured from the 200 data (the spread of PR over resamples of them)
  T.eq(a.tolerance, r.tolerance)
  T.truthy(r.tolerance_basis:find("1000 bootstrap resamples of the 200 data rows", 1, true), r.tolerance_basis)
  -- the means move along (2, -1): the strict clustering sees several points
  local lo, hi = math.huge, -math.huge
  for _, s in ipairs(r.starts) do lo, hi = math.min(lo, s.params["x1.mean"]), math.max(hi, s.params["x1.mean"]) end
  T.truthy(hi - lo > 0.05, "the starts' x1.mean differ: " .. lo .. " .. " .. hi)
  T.eq(r.starts_agree, false, "strictly, distinct points")
  T.eq(a.agree, true, a.text)
  T.eq(a.same, 4)
  -- the stds move along the curved sigma1^2 + 4 sigma2^2 = const, which a straight path leaves;
  -- the predicted y's summaries tell that the starts predict the same (within one standard error
  -- of 200 data)
  for i, row in ipairs(a.rows) do
    T.truthy(row.gap <= a.tolerance, "start " .. i .. " within")
    T.truthy(row.same_prediction and row.prediction_distance <= 1, "start " .. i .. " predicts the same")
  end
  T.truthy(a.largest_prediction_distance > 0.05, "the starts' predictions do differ a little")
  -- the starts' optima fit as well: they are in the near-optimal set
  local found = 0
  for _, s in ipairs(r.starts) do
    for _, p in ipairs(r.near_optimal.points) do
      if p["x1.mean"] == s.params["x1.mean"] and p["x2.mean"] == s.params["x2.mean"] then found = found + 1; break end
    end
  end
  T.eq(found, 4, "every start's optimum is a near-optimal point")
end)

T.case("two basins: the agreement names the worse start; hops bring every start to the lower basin", function()
  -- (m^2 - 1)^2 + 0.1 (m - 1)^2: the m = -1 basin is about 0.4 higher
  local f = function(t) return (t.m * t.m - 1) ^ 2 + 0.1 * (t.m - 1) ^ 2 end
  local spec = {parameters = {{"m", -2, 2, -1.5}}, objective = f, multistart = 6, seed = 3,
                xtol_rel = 1e-10, ftol_abs = 1e-14, identifiability = {tolerance = 0.05, directions = false}}
  local r = smi.calibrate(spec)
  T.eq(r.agreement.agree, false)
  T.truthy(r.agreement.largest_gap > 0.3, "the upper basin's gap")
  T.truthy(r.agreement.text:find("fit worse than the best"), r.agreement.text)
  local warned = false
  for _, w in ipairs(r.warnings) do warned = warned or w:find("reached the best's optimum") ~= nil end
  T.truthy(warned, "said in the warnings")
  spec.hops, spec.hop_step = 20, 1.0
  local h = smi.calibrate(spec)
  T.eq(h.starts_agree, true)
  T.eq(h.agreement.agree, true)
  for i, s in ipairs(h.starts) do
    T.near(s.params.m, 1, 1e-5, "start " .. i)
    T.eq(s.hops, 20)
    T.truthy(s.objective <= r.starts[i].objective + 1e-12, "never worse than without hops")
  end
end)

T.case("one start: no agreement table; bad hops are named", function()
  local f = function(t) return (t.m - 0.5) ^ 2 end
  local r = smi.calibrate{parameters = {{"m", -2, 2, -1.5}}, objective = f, identifiability = false}
  T.eq(r.agreement, nil)
  T.eq(r.starts[1].hops, nil)
  T.raises(function() smi.calibrate{parameters = {{"m", -2, 2, -1.5}}, objective = f, hops = -1} end, "hops must be >= 0")
  T.raises(function() smi.calibrate{parameters = {{"m", -2, 2, -1.5}}, objective = f, hops = 2, hop_step = 2} end,
           "hop_step must be in (0, 1]")
end)

T.case("an objective that fails after the optimum (a path point, a sweep point): the calibration stands, the warning says why", function()
  -- wells at m = -1 and m = 1 (both 0); the objective refuses |m| < 0.05, which with seed 1 only the
  -- path between the two starts' optima crosses (its midpoint is m = 0)
  local f = function(t)
    if math.abs(t.m) < 0.05 then error("solver diverged at m = " .. t.m) end
    return (math.abs(t.m) - 1) ^ 2
  end
  local r = smi.calibrate{parameters = {{"m", -2, 2, -1.5}}, objective = f, multistart = 2, seed = 1, identifiability = false}
  T.near(r.params.m, -1, 1e-6, "the given start's well")
  T.near(r.starts[2].params.m, 1, 1e-6, "the seeded start's well")
  T.eq(r.agreement, nil, "no agreement table")
  -- the same for the identifiability sweep, which crosses m = 0 as well
  local ri = smi.calibrate{parameters = {{"m", -2, 2, -1.5}}, objective = f, seed = 1}
  T.near(ri.params.m, -1, 1e-6, "the optimum stands")
  T.eq(ri.identifiability, nil)
  local said = false
  for _, w in ipairs(ri.warnings) do said = said or w:find("^identifiability could not be computed") ~= nil end
  T.truthy(said, "the sweep's error is in the warnings")
  local warned = false
  for _, w in ipairs(r.warnings) do warned = warned or w:find("whether the starts agree could not be computed %(the optimum above stands%): .*solver diverged at m = 0") ~= nil end
  T.truthy(warned, "the path's error is in the warnings")
end)

T.finish()
