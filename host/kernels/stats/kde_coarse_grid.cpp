// SPDX-License-Identifier: MIT
#include "kernels/stats/kde_coarse_grid.hpp"

#include <array>
#include <cmath>
#include <vector>

#include "kernels/stats/kde.hpp"

namespace smi::stats {
namespace {

constexpr int kStencil = 8;  ///< coarse nodes per interpolated value (degree 7)
constexpr int kHalfStencil = kStencil / 2;

/// The Lagrange weights of the stencil's coarse nodes, at offsets 1 − kHalfStencil .. kHalfStencil
/// from the coarse node at or before the point, for a point at t in [0, 1) of a coarse step.
std::array<double, kStencil> lagrange_weights(double t) {
  std::array<double, kStencil> w{};
  for (int a = 0; a < kStencil; ++a) {
    const double oa = static_cast<double>(a + 1 - kHalfStencil);
    double v = 1.0;
    for (int b = 0; b < kStencil; ++b) {
      if (b == a) continue;
      const double ob = static_cast<double>(b + 1 - kHalfStencil);
      v *= (t - ob) / (oa - ob);
    }
    w[static_cast<std::size_t>(a)] = v;
  }
  return w;
}

/// Calls f(fine node j, first coarse node of its stencil, weights) for every fine node (coarse
/// node kHalfStencil − 1 sits at the fine grid's first node).
template <class F>
void for_each_stencil(const CoarseGrid& c, F&& f) {
  std::vector<std::array<double, kStencil>> w(static_cast<std::size_t>(c.ratio));
  for (Eigen::Index k = 0; k < c.ratio; ++k)
    w[static_cast<std::size_t>(k)] = lagrange_weights(static_cast<double>(k) / static_cast<double>(c.ratio));
  for (Eigen::Index j = 0; j < c.fine_n; ++j) f(j, j / c.ratio, w[static_cast<std::size_t>(j % c.ratio)]);
}

}  // namespace

std::optional<CoarseGrid> coarse_grid(const Grid& fine, double h) {
  const double dx = fine.step();
  if (!(dx > 0.0) || !(h > 0.0)) return std::nullopt;
  const auto ratio = static_cast<Eigen::Index>(std::floor(h * kCoarseKdeStep / dx));
  if (ratio < 2) return std::nullopt;
  CoarseGrid c;
  c.ratio = ratio;
  c.fine_n = fine.n;
  // kHalfStencil − 1 nodes before the fine range, kHalfStencil after its last coarse step
  const Eigen::Index n = (fine.n - 1) / ratio + kStencil;
  const double step = static_cast<double>(ratio) * dx;
  const double lo = fine.lo - static_cast<double>(kHalfStencil - 1) * step;
  c.coarse = Grid{lo, lo + static_cast<double>(n - 1) * step, n};
  return c;
}

Eigen::VectorXd interpolate_to_fine(const CoarseGrid& c, ConstVec coarse_values) {
  Eigen::VectorXd out(c.fine_n);
  for_each_stencil(c, [&](Eigen::Index j, Eigen::Index k, const std::array<double, kStencil>& w) {
    double v = 0.0;
    for (int m = 0; m < kStencil; ++m) v += w[static_cast<std::size_t>(m)] * coarse_values[k + m];
    out[j] = v;
  });
  return out;
}

Eigen::VectorXd interpolate_adjoint(const CoarseGrid& c, ConstVec fine_weights) {
  Eigen::VectorXd out = Eigen::VectorXd::Zero(c.coarse.n);
  for_each_stencil(c, [&](Eigen::Index j, Eigen::Index k, const std::array<double, kStencil>& w) {
    for (int m = 0; m < kStencil; ++m) out[k + m] += w[static_cast<std::size_t>(m)] * fine_weights[j];
  });
  return out;
}

Eigen::VectorXd kde_pdf_resolved(ConstVec data, double h, const Grid& g, const std::optional<CoarseGrid>& c, int threads) {
  if (!c) return kde_pdf_grid(data, h, g, threads);
  return interpolate_to_fine(*c, kde_pdf_grid(data, h, c->coarse, threads));
}

Eigen::VectorXd kde_pdf_resolved(ConstVec data, double h, const Grid& g, int threads) {
  return kde_pdf_resolved(data, h, g, coarse_grid(g, h), threads);
}

}  // namespace smi::stats
