// SPDX-License-Identifier: MIT
// Prediction on whole blocks of points (spec §4 predictor and MSE):
//   yhat = mY + sY (F_x beta + R_x gamma)                       (GEMM)
//   Rt = C^-1 R_x^T, U = G^-T (Ft^T Rt - F_x^T)                  (TRSM + GEMM)
//   mse = sigma2 sY^2 (1 + |U|^2 - |Rt|^2) per column, clamped at 0.
// Blocks go to the workers as they free up; each writes its own rows only.
#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "kernels/surrogate/fused_mean.hpp"
#include "kernels/surrogate/kriging.hpp"
#include "platform/core/errors.hpp"
#include "platform/core/thread_pool.hpp"

namespace smi::surrogate::kriging {
namespace {

constexpr Eigen::Index kBlock = 128;  // a block's correlations (128 x m) stay in L2 for m ~ 1000

void check_input(const Model& md, const Eigen::MatrixXd& X) {
  if (md.S.size() == 0) throw InvalidArgument("the model is empty (not fitted)");
  if (X.cols() != md.inputs())
    throw DimensionMismatch("points have " + std::to_string(X.cols()) + " columns but the model has " +
                            std::to_string(md.inputs()) + " inputs");
  // A NaN coordinate makes every correlation NaN-free but meaningless (exp of NaN distances
  // was clamped to a finite mean): refuse it, naming the point.
  for (Eigen::Index i = 0; i < X.rows(); ++i)
    for (Eigen::Index j = 0; j < X.cols(); ++j)
      if (!std::isfinite(X(i, j)))
        throw InvalidArgument(fmt::format("point {} input {} is {}: Kriging predicts at finite points only (a NaN "
                                          "usually comes from a failed model run or a missing data cell upstream)",
                                          i + 1, j + 1, std::isnan(X(i, j)) ? "NaN" : fmt::format("{}", X(i, j))));
}

template <class Body>
void blocks(const Eigen::MatrixXd& X, int threads, Body&& body) {
  const Eigen::Index nb = (X.rows() + kBlock - 1) / kBlock;
  pool::parallel_for(static_cast<long>(nb), threads, [&](long b) {
    const Eigen::Index r0 = b * kBlock, nr = std::min(kBlock, X.rows() - r0);
    body(r0, nr);
  });
}

/// Rows r0 .. r0+nr-1 of X in the model's normalised units.
Eigen::MatrixXd normalised(const Model& md, const Eigen::MatrixXd& X, Eigen::Index r0, Eigen::Index nr) {
  return (X.middleRows(r0, nr).rowwise() - md.mS).array().rowwise() / md.sS.array();
}

/// The predicted mean of a block, one kernel for predict_mean and predict so that both give the
/// same numbers: the Gaussian family by the fused kernel where the CPU has it (fused_mean.hpp:
/// no correlation matrix), any other by R_x gamma (R_x computed here unless given).
class Mean {
 public:
  explicit Mean(const Model& md) : md_(md), fused_(md.corr == Corr::gauss && detail::fused_gauss_available()) {
    if (!fused_) return;
    w_ = md.theta.cwiseSqrt().transpose();
    Sw_ = md.S.array().rowwise() * w_.array();
  }
  Eigen::VectorXd operator()(const Eigen::MatrixXd& Xn, const Eigen::MatrixXd& Fx, const Eigen::MatrixXd* Rx = nullptr) const {
    Eigen::VectorXd r(Xn.rows());
    if (fused_) {
      const Eigen::MatrixXd Xw = Xn.array().rowwise() * w_.array();
      detail::fused_gauss_sum(Xw, Sw_, md_.gamma, r.data());
    } else if (Rx) {
      r.noalias() = *Rx * md_.gamma;
    } else {
      r.noalias() = cross_correlation(md_.corr, md_.theta, Xn, md_.S) * md_.gamma;
    }
    return (md_.mY + md_.sY * (Fx * md_.beta + r).array()).matrix();
  }

 private:
  const Model& md_;
  bool fused_;
  Eigen::RowVectorXd w_;
  detail::RowMatrix Sw_;
};

}  // namespace

Eigen::VectorXd predict_mean(const Model& md, const Eigen::MatrixXd& X, int threads) {
  check_input(md, X);
  const Mean mean_of(md);
  Eigen::VectorXd mean(X.rows());
  blocks(X, threads, [&](Eigen::Index r0, Eigen::Index nr) {
    const Eigen::MatrixXd Xn = normalised(md, X, r0, nr);
    mean.segment(r0, nr) = mean_of(Xn, trend_basis(md.trend, Xn));
  });
  return mean;
}

Prediction predict(const Model& md, const Eigen::MatrixXd& X, int threads) {
  check_input(md, X);
  Prediction out;
  out.mean.resize(X.rows());
  out.mse.resize(X.rows());
  const double s2 = md.process_variance();
  const Mean mean_of(md);
  blocks(X, threads, [&](Eigen::Index r0, Eigen::Index nr) {
    const Eigen::MatrixXd Xn = normalised(md, X, r0, nr);
    const Eigen::MatrixXd Rx = cross_correlation(md.corr, md.theta, Xn, md.S);
    const Eigen::MatrixXd Fx = trend_basis(md.trend, Xn);
    out.mean.segment(r0, nr) = mean_of(Xn, Fx, &Rx);
    Eigen::MatrixXd Rt = Rx.transpose();
    md.C.triangularView<Eigen::Lower>().solveInPlace(Rt);
    Eigen::MatrixXd U = md.Ft.transpose() * Rt - Fx.transpose();
    md.G.transpose().triangularView<Eigen::Lower>().solveInPlace(U);
    const Eigen::ArrayXd v = 1.0 + U.colwise().squaredNorm().array() - Rt.colwise().squaredNorm().array();
    out.mse.segment(r0, nr) = (s2 * v.max(0.0)).matrix();
  });
  return out;
}

}  // namespace smi::surrogate::kriging
