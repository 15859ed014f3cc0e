// SPDX-License-Identifier: MIT
// The Kriging predictor's input gradient in closed form against central differences of the
// predicted mean, for every correlation family and trend.
#include <catch2/catch.hpp>

#include <cmath>

#include "kernels/surrogate/kriging.hpp"
#include "platform/core/rng.hpp"

using namespace smi::surrogate::kriging;

TEST_CASE("predict_gradient matches central differences of predict_mean") {
  smi::Rng g(7);
  const Eigen::MatrixXd X = g.uniform_matrix(40, 3);
  Eigen::VectorXd y(X.rows());
  for (Eigen::Index i = 0; i < X.rows(); ++i) y[i] = std::sin(3 * X(i, 0)) + X(i, 1) * X(i, 1) * 2 - X(i, 2) + 0.5 * X(i, 0) * X(i, 2);
  Eigen::MatrixXd P = g.uniform_matrix(300, 3);  // 300 points: several blocks
  P = (P.array() * 1.2 - 0.1).matrix();          // a little outside the design too
  for (Corr c : {Corr::gauss, Corr::exp, Corr::matern32, Corr::matern52})
    for (Trend t : {Trend::constant, Trend::linear, Trend::quadratic}) {
      FitOptions o;
      o.corr = c;
      o.trend = t;
      o.theta = Eigen::Vector3d(2.0, 0.7, 1.3);
      const Model md = fit(X, y, o);
      const Eigen::MatrixXd G = predict_gradient(md, P, 2);
      REQUIRE(G.rows() == P.rows());
      const double h = 1e-6;
      double worst = 0.0;
      for (Eigen::Index d = 0; d < 3; ++d) {
        Eigen::MatrixXd Pp = P, Pm = P;
        Pp.col(d).array() += h;
        Pm.col(d).array() -= h;
        const Eigen::VectorXd fd = (predict_mean(md, Pp, 1) - predict_mean(md, Pm, 1)) / (2 * h);
        worst = std::max(worst, (fd - G.col(d)).cwiseAbs().maxCoeff() / (1.0 + fd.cwiseAbs().maxCoeff()));
      }
      INFO("corr " << corr_name(c) << ", trend " << trend_name(t));
      // exp is not differentiable where a coordinate equals a design point's: none of the
      // random points does, but differences straddle kinks close by, hence its looser bound.
      CHECK(worst < (c == Corr::exp ? 1e-4 : 1e-6));
    }
}
