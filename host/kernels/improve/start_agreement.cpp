// SPDX-License-Identifier: MIT
#include "kernels/improve/start_agreement.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "platform/core/errors.hpp"

namespace smi::improve {

namespace {

/// The path's interior fractions, middle first: a single ridge between two basins is found by
/// the first evaluations, and the walk stops there.
std::vector<double> middle_first(int m) {
  std::vector<int> i(static_cast<std::size_t>(m));
  std::iota(i.begin(), i.end(), 1);
  const double mid = 0.5 * (m + 1);
  std::stable_sort(i.begin(), i.end(), [mid](int a, int b) { return std::abs(a - mid) < std::abs(b - mid); });
  std::vector<double> t;
  for (int j : i) t.push_back(static_cast<double>(j) / (m + 1));
  return t;
}

/// Largest |a - b| / resolution.
double prediction_distance(const Eigen::VectorXd& a, const Eigen::VectorXd& b, const Eigen::VectorXd& resolution) {
  if (a.size() != resolution.size() || b.size() != resolution.size())
    throw DimensionMismatch(fmt::format("start agreement: {} summaries for {} resolutions", a.size(), resolution.size()));
  return ((a - b).array().abs() / resolution.array()).maxCoeff();
}

/// The largest objective on the straight path from the best point to θ, minus the best's; stops at
/// the first point above the tolerance.
double path_barrier(const std::vector<Parameter>& params, const Objective& f, const OptimizationResult& res, const Eigen::VectorXd& theta,
                    double tolerance, const std::vector<double>& fractions, std::size_t s, int& evaluations) {
  double barrier = 0.0;
  for (double t : fractions) {
    Eigen::VectorXd th = res.theta + t * (theta - res.theta);
    for (Eigen::Index i = 0; i < th.size(); ++i)
      th[i] = std::clamp(th[i], params[static_cast<std::size_t>(i)].lower, params[static_cast<std::size_t>(i)].upper);
    const double v = f(th).value;
    ++evaluations;
    if (!std::isfinite(v)) throw InvalidArgument(fmt::format("start agreement: the objective returned {} on the path of start {}", v, s + 1));
    barrier = std::max(barrier, v - res.value);
    if (barrier > tolerance) break;
  }
  return barrier;
}

}  // namespace

StartAgreement start_agreement(const std::vector<Parameter>& params, const Objective& f, const OptimizationResult& res, double tolerance,
                               const PredictionCheck& predictions, int path_points) {
  if (!(tolerance >= 0.0) || !std::isfinite(tolerance))
    throw InvalidArgument(fmt::format("start agreement: tolerance must be a finite number >= 0, got {}", tolerance));
  if (path_points < 1) throw InvalidArgument(fmt::format("start agreement: path_points must be >= 1, got {}", path_points));
  if (res.starts.empty()) throw InvalidArgument("start agreement: the result has no starts");
  if (res.best < 0 || res.best >= static_cast<int>(res.starts.size()))
    throw InvalidArgument(fmt::format("start agreement: best start {} is not one of the {} starts", res.best, res.starts.size()));
  if (predictions.summaries && !(predictions.resolution.array() > 0.0).all())
    throw InvalidArgument("start agreement: every prediction resolution must be > 0");
  StartAgreement a;
  a.tolerance = tolerance;
  a.path_points = path_points;
  const bool predict = static_cast<bool>(predictions.summaries);
  if (!predict) a.largest_prediction_distance = std::numeric_limits<double>::quiet_NaN();
  const std::size_t best = static_cast<std::size_t>(res.best);
  const std::vector<double> fractions = middle_first(path_points);
  Eigen::VectorXd best_summary;
  for (std::size_t s = 0; s < res.starts.size(); ++s) {
    const StartResult& st = res.starts[s];
    StartAgreementRow row;
    row.gap = std::max(0.0, st.value - res.value);
    row.within = row.gap <= tolerance;
    row.prediction_distance = predict ? 0.0 : std::numeric_limits<double>::quiet_NaN();
    if (s != best && row.within) {
      if (predict) {
        if (best_summary.size() == 0) {
          best_summary = predictions.summaries(res.theta);
          ++a.predictions;
        }
        row.prediction_distance = prediction_distance(predictions.summaries(st.theta), best_summary, predictions.resolution);
        ++a.predictions;
        a.largest_prediction_distance = std::max(a.largest_prediction_distance, row.prediction_distance);
      }
      row.same_prediction = predict && row.prediction_distance <= 1.0;
      if (!row.same_prediction) row.barrier = path_barrier(params, f, res, st.theta, tolerance, fractions, s, a.evaluations);
    }
    if (s == best) row.same_prediction = predict;
    row.same = row.within && (row.same_prediction || row.barrier <= tolerance);
    a.same += row.same;
    a.largest_gap = std::max(a.largest_gap, row.gap);
    a.largest_barrier = std::max(a.largest_barrier, row.barrier);
    a.rows.push_back(row);
  }
  a.agree = a.same == static_cast<int>(a.rows.size());
  return a;
}

namespace {

/// The number of observations behind a response: its data, or the sample of a KDE given as its
/// experimental PDF (a KDE-ebd's added points are not observations); 0 when unknown.
double observations(const ResponseSpec& r) {
  if (r.data.size() > 0) return static_cast<double>(r.data.size());
  if (!r.f_exp) return 0.0;
  const double n = r.f_exp->field("n").value_or(0.0), added = r.f_exp->field("added").value_or(0.0);
  return std::max(0.0, n - added);
}

}  // namespace

PredictionCheck prediction_check(const StatisticalObjective& obj) {
  const auto& rs = obj.responses();
  PredictionCheck pc;
  pc.resolution.resize(4 * static_cast<Eigen::Index>(rs.size()));
  for (std::size_t j = 0; j < rs.size(); ++j) {
    const double n = observations(rs[j]);
    if (n < 2) return {};
    pc.resolution.segment(4 * static_cast<Eigen::Index>(j), 4).setConstant(1.0 / std::sqrt(n));
  }
  pc.summaries = [&obj](const Eigen::VectorXd& t) { return obj.summaries(t); };
  return pc;
}

std::string describe(const StartAgreement& a) {
  const int n = static_cast<int>(a.rows.size());
  const bool predict = !std::isnan(a.largest_prediction_distance);
  if (a.agree)
    return fmt::format("the {} starts reached the same optimum where the data can tell: objectives within {:.3g} of the best (tolerance {:.3g}){}; "
                       "their points differ only where the data do not determine them",
                       n, a.largest_gap, a.tolerance,
                       predict ? fmt::format(", predictions within {:.2g} standard errors of the data's summaries, or no barrier between them",
                                             a.largest_prediction_distance)
                               : fmt::format(" and no barrier above the tolerance on the paths between them (largest {:.3g})", a.largest_barrier));
  int outside = 0, split = 0;
  for (const StartAgreementRow& r : a.rows) {
    outside += !r.within;
    split += r.within && !r.same;
  }
  std::string why;
  if (outside > 0) why += fmt::format("{} fit worse than the best by more than the tolerance (largest gap {:.3g})", outside, a.largest_gap);
  if (split > 0)
    why += fmt::format("{}{} fit as well but predict differently{} and are separated from the best by a barrier above the tolerance (a second "
                       "near-optimal region)",
                       why.empty() ? "" : "; ", split, predict ? fmt::format(" (up to {:.2g} standard errors)", a.largest_prediction_distance) : "");
  return fmt::format("{} of the {} starts reached the best's optimum where the data can tell (tolerance {:.3g}): {}; the problem is "
                     "multimodal: see optima, or raise multistart or hops",
                     a.same, n, a.tolerance, why);
}

}  // namespace smi::improve
