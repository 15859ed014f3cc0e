// SPDX-License-Identifier: MIT
#include "kernels/improve/overlap_start.hpp"

#include <Eigen/Cholesky>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <tuple>
#include <vector>

#include "kernels/improve/input_derivatives.hpp"
#include "platform/core/descriptive.hpp"

namespace smi::improve {

double moment_mismatch(const StatisticalObjective& obj, const Eigen::VectorXd& theta) {
  const Eigen::MatrixXd Y = obj.predict(theta);
  double s = 0.0;
  for (Eigen::Index j = 0; j < Y.cols(); ++j) {
    const ResponseSpec& r = obj.responses()[static_cast<std::size_t>(j)];
    auto [m, sd] = r.moments();
    if (!(sd > 0.0) || !std::isfinite(sd) || !std::isfinite(m)) continue;
    const double pm = Y.col(j).mean(), ps = std::max(stddev(Y.col(j)), 1e-12 * sd);
    s += std::pow((pm - m) / sd, 2) + std::pow(std::log(ps / sd), 2);
  }
  return s;
}

Eigen::VectorXd moment_residuals(const StatisticalObjective& obj, const Eigen::VectorXd& theta, Eigen::MatrixXd* jacobian, int& runs) {
  const Eigen::Index k = theta.size();
  std::vector<std::pair<double, double>> target;  // measured (mean, sd) per response; sd 0 = skipped
  for (const ResponseSpec& r : obj.responses()) {
    auto [m, sd] = r.moments();
    target.emplace_back(m, (sd > 0.0 && std::isfinite(sd) && std::isfinite(m)) ? sd : 0.0);
  }
  auto residuals = [&](const Eigen::MatrixXd& Y) {
    std::vector<double> r;
    for (Eigen::Index j = 0; j < Y.cols(); ++j) {
      const auto [m, sd] = target[static_cast<std::size_t>(j)];
      if (!(sd > 0.0)) continue;
      r.push_back((Y.col(j).mean() - m) / sd);
      r.push_back(std::log(std::max(stddev(Y.col(j)), 1e-12 * sd) / sd));
    }
    return Eigen::VectorXd(Eigen::Map<Eigen::VectorXd>(r.data(), static_cast<Eigen::Index>(r.size())));
  };
  // With a Jacobian or model differences the predictions come with dY/dX (one model call).
  const bool chain = jacobian && (obj.has_model_jacobian() || obj.has_model_differences());
  Eigen::MatrixXd Y;
  std::vector<Eigen::MatrixXd> J;
  if (chain) std::tie(Y, J) = obj.predict_with_jacobian(theta);
  else Y = obj.predict(theta);
  ++runs;
  const Eigen::VectorXd r = residuals(Y);
  if (!jacobian) return r;
  jacobian->setZero(r.size(), k);
  if (!chain) {
    // Forward differences, 1e-6 of each range (away from the upper bound).
    for (Eigen::Index p = 0; p < k; ++p) {
      const Parameter& par = obj.parameters()[static_cast<std::size_t>(p)];
      const double h = 1e-6 * (par.upper - par.lower) * (theta[p] + 1e-6 * (par.upper - par.lower) <= par.upper ? 1.0 : -1.0);
      Eigen::VectorXd t = theta;
      t[p] += h;
      jacobian->col(p) = (residuals(obj.predict(t)) - r) / h;
      ++runs;
    }
    return r;
  }
  // dr/dθ_p = Σ_i w_i Σ_c J_ic dx_ic/dθ_p with w = 1/(N sd_r) (mean) or (y_i − ȳ)/((N − 1) sd(y)²) (log sd).
  const auto mom = obj.input_moments(theta);
  std::vector<InputDerivatives> dx;
  for (std::size_t c = 0; c < obj.inputs().size(); ++c)
    dx.push_back(input_derivatives(obj.inputs()[c].family, mom[c].first, mom[c].second, obj.crn().col(static_cast<Eigen::Index>(c))));
  const double N = static_cast<double>(Y.rows());
  Eigen::Index row = 0;
  for (Eigen::Index j = 0; j < Y.cols(); ++j) {
    const double sd = target[static_cast<std::size_t>(j)].second;
    if (!(sd > 0.0)) continue;
    const double ps = std::max(stddev(Y.col(j)), 1e-12 * sd);
    const Eigen::VectorXd wm = Eigen::VectorXd::Constant(Y.rows(), 1.0 / (N * sd));
    const Eigen::VectorXd ws = (Y.col(j).array() - Y.col(j).mean()).matrix() / ((N - 1.0) * ps * ps);
    for (std::size_t c = 0; c < obj.inputs().size(); ++c) {
      const InputSpec& in = obj.inputs()[c];
      const Eigen::VectorXd g = J[static_cast<std::size_t>(j)].col(static_cast<Eigen::Index>(c));
      for (int which = 0; which < 2; ++which) {
        const Eigen::VectorXd& w = which == 0 ? wm : ws;
        const Eigen::VectorXd s = g.cwiseProduct(w);
        if (in.mean_param >= 0) (*jacobian)(row + which, in.mean_param) += s.dot(dx[c].dmean);
        if (in.std_param >= 0) (*jacobian)(row + which, in.std_param) += s.dot(dx[c].dstd);
      }
    }
    row += 2;
  }
  return r;
}

namespace {

/// The parameters an LM step at u (scaled position in [0, 1]) may move: all but those on a bound
/// whose descent direction points out of the box.
std::vector<Eigen::Index> free_parameters(const Eigen::VectorXd& u, const Eigen::VectorXd& descent) {
  std::vector<Eigen::Index> free;
  for (Eigen::Index p = 0; p < u.size(); ++p)
    if (!((u[p] <= 1e-12 && descent[p] < 0.0) || (u[p] >= 1.0 - 1e-12 && descent[p] > 0.0))) free.push_back(p);
  return free;
}

/// One damped Gauss-Newton step du in scaled units that stays in the box: (J_fᵀJ_f + λI) du_f =
/// −J_fᵀ r over the free parameters; one the step would carry past a bound stops on it and is held
/// there while the others are solved again with its move in r (at most k passes). Cutting the
/// full step at the bounds instead (projection) left LM crawling along them: trial 2 of the
/// steering column was still at a mismatch of 2.6e-3 after its 30 iterations (5e-13 in 35 model
/// runs this way).
Eigen::VectorXd bounded_step(const Eigen::MatrixXd& Ju, const Eigen::VectorXd& r, const Eigen::VectorXd& u,
                             std::vector<Eigen::Index> free, double lambda) {
  Eigen::VectorXd du = Eigen::VectorXd::Zero(u.size());
  for (Eigen::Index pass = 0; pass <= u.size() && !free.empty(); ++pass) {
    const Eigen::Index nf = static_cast<Eigen::Index>(free.size());
    Eigen::MatrixXd Jf(Ju.rows(), nf);
    for (Eigen::Index i = 0; i < nf; ++i) Jf.col(i) = Ju.col(free[static_cast<std::size_t>(i)]);
    Eigen::VectorXd held = du;  // the moves of the parameters stopped on a bound so far
    for (Eigen::Index p : free) held[p] = 0.0;
    const Eigen::VectorXd rh = r + Ju * held;
    const Eigen::VectorXd df = (Jf.transpose() * Jf + lambda * Eigen::MatrixXd::Identity(nf, nf)).ldlt().solve(-Jf.transpose() * rh);
    std::vector<Eigen::Index> still;
    for (Eigen::Index i = 0; i < nf; ++i) {
      const Eigen::Index p = free[static_cast<std::size_t>(i)];
      const double v = u[p] + df[i];
      du[p] = v < 0.0 ? -u[p] : v > 1.0 ? 1.0 - u[p] : df[i];
      if (v >= 0.0 && v <= 1.0) still.push_back(p);
    }
    if (still.size() == free.size()) break;
    free = std::move(still);
  }
  return du;
}

/// The parameters at scaled position u, one at or past a bound exactly on it.
Eigen::VectorXd point_at(const std::vector<Parameter>& params, const Eigen::VectorXd& u) {
  Eigen::VectorXd t(u.size());
  for (Eigen::Index p = 0; p < u.size(); ++p) {
    const Parameter& q = params[static_cast<std::size_t>(p)];
    t[p] = u[p] <= 0.0 ? q.lower : u[p] >= 1.0 ? q.upper : q.lower + (q.upper - q.lower) * u[p];
  }
  return t;
}

}  // namespace

PreparedStart moment_start(const StatisticalObjective& obj, const Eigen::VectorXd& theta, const MomentStartOptions& opt) {
  PreparedStart out;
  out.theta = theta;
  const std::vector<Parameter>& params = obj.parameters();
  const Eigen::Index k = theta.size();
  Eigen::VectorXd range(k), lower(k);
  for (Eigen::Index p = 0; p < k; ++p) {
    lower[p] = params[static_cast<std::size_t>(p)].lower;
    range[p] = params[static_cast<std::size_t>(p)].upper - lower[p];
  }
  int runs = 0;
  Eigen::VectorXd t = theta;
  Eigen::MatrixXd Jt;
  Eigen::VectorXd r = moment_residuals(obj, t, &Jt, runs);
  if (r.size() == 0) return out;  // no response with a measured sd: nothing to match, no status
  const double start_mismatch = r.squaredNorm();
  out.criterion_before = start_mismatch;
  // why LM stopped: the mismatch at the tolerance, no step in the box lowering it (a constrained
  // minimum: the moments cannot be matched better there), or the iteration budget
  out.status = "max_iterations";
  double lambda = -1.0;
  for (int it = 0; it < opt.max_iterations; ++it) {
    if (r.squaredNorm() <= opt.tolerance) {
      out.status = "tolerance_reached";
      break;
    }
    const Eigen::MatrixXd Ju = Jt * range.asDiagonal();  // scaled units
    const Eigen::VectorXd descent = -Ju.transpose() * r;  // of ½‖r‖²
    const Eigen::VectorXd u = (t - lower).cwiseQuotient(range);
    const std::vector<Eigen::Index> free = free_parameters(u, descent);
    double slope = 0.0;
    for (Eigen::Index p : free) slope = std::max(slope, std::abs(descent[p]));
    // first-order optimality within the box: no free descent left (relative to the residuals)
    if (free.empty() || slope <= 1e-10 * (1.0 + r.squaredNorm())) {
      out.status = "stationary";
      break;
    }
    if (lambda < 0.0) lambda = 1e-3 * std::max(1e-12, Ju.colwise().squaredNorm().maxCoeff());
    bool accepted = false, small = false;
    for (int tries = 0; tries < 12 && !accepted; ++tries) {
      const Eigen::VectorXd du = bounded_step(Ju, r, u, free, lambda);
      if (du.norm() < 1e-12) break;
      const Eigen::VectorXd tn = point_at(params, u + du);
      Eigen::MatrixXd Jn;
      const Eigen::VectorXd rn = moment_residuals(obj, tn, &Jn, runs);
      if (rn.allFinite() && rn.squaredNorm() < r.squaredNorm()) {
        small = r.squaredNorm() - rn.squaredNorm() <= opt.ftol_rel * r.squaredNorm() + opt.ftol_abs;
        t = tn, r = rn, Jt = Jn, accepted = true;
        lambda = std::max(1e-15, lambda / 3.0);
      } else {
        lambda *= 5.0;
      }
    }
    if (!accepted) {
      out.status = "stationary";
      break;
    }
    if (small) {
      out.status = "ftol_reached";
      break;
    }
  }
  if (out.status == "max_iterations" && r.squaredNorm() <= opt.tolerance) out.status = "tolerance_reached";
  out.criterion_after = r.squaredNorm();
  out.evaluations = runs;
  if (t == theta) return out;
  const double before = obj(theta).value, after = obj(t).value;
  out.evaluations += 2;
  if (!(after < before)) return out;
  out.theta = t;
  out.note = fmt::format("moved to a moment-matching start (means and sds of the responses; mismatch {:.3g} -> {:.3g}, objective {:.4g} -> "
                         "{:.4g}, {} model runs)", start_mismatch, r.squaredNorm(), before, after, out.evaluations);
  return out;
}

PreparedStart overlap_start(const StatisticalObjective& obj, const Eigen::VectorXd& theta, const OverlapStartOptions& opt) {
  PreparedStart out;
  out.theta = theta;
  if (obj.options().metric != MetricKind::pr) return out;
  const Evaluation e = obj(theta);
  out.evaluations = 1;
  std::string flat;
  for (Eigen::Index j = 0; j < e.parts.size(); ++j)
    if (e.parts[j] > 2.0 - opt.saturation) flat += fmt::format("{}'{}' {:.3f}", flat.empty() ? "" : ", ", obj.responses()[static_cast<std::size_t>(j)].name, e.parts[j]);
  if (flat.empty()) return out;
  std::vector<Parameter> params = obj.parameters();
  for (std::size_t i = 0; i < params.size(); ++i) params[i].start = theta[static_cast<Eigen::Index>(i)];
  OptimizerOptions oo;
  oo.maxeval = opt.maxeval;
  oo.xtol_rel = 1e-4;
  oo.ftol_abs = 1e-10;
  const OptimizationResult m = minimize(params, [&obj](const Eigen::VectorXd& t) { return Evaluation{moment_mismatch(obj, t), {}}; }, oo);
  const Evaluation after = obj(m.theta);
  out.evaluations += m.evaluations + 1;
  if (!(after.value < e.value)) return out;
  std::string to;
  for (std::size_t i = 0; i < params.size(); ++i) to += fmt::format("{}{} = {:.6g}", i ? ", " : "", params[i].name, m.theta[static_cast<Eigen::Index>(i)]);
  out.theta = m.theta;
  out.note = fmt::format("the predicted and experimental PDFs did not overlap (PR {}: no gradient there); moved to a moment-matching "
                         "start ({}; objective {:.4g} -> {:.4g})", flat, to, e.value, after.value);
  return out;
}

}  // namespace smi::improve
