// SPDX-License-Identifier: MIT
// Identifiability as directions on closed-form objectives.
#include <catch2/catch.hpp>

#include <cmath>

#include "kernels/improve/directions.hpp"

using namespace smi::improve;

TEST_CASE("a combination the objective cannot see is an undetermined direction; the others are determined") {
  // f = (a + 2b − 3)² + (c − 1)²: flat along (a, b) ∝ (2, −1) for equal ranges (scaled units).
  std::vector<Parameter> p{{"a", -4.0, 4.0, 0.0}, {"b", -4.0, 4.0, 0.0}, {"c", -2.0, 2.0, 0.0}};
  auto f = [](const Eigen::VectorXd& t) {
    const double r = t[0] + 2 * t[1] - 3, s = t[2] - 1;
    return Evaluation{r * r + s * s, {}};
  };
  const Eigen::Vector3d opt(1.0, 1.0, 1.0);
  DirectionsOptions o;
  o.tolerance = 1e-6;
  const DirectionsResult r = identifiability_directions(p, f, opt, 0.0, o);
  REQUIRE(r.directions.size() == 3);
  CHECK(r.basis == "hessian");
  CHECK(r.directions[0].determined);
  CHECK(r.directions[1].determined);
  const Direction& weak = r.directions[2];
  CHECK_FALSE(weak.determined);
  CHECK(std::abs(weak.loadings[0]) == Approx(2 / std::sqrt(5.0)).margin(1e-6));
  CHECK(weak.loadings[1] == Approx(-weak.loadings[0] / 2).margin(1e-6));
  CHECK(weak.loadings[2] == Approx(0).margin(1e-6));
  CHECK(std::abs(weak.curvature) < 1e-4);
  // Closed-form curvatures in scaled units: 2·|(8, 16, 0)|² / |.|²... the strongest is
  // 2·(8² + 16²) = 640 along (1, 2, 0)/√5, then 2·4² = 32 along c.
  CHECK(r.directions[0].curvature == Approx(640).epsilon(1e-4));
  CHECK(r.directions[1].curvature == Approx(32).epsilon(1e-4));
  // Near-optimal points: the optimum, then the far ends of the flat valley (a bound reached).
  REQUIRE(r.near_optimal.size() == 3);
  for (std::size_t i = 0; i < r.near_optimal.size(); ++i) {
    CHECK(f(r.near_optimal[i]).value <= o.tolerance);
    CHECK(r.near_optimal_values[i] == Approx(f(r.near_optimal[i]).value).margin(1e-12));
  }
  CHECK(std::abs(r.near_optimal[1][0] - 1.0) > 2.0);  // spread along the valley, not near the optimum
  REQUIRE_FALSE(r.warnings.empty());
}

TEST_CASE("a problem where every parameter is identifiable has every direction determined") {
  std::vector<Parameter> p{{"a", 0.0, 2.0, 1.0}, {"b", 0.0, 2.0, 1.0}, {"c", 0.0, 2.0, 1.0}};
  auto f = [](const Eigen::VectorXd& t) {
    const Eigen::Vector3d d = t - Eigen::Vector3d(0.7, 1.2, 0.4);
    return Evaluation{d[0] * d[0] + 2 * d[1] * d[1] + 0.5 * d[2] * d[2] + d[0] * d[1], {}};
  };
  DirectionsOptions o;
  o.tolerance = 1e-3;
  const DirectionsResult r = identifiability_directions(p, f, Eigen::Vector3d(0.7, 1.2, 0.4), 0.0, o);
  for (const Direction& d : r.directions) CHECK(d.determined);
  CHECK(r.near_optimal.size() == 1);
  CHECK(r.warnings.empty());
}

TEST_CASE("with summaries, a curved valley is followed: the profile stays flat where a straight line climbs") {
  // Summaries s = (a² + b²) and the objective (s − 1)²: the valley a² + b² = 1 is a circle; its
  // tangent at (0.6, 0.8) leaves it, but the corrected profile keeps s at 1.
  std::vector<Parameter> p{{"a", 0.0, 1.0, 0.5}, {"b", 0.0, 1.0, 0.5}};
  auto summ = [](const Eigen::VectorXd& t) { return Eigen::VectorXd::Constant(1, t[0] * t[0] + t[1] * t[1]); };
  auto f = [&](const Eigen::VectorXd& t) {
    const double s = summ(t)[0] - 1;
    return Evaluation{s * s, {}};
  };
  DirectionsOptions o;
  o.tolerance = 1e-4;
  const Eigen::Vector2d opt(0.6, 0.8);
  const DirectionsResult r = identifiability_directions(p, f, opt, 0.0, o, summ);
  CHECK(r.basis == "summaries");
  CHECK(r.directions[0].determined);
  CHECK_FALSE(r.directions[1].determined);
  CHECK(r.directions[1].rise <= o.tolerance);
  for (const auto& t : r.near_optimal) CHECK(f(t).value <= o.tolerance);
  // Without summaries the straight tangent line climbs out of the valley and calls it determined.
  const DirectionsResult h = identifiability_directions(p, f, opt, 0.0, o);
  CHECK(h.directions[1].determined);
}
