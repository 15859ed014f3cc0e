// SPDX-License-Identifier: MIT
// Given-data Borgonovo delta (see delta.hpp).
#include "kernels/surrogate/delta.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

#include "kernels/stats/bandwidth.hpp"
#include "kernels/stats/grid.hpp"
#include "kernels/stats/kde.hpp"
#include "kernels/stats/metrics.hpp"
#include "platform/core/errors.hpp"
#include "platform/core/rng.hpp"

namespace smi::surrogate::delta {
namespace {

// 1/2 sum over classes of (n_m / n) L1(f_Y, f_m); `order` lists the rows sorted by the input.
double delta_of_order(const std::vector<Eigen::Index>& order, const Eigen::VectorXd& y, Eigen::Index M,
                      const Eigen::VectorXd& fy, const stats::Grid& g) {
  const Eigen::Index n = y.size();
  double d = 0;
  for (Eigen::Index c = 0; c < M; ++c) {
    const Eigen::Index a = c * n / M, b = (c + 1) * n / M;
    Eigen::VectorXd yc(b - a);
    for (Eigen::Index i = a; i < b; ++i) yc(i - a) = y(order[static_cast<std::size_t>(i)]);
    double area;
    if (yc.maxCoeff() > yc.minCoeff())
      area = stats::l1_area_on_grid(stats::kde_pdf_grid(yc, stats::bandwidth_normal_reference(yc), g, 1), fy, g);
    else
      area = 2.0;  // a point mass against a continuous PDF
    d += static_cast<double>(b - a) / static_cast<double>(n) * area;
  }
  return 0.5 * d;
}

}  // namespace

Eigen::Index default_classes(Eigen::Index n) {
  const double e = 2.0 / (7.0 + std::tanh((1500.0 - static_cast<double>(n)) / 500.0));
  return std::min<Eigen::Index>(static_cast<Eigen::Index>(std::ceil(std::pow(static_cast<double>(n), e))), 48);
}

Result estimate(const Eigen::MatrixXd& X, const Eigen::VectorXd& y, const Options& opt) {
  const Eigen::Index n = X.rows();
  if (y.size() != n) throw DimensionMismatch("delta: sample has " + std::to_string(n) + " rows, outputs " + std::to_string(y.size()));
  if (n < 20) throw InvalidArgument("delta needs at least 20 points, got " + std::to_string(n) +
                                   " (add runs, or delta = false)");
  if (!y.allFinite()) throw InvalidArgument("delta: an output is not finite");
  Result r;
  r.classes = opt.classes > 0 ? opt.classes : default_classes(n);
  if (r.classes < 2 || r.classes > n / 5)
    throw InvalidArgument("delta: classes must be between 2 and n/5 = " + std::to_string(n / 5) + ", got " +
                          std::to_string(r.classes));
  r.delta = Eigen::VectorXd::Zero(X.cols());
  if (!(y.maxCoeff() > y.minCoeff())) return r;
  // Common grid: wide enough for the widest class bandwidth (about (n/M)^-1/5 of the spread).
  const double hy = stats::bandwidth_normal_reference(y);
  const double hwide = hy * std::pow(static_cast<double>(r.classes), 0.2) * 3.0;
  const stats::Grid g = stats::Grid::covering(y.minCoeff(), y.maxCoeff(), hwide, opt.grid);
  const Eigen::VectorXd fy = stats::kde_pdf_grid(y, hy, g);
  std::vector<Eigen::Index> order(static_cast<std::size_t>(n));
  for (Eigen::Index j = 0; j < X.cols(); ++j) {
    if (!(X.col(j).maxCoeff() > X.col(j).minCoeff())) continue;
    std::iota(order.begin(), order.end(), Eigen::Index{0});
    std::stable_sort(order.begin(), order.end(), [&](Eigen::Index a, Eigen::Index b) { return X(a, j) < X(b, j); });
    r.delta(j) = delta_of_order(order, y, r.classes, fy, g);
  }
  // Noise floor: classes of a random row order.
  std::iota(order.begin(), order.end(), Eigen::Index{0});
  Rng rng = Rng::derive(opt.seed, "delta/floor");
  for (Eigen::Index i = n - 1; i > 0; --i)
    std::swap(order[static_cast<std::size_t>(i)], order[static_cast<std::size_t>(rng.integer(0, i))]);
  r.floor = delta_of_order(order, y, r.classes, fy, g);
  return r;
}

}  // namespace smi::surrogate::delta
