// SPDX-License-Identifier: MIT
#include "kernels/improve/decision_matrix.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "platform/core/errors.hpp"

namespace smi::improve {

namespace {
std::string label(const std::vector<std::string>& names, Eigen::Index i, const char* kind) {
  const auto u = static_cast<std::size_t>(i);
  return u < names.size() && !names[u].empty() ? fmt::format("{} '{}'", kind, names[u]) : fmt::format("{} {}", kind, i + 1);
}
}  // namespace

DecisionResult decision_matrix(const Eigen::MatrixXd& M, const Eigen::VectorXd& w, const std::vector<std::string>& cand,
                               const std::vector<std::string>& crit, double tie_tol) {
  const Eigen::Index J = M.rows(), I = M.cols();
  if (J < 1 || I < 1) throw InvalidArgument(fmt::format("decision matrix needs at least 1 candidate and 1 criterion, got {}×{}", J, I));
  if (w.size() != I) throw DimensionMismatch(fmt::format("{} weights for {} criteria", w.size(), I));
  double wsum = 0.0;
  for (Eigen::Index i = 0; i < I; ++i) {
    if (!std::isfinite(w[i]) || w[i] < 0.0)
      throw InvalidArgument(fmt::format("{}: weight must be finite and >= 0, got {}", label(crit, i, "criterion"), w[i]));
    wsum += w[i];
  }
  if (std::abs(wsum - 1.0) > 1e-9)
    throw InvalidArgument(fmt::format("weights must sum to 1, got {:.12g} (divide each weight by the sum)", wsum));
  for (Eigen::Index j = 0; j < J; ++j)
    for (Eigen::Index i = 0; i < I; ++i)
      if (!std::isfinite(M(j, i)) || M(j, i) < 0.0)
        throw InvalidArgument(fmt::format("{}, {}: magnitude must be finite and >= 0 (smaller is better), got {}",
                                          label(cand, j, "candidate"), label(crit, i, "criterion"), M(j, i)));
  DecisionResult r;
  r.magnitudes = M;
  r.standardized.resize(J, I);
  for (Eigen::Index i = 0; i < I; ++i) {
    const double mx = M.col(i).maxCoeff();
    if (mx == 0.0) {
      // Every candidate is perfect on this criterion: it does not discriminate.
      r.standardized.col(i).setOnes();
      if (J > 1) r.warnings.push_back(fmt::format("{}: every magnitude is 0, so it does not discriminate", label(crit, i, "criterion")));
    } else {
      r.standardized.col(i) = (1.0 - M.col(i).array() / mx).matrix();
    }
  }
  r.ratings = r.standardized * w.asDiagonal();
  r.overall = r.ratings.rowwise().sum();
  r.overall.maxCoeff(&r.best);
  for (Eigen::Index j = 0; j < J; ++j)
    if (r.overall[r.best] - r.overall[j] <= tie_tol) r.ties.push_back(j);
  if (r.ties.size() > 1) {
    std::string who;
    for (auto j : r.ties) who += (who.empty() ? "" : ", ") + label(cand, j, "candidate");
    r.warnings.push_back(fmt::format("tie for the best overall score {:.6g}: {}", r.overall[r.best], who));
  }
  return r;
}

std::string format_decision(const DecisionResult& r, const std::vector<std::string>& cand, const std::vector<std::string>& crit,
                            const Eigen::VectorXd& w) {
  const Eigen::Index J = r.magnitudes.rows(), I = r.magnitudes.cols();
  auto cname = [&](Eigen::Index j) {
    const auto u = static_cast<std::size_t>(j);
    return u < cand.size() ? cand[u] : fmt::format("{}", j + 1);
  };
  auto iname = [&](Eigen::Index i) {
    const auto u = static_cast<std::size_t>(i);
    return u < crit.size() ? crit[u] : fmt::format("c{}", i + 1);
  };
  std::size_t cw = 9;
  for (Eigen::Index j = 0; j < J; ++j) cw = std::max(cw, cname(j).size());
  std::size_t colw = 10;
  for (Eigen::Index i = 0; i < I; ++i) colw = std::max(colw, iname(i).size() + 1);
  std::string out;
  auto block = [&](const char* title, const Eigen::MatrixXd& X, bool with_overall) {
    out += fmt::format("{}\n{:<{}}", title, "candidate", cw);
    for (Eigen::Index i = 0; i < I; ++i) out += fmt::format(" {:>{}}", iname(i), colw);
    if (with_overall) out += fmt::format(" {:>{}}", "overall", colw);
    out += "\n";
    for (Eigen::Index j = 0; j < J; ++j) {
      out += fmt::format("{:<{}}", cname(j), cw);
      for (Eigen::Index i = 0; i < I; ++i) out += fmt::format(" {:>{}.5g}", X(j, i), colw);
      if (with_overall) out += fmt::format(" {:>{}.5g}{}", r.overall[j], colw, j == r.best ? "  <- best" : "");
      out += "\n";
    }
  };
  out += fmt::format("{:<{}}", "weights", cw);
  for (Eigen::Index i = 0; i < I; ++i) out += fmt::format(" {:>{}.5g}", w[i], colw);
  out += "\n";
  block("magnitudes M (smaller is better)", r.magnitudes, false);
  block("standardized S = 1 - M/max M", r.standardized, false);
  block("ratings r = w*S", r.ratings, true);
  for (const auto& s : r.warnings) out += "warning: " + s + "\n";
  return out;
}

}  // namespace smi::improve
