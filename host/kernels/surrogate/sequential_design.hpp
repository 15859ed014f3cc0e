// SPDX-License-Identifier: MIT
#pragma once
// Sequential Kriging designs: instead of one fixed Latin hypercube sized for the worst
// case, start from a small design, fit, and add batches of points where the Kriging is least sure
// weighted by where the input distributions put their mass; stop when every output's
// leave-one-out Q2 (and RMSE, when given) meets its target, or at max_points. The Kriging
// variance does not depend on the responses, so a whole batch is chosen before any model run and
// goes to a parallel evaluator in one call.
#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

#include "kernels/surrogate/kriging.hpp"

namespace smi::surrogate::kriging {

/// `batch` distinct rows of `candidates` (in the models' input units), chosen greedily: each the
/// candidate with the largest weight x max over models of the Kriging variance ratio
/// 1 - r' R^-1 r (the model's correlation family, theta and input normalisation), given the
/// models' design plus the rows already chosen. Candidates with weight <= 0 are never chosen.
/// All models must share one design (one fit per output on the same X). Throws on mismatched
/// sizes or fewer usable candidates than `batch`.
std::vector<Eigen::Index> select_batch(const std::vector<const Model*>& models, const Eigen::MatrixXd& candidates,
                                       const Eigen::VectorXd& weights, Eigen::Index batch);

struct SequentialOptions {
  Eigen::Index batch = 10;       // points added per round (one model call each)
  Eigen::Index max_points = 100; // the design never grows past this
  double q2_target = 0.999;      // leave-one-out Q2 every output must reach
  Eigen::VectorXd rmse_target;   // per output, LOO RMSE in the output's units (empty or NaN: none)
  FitOptions fit;                // the Kriging of every output
};

struct SequentialStep {
  Eigen::Index points = 0;
  Eigen::VectorXd q2, rmse;      // per output, leave-one-out at this design
};

struct SequentialResult {
  Eigen::MatrixXd X, Y;          // the design and the model's outputs (one column per output)
  std::vector<Model> models;     // the last fit, one per output
  std::vector<SequentialStep> history;
  bool reached = false;          // the targets were met (else max_points or the candidates ran out)
  std::string stop;              // why it stopped, in words
};

/// Rows -> outputs (one column each); called once on `initial`, then once per batch.
using DesignModel = std::function<Eigen::MatrixXd(const Eigen::MatrixXd&)>;

SequentialResult sequential_design(const Eigen::MatrixXd& initial, const Eigen::MatrixXd& candidates,
                                   const Eigen::VectorXd& weights, const DesignModel& model,
                                   const SequentialOptions& opt);

}  // namespace smi::surrogate::kriging
