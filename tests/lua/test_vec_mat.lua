-- SPDX-License-Identifier: MIT
-- smi.vec, smi.mat and smi.rng from Lua: construction, indexing, arithmetic, reductions.
local T = require "smi.testing"

T.case("vec from a table, 1-based indexing and length", function()
  local v = smi.vec{3, 1, 2}
  T.eq(#v, 3); T.eq(v[1], 3); T.eq(v[3], 2)
  v[2] = 5; T.eq(v[2], 5)
  T.raises(function() return v[4] end, "out of range 1..3")
  T.raises(function() v[0] = 1 end, "out of range")
end)

T.case("reductions match closed forms", function()
  local x = smi.vec{30.12, 30.45, 29.88, 30.61, 30.02, 29.75, 30.33, 30.90, 30.20}
  T.near(x:mean(), 30.251111111, 1e-8)
  T.near(x:std(), 0.3636084585, 1e-9)
  T.near(x:quantile(0.75) - x:quantile(0.25), 0.43, 1e-12)
  T.near(x:sum(), 272.26, 1e-9)
  T.eq(x:min(), 29.75); T.eq(x:max(), 30.90)
  local q = x:quantile{0.25, 0.75}
  T.near(q[2] - q[1], 0.43, 1e-12)
end)

T.case("arithmetic with scalars and vectors", function()
  local a, b = smi.vec{1, 2, 3}, smi.vec{4, 5, 6}
  local c = a + b * 2 - 1
  T.eq(c[1], 8); T.eq(c[3], 14)
  T.eq((2 / a)[2], 1); T.eq((-a)[1], -1); T.eq((a ^ 2)[3], 9)
  T.raises(function() return a + smi.vec{1, 2} end, "lengths differ (3 and 2)")
end)

T.case("sort, slices, totable and tostring", function()
  local v = smi.vec{5, 1, 4, 2, 3}
  local s = v:sort()
  T.eq(s[1], 1); T.eq(s[5], 5); T.eq(v[1], 5)
  local sub = v:sub(2, 4); T.eq(#sub, 3); T.eq(sub[1], 1)
  T.eq(v:sub(-2)[1], 2)
  T.eq(#v:totable(), 5)
  local big = smi.vec.linspace(0, 1, 1000000)
  local str = tostring(big)
  T.truthy(#str < 200, "a million-element vec prints a summary")
  T.truthy(str:find("vec(1000000)", 1, true), "summary names the length")
end)

T.case("bad input names the element", function()
  T.raises(function() smi.vec{1, "x", 3} end, "smi.vec[2] must be a number, got string")
end)

T.case("mat from rows, indexing, products", function()
  local m = smi.mat{{1, 2}, {3, 4}, {5, 6}}
  T.eq(m:rows(), 3); T.eq(m:cols(), 2); T.eq(#m, 3)
  T.eq(m:get(2, 1), 3); T.eq(m[3][2], 6)
  local y = m:dot(smi.vec{1, 1})
  T.eq(y[1], 3); T.eq(y[3], 11)
  T.eq(m:t():rows(), 2)
  T.eq(m:colmeans()[2], 4)
  T.raises(function() smi.mat{{1, 2}, {3}} end, "every row needs the same length")
  local h = smi.mat.hcat{smi.vec{1, 2}, smi.vec{3, 4}}
  T.eq(h:get(2, 2), 4)
end)

T.case("rng: same seed, same numbers; moments", function()
  local a = smi.rng(123):normal(5)
  local b = smi.rng(123):normal(5)
  for i = 1, 5 do T.eq(a[i], b[i]) end
  local z = smi.rng(1):normal(100000, 10, 2)
  T.near(z:mean(), 10, 0.03); T.near(z:std(), 2, 0.03)
  local u = smi.rng(2):uniform(100000, -1, 1)
  T.truthy(u:min() > -1 and u:max() < 1, "uniform stays inside (lo, hi)")
  local k = smi.rng(3):integers(1000, 1, 6)
  T.truthy(k:min() == 1 and k:max() == 6, "integers cover [1, 6]")
  T.raises(function() smi.rng(1.5) end, "seed must be an integer")
end)

T.finish()
