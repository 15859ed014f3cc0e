// SPDX-License-Identifier: MIT
// Vectorized exp(-x): 2^k * exp(r), k = round(-x / ln 2), |r| <= ln2 / 2, Taylor to r^13
// (truncation < 5e-18 relative). An AVX2 version written with intrinsics (selected at run
// time by CPU detection) and a scalar version with the same arithmetic for other CPUs.
#include "kernels/surrogate/fast_exp.hpp"

#include <immintrin.h>

#include <bit>
#include <cstdint>

namespace smi::surrogate::kriging {
namespace {

constexpr double kLog2e = 1.4426950408889634074;
constexpr double kLn2Hi = 6.93147180369123816490e-01, kLn2Lo = 1.90821492927058770002e-10;
constexpr double kShift = 6755399441055744.0;  // 1.5 * 2^52: adding it rounds to an integer
constexpr double kC[14] = {1.0 / 6227020800.0, 1.0 / 479001600.0, 1.0 / 39916800.0, 1.0 / 3628800.0, 1.0 / 362880.0,
                           1.0 / 40320.0,      1.0 / 5040.0,      1.0 / 720.0,       1.0 / 120.0,     1.0 / 24.0,
                           1.0 / 6.0,          0.5,               1.0,               1.0};

double exp_neg_scalar(double x) {
  const double c = x < 0.0 ? 0.0 : (x > 708.0 ? 708.0 : x);
  const double t = -c;
  const double kd = t * kLog2e + kShift;
  const std::uint64_t ki = std::bit_cast<std::uint64_t>(kd);  // low bits hold k
  const double k = kd - kShift;
  const double r = (t - k * kLn2Hi) - k * kLn2Lo;
  double p = kC[0];
  for (int j = 1; j < 14; ++j) p = p * r + kC[j];
  return p * std::bit_cast<double>((ki + 1023) << 52);
}

__attribute__((target("avx2"))) void exp_neg_avx2(double* x, long n) {
  const __m256d zero = _mm256_setzero_pd(), hi = _mm256_set1_pd(708.0), log2e = _mm256_set1_pd(kLog2e),
                shift = _mm256_set1_pd(kShift), ln2hi = _mm256_set1_pd(kLn2Hi), ln2lo = _mm256_set1_pd(kLn2Lo);
  const __m256i bias = _mm256_set1_epi64x(1023);
  long i = 0;
  for (; i + 4 <= n; i += 4) {
    __m256d c = _mm256_min_pd(_mm256_max_pd(_mm256_loadu_pd(x + i), zero), hi);
    const __m256d t = _mm256_sub_pd(zero, c);
    const __m256d kd = _mm256_add_pd(_mm256_mul_pd(t, log2e), shift);
    const __m256d k = _mm256_sub_pd(kd, shift);
    const __m256d r = _mm256_sub_pd(_mm256_sub_pd(t, _mm256_mul_pd(k, ln2hi)), _mm256_mul_pd(k, ln2lo));
    __m256d p = _mm256_set1_pd(kC[0]);
    for (int j = 1; j < 14; ++j) p = _mm256_add_pd(_mm256_mul_pd(p, r), _mm256_set1_pd(kC[j]));
    const __m256i e = _mm256_slli_epi64(_mm256_add_epi64(_mm256_castpd_si256(kd), bias), 52);
    _mm256_storeu_pd(x + i, _mm256_mul_pd(p, _mm256_castsi256_pd(e)));
  }
  for (; i < n; ++i) x[i] = exp_neg_scalar(x[i]);
}

const bool kHasAvx2 = (__builtin_cpu_init(), __builtin_cpu_supports("avx2"));

}  // namespace

void exp_neg_inplace(double* x, long n) {
  if (kHasAvx2) {
    exp_neg_avx2(x, n);
    return;
  }
  for (long i = 0; i < n; ++i) x[i] = exp_neg_scalar(x[i]);
}

}  // namespace smi::surrogate::kriging
