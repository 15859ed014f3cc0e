// SPDX-License-Identifier: MIT
// Surrogate screening: the ridge polynomial's closed-form leave-one-out error, the
// eq.-3 PDF areas of a linear model with normal inputs against their closed form, a quadratic
// model the surrogate reproduces against the full screening on the same CRN sample, a poor
// surrogate reported, and Borgonovo's delta against numerical integration of its definition.
#include <Eigen/Dense>
#include <catch2/catch.hpp>
#include <cmath>
#include <memory>

#include "kernels/stats/families.hpp"
#include "kernels/surrogate/delta.hpp"
#include "kernels/surrogate/poly_ridge.hpp"
#include "kernels/surrogate/screen_surrogate.hpp"
#include "platform/core/normal.hpp"
#include "platform/core/rng.hpp"

using namespace smi;

namespace {

// L1 area between N(0, s1^2) and N(0, s2^2), s1 > s2: the densities cross at +-c with
// c^2 = 2 s1^2 s2^2 ln(s1/s2) / (s1^2 - s2^2), the narrower one above inside.
double area_two_normals(double s1, double s2) {
  const double c = std::sqrt(2 * s1 * s1 * s2 * s2 * std::log(s1 / s2) / (s1 * s1 - s2 * s2));
  return 4 * (normal_cdf(c / s2) - normal_cdf(c / s1));
}

std::vector<surrogate::propagate::Input> normals(int k) {
  std::vector<surrogate::propagate::Input> in;
  for (int i = 0; i < k; ++i) in.push_back({"x" + std::to_string(i + 1), std::make_shared<stats::Normal>(0.0, 1.0)});
  return in;
}

const surrogate::screen::Row& row(const surrogate::screen::Result& r, const std::string& name) {
  for (const auto& w : r.rows)
    if (w.input == name) return w;
  FAIL("no row " << name);
  return r.rows[0];
}

}  // namespace

TEST_CASE("ridge polynomial: PRESS equals brute-force leave-one-out at the same ridge weight", "[screen_surrogate]") {
  Rng rng(7);
  const Eigen::MatrixXd X = rng.normal_matrix(40, 3);
  Eigen::VectorXd y = 1.0 + 2.0 * X.col(0).array() - X.col(1).array().square() + 0.3 * X.col(2).array();
  y += 0.2 * rng.normal(40);
  for (double lam : {0.0, 3.0}) {
    const surrogate::polyfit::Fit f = surrogate::polyfit::fit(X, y, surrogate::polyfit::Basis::quadratic, lam);
    double press = 0;
    for (Eigen::Index i = 0; i < X.rows(); ++i) {
      Eigen::MatrixXd Xi(X.rows() - 1, X.cols());
      Eigen::VectorXd yi(X.rows() - 1);
      for (Eigen::Index r = 0, o = 0; r < X.rows(); ++r)
        if (r != i) Xi.row(o) = X.row(r), yi(o++) = y(r);
      // Refit on the remaining points with the full design's standardisation and weight:
      // ridge on centred columns, an unpenalised intercept (the definition, solved directly).
      Eigen::MatrixXd F(X.rows(), 6);
      for (int j = 0; j < 3; ++j) {
        F.col(j) = (X.col(j).array() - f.mu(j)) / f.sd(j);
        F.col(3 + j) = F.col(j).array().square() - 1.0;
      }
      Eigen::MatrixXd Fi(X.rows() - 1, 6);
      for (Eigen::Index r = 0, o = 0; r < X.rows(); ++r)
        if (r != i) Fi.row(o++) = F.row(r);
      const Eigen::RowVectorXd fm = Fi.colwise().mean();
      const Eigen::MatrixXd Fc = Fi.rowwise() - fm;
      const double ym = yi.mean();
      const Eigen::VectorXd b =
          (Fc.transpose() * Fc + lam * Eigen::MatrixXd::Identity(6, 6)).ldlt().solve(Fc.transpose() * (yi.array() - ym).matrix());
      const double pred = ym + (F.row(i) - fm).dot(b);
      press += (y(i) - pred) * (y(i) - pred);
    }
    CHECK(f.press == Approx(press).epsilon(1e-9));
    CHECK(f.q2 == Approx(1 - press / (y.array() - y.mean()).square().sum()).epsilon(1e-9));
  }
  // Automatic choice: no worse than either weight above.
  const surrogate::polyfit::Fit a = surrogate::polyfit::fit(X, y, surrogate::polyfit::Basis::quadratic);
  CHECK(a.press <= surrogate::polyfit::fit(X, y, surrogate::polyfit::Basis::quadratic, 0.0).press * (1 + 1e-12));
  CHECK(a.press <= surrogate::polyfit::fit(X, y, surrogate::polyfit::Basis::quadratic, 3.0).press * (1 + 1e-12));
}

