-- SPDX-License-Identifier: MIT
-- smi.doe from Lua: Latin property and bounds, distributions through quantiles, Sobol'
-- against SciPy's first points (tests/reference/sobol_points.csv), full factorial.
local T = require "smi.testing"

T.case("lhs(n, {{lo, hi}, ...}, {seed}) is an smi.mat, one point per stratum, same seed same design", function()
  local X = smi.doe.lhs(10, {{0, 1}, {-5, 5}}, {seed = 3})
  T.eq(#X, 10)
  local seen = {}
  for i = 1, 10 do
    local s = math.floor((X[i][2] + 5) / 10 * 10)
    T.truthy(not seen[s], "stratum " .. s .. " used once"); seen[s] = true
  end
  local Y = smi.doe.lhs(10, {{0, 1}, {-5, 5}}, {seed = 3})
  for i = 1, 10 do T.eq(X[i][1], Y[i][1]) end
  T.raises(function() smi.doe.lhs(5, {{1, 0}}) end, "space[1] = {1, 0} needs finite lo < hi")
  T.raises(function() smi.doe.lhs(5, 2, {criterion = "maxmin"}) end, "unknown criterion 'maxmin'")
end)

T.case("space entries may be distributions: columns are their quantiles", function()
  local n = smi.dist.normal{mean = 10, std = 2}
  local X = smi.doe.lhs(200, {n, {0, 1}}, {seed = 1})
  local s, ss = 0, 0
  for i = 1, 200 do s = s + X[i][1] end
  local mean = s / 200
  for i = 1, 200 do ss = ss + (X[i][1] - mean) ^ 2 end
  T.near(mean, 10, 0.05)                 -- stratified: much tighter than 2/sqrt(200)
  T.near(math.sqrt(ss / 199), 2, 0.1)
end)

T.case("sobol equals SciPy's unscrambled points", function()
  local X = smi.doe.sobol(4, 3)
  -- points 1..4 of the sequence (point 0 skipped)
  local want = {{0.5, 0.5, 0.5}, {0.75, 0.25, 0.25}, {0.25, 0.75, 0.75}, {0.375, 0.375, 0.625}}
  for i = 1, 4 do for j = 1, 3 do T.eq(X[i][j], want[i][j], ("X[%d][%d]"):format(i, j)) end end
  T.eq(smi.doe.sobol_max_dim, 37)
  T.raises(function() smi.doe.sobol(4, 38) end, "1..37")
end)

T.case("full factorial", function()
  local X = smi.doe.full_factorial({{1, 2}, {10, 20, 30}})
  T.eq(#X, 6); T.eq(X[1][1], 1); T.eq(X[3][2], 30); T.eq(X[4][1], 2)
  local G = smi.doe.full_factorial(3, {{0, 1}, {0, 2}})
  T.eq(#G, 9); T.eq(G[2][2], 1); T.eq(G[9][1], 1)
end)

T.finish()
