// SPDX-License-Identifier: MIT
// Reference texts of smi.mat (registered in mat.cpp; format: stdlib/smi/doc.lua).
#include "bindings/doc.hpp"

namespace smi::bind {

// long: one raw string of reference text (data, no logic); doc.lua reads it entry by entry
DocText doc_mat() {
  return {"bindings/mat_doc.cpp", R"DOC(
@ smi.mat(rows | vec | mat | r, c) -> mat
A float64 matrix (column-major, 1-based) owned by Lua: + - between mats of one shape, * / by a
number, unary -, m[i] (row i as a vec), #m (rows), tostring, and the methods smi.mat:*.
smi.mat{{1, 2}, {3, 4}} copies a table of rows (each a table or a vec); smi.mat(v) makes a
one-column matrix; smi.mat(r, c) gives r x c zeros.
returns: a new mat
errors: rows of different lengths, an element that is not a number (row and column named),
  negative sizes
example:
  local m = smi.mat{{1, 2}, {3, 4}}
  print(m, #m, m[2])

@ smi.mat.zeros(r, c) -> mat
An r x c matrix of zeros.
returns: a new mat
errors: a negative size
example:
  print(smi.mat.zeros(2, 3))

@ smi.mat.identity(n) -> mat
The n x n identity matrix.
returns: a new mat
errors: a negative size
example:
  print(smi.mat.identity(2))

@ smi.mat.hcat{a, b, ...} -> mat
Blocks side by side (columns); each block is a mat, a vec (one column) or a table of numbers.
returns: a new mat
errors: blocks with different numbers of rows; an argument that is not a table of blocks
example:
  print(smi.mat.hcat{smi.vec{1, 2}, smi.mat{{3, 4}, {5, 6}}})

@ smi.mat.vcat{a, b, ...} -> mat
Blocks stacked (rows); each block is a mat, or a vec/table taken as one column (so a vec
stacks under a one-column mat).
returns: a new mat
errors: blocks with different numbers of columns
example:
  print(smi.mat.vcat{smi.mat{{1, 2}}, smi.mat{{3, 4}}}, smi.mat.vcat{smi.vec{1, 2}, {3}})

@ smi.mat:rows() -> n
The number of rows.
returns: an integer
errors: none
example:
  print(smi.mat.zeros(2, 3):rows())

@ smi.mat:cols() -> n
The number of columns.
returns: an integer
errors: none
example:
  print(smi.mat.zeros(2, 3):cols())

@ smi.mat:shape() -> rows, cols
Both sizes.
returns: two integers
errors: none
example:
  print(smi.mat.zeros(2, 3):shape())

@ smi.mat:get(i, j) -> number
The element in row i, column j.
returns: a number
errors: an index out of range ("smi.mat row 3 out of range 1..2")
example:
  print(smi.mat{{1, 2}, {3, 4}}:get(2, 1))

@ smi.mat:set(i, j, x)
Sets one element in place.
returns: nothing
errors: an index out of range; x not a number
example:
  local m = smi.mat.zeros(2, 2); m:set(1, 2, 5)
  print(m)

@ smi.mat:row(i) -> vec
Row i as a new vec (the same as m[i]).
returns: a new vec
errors: i out of range
example:
  print(smi.mat{{1, 2}, {3, 4}}:row(2))

@ smi.mat:col(j) -> vec
Column j as a new vec.
returns: a new vec
errors: j out of range
example:
  print(smi.mat{{1, 2}, {3, 4}}:col(2))

@ smi.mat:set_col(j, v)
Replaces column j in place with the values of a vec or table.
returns: nothing
errors: j out of range; a length other than the number of rows ("3 values for 2 rows")
example:
  local m = smi.mat.zeros(2, 2); m:set_col(1, {5, 6})
  print(m)

@ smi.mat:set_row(i, v)
Replaces row i in place with the values of a vec or table.
returns: nothing
errors: i out of range; a length other than the number of columns
example:
  local m = smi.mat.zeros(2, 2); m:set_row(2, {7, 8})
  print(m)

@ smi.mat:sub(i1, i2 [, j1, j2]) -> mat
A block copy: rows i1..i2 and columns j1..j2 (inclusive; all columns when j1, j2 are omitted).
returns: a new mat
errors: an index out of range; an empty range
example:
  print(smi.mat{{1, 2, 3}, {4, 5, 6}}:sub(1, 2, 2, 3))

@ smi.mat:t() -> mat
The transpose.
returns: a new mat
errors: none
example:
  print(smi.mat{{1, 2}, {3, 4}}:t())

@ smi.mat:copy() -> mat
A copy that shares nothing with m.
returns: a new mat
errors: none
example:
  print(smi.mat.identity(2):copy())

@ smi.mat:sum() -> number
The sum of all elements.
returns: a number
errors: none
example:
  print(smi.mat{{1, 2}, {3, 4}}:sum())

@ smi.mat:colmeans() -> vec
The mean of each column.
returns: a vec with one value per column
errors: a matrix with no rows
example:
  print(smi.mat{{1, 2}, {3, 4}}:colmeans())

@ smi.mat:colstds() -> vec
The sample standard deviation (divisor n - 1) of each column.
returns: a vec with one value per column
errors: fewer than 2 rows
example:
  print(smi.mat{{1, 2}, {3, 4}}:colstds())

@ smi.mat:dot(x) -> mat | vec
The matrix product m * x with a mat, or m * v with a vec.
returns: a new mat, or a vec for a vec argument
errors: sizes that do not match ("2x2 times vec(3)")
example:
  print(smi.mat{{1, 2}, {3, 4}}:dot(smi.vec{1, 1}))

@ smi.mat:totable() -> table
The rows as a Lua table of tables.
returns: a new table {{...}, {...}}
errors: none
example:
  print(smi.mat{{1, 2}, {3, 4}}:totable()[2][1])

@ smi.mat:solve(b) -> vec | mat
The x with A x = b for a square A (LU with full pivoting): b a vec or a table of numbers gives
a vec; b a mat with one column per right-hand side gives a mat.
returns: a new vec or mat
errors: A not square ("A must be square, got 2x3"); b with another number of rows ("A is 2x2
  but b has 3 rows"); A singular to working precision ("A (2x2) is singular: numerical rank 1
  of 2"); a NaN or infinite entry (named by row and column)
example:
  local A = smi.mat{{4, 1}, {2, 3}}
  print(A:solve(smi.vec{1, 2}))   -- 0.1, 0.6

@ smi.mat:inverse() -> mat
The inverse of a square matrix (prefer A:solve(b) to A:inverse():dot(b): fewer operations and
smaller rounding errors).
returns: a new mat
errors: not square; singular ("numerical rank r of n"); a NaN or infinite entry
example:
  print(smi.mat{{4, 1}, {2, 3}}:inverse())   -- {{0.3, -0.1}, {-0.2, 0.4}}

@ smi.mat:det() -> number
The determinant of a square matrix (LU with partial pivoting); a singular matrix gives 0 (or
a number near it), not an error.
returns: a number
errors: not square; a NaN or infinite entry
example:
  print(smi.mat{{4, 1}, {2, 3}}:det())   -- 10

@ smi.mat:chol() -> mat
The Cholesky factor: the lower triangular L with A = L L^T, for a symmetric positive definite A.
returns: a new mat (lower triangular)
errors: not square; not symmetric (relative tolerance 1e-10 of the largest entry; the first
  pair that differs is named); not positive definite ("A (2x2) is not positive definite")
example:
  local L = smi.mat{{4, 2}, {2, 3}}:chol()
  print(L, L:dot(L:t()))   -- {{2, 0}, {1, 1.414}}, then A again

@ smi.mat.eigh(K [, M]) -> values, vectors
The symmetric eigenproblem K phi = lambda phi, or with M the generalised one K phi = lambda M phi
(M symmetric positive definite: a mass matrix). Eigenvalues ascending; eigenvectors by column,
in the same order, of unit length without M and M-normalised (phi^T M phi = 1) with it. Each
vector's sign is fixed: its entry of largest magnitude is positive. For a lumped-mass model the
natural frequencies are sqrt(values[i]) / (2 pi).
returns: a vec of eigenvalues and a mat of eigenvectors (column j for values[j])
errors: K or M not square, of different sizes, not symmetric (the first pair named) or with a
  NaN entry; M not positive definite
example:
  local K = smi.mat{{2, -1}, {-1, 2}}          -- two masses, three springs
  local lambda, phi = smi.mat.eigh(K, smi.mat.identity(2))
  print(lambda, phi)   -- 1 and 3; columns (1, 1)/sqrt(2) and (1, -1)/sqrt(2)
)DOC"};
}

}  // namespace smi::bind
