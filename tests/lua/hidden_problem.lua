-- SPDX-License-Identifier: MIT
-- The hidden-style calibration (shared by tests/lua/test_calibrate_model_differences.lua
-- and bench/calibrate_hidden.lua): ten parameters (the means and standard deviations of five
-- inputs: normal, lognormal, uniform, normal, lognormal), three responses of a smooth nonlinear
-- Lua function model with no gradient, nine measurements each, PR, n = 2000.
-- Returns spec(options) -> the table for smi.calibrate (options are copied over it), and the truth.
local M = {}

M.truth = { x1 = { 10, 0.8 }, x2 = { 2, 0.3 }, x3 = { 5, 0.5 }, x4 = { 0, 0.5 }, x5 = { 1, 0.15 } }

--- y1 = x1·x2 + x3, y2 = x3·exp(0.2·x4) + 2·x5², y3 = x1/x5 + x2·x4 + 0.2·x3²
function M.model(X)
  local x1, x2, x3, x4, x5 = X:col(1), X:col(2), X:col(3), X:col(4), X:col(5)
  return { y1 = x1 * x2 + x3, y2 = x3 * (x4 * 0.2):exp() + x5 * x5 * 2, y3 = x1 / x5 + x2 * x4 + x3 * x3 * 0.2 }
end

--- Nine experiments drawn from the truth (seeded; lognormal from its mean and sd, uniform from its
-- mean and sd), as one data table {y1 =, y2 =, y3 =}.
function M.data()
  local g = smi.rng(29)
  local t = M.truth
  local function lognormal(m, s)
    local v = math.log(1 + (s / m) ^ 2)
    local z = g:normal(9)
    local out = {}
    for i = 1, 9 do out[i] = math.exp(math.log(m) - v / 2 + math.sqrt(v) * z[i]) end
    return smi.vec(out)
  end
  local half = math.sqrt(3) * t.x3[2]
  local X = smi.mat(9, 5)
  local cols = { g:normal(9, t.x1[1], t.x1[2]), lognormal(t.x2[1], t.x2[2]), g:uniform(9, t.x3[1] - half, t.x3[1] + half),
                 g:normal(9, t.x4[1], t.x4[2]), lognormal(t.x5[1], t.x5[2]) }
  for j = 1, 5 do X:set_col(j, cols[j]) end
  return M.model(X)
end

function M.spec(options)
  local s = {
    model = M.model,
    inputs = {
      { name = "x1", dist = "normal", mean = { 8, 12, 9 }, std = { 0.2, 2, 1.2 } },
      { name = "x2", dist = "lognormal", mean = { 1.5, 3, 2.6 }, std = { 0.05, 0.6, 0.2 } },
      { name = "x3", dist = "uniform", mean = { 3, 7, 4 }, std = { 0.1, 1.5, 0.8 } },
      { name = "x4", dist = "normal", mean = { -1, 1, 0.4 }, std = { 0.1, 1, 0.3 } },
      { name = "x5", dist = "lognormal", mean = { 0.6, 1.6, 1.3 }, std = { 0.05, 0.5, 0.3 } },
    },
    data = M.data(), metric = "pr", n = 2000, seed = 7, identifiability = false,
  }
  for k, v in pairs(options or {}) do s[k] = v end
  return s
end

return M
