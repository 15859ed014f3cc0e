// SPDX-License-Identifier: MIT
// Profile intervals against the closed-form likelihood-ratio intervals of a
// normal sample's mean and standard deviation.
#include <catch2/catch.hpp>

#include <cmath>

#include "kernels/improve/profile_intervals.hpp"
#include "kernels/stats/special.hpp"
#include "platform/core/rng.hpp"

using namespace smi::improve;

TEST_CASE("½ χ²₁ quantiles") {
  CHECK(likelihood_ratio_delta(0.90) == Approx(2.705543 / 2).epsilon(1e-6));
  CHECK(likelihood_ratio_delta(0.95) == Approx(3.841459 / 2).epsilon(1e-6));
}

TEST_CASE("Student t quantiles and the small-sample delta against SciPy (tests/reference/student_t_quantile.py)") {
  CHECK(smi::stats::student_t_quantile(0.95, 22) == Approx(1.717144374380242).epsilon(1e-9));
  CHECK(smi::stats::student_t_quantile(0.975, 3) == Approx(3.182446305284263).epsilon(1e-9));
  CHECK(smi::stats::student_t_quantile(0.05, 1) == Approx(-6.313751514800938).epsilon(1e-9));
  CHECK(smi::stats::student_t_quantile(0.999, 2.5) == Approx(13.822193110834316).epsilon(1e-9));
  CHECK(smi::stats::student_t_quantile(0.6, 100) == Approx(0.25402218245699415).epsilon(1e-9));
  CHECK(likelihood_ratio_delta(0.9, 25, 3) == Approx(1.5721830735804492).epsilon(1e-9));
  CHECK(likelihood_ratio_delta(0.95, 30, 2) == Approx(2.094552536206453).epsilon(1e-9));
  // Large n: back to ½ χ²₁.
  CHECK(likelihood_ratio_delta(0.9, 1000000, 3) == Approx(likelihood_ratio_delta(0.9)).epsilon(1e-5));
  CHECK_THROWS_WITH(likelihood_ratio_delta(0.9, 3, 3), Catch::Contains("more observations than parameters"));
}

TEST_CASE("normal sample: profile intervals of mu and sigma equal the closed-form likelihood-ratio intervals") {
  smi::Rng g(21);
  const Eigen::VectorXd x = g.normal_matrix(30, 1).col(0) * 2.0 + Eigen::VectorXd::Constant(30, 7.0);
  const double n = static_cast<double>(x.size()), xbar = x.mean();
  const double s2 = (x.array() - xbar).square().sum() / n;  // MLE variance
  auto nll = [&](const Eigen::VectorXd& t) {
    return Evaluation{n * std::log(t[1]) + (x.array() - t[0]).square().sum() / (2 * t[1] * t[1]), {}};
  };
  std::vector<Parameter> p{{"mu", 0.0, 15.0, 5.0}, {"sigma", 0.2, 8.0, 1.0}};
  const Eigen::Vector2d opt(xbar, std::sqrt(s2));
  ProfileOptions o;
  o.delta = likelihood_ratio_delta(0.9);
  o.optimizer.xtol_rel = 1e-10;
  o.optimizer.ftol_abs = 1e-12;
  const ProfileResult r = profile_intervals(p, nll, opt, nll(opt).value, o);
  // mu: n/2 ln(1 + (xbar − mu)²/s2) = delta.
  const double half = std::sqrt(s2 * (std::exp(2 * o.delta / n) - 1));
  CHECK(r.intervals[0].lower == Approx(xbar - half).epsilon(1e-5));
  CHECK(r.intervals[0].upper == Approx(xbar + half).epsilon(1e-5));
  // sigma: n ln(s/ŝ) + n s2/(2 s²) − n/2 = delta, solved by bisection on each side.
  auto excess = [&](double s) { return n * std::log(s / std::sqrt(s2)) + n * s2 / (2 * s * s) - n / 2 - o.delta; };
  auto root = [&](double a, double b) {
    for (int i = 0; i < 200; ++i) {
      const double m = 0.5 * (a + b);
      ((excess(a) > 0) == (excess(m) > 0) ? a : b) = m;
    }
    return 0.5 * (a + b);
  };
  CHECK(r.intervals[1].lower == Approx(root(0.2, std::sqrt(s2))).epsilon(1e-5));
  CHECK(r.intervals[1].upper == Approx(root(std::sqrt(s2), 8.0)).epsilon(1e-5));
  for (const auto& iv : r.intervals) {
    CHECK(iv.determined);
    CHECK_FALSE(iv.lower_open);
    CHECK_FALSE(iv.upper_open);
  }
}

TEST_CASE("a parameter the objective ignores is not determined; a flat combination leaves both open") {
  // (a + 2b − 3)²·50: the profile of a is flat (b compensates) until b hits its bounds.
  std::vector<Parameter> p{{"a", -1.0, 1.0, 0.0}, {"b", -10.0, 10.0, 0.0}, {"c", 0.0, 1.0, 0.5}};
  auto f = [](const Eigen::VectorXd& t) { return Evaluation{50 * std::pow(t[0] + 2 * t[1] - 3, 2) + 1e-9 * t[2], {}}; };
  ProfileOptions o;
  o.delta = 0.5;
  const ProfileResult r = profile_intervals(p, f, Eigen::Vector3d(1.0, 1.0, 0.0), 1e-9 * 0.0 + f(Eigen::Vector3d(1.0, 1.0, 0.0)).value, o);
  CHECK_FALSE(r.intervals[0].determined);
  CHECK(r.intervals[0].lower == -1.0);
  CHECK(r.intervals[0].upper == 1.0);
  CHECK_FALSE(r.intervals[2].determined);
  CHECK(r.warnings.size() >= 2);
}
