// SPDX-License-Identifier: MIT
// Kriging against the DACE reference values of spec §8.4 (1-D and 2-D, corrgauss/correxp,
// regpoly0/1, fixed theta and boxmin with its evaluation counts).
#include <catch2/catch.hpp>
#include <cmath>

#include "kernels/surrogate/kriging.hpp"

using namespace smi::surrogate::kriging;
using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;

namespace {
Eigen::MatrixXd S1() { return (Eigen::MatrixXd(5, 1) << 0, 0.2, 0.45, 0.7, 1.0).finished(); }
Eigen::VectorXd Y1() {
  Eigen::VectorXd y(5);
  for (int i = 0; i < 5; ++i) y[i] = S1()(i, 0) + std::sin(5 * S1()(i, 0));
  return y;
}
Eigen::MatrixXd S2() {
  return (Eigen::MatrixXd(8, 2) << 0, 0, 1, 0.2, 0.3, 0.9, 0.8, 0.7, 0.5, 0.4, 0.1, 0.6, 0.9, 1, 0.6, 0.05).finished();
}
Eigen::VectorXd Y2() {
  const Eigen::MatrixXd S = S2();
  return (S.col(0).array().square() + (3 * S.col(1).array()).sin()).matrix();
}
FitOptions fixed(Trend t, Corr c, Eigen::VectorXd theta) {
  FitOptions o;
  o.trend = t, o.corr = c, o.theta = std::move(theta);
  return o;
}
Eigen::MatrixXd pts(std::initializer_list<double> v, int n) {
  Eigen::MatrixXd X(static_cast<Eigen::Index>(v.size()) / n, n);
  int k = 0;
  for (double x : v) X(k / n, k % n) = x, ++k;
  return X;
}
}  // namespace

TEST_CASE("DACE 1-D regpoly0 corrgauss theta=1 (spec 8.4)") {
  const Model m = fit(S1(), Y1(), fixed(Trend::constant, Corr::gauss, Eigen::VectorXd::Constant(1, 1.0)));
  CHECK_THAT(m.mS[0], WithinAbs(0.47, 1e-12));
  CHECK_THAT(m.sS[0], WithinAbs(0.3962322551, 1e-10));
  CHECK_THAT(m.mY, WithinAbs(0.5319673359, 1e-10));
  CHECK_THAT(m.sY, WithinAbs(0.5704206619, 1e-10));
  CHECK_THAT(m.psi, WithinAbs(0.8100877481, 1e-9));
  CHECK_THAT(m.beta[0], WithinAbs(-0.4673905560, 1e-9));
  CHECK_THAT(m.process_variance(), WithinAbs(0.5251229240, 1e-9));
  const Prediction p = predict(m, pts({0.3, 0.85}, 1));
  CHECK_THAT(p.mean[0], WithinAbs(1.3372431829, 1e-9));
  CHECK_THAT(p.mse[0], WithinAbs(0.0012880874, 1e-10));
  CHECK_THAT(p.mean[1], WithinAbs(0.0607423314, 1e-9));
  CHECK_THAT(p.mse[1], WithinAbs(0.0078628370, 1e-10));
}

TEST_CASE("DACE 1-D regpoly1 and correxp (spec 8.4)") {
  const Model m = fit(S1(), Y1(), fixed(Trend::linear, Corr::gauss, Eigen::VectorXd::Constant(1, 1.0)));
  CHECK_THAT(m.psi, WithinAbs(0.7776998508, 1e-9));
  CHECK_THAT(m.beta[0], WithinAbs(-0.4832564887, 1e-9));
  CHECK_THAT(m.beta[1], WithinAbs(0.3083783422, 1e-9));
  CHECK_THAT(m.process_variance(), WithinAbs(0.5041281276, 1e-9));
  const Prediction p = predict(m, pts({0.3, 0.85}, 1));
  CHECK_THAT(p.mean[0], WithinAbs(1.3305753210, 1e-9));
  CHECK_THAT(p.mse[0], WithinAbs(0.0014501057, 1e-10));
  CHECK_THAT(p.mean[1], WithinAbs(0.0423963521, 1e-9));
  CHECK_THAT(p.mse[1], WithinAbs(0.0091648461, 1e-10));

  const Model e = fit(S1(), Y1(), fixed(Trend::constant, Corr::exp, Eigen::VectorXd::Constant(1, 1.0)));
  CHECK_THAT(e.psi, WithinAbs(1.0263303053, 1e-9));
  const Prediction q = predict(e, pts({0.3}, 1));
  CHECK_THAT(q.mean[0], WithinAbs(1.0810272472, 1e-9));
  CHECK_THAT(q.mse[0], WithinAbs(0.1292870588, 1e-9));
}

