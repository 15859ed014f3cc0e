// SPDX-License-Identifier: MIT
#pragma once
// Whether the starts of a multistart calibration reached the same optimum where the data can
// tell. Two starts that end at different points need not disagree: along a
// direction the data do not determine (y = x1 + 2 x2: only mu1 + 2 mu2 and sigma1^2 + 4 sigma2^2
// are seen) every point of the valley fits as well, and the optimiser stops wherever it enters
// it. A start is at the best's optimum "where the data can tell" when its objective is within
// `tolerance` of the best and either
//   - it predicts the same: the summaries of its predicted responses (Hermite moments in units
//     of the data, statistical_objective.hpp) differ from the best's by at most `resolution`
//     (one standard error of the data's own summary, 1/sqrt(n)); data of that size cannot tell
//     the two predictions apart; or
//   - no barrier separates them: the objective stays within `tolerance` of the best all along
//     the straight path between the two points (the objective form, with no predictions).
// A straight path can leave a curved valley (sigma1^2 + 4 sigma2^2 constant), so the prediction
// test comes first when there is one. Two basins that predict differently and are split by a
// ridge higher than the tolerance are not the same optimum even when both fit as well: that is
// reported as a second near-optimal region, not hidden.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "kernels/improve/bounded_optimizer.hpp"
#include "kernels/improve/directions.hpp"
#include "kernels/improve/statistical_objective.hpp"

namespace smi::improve {

struct StartAgreementRow {
  double gap = 0.0;      ///< the start's objective minus the best's
  double barrier = 0.0;  ///< largest objective on the straight path to the best, minus the best's (0: no path walked)
  /// Largest difference of the predicted summaries from the best's, in units of `resolution`
  /// (NaN without predictions).
  double prediction_distance = 0.0;
  bool within = false;           ///< gap <= tolerance: the start's optimum fits the data as well as the best
  bool same_prediction = false;  ///< prediction_distance <= 1
  bool same = false;             ///< within, and the same prediction or no barrier above the tolerance
};

/// The predictions to compare, when the calibration has a model: summaries at θ and the
/// difference of each that the data can just resolve (same length).
struct PredictionCheck {
  Summaries summaries;
  Eigen::VectorXd resolution;
};

struct StartAgreement {
  double tolerance = 0.0;  ///< objective increase that still fits as well as the best
  int path_points = 0;     ///< interior points evaluated on each start's path to the best
  std::vector<StartAgreementRow> rows;  ///< one per start, in start order
  int same = 0;            ///< starts at the best's optimum (the best start included)
  bool agree = false;      ///< every start is
  double largest_gap = 0.0;
  double largest_barrier = 0.0;
  double largest_prediction_distance = 0.0;  ///< over the starts within the tolerance (NaN without predictions)
  int evaluations = 0;     ///< objective evaluations on the paths
  int predictions = 0;     ///< summaries computed (one model run each)
};

/// The agreement of res.starts with the best start (res.theta, res.value). Starts outside the
/// tolerance need no test; a start that predicts the same needs no path; `path_points` interior
/// points per path (>= 1), walked middle first until one is above the tolerance. Rethrows the
/// objective's exceptions.
StartAgreement start_agreement(const std::vector<Parameter>& params, const Objective& f, const OptimizationResult& res, double tolerance,
                               const PredictionCheck& predictions = {}, int path_points = 9);

/// The statistical form's predictions to compare starts by: the summaries of the predicted
/// responses (StatisticalObjective::summaries), each resolvable to one standard error of the
/// data's own, 1/sqrt(n), n the response's observations (its data, or the sample of a KDE given
/// as f_exp without a KDE-ebd's added points). Empty when some response's count is unknown.
/// Keeps a reference to obj.
PredictionCheck prediction_check(const StatisticalObjective& obj);

/// One line for the result's warnings or a report: how many starts reached the best's optimum
/// where the data can tell, the largest gap and barrier, against the tolerance.
std::string describe(const StartAgreement& a);

}  // namespace smi::improve
