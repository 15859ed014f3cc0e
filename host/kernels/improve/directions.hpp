// SPDX-License-Identifier: MIT
#pragma once
// Identifiability as directions. A one-parameter-at-a-time sweep misses a
// combination the data cannot determine (y = x1 + 2 x2: only mu1 + 2 mu2 is seen). Directions
// come, in parameters scaled to [0, 1] by their bounds, from
//   - the Jacobian of the predicted responses' summaries (quantiles, in units of the data's
//     spread) when the calibration has a model: its right singular vectors. Summaries are
//     first derivatives of smooth CRN functions, so differences are reliable where second
//     differences of PR are not (PR is an L1 area on a grid: its Hessian is mostly noise);
//   - otherwise the objective's Hessian by central differences, split into eigenvectors.
// Along each direction the objective is profiled from the optimum towards both bounds; with
// summaries, each profile node is corrected by Gauss-Newton steps along the other directions
// to keep the summaries at the optimum's, so the profile follows a curved valley (y = x1 + 2 x2:
// sigma1^2 + 4 sigma2^2 constant) instead of climbing out of it. A direction is determined when
// its profile rises by more than `tolerance` on both sides before the bounds (a side where the
// optimum sits on the bound counts as closed); along the undetermined ones the farthest points
// still within `tolerance` are kept as near-optimal parameter sets.
#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

#include "kernels/improve/bounded_optimizer.hpp"

namespace smi::improve {

/// The largest finite-difference step of the directions (scaled units).
inline constexpr double kMaxDirectionsStep = 0.05;

struct DirectionsOptions {
  /// Objective increase that still counts as fitting the data as well as the optimum.
  double tolerance = 1e-3;
  /// Profile nodes along each direction (both sides of the optimum together, optimum included).
  int points = 11;
  /// Finite-difference step of the Jacobian or Hessian, scaled units.
  double step = 2e-3;
  /// Gauss-Newton corrections per profile node (summaries only).
  int corrections = 2;
};

struct Direction {
  Eigen::VectorXd loadings;  ///< unit vector in scaled parameters (largest |loading| positive)
  /// Hessian form: second derivative of the objective along it. Summaries form: the squared
  /// singular value (change of the summaries, squared, per unit step; Gauss-Newton curvature).
  double curvature = 0.0;
  double rise = 0.0;         ///< largest objective increase over its profile
  bool determined = false;
  Eigen::VectorXd t;         ///< profile nodes: signed distance from the optimum, scaled units
  Eigen::VectorXd profile;   ///< objective at the nodes
  double t_lower = 0.0, t_upper = 0.0;  ///< where the line leaves the box (t_lower <= 0 <= t_upper)
};

struct DirectionsResult {
  std::vector<Direction> directions;        ///< strongest (largest curvature) first
  std::string basis;                        ///< "summaries" or "hessian"
  double tolerance = 0.0;
  std::vector<Eigen::VectorXd> near_optimal;  ///< θ in the parameters' own units, the optimum first
  std::vector<double> near_optimal_values;    ///< objective at each near-optimal θ
  int evaluations = 0;
  std::vector<std::string> warnings;
};

/// Summaries of the predicted responses at θ (own units), a fixed-length vector in comparable
/// units (e.g. quantiles divided by the data's standard deviation).
using Summaries = std::function<Eigen::VectorXd(const Eigen::VectorXd& theta)>;

/// `value` is the objective at `optimum` (not re-evaluated). Without `summaries`, the Hessian.
DirectionsResult identifiability_directions(const std::vector<Parameter>& params, const Objective& f, const Eigen::VectorXd& optimum,
                                            double value, const DirectionsOptions& opt = {}, const Summaries& summaries = {});

}  // namespace smi::improve