TEST_CASE("surrogate screening of a linear model: eq.-3 areas match the two-normal closed form", "[screen_surrogate]") {
  const auto in = normals(4);
  const double a[4] = {3, 2, 1, 0};
  auto model = [&](const Eigen::MatrixXd& X) {
    Eigen::MatrixXd Y = Eigen::MatrixXd::Zero(X.rows(), 1);
    for (int j = 0; j < 4; ++j) Y.col(0) += a[j] * X.col(j);
    return Y;
  };
  surrogate::screen::Options opt;
  opt.n = 20000;
  opt.seed = 11;
  opt.sobol = false;
  surrogate::screen::SurrogateOptions so;
  so.runs = 40;
  so.basis = surrogate::polyfit::Basis::linear;
  const auto res = surrogate::screen::screen_surrogate(in, model, {"y"}, opt, so);
  REQUIRE(res.fits.size() == 1);
  CHECK(res.model_runs == 40);
  CHECK(res.fits[0].q2 > 1 - 1e-9);
  CHECK(res.screening[0].warnings.empty());
  const double s2 = 9 + 4 + 1;
  for (int j = 0; j < 3; ++j) {
    const double ref = area_two_normals(std::sqrt(s2), std::sqrt(s2 - a[j] * a[j]));
    // KDE smoothing and sampling noise at n = 20000: within 0.012 of an area that runs to 2.
    CHECK(row(res.screening[0], "x" + std::to_string(j + 1)).e == Approx(ref).margin(0.012));
  }
  CHECK(row(res.screening[0], "x4").e < 1e-6);
  CHECK(res.screening[0].rows[0].input == "x1");
  CHECK(res.screening[0].rows[1].input == "x2");
  CHECK(res.screening[0].rows[2].input == "x3");
  // The same indices as the full screening of the model on the same CRN sample.
  const auto full = surrogate::screen::screen(in, model, {"y"}, opt);
  for (int j = 0; j < 4; ++j) {
    const std::string n = "x" + std::to_string(j + 1);
    CHECK(row(res.screening[0], n).e == Approx(row(full[0], n).e).margin(1e-6));
  }
}

TEST_CASE("surrogate screening of a quadratic model equals the full screening on the same CRN sample",
          "[screen_surrogate]") {
  std::vector<surrogate::propagate::Input> in = {{"u", std::make_shared<stats::Uniform>(-1.0, 2.0)},
                                      {"g", std::make_shared<stats::Normal>(5.0, 0.5)},
                                      {"l", std::make_shared<stats::LogNormal>(stats::LogNormal::from_log_params(0.2, 0.3))},
                                      {"c", nullptr, 4.0}};
  auto model = [](const Eigen::MatrixXd& X) {
    Eigen::MatrixXd Y(X.rows(), 2);
    Y.col(0) = X.col(0).array().square() + 2 * X.col(1).array() + 0.5 * X.col(2).array().square() - X.col(2).array() +
               X.col(3).array();
    Y.col(1) = 3 * X.col(2).array() - 0.7 * (X.col(1).array() - 5).square();
    return Y;
  };
  surrogate::screen::Options opt;
  opt.n = 4000;
  opt.seed = 3;
  opt.bootstrap = 0;
  surrogate::screen::SurrogateOptions so;
  so.runs = 30;
  const auto res = surrogate::screen::screen_surrogate(in, model, {"a", "b"}, opt, so);
  const auto full = surrogate::screen::screen(in, model, {"a", "b"}, opt);
  for (int o = 0; o < 2; ++o) {
    CHECK(res.fits[static_cast<std::size_t>(o)].q2 > 1 - 1e-9);
    for (std::size_t i = 0; i < full[static_cast<std::size_t>(o)].rows.size(); ++i) {
      const auto& f = full[static_cast<std::size_t>(o)].rows[i];
      const auto& s = res.screening[static_cast<std::size_t>(o)].rows[i];
      CHECK(s.input == f.input);
      CHECK(s.e == Approx(f.e).margin(1e-6));
      CHECK(s.st == Approx(f.st).margin(1e-6));  // Sobol' on the surrogate too, at no model cost
    }
  }
}

