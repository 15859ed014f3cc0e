-- SPDX-License-Identifier: MIT
--- The sequential Kriging design of a trial (--design sequential; the default is the
-- fixed maximin hypercube of n_design points). Sequential: a maximin hypercube of 4 points per unknown, then
-- batches of 8 (a multiple of the solver concurrency) chosen by smi.kriging.sequential where the
-- Kriging variance weighted by the calibration's reach is largest, until every response's
-- leave-one-out Q2 reaches Q2_TARGET or the design holds the model's n_design points (the size
-- of the fixed design it replaces, so it never costs more). Measured on the committed data
-- (--quick): trial 1 ends at 80 points with Q2 0.9993/0.99999/0.9985, trial 2 at 120 with
-- 0.998/0.9999/0.992, no fewer runs, and trial 1's calibration lands at another optimum (its mode1
-- and mode2 verdicts change): smi-column-fe's modes vary over the whole box, so the variance-weighted
-- points buy no accuracy a space-filling design lacks. Hence not the default.
local stream = require "smi.improve.stream"

local M = {}

M.Q2_TARGET = 0.999  -- the fixed 80-point design of trial 1 reaches 0.9987-0.99998 over the responses
M.BATCH = 8
M.CANDIDATES = 2000


--- Weight of each candidate row: where the calibration can put the unknowns' mass, the product
-- over the unknowns of P(value | mean uniform in its bounds, std at its upper bound) — flat over
-- the mean bounds, falling off over the design box's margins — plus a floor of a fifth of the
-- largest weight so that no part of the box is left without points.
function M.weights(C, unknowns, specs)
  local n = C:rows()
  local w = smi.vec.ones(n)
  for j, name in ipairs(unknowns) do
    local u = specs[name]
    local lo, hi, s = u.mean[1], u.mean[2], u.std[2]
    local z = smi.dist.normal{ mean = 0, std = 1 }
    local x = C:col(j)
    local a = z:cdf((x - lo) / s)
    local b = z:cdf((x - hi) / s)
    w = w * (a - b)
  end
  local floor = 0.2 * w:max()
  return w + floor
end

--- t: {box = {{lo, hi}, ...}, unknowns, specs, model (the solver model), max, seed, trend}
-- -> X (mat), Y ({response = vec}), info {rounds, reached, stop, history}
function M.sequential(t)
  local d = #t.unknowns
  local n0 = math.min(t.max, 4 * d)
  local X0 = smi.doe.lhs(n0, t.box, { seed = t.seed, criterion = "maximin" })
  local C = smi.doe.lhs(M.CANDIDATES, t.box, { seed = stream(t.seed, "sequential candidates"), criterion = "none" })
  local r = smi.kriging.sequential{ model = t.model, design = X0, candidates = C,
                                    weights = M.weights(C, t.unknowns, t.specs),
                                    batch = M.BATCH, max = t.max, q2 = M.Q2_TARGET, trend = t.trend, corr = "gauss",
                                    seed = t.seed, inputs = t.unknowns }
  local history = {}
  for i, h in ipairs(r.history) do history[i] = { points = h.points, q2 = h.q2, rmse = h.rmse } end
  return r.X, r.Y, { initial = n0, batch = M.BATCH, q2_target = M.Q2_TARGET, max = t.max, reached = r.reached,
                     stop = r.stop, history = history }
end

return M
