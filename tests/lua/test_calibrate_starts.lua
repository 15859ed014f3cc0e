-- SPDX-License-Identifier: MIT
-- smi.calibrate: a start where PR saturates at 2 (no overlap, no gradient) is moved to a
-- moment-matching start inside the kernel.
local T = require "smi.testing"

T.case("no overlap at the start: moved by moment matching, then calibrated", function()
  local g = smi.rng(3)
  local x1, x2 = g:normal(200, 1, 0.1), g:normal(200, 2, 0.05)
  local spec = {
    model = function(M) return {y = M:col(1) + M:col(2) * 2} end,
    inputs = {x1 = {mean = {0, 4, 0.2}, std = {0.01, 1, 0.05}}, x2 = {mean = {0, 4, 0.2}, std = 0.05}},
    data = {y = x1 + x2 * 2}, n = 500, grid_nodes = 2001, seed = 4, identifiability = false, maxeval = 150,
  }
  local r = smi.calibrate(spec)
  local moved = false
  for _, w in ipairs(r.warnings) do moved = moved or w:find("did not overlap", 1, true) ~= nil end
  T.truthy(moved, "the start was moved (and said so)")
  T.truthy(r.starts[1].start["x1.mean"] > 1, "the optimiser began at the moment-matching point")
  T.truthy(r.objective < 0.2, "calibrated: PR " .. r.objective)
  T.near(r.params["x1.mean"] + 2 * r.params["x2.mean"], 5, 0.05, "the mean of y matched")
  -- The old behaviour, kept behind overlap_start = false, is stuck at PR = 2.
  spec.overlap_start = false
  local stuck = smi.calibrate(spec)
  T.truthy(stuck.objective > 1.99, "without it the optimiser cannot leave PR = 2")
end)

T.case("moment_start: every start matched to the data's mean and sd first, then the same optimum in fewer evaluations", function()
  local g = smi.rng(8)
  local a, b = g:normal(80, 5, 0.3), g:normal(80, 2, 0.2)
  local y1, y2 = {}, {}
  for i = 1, #a do y1[i] = a[i] + b[i] ^ 2; y2[i] = 3 * a[i] - b[i] end
  local spec = {
    model = function(M) return {y1 = M:col(1) + M:col(2):map(function(v) return v * v end), y2 = M:col(1) * 3 - M:col(2)} end,
    inputs = {{name = "a", mean = {3, 7, 4.2}, std = {0.05, 1, 0.6}}, {name = "b", mean = {1, 3, 2.4}, std = {0.05, 1, 0.5}}},
    data = {y1 = smi.vec(y1), y2 = smi.vec(y2)}, n = 400, grid_nodes = 1001, seed = 2, identifiability = false,
  }
  local plain = smi.calibrate(spec)
  spec.moment_start = true
  local moved = smi.calibrate(spec)
  local said = false
  for _, w in ipairs(moved.warnings) do said = said or w:find("moment-matching start", 1, true) ~= nil end
  T.truthy(said, "the start was moved (and said so)")
  -- The moved start reproduces the data's mean of y2 = 3a - b: 3 mean(a) - mean(b).
  local m2 = 0
  for i = 1, #y2 do m2 = m2 + y2[i] / #y2 end
  T.near(3 * moved.starts[1].start["a.mean"] - moved.starts[1].start["b.mean"], m2, 0.02 * math.abs(m2), "the start matches the mean of y2")
  -- 4 moments, 4 parameters inside their bounds: LM ends on a tolerance (the mismatch's, or a
  -- step changing it by less than 1e-4: 1 % of an sd), and says so
  local prep = moved.starts[1].prepared
  T.truthy(prep.status == "tolerance_reached" or prep.status == "ftol_reached", "how the moment start ended: " .. prep.status)
  T.truthy(prep.after <= 1e-4 and prep.before > 1, ("mismatch %g -> %g"):format(prep.before, prep.after))
  T.near(moved.objective, plain.objective, 1e-3, "the same optimum")
  for _, p in ipairs{"a.mean", "a.std", "b.mean", "b.std"} do T.near(moved.params[p], plain.params[p], 0.02, p) end
  print(("evaluations: plain %d, moment start %d (+%d model runs choosing the start)"):format(plain.evaluations, moved.evaluations, moved.start_evaluations or -1))
  T.truthy(moved.evaluations < plain.evaluations, ("fewer optimiser evaluations: %d < %d"):format(moved.evaluations, plain.evaluations))
end)

T.finish()
