-- SPDX-License-Identifier: MIT
-- smi.propagate: CRN sample pushed through a Lua model on the whole matrix, a Kriging model
-- and an object with :evaluate; moments against closed forms.
local T = require "smi.testing"

local inputs = {{"a", smi.dist.normal{mean = 1, std = 2}}, {"b", smi.dist.uniform{lower = 0, upper = 1}}, {"c", 3}}

T.case("a Lua function gets the whole matrix once; moments match the closed form", function()
  local calls = 0
  local out, X = smi.propagate{model = function(M) calls = calls + 1; return {y = M:col(1) * 2 + M:col(2) + M:col(3)} end,
                               inputs = inputs, n = 20000, seed = 5}
  T.eq(calls, 1)
  T.eq(#out.y, 20000)
  -- y = 2a + b + 3: mean 2 + 0.5 + 3, var 4*4 + 1/12
  T.near(out.y:mean(), 5.5, 0.06)
  T.near(out.y:std(), math.sqrt(16 + 1 / 12), 0.06)
  T.eq(X[1][3], 3)
end)

T.case("common random numbers: same seed, same sample; a changed input moves only its column", function()
  local f = function(M) return {a = M:col(1), b = M:col(2)} end
  local o1 = smi.propagate{model = f, inputs = inputs, n = 100, seed = 9}
  local o2 = smi.propagate{model = f, inputs = {{"a", smi.dist.normal{mean = 2, std = 2}}, inputs[2], inputs[3]}, n = 100, seed = 9}
  for i = 1, 100 do
    T.near(o2.a[i] - o1.a[i], 1, 1e-12)   -- same standard sample, shifted mean
    T.eq(o2.b[i], o1.b[i])
  end
end)

T.case("a Kriging model and an object with :evaluate", function()
  local X = smi.doe.lhs(30, {{-4, 6}, {0, 1}}, {seed = 2})
  local y = {}
  for i = 1, 30 do y[i] = 2 * X[i][1] + X[i][2] end
  local m = smi.kriging.fit(X, y, {trend = "linear", inputs = {"a", "b"}, output = "y"})
  local out = smi.propagate{model = m, inputs = {a = inputs[1][2], b = inputs[2][2]}, n = 5000, seed = 1}
  T.near(out.y:mean(), 2.5, 0.1)
  local obj = {inputs = {"a", "b"}, outputs = {"s"}}
  function obj:evaluate(M) return {s = M:col(1) + M:col(2)} end
  local o = smi.propagate{model = obj, inputs = {b = 0.5, a = 1}, n = 3}
  T.eq(o.s[1], 1.5)
  T.raises(function() smi.propagate{model = obj, inputs = {a = 1}, n = 3} end, "no entry 'b'")
  -- the sample size's range is the schema's (kMaxSampleSize = 2^28): named before anything runs
  T.raises(function() smi.propagate{model = obj, inputs = {a = 1, b = 1}, n = 0} end,
           "smi.propagate: n must be in 1..268435456, got 0")
  T.raises(function() smi.propagate{model = obj, inputs = {a = 1, b = 1}, n = 2 ^ 40 // 1} end,
           "smi.propagate: n must be in 1..268435456, got 1099511627776")
end)

T.finish()
