// SPDX-License-Identifier: MIT
// Closed-form LOO against brute-force refits; save/load round trip; ill-conditioning
// diagnoses (duplicates, near-singular R) and their ways out; nugget estimation on noise.
#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>
#include <iterator>
#include <cstdio>

#include "kernels/surrogate/kriging.hpp"
#include "platform/core/rng.hpp"

using namespace smi::surrogate::kriging;

namespace {
Eigen::VectorXd f(const Eigen::MatrixXd& X) {
  return ((2 * X.col(0).array()).sin() + X.col(1).array().square() * X.col(0).array()).matrix();
}
}  // namespace

TEST_CASE("closed-form LOO residuals equal refits without each point") {
  smi::Rng rng(3);
  const Eigen::MatrixXd X = rng.uniform_matrix(15, 2);
  const Eigen::VectorXd y = f(X);
  for (Trend t : {Trend::constant, Trend::linear}) {
    FitOptions o;
    o.trend = t, o.theta = Eigen::Vector2d(0.8, 2.5), o.normalize = false;
    const Model m = fit(X, y, o);
    const LooResult r = loo(m);
    double ss = 0;
    for (int i = 0; i < 15; ++i) {
      Eigen::MatrixXd Xi(14, 2);
      Eigen::VectorXd yi(14);
      for (int k = 0, r2 = 0; k < 15; ++k)
        if (k != i) Xi.row(r2) = X.row(k), yi[r2++] = y[k];
      const Model mi = fit(Xi, yi, o);
      const Prediction p = predict(mi, X.row(i));
      CHECK(std::abs(r.residuals[i] - (y[i] - p.mean[0])) < 1e-8);
      // same sigma2 is assumed by the closed form: compare the correlation part
      CHECK(std::abs(r.variance[i] / m.process_variance() - p.mse[0] / mi.process_variance()) < 1e-8);
      ss += std::pow(y[i] - p.mean[0], 2);
    }
    CHECK(std::abs(r.rmse - std::sqrt(ss / 15)) < 1e-9);
    CHECK(std::abs(r.q2 - (1 - ss / (y.array() - y.mean()).square().sum())) < 1e-9);
  }
}

TEST_CASE("save and load give the same predictions bit for bit") {
  smi::Rng rng(5);
  const Eigen::MatrixXd X = rng.uniform_matrix(20, 2);
  FitOptions o;
  o.trend = Trend::quadratic;
  o.corr = Corr::matern52;
  const Model m = fit(X, f(X), o);
  const std::string path = "test_kriging_model.txt";
  save(m, path);
  const Model l = load(path);
  std::remove(path.c_str());
  const Eigen::MatrixXd T = rng.uniform_matrix(50, 2);
  const Prediction a = predict(m, T), b = predict(l, T);
  CHECK(a.mean == b.mean);
  CHECK(a.mse == b.mse);
  CHECK(l.method == m.method);
  CHECK_THROWS_WITH(load("no/such/model.txt"), Catch::Contains("cannot open"));
}

TEST_CASE("model files carry the input and output names; version 1 files still load") {
  smi::Rng rng(6);
  const Eigen::MatrixXd X = rng.uniform_matrix(12, 2);
  const Model m = fit(X, f(X));
  const std::string path = "test_kriging_names.txt";
  save(m, path, {{"column frame E", "ecu_bracket_thickness"}, "mode 4"});
  ModelNames nm;
  const Model l = load(path, &nm);
  CHECK(nm.inputs == std::vector<std::string>{"column frame E", "ecu_bracket_thickness"});
  CHECK(nm.output == "mode 4");
  CHECK(predict_mean(l, X) == predict_mean(m, X));
  // The same file as version 1 wrote it: no names section.
  std::ifstream in(path);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  in.close();
  text.replace(text.find("smi-kriging 2"), 13, "smi-kriging 1");
  text.erase(text.find("names 2"), text.find("end\n") - text.find("names 2"));
  std::ofstream(path) << text;
  ModelNames none{{"stale"}, "stale"};
  const Model v1 = load(path, &none);
  CHECK(none.inputs.empty());
  CHECK(none.output.empty());
  CHECK(predict_mean(v1, X) == predict_mean(m, X));
  std::remove(path.c_str());
  CHECK_THROWS_WITH(save(m, path, {{"only one"}, "y"}), Catch::Contains("1 input names for a model of 2 inputs"));
  CHECK_THROWS_WITH(save(m, path, {{"a", "b\nc"}, "y"}), Catch::Contains("on one line"));
}

