// Prediction on whole blocks of points (spec §4 predictor and MSE):
//   yhat = mY + sY (F_x beta + R_x gamma)                       (GEMM)
//   Rt = C^-1 R_x^T, U = G^-T (Ft^T Rt - F_x^T)                  (TRSM + GEMM)
//   mse = sigma2 sY^2 (1 + |U|^2 - |Rt|^2) per column, clamped at 0.
// Blocks go to the workers by stride; each writes its own rows only.
#include <algorithm>

#include "core/errors.hpp"
#include "surrogate/fused_mean.hpp"
#include "surrogate/kriging.hpp"
#include "surrogate/parallel.hpp"

namespace smi::kriging {
namespace {

constexpr Eigen::Index kBlock = 128;  // a block's correlations (128 x m) stay in L2 for m ~ 1000

void check_input(const Model& md, const Eigen::MatrixXd& X) {
  if (md.S.size() == 0) throw InvalidArgument("the model is empty (not fitted)");
  if (X.cols() != md.inputs())
    throw DimensionMismatch("points have " + std::to_string(X.cols()) + " columns but the model has " +
                            std::to_string(md.inputs()) + " inputs");
}

template <class Body>
void blocks(const Eigen::MatrixXd& X, int threads, Body&& body) {
  const Eigen::Index nb = (X.rows() + kBlock - 1) / kBlock;
  smi::detail::parallel_for(static_cast<long>(nb), threads, [&](long b) {
    const Eigen::Index r0 = b * kBlock, nr = std::min(kBlock, X.rows() - r0);
    body(r0, nr);
  });
}

}  // namespace

namespace {
/// Mean for the Gaussian family by the fused kernel (fused_mean.hpp): no correlation matrix.
Eigen::VectorXd predict_mean_fused(const Model& md, const Eigen::MatrixXd& X, int threads) {
  Eigen::VectorXd mean(X.rows());
  const Eigen::RowVectorXd w = md.theta.cwiseSqrt().transpose();
  const detail::RowMatrix Sw = md.S.array().rowwise() * w.array();
  blocks(X, threads, [&](Eigen::Index r0, Eigen::Index nr) {
    const Eigen::MatrixXd Xn = (X.middleRows(r0, nr).rowwise() - md.mS).array().rowwise() / md.sS.array();
    const Eigen::MatrixXd Xw = Xn.array().rowwise() * w.array();
    Eigen::VectorXd r(nr);
    detail::fused_gauss_sum(Xw, Sw, md.gamma, r.data());
    const Eigen::MatrixXd Fx = trend_basis(md.trend, Xn);
    mean.segment(r0, nr) = (md.mY + md.sY * (Fx * md.beta + r).array()).matrix();
  });
  return mean;
}
}  // namespace

Eigen::VectorXd predict_mean(const Model& md, const Eigen::MatrixXd& X, int threads) {
  check_input(md, X);
  if (md.corr == Corr::gauss && detail::fused_gauss_available()) return predict_mean_fused(md, X, threads);
  Eigen::VectorXd mean(X.rows());
  blocks(X, threads, [&](Eigen::Index r0, Eigen::Index nr) {
    const Eigen::MatrixXd Xn = (X.middleRows(r0, nr).rowwise() - md.mS).array().rowwise() / md.sS.array();
    const Eigen::MatrixXd Rx = cross_correlation(md.corr, md.theta, Xn, md.S);
    const Eigen::MatrixXd Fx = trend_basis(md.trend, Xn);
    mean.segment(r0, nr) = (md.mY + md.sY * (Fx * md.beta + Rx * md.gamma).array()).matrix();
  });
  return mean;
}

Prediction predict(const Model& md, const Eigen::MatrixXd& X, int threads) {
  check_input(md, X);
  Prediction out;
  out.mean.resize(X.rows());
  out.mse.resize(X.rows());
  const double s2 = md.process_variance();
  // The mean by the same kernel as predict_mean, so that both give the same numbers.
  const bool fused = md.corr == Corr::gauss && detail::fused_gauss_available();
  const Eigen::RowVectorXd w = md.theta.cwiseSqrt().transpose();
  const detail::RowMatrix Sw = md.S.array().rowwise() * w.array();
  blocks(X, threads, [&](Eigen::Index r0, Eigen::Index nr) {
    const Eigen::MatrixXd Xn = (X.middleRows(r0, nr).rowwise() - md.mS).array().rowwise() / md.sS.array();
    const Eigen::MatrixXd Rx = cross_correlation(md.corr, md.theta, Xn, md.S);
    const Eigen::MatrixXd Fx = trend_basis(md.trend, Xn);
    Eigen::VectorXd r(nr);
    if (fused) {
      const Eigen::MatrixXd Xw = Xn.array().rowwise() * w.array();
      detail::fused_gauss_sum(Xw, Sw, md.gamma, r.data());
    } else {
      r.noalias() = Rx * md.gamma;
    }
    out.mean.segment(r0, nr) = (md.mY + md.sY * (Fx * md.beta + r).array()).matrix();
    Eigen::MatrixXd Rt = Rx.transpose();
    md.C.triangularView<Eigen::Lower>().solveInPlace(Rt);
    Eigen::MatrixXd U = md.Ft.transpose() * Rt - Fx.transpose();
    md.G.transpose().triangularView<Eigen::Lower>().solveInPlace(U);
    const Eigen::ArrayXd v = 1.0 + U.colwise().squaredNorm().array() - Rt.colwise().squaredNorm().array();
    out.mse.segment(r0, nr) = (s2 * v.max(0.0)).matrix();
  });
  return out;
}

}  // namespace smi::kriging
