// SPDX-License-Identifier: MIT
#pragma once
// How much the probability residual may rise above the optimum and still fit the data as well,
// measured from the data: the standard deviation of the summed PR at the optimum over bootstrap
// resamples of the data rows (paired across responses: a row is one specimen). Two calibrations
// whose objectives differ by less than that are not told apart by the specimens at hand. Each
// resample's experimental PDF is the plain KDE of its points (the KDE-ebd's bounded-data loop on
// every resample would cost more than the calibration; the spread is what is measured), against
// the prediction's KDE at the optimum on the objective's own grids and outside mass.
#include <Eigen/Core>
#include <cstdint>

#include "kernels/improve/statistical_objective.hpp"

namespace smi::improve {

/// The default: 1000 resamples. The summed PR over resamples of nine rows is skewed and
/// heavy-tailed, so its standard deviation from B resamples scatters more than the normal
/// 1/sqrt(2(B − 1)): on the steering column's trial 1, 200 resamples gave 0.189 where 2000 give
/// 0.153–0.163 (docs/design.md). 1000 cost about 0.05 s on a study's grid of 6001 nodes.
inline constexpr int kPrToleranceResamples = 1000;

struct PrTolerance {
  double value = 0.0;  ///< the standard deviation of the summed PR over the resamples
  double mean = 0.0;   ///< their mean
  int resamples = 0;   ///< resamples that gave a value
  int failed = 0;      ///< degenerate resamples (all points equal: no KDE), left out
  bool paired = true;  ///< rows resampled paired (every response has as many points)
};

/// True when the objective can measure it: PR on every response, each with two or more points.
bool can_measure_pr_tolerance(const StatisticalObjective& obj);

/// The measured tolerance at θ: resample b is Rng::derive(seed, "tolerance/<b>"), summed against
/// the prediction's KDE at θ computed once (StatisticalObjective::pr_sums_against: at most one
/// model run, on the calling thread), so the value does not depend on `threads`. Throws when
/// fewer than two resamples give a value.
PrTolerance measure_pr_tolerance(const StatisticalObjective& obj, const Eigen::VectorXd& theta, int resamples,
                                 std::uint64_t seed, int threads);

}  // namespace smi::improve
