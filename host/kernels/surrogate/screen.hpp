// SPDX-License-Identifier: MIT
#pragma once
// Variable screening (spec §3): the PDF-area index of Son et al. (2020), eq. (3) and (7),
// e_k = integral |f_k - g| with input k fixed, N_ek = e_k / sum e_i, on one CRN base sample;
// beside it the Sobol' first-order (Saltelli 2010) and total (Jansen 1999) indices with
// percentile bootstrap confidence intervals.
#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "platform/core/cancel.hpp"
#include "kernels/surrogate/propagate.hpp"
#include "platform/core/defaults.hpp"

namespace smi::surrogate::screen {

/// The smallest Monte Carlo sample of the screening.
inline constexpr int kMinScreenN = 10;

struct Options {
  Eigen::Index n = 10000;
  std::uint64_t seed = kDefaultSeed;
  std::string fix = "mean";  // value an input is fixed at: "mean" | "median"
  bool sobol = true;
  int bootstrap = 200;       // resamples for the Sobol' CIs (0 = none)
  double level = 0.95;
  Eigen::Index grid = kDefaultGridNodes;  // §0 grid nodes
};

/// Indices of one input for one output.
struct Row {
  std::string input;
  double e = 0, ne = 0;  // PDF area and its normalised value
  int rank = 0;          // 1 = most influential by ne
  double s1 = 0, s1_lo = 0, s1_hi = 0, st = 0, st_lo = 0, st_hi = 0;
};

struct Result {
  std::string output;
  std::vector<Row> rows;  // sorted by rank
  std::vector<std::string> warnings;
  double variance = 0;    // of the output over the base sample
};

/// `model` maps an n x k matrix (columns in the order of `inputs`) to n x q outputs named
/// `outputs`. Model calls: 1 + (#random inputs) for the PDF areas, + 1 + (#random inputs) for
/// Sobol'. `outputs` is read after the first model call (adapters may fill it then).
std::vector<Result> screen(const std::vector<propagate::Input>& inputs, const propagate::MatrixModel& model,
                           const std::vector<std::string>& outputs, const Options& opt);

/// Sobol' estimators on given model outputs: fA, fB (n) and fAB (n x k, column k from A with
/// input k taken from B). Writes s1/st (and CIs when bootstrap > 0) into rows[0..k). `stop` is
/// polled between bootstrap resamples.
void sobol_indices(const Eigen::VectorXd& fA, const Eigen::VectorXd& fB, const Eigen::MatrixXd& fAB, int bootstrap,
                   double level, std::uint64_t seed, std::vector<Row>& rows,
                   const cancel::Token& stop = cancel::process_token());

}  // namespace smi::surrogate::screen
