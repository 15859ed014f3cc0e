// SPDX-License-Identifier: MIT
// Weighted decision matrix (spec §6) against spec §8.5.
#include <catch2/catch.hpp>

#include "kernels/improve/decision_matrix.hpp"
#include "platform/core/errors.hpp"

using namespace smi::improve;

namespace {
Eigen::MatrixXd spec_M() {
  Eigen::MatrixXd M(3, 4);
  M << 0.08, 5, 12, 120, 0.05, 0, 10, 30, 0.02, 1, 11, 60;
  return M;
}
}  // namespace

TEST_CASE("spec 8.5: standardisation and both weightings") {
  Eigen::VectorXd w(4);
  w << 0.4, 0.2, 0.2, 0.2;
  const DecisionResult r = decision_matrix(spec_M(), w);
  Eigen::MatrixXd S(3, 4);
  S << 0, 0, 0, 0, 0.375, 1, 1.0 / 6, 0.75, 0.75, 0.8, 1.0 / 12, 0.5;
  CHECK((r.standardized - S).cwiseAbs().maxCoeff() < 1e-12);
  CHECK(r.overall[0] == Approx(0.0).margin(1e-15));
  CHECK(r.overall[1] == Approx(0.53333333333).epsilon(1e-10));
  CHECK(r.overall[2] == Approx(0.57666666667).epsilon(1e-10));
  CHECK(r.best == 2);
  CHECK(r.ties.size() == 1);

  w.setConstant(0.25);
  const DecisionResult e = decision_matrix(spec_M(), w);
  CHECK(e.overall[1] == Approx(0.572917).epsilon(1e-6));
  CHECK(e.overall[2] == Approx(0.533333).epsilon(1e-6));
  CHECK(e.best == 1);
  const std::string txt = format_decision(e, {"a", "b", "c"}, {"correctness", "robustness", "comp", "impl"}, w);
  CHECK_THAT(txt, Catch::Contains("<- best") && Catch::Contains("correctness"));
}

TEST_CASE("criterion with max M = 0 scores 1 for everyone; single candidate scores 0") {
  Eigen::MatrixXd M(2, 2);
  M << 0, 3, 0, 1;
  Eigen::VectorXd w(2);
  w << 0.5, 0.5;
  const DecisionResult r = decision_matrix(M, w);
  CHECK(r.standardized(0, 0) == 1.0);
  CHECK(r.standardized(1, 0) == 1.0);
  CHECK(r.overall[1] == Approx(0.5 + 0.5 * (1 - 1.0 / 3)));
  CHECK(!r.warnings.empty());
  Eigen::MatrixXd one(1, 2);
  one << 2, 4;
  CHECK(decision_matrix(one, w).overall[0] == 0.0);
}

TEST_CASE("ties are reported") {
  Eigen::MatrixXd M(3, 2);
  M << 1, 2, 2, 1, 2, 2;
  Eigen::VectorXd w(2);
  w << 0.5, 0.5;
  const DecisionResult r = decision_matrix(M, w);
  REQUIRE(r.ties.size() == 2);
  CHECK(r.ties[0] == 0);
  CHECK(r.ties[1] == 1);
  CHECK_THAT(r.warnings.back(), Catch::Contains("tie"));
}

TEST_CASE("bad weights and magnitudes name the culprit") {
  Eigen::VectorXd w(4);
  w << 0.4, 0.4, 0.4, 0.4;
  CHECK_THROWS_WITH(decision_matrix(spec_M(), w), Catch::Contains("sum to 1") && Catch::Contains("1.6"));
  w << 0.5, 0.5, -0.25, 0.25;
  CHECK_THROWS_WITH(decision_matrix(spec_M(), w, {}, {"a", "b", "cost", "d"}), Catch::Contains("'cost'"));
  Eigen::MatrixXd M = spec_M();
  M(1, 2) = -1;
  w.setConstant(0.25);
  CHECK_THROWS_WITH(decision_matrix(M, w, {"x", "airbag", "z"}), Catch::Contains("'airbag'") && Catch::Contains("criterion 3"));
  CHECK_THROWS_AS(decision_matrix(spec_M(), Eigen::VectorXd::Constant(3, 1.0 / 3)), smi::DimensionMismatch);
}
