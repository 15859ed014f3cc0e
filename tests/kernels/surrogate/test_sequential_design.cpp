// SPDX-License-Identifier: MIT
// Sequential Kriging designs: the batch choice against the Kriging variance written
// out by hand, and on a closed-form function the sequential design reaching its leave-one-out
// target with fewer points than fixed maximin hypercubes need for the same accuracy where the
// input distribution puts its mass.
#include <catch2/catch.hpp>
#include <cmath>

#include "kernels/surrogate/doe.hpp"
#include "kernels/surrogate/sequential_design.hpp"
#include "platform/core/errors.hpp"
#include "platform/core/rng.hpp"

using namespace smi::surrogate::kriging;

TEST_CASE("select_batch picks the largest weighted Kriging variance, written out for two design points") {
  // 1-D, gauss, theta = 4, no normalisation: r(d) = exp(-4 d^2); design {0.2, 0.8}.
  Eigen::MatrixXd X(2, 1);
  X << 0.2, 0.8;
  FitOptions o;
  o.theta = Eigen::VectorXd::Constant(1, 4.0), o.normalize = false;
  const Model m = fit(X, Eigen::Vector2d(1.0, 2.0), o);
  Eigen::MatrixXd C(101, 1);
  for (int i = 0; i <= 100; ++i) C(i, 0) = i / 100.0;
  auto var = [](double x) {  // 1 - r' R^-1 r with the 2 x 2 inverse by hand
    const double a = std::exp(-4 * (x - 0.2) * (x - 0.2)), b = std::exp(-4 * (x - 0.8) * (x - 0.8));
    const double rho = std::exp(-4 * 0.36), det = 1 - rho * rho;
    return 1 - (a * a + b * b - 2 * rho * a * b) / det;
  };
  auto best = [&](const Eigen::VectorXd& w) {
    int k = 0;
    for (int i = 1; i <= 100; ++i)
      if (w(i) * var(C(i, 0)) > w(k) * var(C(k, 0))) k = i;
    return k;
  };
  Eigen::VectorXd w = Eigen::VectorXd::Ones(101);
  std::vector<Eigen::Index> p = select_batch({&m}, C, w, 1);
  REQUIRE(p.size() == 1);
  // an end of the interval (0 and 1 tie): farthest from both points
  CHECK(var(C(p[0], 0)) == Approx(var(C(best(w), 0))).epsilon(1e-9));
  CHECK((p[0] == 0 || p[0] == 100));
  // weight: a density centred at 0.5 makes the middle worth more than the ends
  for (int i = 0; i <= 100; ++i) w(i) = std::exp(-0.5 * std::pow((C(i, 0) - 0.5) / 0.1, 2));
  p = select_batch({&m}, C, w, 1);
  CHECK(p[0] == best(w));
  CHECK(std::abs(C(p[0], 0) - 0.5) < 0.15);
  // a batch never repeats a point, and the second pick accounts for the first
  p = select_batch({&m}, C, Eigen::VectorXd::Ones(101), 2);
  CHECK(p[0] != p[1]);
  CHECK(std::abs(C(p[0], 0) - C(p[1], 0)) > 0.5);  // the two ends, not one end twice
  // bad input is named
  CHECK_THROWS_AS(select_batch({&m}, C, Eigen::VectorXd::Ones(3), 1), smi::DimensionMismatch);
  CHECK_THROWS_AS(select_batch({&m}, C, Eigen::VectorXd::Zero(101), 1), smi::InvalidArgument);
}

namespace {
// closed form on [0,1]^2, wavy enough that a Kriging needs a few dozen points
Eigen::MatrixXd f(const Eigen::MatrixXd& X) {
  return ((6 * X.col(0).array()).sin() + (5 * X.col(1).array()).cos() * X.col(0).array() + X.col(1).array().square()).matrix();
}
// the input distribution: independent normals (0.3, 0.08) and (0.65, 0.08), inside the box
Eigen::VectorXd density(const Eigen::MatrixXd& X) {
  return (-0.5 * ((X.col(0).array() - 0.3) / 0.08).square() - 0.5 * ((X.col(1).array() - 0.65) / 0.08).square()).exp().matrix();
}
double test_rmse(const std::vector<Model>& ms, const Eigen::MatrixXd& T) {
  const Eigen::VectorXd p = predict_mean(ms[0], T), y = f(T);
  return std::sqrt((p - y).squaredNorm() / static_cast<double>(T.rows()));
}
}  // namespace

