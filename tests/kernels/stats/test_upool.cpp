// SPDX-License-Identifier: MIT
// u-pooling statistic, thresholds, p-values and exact null means against spec §5/§8.3.
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <vector>

#include "kernels/stats/kde.hpp"
#include "kernels/stats/upool.hpp"

using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;

namespace {
Eigen::VectorXd vec(std::initializer_list<double> v) {
  Eigen::VectorXd x(static_cast<Eigen::Index>(v.size()));
  Eigen::Index i = 0;
  for (double d : v) x[i++] = d;
  return x;
}
}  // namespace

TEST_CASE("U statistic: spec 8.3 deterministic values and range") {
  CHECK_THAT(smi::stats::upool_statistic(vec({0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9})), WithinAbs(0.0351852, 1e-7));
  CHECK_THAT(smi::stats::upool_statistic(vec({0.05, 0.15, 0.3, 0.42, 0.5, 0.61, 0.77, 0.88, 0.93})), WithinAbs(0.0342185, 1e-7));
  Eigen::VectorXd mid(9);
  for (int i = 0; i < 9; ++i) mid[i] = (2.0 * (i + 1) - 1.0) / 18.0;
  CHECK_THAT(smi::stats::upool_statistic(mid), WithinAbs(1.0 / 36.0, 1e-15));
  CHECK_THAT(smi::stats::upool_statistic(Eigen::VectorXd::Constant(9, 0.5)), WithinAbs(0.25, 1e-15));
  CHECK_THAT(smi::stats::upool_statistic(Eigen::VectorXd::Zero(9)), WithinAbs(0.5, 1e-15));
  CHECK_THAT(smi::stats::upool_statistic(Eigen::VectorXd::Ones(9)), WithinAbs(0.5, 1e-15));
  CHECK_THAT(smi::stats::upool_statistic(vec({0.3})), WithinAbs(0.04 + 0.25, 1e-15));  // (u − ½)² + ¼
  CHECK_THROWS_WITH(smi::stats::upool_statistic(vec({0.3, 1.2})), Catch::Contains("u-values[2] = 1.2"));
}

TEST_CASE("thresholds match spec 8.3 (1e6 sets, MC se ~1e-4)") {
  CHECK_THAT(smi::stats::upool_threshold(9, 0.95), WithinAbs(0.1927, 4e-4));
  CHECK_THAT(smi::stats::upool_threshold(9, 0.90), WithinAbs(0.1663, 4e-4));
  CHECK_THAT(smi::stats::upool_threshold(9, 0.99), WithinAbs(0.2450, 8e-4));
  CHECK_THAT(smi::stats::upool_threshold(10, 0.95), WithinAbs(0.1830, 4e-4));
  CHECK_THAT(smi::stats::upool_threshold(2, 0.95), WithinAbs(0.3927, 4e-4));
  CHECK_THAT(smi::stats::upool_threshold(1, 0.95), WithinAbs(0.475625, 1e-15));
  // The paper's 0.1818 is not the 95 % point.
  CHECK(smi::stats::upool_threshold(9, 0.95) > 0.19);
  // p-value is consistent with the threshold.
  CHECK_THAT(smi::stats::upool_pvalue(9, smi::stats::upool_threshold(9, 0.95)), WithinAbs(0.05, 1e-3));
  CHECK_THROWS_WITH(smi::stats::upool_threshold(9, 1.0), Catch::Contains("confidence must be in (0, 1)"));
  CHECK_THROWS_WITH(smi::stats::upool_threshold(0, 0.95), Catch::Contains("n (the number of u-values) must be >= 1"));
}

TEST_CASE("thread count does not change the null sample") {
  smi::stats::UpoolMcSettings a, b;
  a.replications = b.replications = 100000;
  a.threads = 1;
  b.threads = 2;
  a.seed = b.seed = 99;
  // Same key -> cached; check by a distinct seed for each and compare the values.
  b.seed = 99;
  const auto sa = smi::stats::upool_null_sample(5, a);
  smi::stats::UpoolMcSettings c = b;
  c.replications = 100001;  // different cache key, same chunks for the first 100000
  const auto sc = smi::stats::upool_null_sample(5, c);
  for (std::size_t i = 0; i < 1000; ++i) CHECK((*sa)[i * 97] == (*sc)[i * 97]);
}

