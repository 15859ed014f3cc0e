// SPDX-License-Identifier: MIT
#pragma once
// Weighted decision matrix for model refinement (Oh et al. 2016; Son et al. 2020 eq. 13-14;
// docs/spec/algorithms.md §6). Magnitudes are "smaller is better"; each criterion is
// standardised by its worst candidate, S = 1 − M / max M (S = 1 for all when max M = 0),
// rated r = w·S, and the candidate with the largest overall O = Σ r is revised.
#include <Eigen/Core>
#include <string>
#include <vector>

namespace smi::improve {

struct DecisionResult {
  Eigen::MatrixXd magnitudes;       ///< M, candidates × criteria
  Eigen::MatrixXd standardized;     ///< S
  Eigen::MatrixXd ratings;          ///< r = w·S
  Eigen::VectorXd overall;          ///< O, one per candidate
  Eigen::Index best = 0;            ///< 0-based argmax of O (first one when tied)
  std::vector<Eigen::Index> ties;   ///< every candidate within `tie_tol` of the best O (incl. best)
  std::vector<std::string> warnings;
};

/// The decision's one option (smi.refine.decision_matrix's tie_tol).
struct DecisionOptions {
  double tie_tol = 1e-12;  ///< overall ratings closer than this to the best are ties
};

/// M: candidates (rows) × criteria (columns), finite, >= 0. Weights: one per criterion, >= 0,
/// summing to 1 within 1e-9. Names only label error messages (may be empty).
DecisionResult decision_matrix(const Eigen::MatrixXd& magnitudes, const Eigen::VectorXd& weights,
                               const std::vector<std::string>& candidate_names = {},
                               const std::vector<std::string>& criterion_names = {},
                               double tie_tol = DecisionOptions{}.tie_tol);

/// A fixed-width text table of M, S, r and O for printing.
std::string format_decision(const DecisionResult& r, const std::vector<std::string>& candidate_names,
                            const std::vector<std::string>& criterion_names, const Eigen::VectorXd& weights);

}  // namespace smi::improve
