// SPDX-License-Identifier: MIT
// The Sobol' sequence (Bratley & Fox 1988, Gray-code order of Antonov & Saleev 1979) with
// the direction numbers of Joe & Kuo (2008), table "new-joe-kuo-6.21201", written out below
// for the dimensions we support. Checked point by point against SciPy's unscrambled Sobol
// (tests/reference/sobol_points.py).
#include <cstdint>
#include <string>

#include "kernels/surrogate/doe.hpp"
#include "platform/core/errors.hpp"

namespace smi::surrogate::doe {
namespace {

struct Direction {
  int s;         // degree of the primitive polynomial
  int a;         // its inner coefficients a_1..a_{s-1} as bits, a_1 most significant
  int m[8];      // initial direction integers m_1..m_s (m_k odd, < 2^k)
};

// Dimension 1 is the van der Corput sequence (all m = 1); rows below are dimensions 2, 3, ...
constexpr Direction kJoeKuo[] = {
    {1, 0, {1}},
    {2, 1, {1, 3}},
    {3, 1, {1, 3, 1}},
    {3, 2, {1, 1, 1}},
    {4, 1, {1, 1, 3, 3}},
    {4, 4, {1, 3, 5, 13}},
    {5, 2, {1, 1, 5, 5, 17}},
    {5, 4, {1, 1, 5, 5, 5}},
    {5, 7, {1, 1, 7, 11, 19}},
    {5, 11, {1, 1, 5, 1, 1}},
    {5, 13, {1, 1, 1, 3, 11}},
    {5, 14, {1, 3, 5, 5, 31}},
    {6, 1, {1, 3, 3, 9, 7, 49}},
    {6, 13, {1, 1, 1, 15, 21, 21}},
    {6, 16, {1, 3, 1, 13, 27, 49}},
    {6, 19, {1, 1, 1, 15, 7, 5}},
    {6, 22, {1, 3, 1, 15, 13, 25}},
    {6, 25, {1, 1, 5, 5, 19, 61}},
    {7, 1, {1, 3, 7, 11, 23, 15, 103}},
    {7, 4, {1, 3, 7, 13, 13, 15, 69}},
    {7, 7, {1, 1, 3, 13, 7, 35, 63}},
    {7, 8, {1, 3, 5, 9, 1, 25, 53}},
    {7, 14, {1, 3, 1, 13, 9, 35, 107}},
    {7, 19, {1, 3, 1, 5, 27, 61, 31}},
    {7, 21, {1, 1, 5, 11, 19, 41, 61}},
    {7, 28, {1, 3, 5, 3, 3, 13, 69}},
    {7, 31, {1, 1, 7, 13, 1, 19, 1}},
    {7, 32, {1, 3, 7, 5, 13, 19, 59}},
    {7, 37, {1, 1, 3, 9, 25, 29, 41}},
    {7, 41, {1, 3, 5, 13, 23, 1, 55}},
    {7, 42, {1, 3, 7, 3, 13, 59, 17}},
    {7, 50, {1, 3, 1, 3, 5, 53, 69}},
    {7, 55, {1, 1, 5, 5, 23, 33, 13}},
    {7, 56, {1, 1, 7, 7, 1, 61, 123}},
    {7, 59, {1, 1, 7, 9, 13, 61, 49}},
    {7, 62, {1, 3, 3, 5, 3, 55, 33}},
};
constexpr int kBits = 32;
constexpr int kMaxDim = 1 + static_cast<int>(sizeof(kJoeKuo) / sizeof(kJoeKuo[0]));

/// v[k] = m_{k+1} * 2^(32-(k+1)) for one dimension (0-based dim; 0 = van der Corput).
void directions(int dim, std::uint32_t v[kBits]) {
  if (dim == 0) {
    for (int k = 0; k < kBits; ++k) v[k] = std::uint32_t(1) << (kBits - 1 - k);
    return;
  }
  const Direction& D = kJoeKuo[dim - 1];
  std::uint64_t m[kBits];
  for (int k = 0; k < kBits; ++k) {
    if (k < D.s) {
      m[k] = static_cast<std::uint64_t>(D.m[k]);
    } else {  // m_k = 2 a_1 m_{k-1} ^ 4 a_2 m_{k-2} ^ ... ^ 2^s m_{k-s} ^ m_{k-s}
      std::uint64_t x = m[k - D.s] ^ (m[k - D.s] << D.s);
      for (int j = 1; j < D.s; ++j)
        if ((D.a >> (D.s - 1 - j)) & 1) x ^= m[k - j] << j;
      m[k] = x;
    }
    v[k] = static_cast<std::uint32_t>(m[k] << (kBits - 1 - k));
  }
}

}  // namespace

int sobol_max_dim() { return kMaxDim; }

Eigen::MatrixXd sobol(Eigen::Index n, Eigen::Index d, Eigen::Index skip) {
  if (d < 1 || d > kMaxDim)
    throw InvalidArgument("sobol: dimension must be in 1.." + std::to_string(kMaxDim) + ", got " + std::to_string(d) +
                          " (use lhs for more inputs)");
  if (n < 0 || skip < 0 || n + skip + 1 > (Eigen::Index(1) << 31))
    throw InvalidArgument("sobol: need 0 <= n, skip and n + skip < 2^31");
  Eigen::MatrixXd X(n, d);
  const double scale = 1.0 / 4294967296.0;
  for (Eigen::Index j = 0; j < d; ++j) {
    std::uint32_t v[kBits];
    directions(static_cast<int>(j), v);
    std::uint32_t x = 0;
    for (Eigen::Index i = 1; i <= n + skip; ++i) {
      // Gray code: point i differs from point i-1 by the direction of the lowest zero bit of i-1.
      std::uint64_t c = 0, k = static_cast<std::uint64_t>(i - 1);
      while (k & 1) k >>= 1, ++c;
      x ^= v[c];
      if (i > skip) X(i - skip - 1, j) = static_cast<double>(x) * scale;
    }
  }
  return X;
}

}  // namespace smi::surrogate::doe
