// SPDX-License-Identifier: MIT
// Reference texts of smi.rng (registered in rng.cpp; format: stdlib/smi/doc.lua).
#include "bindings/doc.hpp"

namespace smi::bind {

DocText doc_rng() {
  return {"bindings/rng_doc.cpp", R"DOC(
@ smi.rng(seed [, stream]) -> rng
A seeded random generator (xoshiro256**; normals by inversion), giving the same numbers on every
build and platform. stream (an integer or a label such as "bootstrap") selects an independent
stream for the same seed, so parts of a study draw without sharing a sequence.
returns: a generator with the methods smi.rng:uniform, :normal, :integers
errors: seed not an integer ("seed must be an integer, got a float"); stream not an integer or string
example:
  local g = smi.rng(smi.seed, "example")
  print(g:uniform(3))

@ smi.rng:uniform([n [, lo, hi]]) -> vec | number
n uniform numbers on (lo, hi), default (0, 1); without n, one number in (0, 1).
returns: a vec of n numbers, or one number
errors: n negative; lo >= hi or a bound not finite ("need finite lo < hi")
example:
  local g = smi.rng(1)
  print(g:uniform(2, 10, 20), g:uniform())

@ smi.rng:normal([n [, mean, sd]]) -> vec | number
n normal numbers with the given mean (0) and standard deviation (1); without n, one standard
normal number.
returns: a vec of n numbers, or one number
errors: n negative; mean not finite; sd negative or not finite
example:
  print(smi.rng(1):normal(3, 100, 5))

@ smi.rng:integers(n, lo, hi) -> vec
n integers uniform on [lo, hi] (inclusive), as floats in a vec.
returns: a vec of n whole numbers
errors: lo > hi ("need lo <= hi"); a bound that is not an integer
example:
  print(smi.rng(1):integers(5, 1, 6))
)DOC"};
}

}  // namespace smi::bind
