// SPDX-License-Identifier: MIT
// Gradient of the Kriging predictor with respect to its inputs, in closed form (for the
// gradients of a calibration objective through the surrogate). With x~ = (x − mS)/sS,
//   yhat = mY + sY (f(x~)' beta + Σ_l gamma_l g(s_l)),  s_l = Σ_d theta_d D_d(x~_d − S_ld)
// so d yhat / d x_d = sY / sS_d (d f/d x~_d ' beta + theta_d Σ_l gamma_l g'(s_l) D_d'(x~_d − S_ld)),
// D_d' = 2 (x~_d − S_ld) for the squared families, sign(x~_d − S_ld) for exp. Blocks of points
// share GEMMs as in prediction.
#include <algorithm>

#include "kernels/surrogate/kriging.hpp"
#include "platform/core/errors.hpp"
#include "platform/core/thread_pool.hpp"

namespace smi::surrogate::kriging {
namespace {

constexpr Eigen::Index kGradientBlock = 128;

/// d f(x~)' beta / d x~ for a block (B x n).
Eigen::MatrixXd trend_gradient(Trend t, const Eigen::MatrixXd& Xn, const Eigen::VectorXd& beta) {
  const Eigen::Index B = Xn.rows(), n = Xn.cols();
  Eigen::MatrixXd G = Eigen::MatrixXd::Zero(B, n);
  if (t == Trend::constant) return G;
  for (Eigen::Index d = 0; d < n; ++d) G.col(d).setConstant(beta[1 + d]);
  if (t == Trend::linear) return G;
  Eigen::Index c = n + 1;  // DACE's order: x_k x_l for k <= l
  for (Eigen::Index k = 0; k < n; ++k)
    for (Eigen::Index l = k; l < n; ++l, ++c) {
      if (k == l) {
        G.col(k) += 2.0 * beta[c] * Xn.col(k);
      } else {
        G.col(k) += beta[c] * Xn.col(l);
        G.col(l) += beta[c] * Xn.col(k);
      }
    }
  return G;
}

}  // namespace

Eigen::MatrixXd predict_gradient(const Model& md, const Eigen::MatrixXd& X, int threads) {
  if (md.S.size() == 0) throw InvalidArgument("the model is empty (not fitted)");
  const Eigen::Index n = md.inputs(), m = md.size();
  if (X.cols() != n)
    throw DimensionMismatch("points have " + std::to_string(X.cols()) + " columns but the model has " + std::to_string(n) + " inputs");
  const Eigen::VectorXd theta = md.theta.size() == 1 ? Eigen::VectorXd::Constant(n, md.theta[0]) : md.theta;
  Eigen::MatrixXd out(X.rows(), n);
  const Eigen::Index nb = (X.rows() + kGradientBlock - 1) / kGradientBlock;
  pool::parallel_for(static_cast<long>(nb), threads, [&](long b) {
    const Eigen::Index r0 = b * kGradientBlock, B = std::min(kGradientBlock, X.rows() - r0);
    const Eigen::MatrixXd Xn = (X.middleRows(r0, B).rowwise() - md.mS).array().rowwise() / md.sS.array();
    // s (B x m) as in cross_correlation, then g'(s) weighted by gamma.
    Eigen::MatrixXd s(B, m);
    if (uses_abs(md.corr)) {
      s.setZero();
      for (Eigen::Index d = 0; d < n; ++d)
        for (Eigen::Index l = 0; l < m; ++l) s.col(l).array() += theta[d] * (Xn.col(d).array() - md.S(l, d)).abs();
    } else {
      const Eigen::RowVectorXd w = theta.cwiseSqrt().transpose();
      const Eigen::MatrixXd Xw = Xn.array().rowwise() * w.array(), Sw = md.S.array().rowwise() * w.array();
      s.noalias() = -2.0 * Xw * Sw.transpose();
      s.array().colwise() += Xw.rowwise().squaredNorm().array();
      s.rowwise() += Sw.rowwise().squaredNorm().transpose();
      s = s.cwiseMax(0.0);
    }
    Eigen::ArrayXd flat = Eigen::Map<const Eigen::ArrayXd>(s.data(), s.size()), slope;
    corr_slope(md.corr, flat, slope);
    Eigen::MatrixXd W = Eigen::Map<const Eigen::MatrixXd>(slope.data(), B, m);
    W = W * md.gamma.asDiagonal();  // gamma_l g'(s_l)
    Eigen::MatrixXd G = trend_gradient(md.trend, Xn, md.beta);
    if (uses_abs(md.corr)) {
      for (Eigen::Index d = 0; d < n; ++d)
        for (Eigen::Index l = 0; l < m; ++l)
          G.col(d).array() += theta[d] * W.col(l).array() * (Xn.col(d).array() - md.S(l, d)).sign();
    } else {
      const Eigen::VectorXd wsum = W.rowwise().sum();
      const Eigen::MatrixXd WS = W * md.S;  // B x n
      for (Eigen::Index d = 0; d < n; ++d) G.col(d) += 2.0 * theta[d] * (Xn.col(d).cwiseProduct(wsum) - WS.col(d));
    }
    out.middleRows(r0, B) = (G.array().rowwise() * (md.sY / md.sS.array())).matrix();
  });
  return out;
}

}  // namespace smi::surrogate::kriging
