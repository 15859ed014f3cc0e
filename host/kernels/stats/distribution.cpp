// SPDX-License-Identifier: MIT
#include "kernels/stats/distribution.hpp"

#include <cmath>

namespace smi::stats {

double Distribution::logpdf(double x) const { return std::log(pdf(x)); }
double Distribution::logcdf(double x) const {
  // Above the median log(1 − sf) keeps the precision that rounding cdf to 1 − sf would lose.
  const double c = cdf(x);
  return c > 0.5 ? std::log1p(-sf(x)) : std::log(c);
}
double Distribution::sf(double x) const { return 1.0 - cdf(x); }
double Distribution::isf(double q) const { return quantile(1.0 - q); }

Eigen::VectorXd Distribution::pdf(const Eigen::VectorXd& x) const {
  Eigen::VectorXd y(x.size());
  for (Eigen::Index i = 0; i < x.size(); ++i) y[i] = pdf(x[i]);
  return y;
}

Eigen::VectorXd Distribution::cdf(const Eigen::VectorXd& x) const {
  Eigen::VectorXd y(x.size());
  for (Eigen::Index i = 0; i < x.size(); ++i) y[i] = cdf(x[i]);
  return y;
}

Eigen::VectorXd Distribution::quantile(const Eigen::VectorXd& p) const {
  Eigen::VectorXd y(p.size());
  for (Eigen::Index i = 0; i < p.size(); ++i) y[i] = quantile(p[i]);
  return y;
}

Eigen::VectorXd Distribution::sample(Rng& rng, Eigen::Index n) const {
  Eigen::VectorXd y(n);
  for (Eigen::Index i = 0; i < n; ++i) y[i] = quantile(rng.uniform01());
  return y;
}

}  // namespace smi::stats
