// SPDX-License-Identifier: MIT
// Polynomial trend bases in DACE's column order.
#include "kernels/surrogate/regression.hpp"

#include "platform/core/errors.hpp"

namespace smi::surrogate::kriging {

Trend parse_trend(const std::string& name) {
  if (name == "constant" || name == "regpoly0") return Trend::constant;
  if (name == "linear" || name == "regpoly1") return Trend::linear;
  if (name == "quadratic" || name == "regpoly2") return Trend::quadratic;
  throw InvalidArgument("unknown trend '" + name + "' (use \"constant\", \"linear\" or \"quadratic\")");
}

const char* trend_name(Trend t) {
  switch (t) {
    case Trend::constant: return "constant";
    case Trend::linear: return "linear";
    case Trend::quadratic: return "quadratic";
  }
  return "?";
}

Eigen::Index trend_size(Trend t, Eigen::Index n) {
  switch (t) {
    case Trend::constant: return 1;
    case Trend::linear: return n + 1;
    case Trend::quadratic: return (n + 1) * (n + 2) / 2;
  }
  return 1;
}

Eigen::MatrixXd trend_basis(Trend t, const Eigen::MatrixXd& X) {
  const Eigen::Index m = X.rows(), n = X.cols();
  Eigen::MatrixXd F(m, trend_size(t, n));
  F.col(0).setOnes();
  if (t == Trend::constant) return F;
  F.middleCols(1, n) = X;
  if (t == Trend::linear) return F;
  Eigen::Index c = n + 1;
  for (Eigen::Index k = 0; k < n; ++k)
    for (Eigen::Index l = k; l < n; ++l) F.col(c++) = X.col(k).cwiseProduct(X.col(l));
  return F;
}

}  // namespace smi::surrogate::kriging
