// SPDX-License-Identifier: MIT
// AVX2 + FMA kernel of fused_mean.hpp: 8 points per step (two vectors share each design
// point's broadcasts), exp(-s) by the same reduction and degree-13 polynomial as fast_exp.cpp.
#include "kernels/surrogate/fused_mean.hpp"

#include <immintrin.h>

#include <algorithm>

namespace smi::surrogate::kriging::detail {
namespace {

constexpr double kLog2e = 1.4426950408889634074;
constexpr double kLn2Hi = 6.93147180369123816490e-01, kLn2Lo = 1.90821492927058770002e-10;
constexpr double kShift = 6755399441055744.0;  // 1.5 * 2^52
constexpr double kC[14] = {1.0 / 6227020800.0, 1.0 / 479001600.0, 1.0 / 39916800.0, 1.0 / 3628800.0, 1.0 / 362880.0,
                           1.0 / 40320.0,      1.0 / 5040.0,      1.0 / 720.0,       1.0 / 120.0,     1.0 / 24.0,
                           1.0 / 6.0,          0.5,               1.0,               1.0};

/// exp(-s[v]) for V independent vectors at once: the polynomial steps are interleaved so the
/// FMA latency of one chain hides behind the others (one chain alone would stall the core).
template <int V>
__attribute__((target("avx2,fma"))) inline void exp_neg_many(__m256d* s) {
  __m256d kd[V], r[V], p[V];
  for (int v = 0; v < V; ++v) {
    const __m256d t = _mm256_sub_pd(_mm256_setzero_pd(), _mm256_min_pd(s[v], _mm256_set1_pd(708.0)));
    kd[v] = _mm256_fmadd_pd(t, _mm256_set1_pd(kLog2e), _mm256_set1_pd(kShift));
    const __m256d k = _mm256_sub_pd(kd[v], _mm256_set1_pd(kShift));
    r[v] = _mm256_fnmadd_pd(k, _mm256_set1_pd(kLn2Lo), _mm256_fnmadd_pd(k, _mm256_set1_pd(kLn2Hi), t));
    p[v] = _mm256_set1_pd(kC[0]);
  }
  for (int j = 1; j < 14; ++j) {
    const __m256d c = _mm256_set1_pd(kC[j]);
    for (int v = 0; v < V; ++v) p[v] = _mm256_fmadd_pd(p[v], r[v], c);
  }
  for (int v = 0; v < V; ++v) {
    const __m256i e = _mm256_slli_epi64(_mm256_add_epi64(_mm256_castpd_si256(kd[v]), _mm256_set1_epi64x(1023)), 52);
    s[v] = _mm256_mul_pd(p[v], _mm256_castsi256_pd(e));
  }
}

/// 8 points: x0 points at point 0's first coordinate, coordinate j of point q at x0[j * ld + q].
/// Design points go 4 at a time (8 independent exponentials), the rest one at a time; the
/// sum over k is in k order either way.
__attribute__((target("avx2,fma"))) void eight(const double* x0, Eigen::Index ld, Eigen::Index d, const double* sw,
                                               const double* g, Eigen::Index m, double* out) {
  __m256d acc0 = _mm256_setzero_pd(), acc1 = _mm256_setzero_pd();
  Eigen::Index k = 0;
  for (; k + 4 <= m; k += 4) {
    __m256d s[8];
    for (int v = 0; v < 8; ++v) s[v] = _mm256_setzero_pd();
    for (Eigen::Index j = 0; j < d; ++j) {
      const __m256d x0v = _mm256_loadu_pd(x0 + j * ld), x1v = _mm256_loadu_pd(x0 + j * ld + 4);
      for (int q = 0; q < 4; ++q) {
        const __m256d c = _mm256_broadcast_sd(sw + (k + q) * d + j);
        const __m256d a0 = _mm256_sub_pd(x0v, c), a1 = _mm256_sub_pd(x1v, c);
        s[2 * q] = _mm256_fmadd_pd(a0, a0, s[2 * q]);
        s[2 * q + 1] = _mm256_fmadd_pd(a1, a1, s[2 * q + 1]);
      }
    }
    exp_neg_many<8>(s);
    for (int q = 0; q < 4; ++q) {
      const __m256d gk = _mm256_broadcast_sd(g + k + q);
      acc0 = _mm256_fmadd_pd(gk, s[2 * q], acc0);
      acc1 = _mm256_fmadd_pd(gk, s[2 * q + 1], acc1);
    }
  }
  for (; k < m; ++k) {
    __m256d s[2] = {_mm256_setzero_pd(), _mm256_setzero_pd()};
    for (Eigen::Index j = 0; j < d; ++j) {
      const __m256d c = _mm256_broadcast_sd(sw + k * d + j);
      const __m256d a0 = _mm256_sub_pd(_mm256_loadu_pd(x0 + j * ld), c);
      const __m256d a1 = _mm256_sub_pd(_mm256_loadu_pd(x0 + j * ld + 4), c);
      s[0] = _mm256_fmadd_pd(a0, a0, s[0]);
      s[1] = _mm256_fmadd_pd(a1, a1, s[1]);
    }
    exp_neg_many<2>(s);
    const __m256d gk = _mm256_broadcast_sd(g + k);
    acc0 = _mm256_fmadd_pd(gk, s[0], acc0);
    acc1 = _mm256_fmadd_pd(gk, s[1], acc1);
  }
  _mm256_storeu_pd(out, acc0);
  _mm256_storeu_pd(out + 4, acc1);
}

const bool kHasAvx2Fma = (__builtin_cpu_init(), __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma"));

}  // namespace

bool fused_gauss_available() { return kHasAvx2Fma; }

void fused_gauss_sum(const Eigen::MatrixXd& Xw, const RowMatrix& Sw, const Eigen::VectorXd& gamma, double* out) {
  const Eigen::Index nr = Xw.rows(), d = Xw.cols(), m = Sw.rows();
  Eigen::Index i = 0;
  for (; i + 8 <= nr; i += 8) eight(Xw.data() + i, nr, d, Sw.data(), gamma.data(), m, out + i);
  if (i == nr) return;
  // The last few points go through the same kernel from a zero-padded copy (same arithmetic).
  Eigen::MatrixXd pad = Eigen::MatrixXd::Zero(8, d);
  pad.topRows(nr - i) = Xw.bottomRows(nr - i);
  double tmp[8];
  eight(pad.data(), 8, d, Sw.data(), gamma.data(), m, tmp);
  std::copy(tmp, tmp + (nr - i), out + i);
}

}  // namespace smi::surrogate::kriging::detail
