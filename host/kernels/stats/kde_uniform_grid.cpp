// SPDX-License-Identifier: MIT
#include "kernels/stats/kde_uniform_grid.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "kernels/stats/fast_normal.hpp"
#include "kernels/stats/kde.hpp"
#include "platform/core/thread_pool.hpp"

namespace smi::stats::detail {
namespace {

constexpr Eigen::Index kBlock = 64;

/// Runs body(block_begin, block_end) over blocks of kBlock nodes, blocks split between threads
/// on block boundaries (so chains restart at the same nodes whatever the thread count).
template <class F>
void over_blocks(Eigen::Index m, Eigen::Index n_data, int threads, F&& body) {
  const Eigen::Index nblocks = (m + kBlock - 1) / kBlock;
  pool::parallel_blocks(nblocks, threads, static_cast<double>(m) * static_cast<double>(std::min<Eigen::Index>(n_data, 4000)),
                  [&](Eigen::Index b0, Eigen::Index b1) {
                    for (Eigen::Index b = b0; b < b1; ++b) body(b * kBlock, std::min(m, (b + 1) * kBlock));
                  });
}

/// Data indices [lo, hi) whose kernels reach the nodes x[j0..j1).
std::pair<Eigen::Index, Eigen::Index> active(ConstVec t, double a, double b, double w) {
  const double* tb = t.data();
  const double* te = tb + t.size();
  const double* lo = std::lower_bound(tb, te, a - w);
  const double* hi = std::upper_bound(lo, te, b + w);
  return {lo - tb, hi - tb};
}

}  // namespace

std::optional<double> uniform_spacing(ConstVec x) {
  const Eigen::Index m = x.size();
  if (m < 128) return std::nullopt;
  const double dx = (x[m - 1] - x[0]) / static_cast<double>(m - 1);
  if (!(dx > 0.0) || !std::isfinite(dx)) return std::nullopt;
  const double tol = 8.0 * std::numeric_limits<double>::epsilon() * std::max(std::abs(x[0]), std::abs(x[m - 1]));
  for (Eigen::Index j = 0; j < m; ++j)
    if (std::abs(x[j] - (x[0] + static_cast<double>(j) * dx)) > tol) return std::nullopt;
  return dx;
}

void uniform_pdf_sums(ConstVec t, double h, ConstVec x, double dx, Eigen::VectorXd& out, int threads) {
  // Inside a block of 64 nodes, φ(z0 + jδ)·√(2π) = e^{−z0²/2} · g^j · H_j with g = e^{−z0 δ} and
  // H_j = e^{−δ² j²/2} (shared by all kernels). g^j = (g⁸)^{j/8} · g^{j mod 8}: 16 chained
  // multiplications per kernel and block, then three multiplications per node, vectorised over
  // the nodes. Kernels are added in data order, so the sums do not depend on the thread split.
  const double ih = 1.0 / h, d = dx * ih, w = kKdeCutoff * h;
  double H[kBlock];
  for (Eigen::Index j = 0; j < kBlock; ++j) H[j] = std::exp(-0.5 * d * d * static_cast<double>(j * j));
  over_blocks(x.size(), t.size(), threads, [&](Eigen::Index j0, Eigen::Index j1) {
    const auto [lo, hi] = active(t, x[j0], x[j1 - 1], w);
    double acc[kBlock] = {};
    const Eigen::Index len = j1 - j0;
    for (Eigen::Index i = lo; i < hi; ++i) {
      const double z0 = (x[j0] - t[i]) * ih;
      const double g = std::exp(-z0 * d);
      double p1[8], p8[8];
      p1[0] = 1.0;
      for (int k = 1; k < 8; ++k) p1[k] = p1[k - 1] * g;
      const double g8 = p1[7] * g;
      p8[0] = std::exp(-0.5 * z0 * z0);
      for (int m = 1; m < 8; ++m) p8[m] = p8[m - 1] * g8;
      for (int m = 0; m < 8; ++m) {
        const double pm = p8[m];
        double* a = acc + 8 * m;
        const double* hm = H + 8 * m;
        for (int k = 0; k < 8; ++k) a[k] += pm * (p1[k] * hm[k]);
      }
    }
    for (Eigen::Index j = 0; j < len; ++j) out[j0 + j] = acc[j];
  });
}

void uniform_cdf_sums(ConstVec t, double h, ConstVec x, double dx, Eigen::VectorXd& out, int threads) {
  // Per block: Σ Φ at the first node from the table, then the corrected trapezoid rule
  //   Φ(z + δ) − Φ(z) = δ/2 (φ(z) + φ(z + δ)) + δ²/12 ((zφ)(z + δ) − (zφ)(z)) + O(δ⁵ φ⁗/720)
  // summed over kernels, with φ from the multiplicative chain (5 flops per node and kernel).
  const double ih = 1.0 / h, d = dx * ih, q = std::exp(-d * d), w = 9.0 * h;
  const double* tab = phi_table();
  over_blocks(x.size(), t.size(), threads, [&](Eigen::Index j0, Eigen::Index j1) {
    const auto [lo, hi] = active(t, x[j0], x[j1 - 1], w);
    const Eigen::Index na = hi - lo;
    // Kernels entirely left of the block contribute 1 each.
    out.segment(j0, j1 - j0).setConstant(static_cast<double>(lo));
    if (na == 0) return;
    thread_local std::vector<double> wv, rv, zv;
    wv.resize(static_cast<std::size_t>(na));
    rv.resize(static_cast<std::size_t>(na));
    zv.resize(static_cast<std::size_t>(na));
    double s = static_cast<double>(lo);
    for (Eigen::Index i = 0; i < na; ++i) {
      const double z = (x[j0] - t[lo + i]) * ih;
      zv[i] = z;
      s += fast_normal_cdf(z, tab);
      wv[i] = 0.39894228040143267794 * std::exp(-0.5 * z * z);
      rv[i] = std::exp(-z * d - 0.5 * d * d);
    }
    double *wp = wv.data(), *rp = rv.data(), *zp = zv.data();
    double p0 = 0.0, d0 = 0.0;
    for (Eigen::Index i = 0; i < na; ++i) p0 += wp[i], d0 += zp[i] * wp[i];
    const double c1 = 0.5 * d, c2 = d * d / 12.0;
    out[j0] = std::min(s, static_cast<double>(hi));
    for (Eigen::Index j = j0 + 1; j < j1; ++j) {
      for (Eigen::Index i = 0; i < na; ++i) {
        wp[i] *= rp[i];
        rp[i] *= q;
        zp[i] += d;
      }
      double pa[4] = {0.0, 0.0, 0.0, 0.0}, da[4] = {0.0, 0.0, 0.0, 0.0};
      Eigen::Index i = 0;
      for (; i + 4 <= na; i += 4)
        for (int k = 0; k < 4; ++k) pa[k] += wp[i + k], da[k] += zp[i + k] * wp[i + k];
      for (int k = 0; i < na; ++i, ++k) pa[k] += wp[i], da[k] += zp[i] * wp[i];
      const double p1 = (pa[0] + pa[1]) + (pa[2] + pa[3]), d1 = (da[0] + da[1]) + (da[2] + da[3]);
      s += c1 * (p0 + p1) + c2 * (d1 - d0);
      p0 = p1, d0 = d1;
      out[j] = std::min(s, static_cast<double>(hi));
    }
  });
}

}  // namespace smi::stats::detail
