// SPDX-License-Identifier: MIT
// Sequential Kriging designs: the greedy batch choice by weighted Kriging variance, and the loop
// that fits, checks the leave-one-out targets and asks the model for the next batch.
#include "kernels/surrogate/sequential_design.hpp"

#include <Eigen/Cholesky>
#include <fmt/format.h>
#include <cmath>
#include <limits>
#include <string>

#include "kernels/surrogate/correlation.hpp"
#include "platform/core/errors.hpp"

namespace smi::surrogate::kriging {

namespace {

// Kriging variance ratio 1 - r' R^-1 r at the rows of C (normalised units) given the design D.
// The small diagonal term keeps R factorisable when picks come close; the ratio is only compared.
Eigen::VectorXd variance_ratio(const Model& m, const Eigen::MatrixXd& D, const Eigen::MatrixXd& C) {
  Eigen::MatrixXd R = cross_correlation(m.corr, m.theta, D, D);
  R.diagonal().array() += 1e-10 + m.nugget;
  const Eigen::LLT<Eigen::MatrixXd> llt(R);
  if (llt.info() != Eigen::Success) throw InvalidArgument("select_batch: the design's correlation matrix is not positive definite");
  Eigen::MatrixXd Rt = cross_correlation(m.corr, m.theta, C, D).transpose();  // n x c
  llt.matrixL().solveInPlace(Rt);
  return (1.0 - Rt.colwise().squaredNorm().array()).max(0.0).matrix();
}

Eigen::MatrixXd normalised(const Model& m, const Eigen::MatrixXd& X) {
  return (X.rowwise() - m.mS).array().rowwise() / m.sS.array();
}

// The weights before the first model run (a solver study pays for that run; select_batch
// would only see them after it).
void check_weights(const Eigen::MatrixXd& candidates, const Eigen::VectorXd& weights) {
  if (weights.size() != candidates.rows())
    throw DimensionMismatch("sequential_design: " + std::to_string(weights.size()) + " weights for " +
                            std::to_string(candidates.rows()) + " candidates");
  for (Eigen::Index i = 0; i < weights.size(); ++i)
    if (!std::isfinite(weights(i)))
      throw InvalidArgument("sequential_design: weight " + std::to_string(i + 1) + " is not finite");
}

// The model's outputs Y at the design X are finite; else the first culprit is named by its
// design point and output (the fix is at that run of the model).
void check_finite(const Eigen::MatrixXd& X, const Eigen::MatrixXd& Y) {
  for (Eigen::Index i = 0; i < Y.rows(); ++i)
    for (Eigen::Index j = 0; j < Y.cols(); ++j) {
      if (std::isfinite(Y(i, j))) continue;
      std::string x;
      for (Eigen::Index c = 0; c < X.cols(); ++c) x += (c ? ", " : "") + fmt::format("{}", X(i, c));
      throw InvalidArgument(fmt::format("sequential_design: the model returned {} for output {} at design point {} ({}); "
                                        "it must return finite values",
                                        Y(i, j), j + 1, i + 1, x));
    }
}

}  // namespace

std::vector<Eigen::Index> select_batch(const std::vector<const Model*>& models, const Eigen::MatrixXd& candidates,
                                       const Eigen::VectorXd& weights, Eigen::Index batch) {
  if (models.empty()) throw InvalidArgument("select_batch: no model");
  const Model& first = *models.front();
  if (candidates.cols() != first.inputs())
    throw DimensionMismatch("select_batch: candidates have " + std::to_string(candidates.cols()) + " columns, the models " +
                            std::to_string(first.inputs()) + " inputs");
  if (weights.size() != candidates.rows())
    throw DimensionMismatch("select_batch: " + std::to_string(weights.size()) + " weights for " +
                            std::to_string(candidates.rows()) + " candidates");
  for (const Model* m : models)
    if (m->size() != first.size() || m->inputs() != first.inputs() || !(m->mS.isApprox(first.mS)) || !(m->sS.isApprox(first.sS)))
      throw InvalidArgument("select_batch: the models must be fitted on one design");
  Eigen::Index usable = 0;
  for (Eigen::Index i = 0; i < weights.size(); ++i) {
    if (!std::isfinite(weights(i))) throw InvalidArgument("select_batch: weight " + std::to_string(i + 1) + " is not finite");
    usable += weights(i) > 0;
  }
  if (batch < 1 || batch > usable)
    throw InvalidArgument("select_batch: batch " + std::to_string(batch) + " with " + std::to_string(usable) +
                          " candidates of positive weight");
  const Eigen::MatrixXd C = normalised(first, candidates);
  Eigen::MatrixXd D = first.S;
  Eigen::VectorXd w = weights;
  std::vector<Eigen::Index> picked;
  for (Eigen::Index b = 0; b < batch; ++b) {
    Eigen::VectorXd v = Eigen::VectorXd::Zero(C.rows());
    for (const Model* m : models) v = v.cwiseMax(variance_ratio(*m, D, C));
    Eigen::Index best = -1;
    double best_score = -1;
    for (Eigen::Index i = 0; i < C.rows(); ++i)
      if (w(i) > 0 && w(i) * v(i) > best_score) best_score = w(i) * v(i), best = i;
    picked.push_back(best);
    w(best) = 0;  // never twice
    D.conservativeResize(D.rows() + 1, Eigen::NoChange);
    D.row(D.rows() - 1) = C.row(best);
  }
  return picked;
}

SequentialResult sequential_design(const Eigen::MatrixXd& initial, const Eigen::MatrixXd& candidates,
                                   const Eigen::VectorXd& weights, const DesignModel& model,
                                   const SequentialOptions& opt) {
  if (initial.rows() < 2) throw InvalidArgument("sequential_design: the initial design needs at least 2 points, got " + std::to_string(initial.rows()));
  if (opt.batch < 1) throw InvalidArgument("sequential_design: batch must be >= 1, got " + std::to_string(opt.batch));
  if (opt.max_points < initial.rows())
    throw InvalidArgument("sequential_design: max_points " + std::to_string(opt.max_points) + " is below the initial design's " +
                          std::to_string(initial.rows()) + " points");
  if (candidates.cols() != initial.cols())
    throw DimensionMismatch("sequential_design: candidates have " + std::to_string(candidates.cols()) + " columns, the design " +
                            std::to_string(initial.cols()));
  check_weights(candidates, weights);
  SequentialResult r;
  r.X = initial;
  r.Y = model(initial);
  if (r.Y.rows() != initial.rows() || r.Y.cols() < 1)
    throw DimensionMismatch("sequential_design: the model returned " + std::to_string(r.Y.rows()) + " rows for " +
                            std::to_string(initial.rows()) + " points");
  if (opt.rmse_target.size() != 0 && opt.rmse_target.size() != r.Y.cols())
    throw DimensionMismatch("sequential_design: " + std::to_string(opt.rmse_target.size()) + " RMSE targets for " +
                            std::to_string(r.Y.cols()) + " outputs");
  Eigen::VectorXd w = weights;
  for (;;) {
    check_finite(r.X, r.Y);
    r.models.clear();
    SequentialStep step;
    step.points = r.X.rows();
    step.q2.resize(r.Y.cols());
    step.rmse.resize(r.Y.cols());
    bool met = true;
    for (Eigen::Index j = 0; j < r.Y.cols(); ++j) {
      r.models.push_back(fit(r.X, r.Y.col(j), opt.fit));
      const LooResult l = loo(r.models.back());
      step.q2(j) = l.q2;
      step.rmse(j) = l.rmse;
      met = met && l.q2 >= opt.q2_target;
      if (opt.rmse_target.size() > 0 && std::isfinite(opt.rmse_target(j))) met = met && l.rmse <= opt.rmse_target(j);
    }
    r.history.push_back(step);
    if (met) {
      r.reached = true;
      r.stop = "the leave-one-out targets are met at " + std::to_string(r.X.rows()) + " points";
      break;
    }
    const Eigen::Index room = opt.max_points - r.X.rows();
    const Eigen::Index left = (w.array() > 0).count();
    if (room <= 0 || left == 0) {
      r.stop = room <= 0 ? "max_points (" + std::to_string(opt.max_points) + ") reached before the targets"
                         : "no candidate left before the targets";
      break;
    }
    std::vector<const Model*> ms;
    for (const Model& m : r.models) ms.push_back(&m);
    const std::vector<Eigen::Index> idx = select_batch(ms, candidates, w, std::min({opt.batch, room, left}));
    Eigen::MatrixXd Xn(static_cast<Eigen::Index>(idx.size()), r.X.cols());
    for (std::size_t i = 0; i < idx.size(); ++i) {
      Xn.row(static_cast<Eigen::Index>(i)) = candidates.row(idx[i]);
      w(idx[i]) = 0;
    }
    const Eigen::MatrixXd Yn = model(Xn);
    if (Yn.rows() != Xn.rows() || Yn.cols() != r.Y.cols())
      throw DimensionMismatch("sequential_design: the model returned " + std::to_string(Yn.rows()) + " x " + std::to_string(Yn.cols()) +
                              " for a batch of " + std::to_string(Xn.rows()) + " points and " + std::to_string(r.Y.cols()) + " outputs");
    r.X.conservativeResize(r.X.rows() + Xn.rows(), Eigen::NoChange);
    r.X.bottomRows(Xn.rows()) = Xn;
    r.Y.conservativeResize(r.Y.rows() + Yn.rows(), Eigen::NoChange);
    r.Y.bottomRows(Yn.rows()) = Yn;
  }
  return r;
}

}  // namespace smi::surrogate::kriging
