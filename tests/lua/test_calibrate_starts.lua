-- smi.calibrate: a start where PR saturates at 2 (no overlap, no gradient) is moved to a
-- moment-matching start inside the kernel (issue 11 item 2).
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
