-- SPDX-License-Identifier: MIT
-- One naming scheme for the metatables users see: all lowercase, the name of the smi
-- function or module that makes the value. The name shows in type errors ("smi.kriging
-- expected"), in the doc names of methods ("smi.kriging:predict") and in getmetatable(v).__name.
local T = require "smi.testing"

local function name_of(v) return getmetatable(v).__name end

T.case("each type a script can hold is named after what makes it", function()
  local N = smi.dist.normal{mean = 0, std = 1}
  T.eq(name_of(smi.vec{1}), "smi.vec")
  T.eq(name_of(smi.mat{{1}}), "smi.mat")
  T.eq(name_of(smi.rng(1)), "smi.rng")
  T.eq(name_of(N), "smi.dist")
  T.eq(name_of(smi.kriging.fit({{0}, {1}, {2}}, {0, 1, 4}, {theta = {1}})), "smi.kriging")
  T.eq(name_of(smi.model.lua{inputs = {"x"}, outputs = {"y"}, fn = function(X) return {y = X:col(1)} end}),
       "smi.model")
  T.eq(name_of(smi.screen{model = function(M) return M:col(1) + M:col(2) end, inputs = {{"a", N}, {"b", N}},
                          n = 200, seed = 1, bootstrap = 0}), "smi.screen_result")
  T.eq(name_of(smi.refine.decision_matrix{candidates = {"a", "b"}, criteria = {{name = "c", weight = 1, magnitude = {1, 2}}}}),
       "smi.decision")
  T.eq(name_of(smi.json.null), "smi.json.null")
end)

T.case("every registered type with methods follows the scheme", function()
  local n = 0
  for name in pairs(smi._docs().types) do
    T.truthy(name:match("^smi%.[a-z_]+$") or name:match("^smi%.[a-z_]+%.[a-z_]+$"), "lowercase type name: " .. name)
    n = n + 1
  end
  T.truthy(n >= 6, "types found: " .. n)
end)

T.case("a type error names the type the lowercase way", function()
  T.raises(function() return smi.kriging.fit({{0}, {1}, {2}}, {0, 1, 4}, {theta = {1}}).predict({}, {{0}}) end,
           "smi.kriging expected")
end)

T.finish()
