// SPDX-License-Identifier: MIT
#pragma once
// Economical screening: the eq.-3 PDF-area screening of screen.hpp computed on a
// cheap surrogate of all inputs instead of the model. The model runs once, on a Latin hypercube
// of `runs` points mapped through the inputs' quantiles; a ridge polynomial (poly_ridge.hpp)
// is fitted per output with its closed-form leave-one-out Q2; the full screening (n CRN points,
// one fixed-input sample per input) then runs on the surrogate at no model cost. Beside it,
// Borgonovo's delta (delta.hpp) from the same runs, a check that does not trust the surrogate.
#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "kernels/surrogate/delta.hpp"
#include "kernels/surrogate/poly_ridge.hpp"
#include "kernels/surrogate/screen.hpp"

namespace smi::surrogate::screen {

/// The fewest model runs a screening surrogate is fitted on.
inline constexpr int kMinSurrogateRuns = 10;

struct SurrogateOptions {
  Eigen::Index runs = 300;   // model runs for the surrogate
  polyfit::Basis basis = polyfit::Basis::quadratic;
  double q2_min = 0.9;       // below it the result carries a warning
  bool delta = true;         // Borgonovo delta from the runs
  Eigen::Index delta_classes = 0;
};

struct SurrogateFitInfo {
  std::string output;
  double q2 = 0, r2 = 0, lambda = 0;
  Eigen::Index terms = 0;
  Eigen::VectorXd delta;  // in the order of the inputs (empty without delta)
  double delta_floor = 0;
  Eigen::Index delta_classes = 0;
};

struct SurrogateResult {
  std::vector<Result> screening;         // as screen(), on the surrogate; warnings include low Q2
  std::vector<SurrogateFitInfo> fits;    // one per output, same order
  Eigen::MatrixXd design;                // runs x k, the points the model ran at
  Eigen::MatrixXd design_y;              // runs x q
  Eigen::Index model_runs = 0;
};

/// The design (runs x k): a random Latin hypercube (stream "surrogate-design" of opt.seed)
/// through each input's quantile; constants as columns of their value.
Eigen::MatrixXd surrogate_design(const std::vector<propagate::Input>& inputs, Eigen::Index runs, std::uint64_t seed);

/// Calls `model` once, on the design; `outputs` is read after that call. Screening options
/// (n, seed, fix, sobol, grid) are those of screen().
SurrogateResult screen_surrogate(const std::vector<propagate::Input>& inputs, const propagate::MatrixModel& model,
                                 const std::vector<std::string>& outputs, const Options& opt,
                                 const SurrogateOptions& sopt);

}  // namespace smi::surrogate::screen
