-- SPDX-License-Identifier: MIT
-- smi.calibrate on Kriging surrogates, one per response (model = {y1 = k1, y2 = k2}), as a
-- study would use it: the inputs' true means and stds are recovered through the surrogates, the
-- surrogates' input order is honoured, and leaving the design box is reported.
local T = require "smi.testing"

-- Truth: a ~ N(5, 0.3), b ~ N(2, 0.2); y1 = a + b^2, y2 = 3a - b (smooth: Kriging is accurate).
local g = smi.rng(99)
local a, b = g:normal(300, 5, 0.3), g:normal(300, 2, 0.2)
local data = {y1 = a + b * b, y2 = a * 3 - b}

-- The surrogates take (b, a) in that order, to check that calibrate follows their order.
local box = {{1.0, 3.0}, {3.5, 6.5}}
local D = smi.doe.lhs(40, box, {seed = 3})
local B, A = D:col(1), D:col(2)
local k1 = smi.kriging.fit(D, A + B * B, {inputs = {"b", "a"}, output = "f"})
local k2 = smi.kriging.fit(D, A * 3 - B, {inputs = {"b", "a"}, output = "g"})

local inputs = {a = {mean = {4, 6, 4.5}, std = {0.05, 1, 0.5}}, b = {mean = {1.5, 2.5, 1.8}, std = {0.05, 1, 0.5}}}

T.case("means and stds recovered through two Kriging surrogates", function()
  local r = smi.calibrate{model = {y1 = k1, y2 = k2}, inputs = inputs, data = data, n = 1000, grid_nodes = 2001, seed = 5,
                          design_bounds = {b = box[1], a = box[2]}, identifiability = false}
  T.near(r.params["a.mean"], 5.0, 0.04, "a.mean")
  T.near(r.params["b.mean"], 2.0, 0.04, "b.mean")
  T.near(r.params["a.std"], 0.3, 0.06, "a.std")
  T.near(r.params["b.std"], 0.2, 0.06, "b.std")
  for _, w in ipairs(r.warnings) do T.truthy(not w:find("design range", 1, true), "no design warning: " .. w) end
end)

T.case("an optimum reaching outside the design box is reported", function()
  local r = smi.calibrate{model = {y1 = k1, y2 = k2}, inputs = inputs, data = data, n = 1000, grid_nodes = 2001, seed = 5,
                          design_bounds = {b = {1.0, 3.0}, a = {3.5, 4.9}}, identifiability = false, maxeval = 60}
  local found = false
  for _, w in ipairs(r.warnings) do found = found or (w:find("input 'a'", 1, true) and w:find("design range", 1, true)) ~= nil end
  T.truthy(found, "design-range warning for a")
end)

T.case("an input order that contradicts the surrogates' is refused", function()
  T.raises(function()
    smi.calibrate{model = {y1 = k1, y2 = k2}, inputs = inputs, data = data, order = {"a", "b"}}
  end, "follow the model's order")
end)

T.finish()
