#include "stats/distribution.hpp"

namespace smi {

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

}  // namespace smi
