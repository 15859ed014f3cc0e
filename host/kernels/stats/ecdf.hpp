// SPDX-License-Identifier: MIT
#pragma once
// The empirical distribution of a sample: CDF steps i/n (right-continuous), quantile the
// smallest x with S_n(x) >= p (type 1), sampling = bootstrap. It has no density: pdf() throws
// (use a KDE for densities).
#include "kernels/stats/distribution.hpp"

namespace smi::stats {

class Ecdf : public Distribution {
 public:
  /// Data finite, at least 1 point.
  explicit Ecdf(Eigen::VectorXd data);
  std::string describe() const override;
  std::string family() const override { return "ecdf"; }
  /// Throws InvalidArgument: an ECDF has no density.
  double pdf(double x) const override;
  double cdf(double x) const override;
  double quantile(double p) const override;
  double mean() const override;
  /// Sample std (divisor n−1; 0 for one point).
  double stddev() const override;
  std::pair<double, double> support() const override { return {t_[0], t_[t_.size() - 1]}; }
  Eigen::VectorXd cdf(const Eigen::VectorXd& x) const override;
  Eigen::VectorXd sample(Rng& rng, Eigen::Index n) const override;
  std::optional<double> field(std::string_view name) const override;
  /// Sorted data.
  const Eigen::VectorXd& data() const { return t_; }
  /// Plot series of the step function: x = (t1, t1, t2, t2, ...), y = (0, 1/n, 1/n, 2/n, ...).
  void steps(Eigen::VectorXd& x, Eigen::VectorXd& y) const;

 private:
  Eigen::VectorXd t_;
};

}  // namespace smi::stats