TEST_CASE("duplicate design points: a diagnosis naming the rows, and nugget as the way out") {
  Eigen::MatrixXd X(5, 1);
  X << 0, 0.3, 0.5, 0.3, 1;
  const Eigen::VectorXd y = (Eigen::VectorXd(5) << 0, 1, 2, 1.1, 0).finished();
  CHECK_THROWS_WITH(fit(X, y), Catch::Contains("rows 2 and 4 are identical") && Catch::Contains("nugget = true"));
  FitOptions o;
  o.estimate_nugget = true;
  const Model m = fit(X, y, o);
  CHECK(m.nugget > 1e-6);  // the two responses at x = 0.3 disagree: noise must be estimated
  const Prediction p = predict(m, X.row(1));
  CHECK(std::isfinite(p.mean[0]));
  CHECK(std::abs(p.mean[0] - 1.05) < 0.1);  // between the two noisy values
}

TEST_CASE("nearly singular R (tiny theta, 100 points): finite predictions, no NaN") {
  // With theta = 1e-6 the Gaussian correlation matrix is all ones to 1e-6; DACE's diagonal
  // mu = (10 + m) eps keeps it factorisable and the predictor stays usable.
  Eigen::MatrixXd X = Eigen::VectorXd::LinSpaced(100, 0, 1);
  const Eigen::VectorXd y = (3 * X.col(0).array()).sin().matrix();
  FitOptions o;
  o.theta = Eigen::VectorXd::Constant(1, 1e-6);
  const Model m = fit(X, y, o);
  const Prediction p = predict(m, Eigen::MatrixXd::Constant(1, 1, 0.555));
  CHECK(std::abs(p.mean[0] - std::sin(1.665)) < 0.05);
  CHECK(std::isfinite(p.mse[0]));
  CHECK(p.mse[0] >= 0);
}

TEST_CASE("ML diagnosis: an input the response ignores ends at its lower theta bound, with a warning") {
  smi::Rng rng(9);
  const Eigen::MatrixXd X = rng.uniform_matrix(30, 2);
  const Eigen::VectorXd y = (3 * X.col(0).array()).sin().matrix();  // x2 plays no role
  const Model m = fit(X, y);
  bool found = false;
  for (const auto& w : m.warnings) found = found || w.find("theta[2] is at its lower bound") != std::string::npos;
  CHECK(found);
  CHECK(m.theta[1] < 1e-2 * m.theta[0]);
}

TEST_CASE("bad input is named") {
  Eigen::MatrixXd X(3, 1);
  X << 0, 0.5, 1;
  CHECK_THROWS_WITH(fit(X, Eigen::VectorXd::Ones(2)), Catch::Contains("y has 2 values"));
  Eigen::VectorXd y(3);
  y << 1, NAN, 2;
  CHECK_THROWS_WITH(fit(X, y), Catch::Contains("y[2] is not finite"));
  FitOptions o;
  o.trend = Trend::quadratic;
  Eigen::MatrixXd X2(4, 2);
  X2 << 0, 0, 1, 0, 0, 1, 1, 1;
  CHECK_THROWS_WITH(fit(X2, Eigen::VectorXd::Ones(4), o), Catch::Contains("6 coefficients"));
  o.trend = Trend::constant;
  o.theta = Eigen::Vector3d(1, 1, 1);
  CHECK_THROWS_WITH(fit(X2, Eigen::VectorXd::Ones(4), o), Catch::Contains("theta has 3 values"));
}
