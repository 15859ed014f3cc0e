-- SPDX-License-Identifier: MIT
-- All nine smi.dist families as smi.calibrate inputs: each of the six new
-- families is calibrated (mean and std, or the parent's for truncnormal) on an identity model
-- against the family's own pdf, and must recover the true values; bad families name the choices.
local T = require "smi.testing"

local cases = {
  {dist = "gamma", truth = smi.dist.gamma{shape = 4, scale = 0.5}, mean = 2.0, std = 1.0},
  {dist = "weibull", truth = smi.dist.weibull{shape = 2.5, scale = 3}, extra = {}},
  {dist = "gumbel", truth = smi.dist.gumbel{loc = 1, scale = 0.4}},
  {dist = "beta", truth = smi.dist.beta{alpha = 2, beta = 5, lower = 1, upper = 3}, extra = {lower = 1, upper = 3}},
  {dist = "triangular", truth = smi.dist.triangular{lower = 0, mode = 1, upper = 3}, extra = {mode_at = 1 / 3}},
  {dist = "truncnormal", truth = smi.dist.truncnormal{mean = 1, std = 0.8, lower = 0, upper = 4},
   extra = {lower = 0, upper = 4}, parent = {1, 0.8}},
}

T.case("each new family's mean and std are recovered against its own pdf (PR)", function()
  for _, c in ipairs(cases) do
    local m, s = c.truth:mean(), c.truth:std()
    if c.parent then m, s = c.parent[1], c.parent[2] end
    local input = {dist = c.dist, mean = {m * 0.8, m * 1.2, m * 0.9}, std = {s * 0.5, s * 1.5, s * 1.2}}
    for k, v in pairs(c.extra or {}) do input[k] = v end
    local r = smi.calibrate{
      model = function(M) return {y = M:col(1)} end,
      inputs = {x = input}, data = {y = c.truth}, n = 1000, seed = 3, identifiability = false,
    }
    -- 1,000 CRN samples and their KDE: a few percent of the std.
    T.near(r.params["x.mean"], m, 0.05 * s, c.dist .. " mean")
    T.near(r.params["x.std"], s, 0.08 * s, c.dist .. " std")
    T.eq(r.distributions.x.family, c.dist, c.dist .. " calibrated distribution")
    if not c.parent then
      T.near(r.distributions.x:mean(), r.params["x.mean"], 1e-9 * m, c.dist .. " distribution mean")
      T.near(r.distributions.x:std(), r.params["x.std"], 1e-9 * s, c.dist .. " distribution std")
    end
  end
end)

T.case("an unknown family lists what each family calibrates", function()
  T.raises(function()
    smi.calibrate{model = function(M) return {y = M:col(1)} end, inputs = {x = {dist = "weibul", mean = {1, 2}, std = 0.1}},
                  data = {y = {1, 2, 3}}}
  end, "unknown distribution \"weibul\"")
  T.raises(function()
    smi.calibrate{model = function(M) return {y = M:col(1)} end, inputs = {x = {dist = "weibul", mean = {1, 2}, std = 0.1}},
                  data = {y = {1, 2, 3}}}
  end, "parent normal for \"truncnormal\" (fixed lower, upper)")
  T.raises(function()
    smi.calibrate{model = function(M) return {y = M:col(1)} end, inputs = {x = {dist = "gamma", mean = {1, 2}, std = 0.1, loc = "0"}},
                  data = {y = {1, 2, 3}}}
  end, "inputs.x.loc must be a number")
end)