TEST_CASE("DACE 1-D boxmin: theta and evaluation counts (spec 8.4)") {
  FitOptions o;
  o.method = "boxmin";
  o.theta0 = Eigen::VectorXd::Constant(1, 1.0), o.lower = Eigen::VectorXd::Constant(1, 0.1),
  o.upper = Eigen::VectorXd::Constant(1, 20.0);
  const Model m0 = fit(S1(), Y1(), o);
  CHECK_THAT(m0.theta[0], WithinAbs(std::pow(2.0, 5.0 / 12), 1e-12));
  CHECK_THAT(m0.psi, WithinAbs(0.8029678897, 1e-9));
  CHECK(m0.evaluations == 5);
  o.trend = Trend::linear;
  const Model m1 = fit(S1(), Y1(), o);
  CHECK_THAT(m1.theta[0], WithinAbs(std::pow(2.0, -5.0 / 12), 1e-12));
  CHECK_THAT(m1.psi, WithinAbs(0.7703897349, 1e-9));
  CHECK(m1.evaluations == 7);
}

TEST_CASE("DACE 2-D fixed theta and boxmin (spec 8.4)") {
  const Model m = fit(S2(), Y2(), fixed(Trend::constant, Corr::gauss, Eigen::VectorXd::Constant(2, 1.0)));
  CHECK_THAT(m.psi, WithinAbs(0.8723646750, 1e-9));
  CHECK_THAT(m.beta[0], WithinAbs(-0.1625888795, 1e-9));
  CHECK_THAT(m.process_variance(), WithinAbs(0.2802777906, 1e-9));
  const Prediction p = predict(m, pts({0.4, 0.5, 0.95, 0.1}, 2));
  CHECK_THAT(p.mean[0], WithinAbs(1.1653196913, 1e-9));
  CHECK_THAT(p.mse[0], WithinAbs(0.0375782760, 1e-10));
  CHECK_THAT(p.mean[1], WithinAbs(1.3724446936, 1e-9));
  CHECK_THAT(p.mse[1], WithinAbs(0.0361267652, 1e-10));

  const Model l = fit(S2(), Y2(), fixed(Trend::linear, Corr::gauss, Eigen::VectorXd::Constant(2, 1.0)));
  CHECK_THAT(l.psi, WithinAbs(0.5330890578, 1e-9));
  const Prediction pl = predict(l, pts({0.4, 0.5}, 2));
  CHECK_THAT(pl.mean[0], WithinAbs(1.2093921193, 1e-9));
  CHECK_THAT(pl.mse[0], WithinAbs(0.0244566824, 1e-10));

  FitOptions o;
  o.method = "boxmin";
  o.theta0 = Eigen::VectorXd::Constant(2, 1.0), o.lower = Eigen::VectorXd::Constant(2, 0.1),
  o.upper = Eigen::VectorXd::Constant(2, 20.0);
  const Model b = fit(S2(), Y2(), o);
  CHECK_THAT(b.theta[0], WithinAbs(0.25, 1e-12));
  CHECK_THAT(b.theta[1], WithinAbs(0.5, 1e-12));
  CHECK_THAT(b.psi, WithinAbs(0.7160889914, 1e-9));
  CHECK(b.evaluations == 18);
  const Prediction pb = predict(b, pts({0.4, 0.5}, 2));
  CHECK_THAT(pb.mean[0], WithinAbs(1.1699462, 1e-7));
  CHECK_THAT(pb.mse[0], WithinAbs(0.0043722, 1e-7));
}

TEST_CASE("maximum likelihood finds the true minimiser of psi (spec 8.4: 0.680280)") {
  FitOptions o;  // defaults: ML, constant trend, gauss
  const Model m = fit(S2(), Y2(), o);
  CHECK_THAT(m.psi, WithinAbs(0.680280, 2e-6));
  CHECK_THAT(m.theta[0], WithinRel(0.1195, 0.01));
  CHECK_THAT(m.theta[1], WithinRel(0.3390, 0.01));
  CHECK(m.method == "ml");
}
