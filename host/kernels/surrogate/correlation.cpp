// SPDX-License-Identifier: MIT
// Correlation families and their slopes; cross correlations on whole blocks of points.
#include "kernels/surrogate/correlation.hpp"

#include <cmath>

#include "kernels/surrogate/fast_exp.hpp"
#include "platform/core/errors.hpp"

namespace smi::surrogate::kriging {

Corr parse_corr(const std::string& name) {
  if (name == "gauss" || name == "corrgauss") return Corr::gauss;
  if (name == "exp" || name == "correxp") return Corr::exp;
  if (name == "matern32") return Corr::matern32;
  if (name == "matern52") return Corr::matern52;
  throw InvalidArgument("unknown corr '" + name + "' (use \"gauss\", \"exp\", \"matern32\" or \"matern52\")");
}

const char* corr_name(Corr c) {
  switch (c) {
    case Corr::gauss: return "gauss";
    case Corr::exp: return "exp";
    case Corr::matern32: return "matern32";
    case Corr::matern52: return "matern52";
  }
  return "?";
}

void corr_from_s(Corr c, Eigen::Ref<Eigen::ArrayXd> s) {
  switch (c) {
    case Corr::gauss:
    case Corr::exp:
      exp_neg_inplace(s.data(), static_cast<long>(s.size()));
      return;
    case Corr::matern32: {
      const Eigen::ArrayXd h = std::sqrt(3.0) * s.max(0.0).sqrt();
      s = (1.0 + h) * (-h).exp();
      return;
    }
    case Corr::matern52: {
      const Eigen::ArrayXd h = std::sqrt(5.0) * s.max(0.0).sqrt();
      s = (1.0 + h + h.square() / 3.0) * (-h).exp();
      return;
    }
  }
}

void corr_slope(Corr c, const Eigen::ArrayXd& s, Eigen::ArrayXd& out) {
  switch (c) {
    case Corr::gauss:
    case Corr::exp:  // -e^{-s}, by the vectorized exponential (Eigen's is SSE2-only here)
      out = s;
      exp_neg_inplace(out.data(), static_cast<long>(out.size()));
      out = -out;
      return;
    case Corr::matern32:  // d/ds (1+sqrt(3s)) e^{-sqrt(3s)} = -1.5 e^{-sqrt(3s)}
      out = -1.5 * (-(3.0 * s.max(0.0)).sqrt()).exp();
      return;
    case Corr::matern52: {  // = -(5/6)(1 + sqrt(5s)) e^{-sqrt(5s)}
      const Eigen::ArrayXd h = (5.0 * s.max(0.0)).sqrt();
      out = -(5.0 / 6.0) * (1.0 + h) * (-h).exp();
      return;
    }
  }
}

Eigen::MatrixXd cross_correlation(Corr c, const Eigen::VectorXd& theta, const Eigen::MatrixXd& X,
                                  const Eigen::MatrixXd& S) {
  if (X.cols() != S.cols() || theta.size() != S.cols())
    throw DimensionMismatch("cross_correlation: points have " + std::to_string(X.cols()) + " columns, model " +
                            std::to_string(S.cols()));
  Eigen::MatrixXd s(X.rows(), S.rows());
  if (uses_abs(c)) {
    s.setZero();
    for (Eigen::Index j = 0; j < S.cols(); ++j)
      for (Eigen::Index k = 0; k < S.rows(); ++k)
        s.col(k).array() += theta[j] * (X.col(j).array() - S(k, j)).abs();
  } else {
    // sum theta_j (x_j - s_j)^2 = |x~|^2 + |s~|^2 - 2 x~.s~ with x~ = x sqrt(theta): one GEMM.
    const Eigen::RowVectorXd w = theta.cwiseSqrt().transpose();
    const Eigen::MatrixXd Xw = X.array().rowwise() * w.array();
    const Eigen::MatrixXd Sw = S.array().rowwise() * w.array();
    s.noalias() = -2.0 * Xw * Sw.transpose();
    const Eigen::ArrayXd xx = Xw.rowwise().squaredNorm().array();
    const Eigen::RowVectorXd ss = Sw.rowwise().squaredNorm().transpose();
    if (c == Corr::gauss) {  // one fused pass: add the norms, clamp, exponentiate
      for (Eigen::Index k = 0; k < s.cols(); ++k) {
        s.col(k).array() += xx + ss[k];
        exp_neg_inplace(s.col(k).data(), static_cast<long>(s.rows()));  // clamps s < 0 to 0
      }
      return s;
    }
    s.array().colwise() += xx;
    s.rowwise() += ss;
    s = s.cwiseMax(0.0);
  }
  Eigen::Map<Eigen::ArrayXd> flat(s.data(), s.size());
  corr_from_s(c, flat);
  return s;
}

}  // namespace smi::surrogate::kriging