TEST_CASE("a sequential design meets its target with fewer points than fixed hypercubes of the same accuracy") {
  smi::Rng rng(11);
  Eigen::MatrixXd T(500, 2);  // test points drawn from the input distribution
  for (int i = 0; i < 500; ++i) T.row(i) << 0.3 + 0.08 * rng.normal(), 0.65 + 0.08 * rng.normal();
  const Eigen::MatrixXd cand = smi::surrogate::doe::lhs(2000, 2, 5, {"none"});
  SequentialOptions o;
  o.batch = 4, o.max_points = 80, o.q2_target = 0.9999;
  o.fit.trend = Trend::linear, o.fit.seed = 3;
  int calls = 0;
  const SequentialResult r = sequential_design(smi::surrogate::doe::lhs(8, 2, 7), cand, density(cand), [&](const Eigen::MatrixXd& X) {
    ++calls;
    return f(X);
  }, o);
  REQUIRE(r.reached);
  const Eigen::Index n = r.X.rows();
  CHECK(n < 80);
  CHECK(calls == 1 + static_cast<int>(r.history.size()) - 1);          // one model call per batch
  CHECK(r.history.back().q2(0) >= 0.9999);
  CHECK((r.Y.col(0) - f(r.X)).cwiseAbs().maxCoeff() == 0.0);           // the outputs are the model's
  const double seq = test_rmse(r.models, T);
  // fixed maximin hypercubes over the box: the size that matches the sequential design's error
  // where the distribution puts its mass is larger than n
  Eigen::Index need = 0;
  for (Eigen::Index m = n; m <= 3 * n && need == 0; m += 4) {
    const Eigen::MatrixXd X = smi::surrogate::doe::lhs(m, 2, 7);
    FitOptions fo = o.fit;
    if (test_rmse({fit(X, f(X).col(0), fo)}, T) <= seq) need = m;
  }
  INFO("sequential: " << n << " points, test RMSE " << seq << "; fixed hypercube needs " << need);
  CHECK((need == 0 || need > n));
}

TEST_CASE("sequential_design stops at max_points and names bad input") {
  const Eigen::MatrixXd cand = smi::surrogate::doe::lhs(200, 2, 5, {"none"});
  SequentialOptions o;
  o.batch = 5, o.max_points = 18, o.q2_target = 1.0 + 1e-9;  // unreachable
  const SequentialResult r = sequential_design(smi::surrogate::doe::lhs(8, 2, 7), cand, Eigen::VectorXd::Ones(200), f, o);
  CHECK_FALSE(r.reached);
  CHECK(r.X.rows() == 18);  // 8, 13, 18
  CHECK(r.history.size() == 3);
  SequentialOptions small = o;
  small.max_points = 4;  // below the initial design
  CHECK_THROWS_AS(sequential_design(smi::surrogate::doe::lhs(8, 2, 7), cand, Eigen::VectorXd::Ones(200), f, small), smi::InvalidArgument);
  CHECK_THROWS_AS(sequential_design(smi::surrogate::doe::lhs(8, 2, 7), Eigen::MatrixXd::Zero(5, 3), Eigen::VectorXd::Ones(5), f, o),
                  smi::DimensionMismatch);
  // bad weights are refused before the model runs (each run may be a solver call)
  int runs = 0;
  const DesignModel counted = [&runs](const Eigen::MatrixXd& X) {
    ++runs;
    return f(X);
  };
  CHECK_THROWS_AS(sequential_design(smi::surrogate::doe::lhs(8, 2, 7), cand, Eigen::VectorXd::Ones(199), counted, o),
                  smi::DimensionMismatch);
  Eigen::VectorXd nan_w = Eigen::VectorXd::Ones(200);
  nan_w(3) = std::nan("");
  CHECK_THROWS_WITH(sequential_design(smi::surrogate::doe::lhs(8, 2, 7), cand, nan_w, counted, o), Catch::Contains("weight 4"));
  CHECK(runs == 0);
  // a non-finite model value names the design point and the output
  const DesignModel nan_at_3 = [](const Eigen::MatrixXd& X) {
    Eigen::MatrixXd Y = f(X);
    if (X.rows() > 2) Y(2, 0) = std::nan("");
    return Y;
  };
  CHECK_THROWS_WITH(sequential_design(smi::surrogate::doe::lhs(8, 2, 7), cand, Eigen::VectorXd::Ones(200), nan_at_3, o),
                    Catch::Contains("returned nan for output 1 at design point 3 ("));
}
