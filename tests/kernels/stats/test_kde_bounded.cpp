// SPDX-License-Identifier: MIT
// KDE-bd / KDE-ebd (spec §1.2, §8.1): bounds, the stopping loop and its options.
#include <catch2/catch.hpp>
#include <cmath>

#include "kernels/stats/bandwidth.hpp"
#include "kernels/stats/kde_bounded.hpp"
#include "platform/core/rng.hpp"

using Catch::Matchers::WithinAbs;

namespace {
Eigen::VectorXd spec_x() {
  Eigen::VectorXd x(9);
  x << 30.12, 30.45, 29.88, 30.61, 30.02, 29.75, 30.33, 30.90, 30.20;
  return x;
}
}  // namespace

TEST_CASE("ebd bounds (spec 8.1)") {
  auto [l, u] = smi::stats::ebd_bounds(spec_x(), 0.1);
  CHECK_THAT(l, WithinAbs(29.4147178852, 1e-9));
  CHECK_THAT(u, WithinAbs(31.2352821148, 1e-9));
  std::tie(l, u) = smi::stats::ebd_bounds(spec_x(), 0.05);
  CHECK_THAT(l, WithinAbs(29.2958065869, 1e-9));
  CHECK_THAT(u, WithinAbs(31.3541934131, 1e-9));
  // Widening factor c − 1 = α^{−1/n} − 1 on data [0, 1].
  const std::pair<int, double> table[] = {{2, 2.1622777}, {3, 1.1544347}, {5, 0.5848932}, {9, 0.2915497},
                                          {10, 0.2589254}, {20, 0.1220185}, {50, 0.0471285}};
  for (const auto& [n, w] : table) {
    const Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(n, 0.0, 1.0);
    CHECK_THAT(smi::stats::ebd_bounds(x, 0.1).second - 1.0, WithinAbs(w, 1e-7));
  }
  CHECK_THROWS_WITH(smi::stats::ebd_bounds(spec_x(), 1.5), Catch::Contains("alpha must be in (0, 1)"));
  CHECK_THROWS_WITH(smi::stats::ebd_bounds(Eigen::VectorXd::Constant(3, 1.0), 0.1), Catch::Contains("all 3 data values are equal"));
}

TEST_CASE("stopping loop: pooled bandwidth, IA history, options") {
  smi::stats::BoundedKdeOptions o;
  o.seed = 5;
  const auto r = smi::stats::kde_ebd(spec_x(), 0.1, false, o);
  REQUIRE(r.added >= 1);
  REQUIRE(r.converged);
  CHECK(r.ia_history.back() >= 0.95);
  for (std::size_t k = 0; k + 1 < r.ia_history.size(); ++k) CHECK(r.ia_history[k] < 0.95);
  CHECK(r.kde->data().size() == 9 + r.added);
  Eigen::VectorXd t(9 + r.added);
  t << spec_x(), r.added_points;
  CHECK_THAT(r.kde->bandwidth(), WithinAbs(smi::stats::bandwidth_normal_reference(t), 1e-15));
  for (Eigen::Index i = 0; i < r.added_points.size(); ++i) {
    CHECK(r.added_points[i] >= r.lower);
    CHECK(r.added_points[i] <= r.upper);
  }
  // Deterministic placement, max_added, step.
  smi::stats::BoundedKdeOptions d;
  d.deterministic = true;
  d.critical_area = 1.0;
  d.max_added = 4;
  d.step = 2;
  const auto rd = smi::stats::kde_bounded(spec_x(), 29.0, 31.0, d);
  CHECK(rd.added == 4);
  CHECK_FALSE(rd.converged);
  CHECK(rd.ia_history.size() == 2);
  CHECK_THAT(rd.added_points[0], WithinAbs(29.25, 1e-15));
  CHECK_THAT(rd.added_points[3], WithinAbs(30.75, 1e-15));
}

TEST_CASE("added count for X ~ N(0,1), n = 9: mean about 1.8 (spec 8.1, loose)") {
  smi::Rng rng(17);
  double total = 0;
  int twenty_one = 0;
  const int runs = 300;
  for (int s = 0; s < runs; ++s) {
    smi::stats::BoundedKdeOptions o;
    o.seed = static_cast<std::uint64_t>(s);
    o.grid_nodes = 2001;
    total += smi::stats::kde_ebd(rng.normal(9), 0.1, false, o).added;
    twenty_one += smi::stats::kde_ebd(rng.normal(20), 0.1, false, o).added == 1;
  }
  CHECK(total / runs > 1.5);
  CHECK(total / runs < 2.2);
  CHECK(twenty_one > 0.9 * runs);
}
