// SPDX-License-Identifier: MIT
// Beyond the paper: bootstrap intervals, identifiability warnings, design-range warnings.
#include <catch2/catch.hpp>

#include <cmath>

#include "kernels/improve/bootstrap.hpp"
#include "kernels/improve/design_bounds.hpp"
#include "kernels/improve/identifiability.hpp"
#include "platform/core/rng.hpp"

using namespace smi::improve;

TEST_CASE("bootstrap of a least-squares mean matches the closed-form bootstrap standard error") {
  // θ̂ = argmin Σ(x_i − θ)² = mean(x). Over resamples, sd(mean*) = sqrt(Σ(x − x̄)²/n)/√n exactly
  // in expectation; 400 replicates estimate it to about 3.5 %.
  smi::Rng g(5);
  const Eigen::VectorXd x = g.normal(25, 10.0, 2.0);
  const double n = static_cast<double>(x.size());
  const double se = std::sqrt((x.array() - x.mean()).square().sum() / n / n);
  std::vector<Parameter> p{{"m", 0.0, 20.0, 10.0}};
  ObjectiveFactory make = [](const std::vector<Eigen::VectorXd>& d) -> Objective {
    const Eigen::VectorXd y = d[0];
    return [y](const Eigen::VectorXd& t) { return Evaluation{(y.array() - t[0]).square().sum() / static_cast<double>(y.size()), {}}; };
  };
  BootstrapOptions o;
  o.replicates = 400;
  o.seed = 11;
  o.optimizer.xtol_rel = 1e-10;
  const BootstrapResult r = bootstrap_calibration(p, Eigen::VectorXd::Constant(1, x.mean()), {x}, make, o);
  CHECK(r.thetas.rows() == 400);
  CHECK(r.failed == 0);
  CHECK(r.stddev[0] == Approx(se).epsilon(0.12));
  CHECK(r.lower[0] < x.mean());
  CHECK(r.upper[0] > x.mean());
  CHECK((r.upper[0] - r.lower[0]) == Approx(2 * 1.959964 * se).epsilon(0.15));
  // Same seed, same intervals.
  const BootstrapResult again = bootstrap_calibration(p, Eigen::VectorXd::Constant(1, x.mean()), {x}, make, o);
  CHECK(again.lower[0] == r.lower[0]);
  CHECK(again.upper[0] == r.upper[0]);
}

TEST_CASE("paired resampling when responses have equal length") {
  const Eigen::VectorXd a = Eigen::VectorXd::LinSpaced(6, 1, 6);
  std::vector<Parameter> p{{"m", 0.0, 10.0, 3.5}};
  // Paired rows: b = 2a, so mean(b*) = 2 mean(a*) in every replicate; the objective sees both.
  ObjectiveFactory make = [](const std::vector<Eigen::VectorXd>& d) -> Objective {
    CHECK((d[1] - 2 * d[0]).cwiseAbs().maxCoeff() == 0.0);
    const double m = d[0].mean();
    return [m](const Eigen::VectorXd& t) { return Evaluation{(t[0] - m) * (t[0] - m), {}}; };
  };
  BootstrapOptions o;
  o.replicates = 20;
  const BootstrapResult r = bootstrap_calibration(p, Eigen::VectorXd::Constant(1, 3.5), {a, 2 * a}, make, o);
  CHECK(r.paired);
}

TEST_CASE("an objective that ignores a parameter flags it as unidentifiable") {
  std::vector<Parameter> p{{"a", -1.0, 1.0, 0.0}, {"b", 0.0, 5.0, 1.0}, {"c", 0.0, 1.0, 0.5}};
  auto f = [](const Eigen::VectorXd& t) { return Evaluation{(t[0] - 0.2) * (t[0] - 0.2) + 1e-6 * t[1] + 0.5 * t[2], {}}; };
  const IdentifiabilityResult r = identifiability(p, f, Eigen::Vector3d(0.2, 1.0, 0.0));
  REQUIRE(r.weak.size() == 3);
  CHECK(!r.weak[0]);
  CHECK(r.weak[1]);
  CHECK(!r.weak[2]);
  CHECK(r.span[0] == Approx(1.44));  // (−1 − 0.2)²
  CHECK(r.span[2] == Approx(0.5));
  REQUIRE(r.warnings.size() == 1);
  CHECK_THAT(r.warnings[0], Catch::Contains("'b'"));
  CHECK(r.evaluations == 33);
}

TEST_CASE("design-range warnings") {
  Eigen::MatrixXd X(100, 2);
  X.col(0) = Eigen::VectorXd::LinSpaced(100, 0.0, 1.0);
  X.col(1) = Eigen::VectorXd::LinSpaced(100, 5.0, 6.0);
  const auto none = design_bound_warnings({"a", "b"}, X, {0.5, 5.5}, {{"a", -1, 2}, {"b", 4, 7}});
  CHECK(none.empty());
  const auto tails = design_bound_warnings({"a", "b"}, X, {0.5, 5.5}, {{"a", 0.1, 2}});
  REQUIRE(tails.size() == 1);
  CHECK_THAT(tails[0], Catch::Contains("'a'") && Catch::Contains("10.0 %"));
  const auto mean_out = design_bound_warnings({"a", "b"}, X, {0.5, 5.5}, {{"b", 5.6, 7}});
  CHECK(mean_out.size() == 2);
  CHECK_THROWS_WITH(design_bound_warnings({"a", "b"}, X, {0.5, 5.5}, {{"c", 0, 1}}), Catch::Contains("'c'"));
}
