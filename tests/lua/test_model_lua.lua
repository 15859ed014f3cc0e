-- SPDX-License-Identifier: MIT
-- smi.model.lua: the model interface on a Lua function (no solver, no store).
local T = require "smi.testing"

local m = smi.model.lua{
  name = "quad", inputs = {"a", "b"}, outputs = {"s", "p"},
  fn = function(X)
    local s, p = {}, {}
    for i = 1, X:rows() do
      s[i] = X[i][1] + X[i][2]
      p[i] = X[i][1] * X[i][2]
    end
    return {s = s, p = smi.vec(p)}
  end,
}

T.case("interface fields", function()
  T.eq(m.kind, "lua"); T.eq(m.name, "quad")
  T.eq(#m.inputs, 2); T.eq(m.inputs[2], "b"); T.eq(m.outputs[1], "s")
  T.truthy(tostring(m):find("lua 'quad': 2 inputs %-> 2 outputs"), "tostring")
end)

T.case("fn gets the whole matrix once; Y in row order; info all ok", function()
  local calls = 0
  local counted = smi.model.lua{inputs = {"a"}, outputs = {"y"}, fn = function(X)
    calls = calls + 1
    return {y = X:col(1) * 2}
  end}
  local Y, info = counted:evaluate(smi.mat{{1}, {2}, {3}})
  T.eq(calls, 1); T.eq(#Y.y, 3); T.eq(Y.y[3], 6)
  T.eq(info.status[2], "ok"); T.eq(info.ok[1], 1); T.eq(info.failed, 0); T.eq(#info.failures, 0)
end)

T.case("X as rows, named columns, or one named point", function()
  local Y = m:evaluate{{1, 2}, {3, 4}}
  T.eq(Y.s[2], 7); T.eq(Y.p[2], 12)
  Y = m:evaluate{a = smi.vec{1, 3}, b = {2, 4}}
  T.eq(Y.p[1], 2); T.eq(Y.s[2], 7)
  Y = m:evaluate{a = 5, b = 6}
  T.eq(#Y.s, 1); T.eq(Y.p[1], 30)
end)

T.case("bad designs are named", function()
  T.raises(function() m:evaluate{{1, 2, 3}} end, "X has 3 columns but model 'quad' has 2 inputs (a, b)")
  T.raises(function() m:evaluate{a = {1}, bb = {2}} end, "X has a column 'bb' that is not an input")
  T.raises(function() m:evaluate{a = {1, 2}, b = {2}} end, "X.b has 1 values but X.a has 2")
end)

T.case("non-finite outputs are failed rows; missing outputs raise", function()
  local inv = smi.model.lua{inputs = {"x"}, outputs = {"y"}, fn = function(X) return {y = 1 / X:col(1)} end}
  local Y, info = inv:evaluate{{2}, {0}}
  T.eq(Y.y[1], 0.5); T.truthy(Y.y[2] ~= Y.y[2], "NaN row")
  T.eq(info.status[2], "failed"); T.eq(info.failures[1].row, 2); T.eq(info.reason[2], "output 'y' is inf")
  local bad = smi.model.lua{inputs = {"x"}, outputs = {"y", "z"}, fn = function(X) return {y = X:col(1)} end}
  T.raises(function() bad:evaluate{{1}} end, "fn returned no output 'z'")
  T.raises(function() smi.model.lua{inputs = {"x"}, outputs = {"y"}, fm = print} end, "fm")
end)

T.finish()