TEST_CASE("a poor surrogate is reported with its Q2", "[screen_surrogate]") {
  const auto in = normals(3);
  auto model = [](const Eigen::MatrixXd& X) {
    Eigen::MatrixXd Y(X.rows(), 1);
    Y.col(0) = (4 * X.col(0)).array().sin() * X.col(1).array() + 0.1 * X.col(2).array();
    return Y;
  };
  surrogate::screen::Options opt;
  opt.n = 2000;
  opt.sobol = false;
  surrogate::screen::SurrogateOptions so;
  so.runs = 60;
  const auto res = surrogate::screen::screen_surrogate(in, model, {"y"}, opt, so);
  CHECK(res.fits[0].q2 < 0.5);
  REQUIRE(!res.screening[0].warnings.empty());
  CHECK_THAT(res.screening[0].warnings[0], Catch::Contains("Q2") && Catch::Contains("'y'") && Catch::Contains("method"));
  // Too few runs for delta's classes: a clear error naming the way out.
  so.runs = 12;
  CHECK_THROWS_WITH(surrogate::screen::screen_surrogate(in, model, {"y"}, opt, so), Catch::Contains("delta = false"));
  so.delta = false;
  CHECK_NOTHROW(surrogate::screen::screen_surrogate(in, model, {"y"}, opt, so));
}

TEST_CASE("given-data Borgonovo delta of a linear model against its definition integrated numerically",
          "[screen_surrogate]") {
  // y = 3 x1 + 2 x2 + x3 (+ 0 x4), standard normals: Y ~ N(0, 14), Y | x_i ~ N(a_i x_i, 14 - a_i^2).
  Rng rng(5);
  const Eigen::Index n = 20000;
  const Eigen::MatrixXd X = rng.normal_matrix(n, 4);
  const Eigen::VectorXd y = 3 * X.col(0) + 2 * X.col(1) + X.col(2);
  const surrogate::delta::Result d = surrogate::delta::estimate(X, y);
  CHECK(d.classes == surrogate::delta::default_classes(n));
  const double a[3] = {3, 2, 1};
  for (int j = 0; j < 3; ++j) {
    const double s = std::sqrt(14.0), sc = std::sqrt(14.0 - a[j] * a[j]);
    double ref = 0;
    const double dx = 0.02, dy = 0.01;
    for (double x = -8; x <= 8; x += dx) {
      double inner = 0;
      for (double t = -30; t <= 30; t += dy) {
        const double f = std::exp(-0.5 * t * t / 14.0) / (s * std::sqrt(2 * M_PI));
        const double g = std::exp(-0.5 * (t - a[j] * x) * (t - a[j] * x) / (sc * sc)) / (sc * std::sqrt(2 * M_PI));
        inner += std::abs(f - g) * dy;
      }
      ref += std::exp(-0.5 * x * x) / std::sqrt(2 * M_PI) * inner * dx;
    }
    ref *= 0.5;
    INFO("x" << j + 1 << " reference " << ref << " estimate " << d.delta(j) << " floor " << d.floor);
    CHECK(d.delta(j) == Approx(ref).margin(0.03));
  }
  // An input without influence sits at the estimator's noise floor, far below the others.
  CHECK(d.delta(3) < 2 * d.floor + 0.01);
  CHECK(d.delta(2) > 2 * d.delta(3));
}
