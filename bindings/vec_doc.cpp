// SPDX-License-Identifier: MIT
// Reference texts of smi.vec (registered in vec.cpp; format: stdlib/smi/doc.lua).
#include "bindings/doc.hpp"

namespace smi::bind {

// long: one raw string of reference text (data, no logic); doc.lua reads it entry by entry
DocText doc_vec() {
  return {"bindings/vec_doc.cpp", R"DOC(
@ smi.vec(x) -> vec
A float64 vector (1-based) owned by Lua: arithmetic (+ - * / ^ and unary -, elementwise with a
vec of the same length or a number), #v, v[i], v[i] = x (an index out of range is an error), ==,
tostring, and the methods smi.vec:* (sum, mean, quantile, sort, ...).
x is a table of numbers, a vec or a one-column mat (copied), or a length n (n zeros).
returns: a new vec
errors: a table element that is not a number (named by its index); a negative length
example:
  local v = smi.vec{30.1, 30.4, 29.9}
  print(v, #v, v[1], (v - 30) * 10)

@ smi.vec.zeros(n) -> vec
n zeros.
returns: a new vec of length n
errors: n negative or not a whole number
example:
  print(smi.vec.zeros(3))

@ smi.vec.ones(n) -> vec
n ones.
returns: a new vec of length n
errors: n negative or not a whole number
example:
  print(smi.vec.ones(3) * 2.5)

@ smi.vec.linspace(a, b, n) -> vec
n equally spaced values from a to b inclusive (a plot grid, say).
returns: a new vec of length n
errors: n < 2 ("need at least 2 points")
example:
  print(smi.vec.linspace(0, 1, 5))

@ smi.vec.range(a, b [, step]) -> vec
a, a + step, ... up to b (inclusive when it lands on it), as Lua's numeric for.
returns: a new vec (empty when the range is)
errors: step = 0
example:
  print(smi.vec.range(1, 2, 0.25))

@ smi.vec:size() -> n
The number of elements (the same as #v).
returns: an integer
errors: none
example:
  print(smi.vec{1, 2, 3}:size())

@ smi.vec:sum() -> number
The sum of the elements (compensated summation on whole vectors).
returns: a number (0 for an empty vec)
errors: none
example:
  print(smi.vec{1, 2, 3.5}:sum())

@ smi.vec:mean() -> number
The arithmetic mean.
returns: a number
errors: an empty vec ("data needs at least 1 value")
example:
  print(smi.vec{1, 2, 3, 4}:mean())

@ smi.vec:std() -> number
The sample standard deviation (divisor n - 1), as the paper's tables use.
returns: a number
errors: fewer than 2 elements
example:
  print(smi.vec{1, 2, 3, 4}:std())

@ smi.vec:var() -> number
The sample variance (divisor n - 1).
returns: a number
errors: fewer than 2 elements
example:
  print(smi.vec{1, 2, 3, 4}:var())

@ smi.vec:min() -> number
The smallest element.
returns: a number
errors: an empty vec
example:
  print(smi.vec{3, 1, 2}:min())

@ smi.vec:max() -> number
The largest element.
returns: a number
errors: an empty vec
example:
  print(smi.vec{3, 1, 2}:max())

@ smi.vec:median() -> number
The median (the type-7 quantile at 0.5).
returns: a number
errors: an empty vec
example:
  print(smi.vec{3, 1, 2, 10}:median())

@ smi.vec:quantile(p) -> number | vec
Type-7 quantiles (R's default, NumPy's "linear"): p a probability or a vec/table of them.
returns: a number for a number p, else a vec of the same length as p
errors: an empty vec; p outside [0, 1] ("probability must be in [0, 1]")
example:
  local v = smi.vec.range(1, 10)
  print(v:quantile(0.9), v:quantile{0.05, 0.5, 0.95})

@ smi.vec:argmin() -> i
The 1-based index of the smallest element (the first one on ties).
returns: an integer
errors: an empty vec
example:
  print(smi.vec{3, 1, 2}:argmin())

@ smi.vec:argmax() -> i
The 1-based index of the largest element (the first one on ties).
returns: an integer
errors: an empty vec
example:
  print(smi.vec{3, 1, 2}:argmax())

@ smi.vec:dot(w) -> number
The inner product with another vec (or table of numbers) of the same length.
returns: a number
errors: sizes differ ("sizes differ (3 and 1)")
example:
  print(smi.vec{1, 2, 3}:dot{1, 1, 1})

@ smi.vec:norm() -> number
The Euclidean norm.
returns: a number
errors: none
example:
  print(smi.vec{3, 4}:norm())

@ smi.vec:sort() -> vec
A sorted copy, ascending (v itself is unchanged).
returns: a new vec
errors: none
example:
  print(smi.vec{3, 1, 2}:sort())

@ smi.vec:copy() -> vec
A copy that shares nothing with v.
returns: a new vec
errors: none
example:
  local v = smi.vec{1, 2}
  local w = v:copy(); w[1] = 9
  print(v, w)

@ smi.vec:cumsum() -> vec
Cumulative sums: w[i] = v[1] + ... + v[i].
returns: a new vec of the same length
errors: none
example:
  print(smi.vec{1, 2, 3}:cumsum())

@ smi.vec:sub(i [, j]) -> vec
Elements i..j (1-based, inclusive; negative indices count from the end, as string.sub), a copy.
j defaults to -1 (the last element).
returns: a new vec (empty when i > j)
errors: i or j not a whole number
example:
  local v = smi.vec{10, 20, 30, 40}
  print(v:sub(2, 3), v:sub(-2))

@ smi.vec:slice(i [, j]) -> vec
The same as v:sub(i, j).
returns: a new vec
errors: i or j not a whole number
example:
  print(smi.vec{10, 20, 30}:slice(2))

@ smi.vec:abs() -> vec
Absolute values, elementwise.
returns: a new vec
errors: none
example:
  print(smi.vec{-1, 2}:abs())

@ smi.vec:sqrt() -> vec
Square roots, elementwise (NaN for a negative element, as math.sqrt).
returns: a new vec
errors: none
example:
  print(smi.vec{4, 9}:sqrt())

@ smi.vec:exp() -> vec
e^x, elementwise.
returns: a new vec
errors: none
example:
  print(smi.vec{0, 1}:exp())

@ smi.vec:log() -> vec
Natural logarithms, elementwise (-inf at 0, NaN below).
returns: a new vec
errors: none
example:
  print(smi.vec{1, math.exp(2)}:log())

@ smi.vec:map(f) -> vec
f(x) for every element: a convenience for small vectors (one Lua call per element; prefer
whole-vector arithmetic for large ones).
returns: a new vec of f's results
errors: f raises, or returns something that is not a number (the index is named)
example:
  print(smi.vec{1, 2, 3}:map(function(x) return x * x + 1 end))

@ smi.vec:totable() -> table
The elements as a plain Lua table (for JSON, string.format or code that wants a table).
returns: a new sequence table of numbers
errors: none
example:
  local t = smi.vec{1.5, 2}:totable()
  print(type(t), t[1], #t)
)DOC"};
}

}  // namespace smi::bind
