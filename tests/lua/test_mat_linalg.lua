-- SPDX-License-Identifier: MIT
-- smi.mat's linear algebra (A:solve, :inverse, :det, :chol, smi.mat.eigh) against closed forms
-- and against SciPy (tests/reference/linalg_scipy.py -> linalg_scipy.json), and its errors.
local T = require "smi.testing"

local ref = smi.json.read(os.getenv("SMI_TEST_REFERENCE_DIR") .. "/linalg_scipy.json")

local function mat_near(a, b, tol, what)
  local r, c = a:shape()
  T.eq(r, #b, what .. " rows"); T.eq(c, #b[1], what .. " columns")
  for i = 1, r do
    for j = 1, c do T.near(a:get(i, j), b[i][j], tol, string.format("%s[%d][%d]", what, i, j)) end
  end
end

T.case("2x2 closed forms: solve, inverse, det, chol", function()
  local A = smi.mat{{4, 1}, {2, 3}}
  local x = A:solve(smi.vec{1, 2})   -- (3 - 2, 8 - 2) / 10
  T.near(x[1], 0.1, 1e-15); T.near(x[2], 0.6, 1e-15)
  local y = A:solve{1, 2}
  T.near(y[2], 0.6, 1e-15)
  mat_near(A:inverse(), {{0.3, -0.1}, {-0.2, 0.4}}, 1e-15, "inverse")
  T.near(A:det(), 10, 1e-13)
  T.near(smi.mat{{0, 1}, {1, 0}}:det(), -1, 1e-15)
  mat_near(smi.mat{{4, 2}, {2, 3}}:chol(), {{2, 0}, {1, math.sqrt(2)}}, 1e-15, "chol")
  local X = A:solve(smi.mat{{1, 0}, {0, 1}})
  mat_near(X, {{0.3, -0.1}, {-0.2, 0.4}}, 1e-15, "solve with a mat")
end)

T.case("eigh closed forms: the two-mass chain and its generalised form", function()
  local K = smi.mat{{2, -1}, {-1, 2}}
  local w, V = smi.mat.eigh(K)
  T.near(w[1], 1, 1e-14); T.near(w[2], 3, 1e-14)
  local s = 1 / math.sqrt(2)
  mat_near(V, {{s, s}, {s, -s}}, 1e-14, "unit eigenvectors")
  -- M = 2 I: the same eigenvectors scaled to phi^T M phi = 1, eigenvalues halved
  local w2, V2 = smi.mat.eigh(K, smi.mat.identity(2) * 2)
  T.near(w2[1], 0.5, 1e-14); T.near(w2[2], 1.5, 1e-14)
  mat_near(V2, {{0.5, 0.5}, {0.5, -0.5}}, 1e-14, "M-normalised eigenvectors")
end)

T.case("SciPy: solve, inverse, det and Cholesky of a 5x5 system", function()
  local A = smi.mat(ref.A)
  local x = A:solve(smi.vec(ref.b))
  for i = 1, 5 do T.near(x[i], ref.solve_b[i], 1e-12, "solve") end
  mat_near(A:solve(smi.mat(ref.B)), ref.solve_B, 1e-12, "solve B")
  mat_near(A:inverse(), ref.inverse, 1e-12, "inverse")
  T.rel(A:det(), ref.det, 1e-12, "det")
  mat_near(smi.mat(ref.S):chol(), ref.chol, 1e-12, "chol")
end)

T.case("SciPy: eigh of a symmetric matrix and of a spring-mass chain K phi = lambda M phi", function()
  local w, V = smi.mat.eigh(smi.mat(ref.S))
  for i = 1, 5 do T.rel(w[i], ref.eigh_values[i], 1e-12, "eigenvalue") end
  mat_near(V, ref.eigh_vectors, 1e-10, "eigenvectors")
  local K, M = smi.mat(ref.K), smi.mat(ref.M)
  local g, P = smi.mat.eigh(K, M)
  for i = 1, 4 do T.rel(g[i], ref.geigh_values[i], 1e-12, "generalised eigenvalue") end
  mat_near(P, ref.geigh_vectors, 1e-8, "M-normalised eigenvectors")
  mat_near(P:t():dot(M):dot(P), smi.mat.identity(4):totable(), 1e-12, "phi^T M phi")
  for i = 2, 4 do T.truthy(g[i] > g[i - 1], "ascending") end
end)

T.case("each error names its cause", function()
  local singular = smi.mat{{1, 2}, {2, 4}}
  T.raises(function() return singular:solve{1, 1} end, "mat:solve: A (2x2) is singular: numerical rank 1 of 2")
  T.raises(function() return singular:inverse() end, "mat:inverse: A (2x2) is singular")
  T.near(singular:det(), 0, 1e-15)
  T.raises(function() return smi.mat{{1, 2, 3}, {4, 5, 6}}:solve{1, 1} end, "A must be square, got 2x3")
  T.raises(function() return smi.mat{{1, 0}, {0, 1}}:solve{1, 2, 3} end, "A is 2x2 but b has 3 rows")
  T.raises(function() return smi.mat{{1, 0}, {0, 0 / 0}}:det() end, "A[2][2] is")
  T.raises(function() return smi.mat{{1, 2}, {2, 1}}:chol() end, "mat:chol: A (2x2) is not positive definite")
  T.raises(function() return smi.mat{{1, 2}, {0, 1}}:chol() end, "A is not symmetric: [2][1] = 0 but [1][2] = 2")
  T.raises(function() return smi.mat.eigh(smi.mat{{1, 2}, {0, 1}}) end, "smi.mat.eigh: K is not symmetric")
  T.raises(function() return smi.mat.eigh(smi.mat.identity(2), smi.mat.identity(3)) end, "K is 2x2 but M is 3x3")
  T.raises(function() return smi.mat.eigh(smi.mat.identity(2), smi.mat{{1, 0}, {0, -1}}) end,
           "M (2x2) is not positive definite")
end)

T.finish()