TEST_CASE("exact null mean matches spec 8.3") {
  CHECK_THAT(smi::stats::upool_null_mean(1), WithinAbs(1.0 / 3.0, 1e-12));
  CHECK_THAT(smi::stats::upool_null_mean(2), WithinAbs(11.0 / 48.0, 1e-12));
  CHECK_THAT(smi::stats::upool_null_mean(3), WithinAbs(5.0 / 27.0, 1e-12));
  CHECK_THAT(smi::stats::upool_null_mean(9), WithinAbs(0.105324, 1e-6));
  CHECK_THAT(smi::stats::upool_null_mean(50), WithinAbs(0.044382, 1e-6));
}

TEST_CASE("verdicts for the spec data under two normal predictions") {
  Eigen::VectorXd x(9);
  x << 30.12, 30.45, 29.88, 30.61, 30.02, 29.75, 30.33, 30.90, 30.20;
  // A one-point KDE with h = sd is exactly N(mean, sd^2).
  auto good = std::make_shared<smi::stats::Kde>(Eigen::VectorXd::Constant(1, 30.25), 0.36);
  auto bad = std::make_shared<smi::stats::Kde>(Eigen::VectorXd::Constant(1, 30.6), 0.36);
  const auto v1 = smi::stats::upool({x}, {good});
  CHECK_THAT(v1.metric, WithinAbs(0.0340603, 1e-7));
  CHECK(v1.pass);
  CHECK(v1.p > 0.999);
  const auto v2 = smi::stats::upool({x}, {bad});
  CHECK_THAT(v2.metric, WithinAbs(0.2574441, 1e-7));
  CHECK_FALSE(v2.pass);
  CHECK_THAT(v2.p, WithinAbs(0.0064, 4e-4));
  CHECK_THAT(v2.describe(), Catch::Contains("INVALID"));
  // Pooling: two groups, each against its own prediction, give the same U as one group.
  const auto v3 = smi::stats::upool({x.head(4), x.tail(5)}, {good, good});
  CHECK_THAT(v3.metric, WithinAbs(v1.metric, 1e-15));
}

// Large n: sqrt(n)·U tends to A = ∫|B(t)|dt (Brownian bridge), whose mean is
// exactly sqrt(pi/32) (E|B(t)| = sqrt(2t(1-t)/pi)). The fitted table's limit must have that mean,
// and the fitted form must agree with a Monte Carlo at n just above the switch.
TEST_CASE("large-n u-pooling thresholds: fitted form against a closed form and Monte Carlo") {
  // mean of A from its quantile function: E A = ∫_0^1 Q_A(p) dp, Q_A(p) = lim sqrt(n) U_crit(n, p)
  const int big = 1000000000;
  const double rn = std::sqrt(static_cast<double>(big));
  double mean = 0;
  const int m = 200000;
  for (int i = 0; i < m; ++i) mean += rn * smi::stats::upool_threshold(big, (i + 0.5) / m, {}) / m;
  CHECK_THAT(mean, WithinRel(std::sqrt(M_PI / 32), 2e-3));
  // n = 60 (past the switch): an independent MC of 10^5 sets (sampling error ~0.3 %)
  smi::stats::UpoolMcSettings s;
  s.replications = 100000;
  s.seed = 99;
  std::vector<double> v(*smi::stats::upool_null_sample(60, s));
  std::sort(v.begin(), v.end());
  for (double c : {0.5, 0.9, 0.95, 0.99}) {
    const double mc = v[static_cast<std::size_t>(c * (v.size() - 1))];
    CHECK_THAT(smi::stats::upool_threshold(60, c), WithinRel(mc, 0.01));
    CHECK_THAT(smi::stats::upool_pvalue(60, mc), WithinAbs(1 - c, 0.004));
  }
  // n = 10,000 returns at once (10^6 MC sets took more than 10 minutes) and is consistent
  const double t = smi::stats::upool_threshold(10000, 0.95);
  CHECK_THAT(smi::stats::upool_pvalue(10000, t), WithinAbs(0.05, 1e-9));
  CHECK(smi::stats::upool_pvalue(10000, 2 * t) < 1e-3);  // past the table: the Gaussian tail of A
  CHECK(smi::stats::upool_pvalue(10000, 3 * t) < smi::stats::upool_pvalue(10000, 2 * t));
}
