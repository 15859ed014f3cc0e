// SPDX-License-Identifier: MIT
// The analytic gradient of ln psi (surrogate/likelihood.cpp) against central differences,
// for every correlation family, with and without the nugget.
#include <catch2/catch.hpp>
#include <cmath>

#include "kernels/surrogate/likelihood.hpp"
#include "platform/core/rng.hpp"

using namespace smi::surrogate::kriging;

TEST_CASE("d ln psi / d ln theta matches central differences") {
  smi::Rng rng(7);
  const Eigen::MatrixXd S = rng.normal_matrix(12, 3);
  Eigen::VectorXd Y(12);
  for (int i = 0; i < 12; ++i) Y[i] = std::sin(S(i, 0)) + S(i, 1) * S(i, 2);
  for (Corr c : {Corr::gauss, Corr::exp, Corr::matern32, Corr::matern52}) {
    for (Trend t : {Trend::constant, Trend::linear}) {
      const detail::Problem pb(S, Y, t, c);
      const Eigen::Vector3d theta(0.3, 0.7, 1.9);
      const double nug = 1e-3;
      const detail::Factors f = detail::factorize(pb, theta, nug);
      REQUIRE(f.ok);
      const Eigen::VectorXd g = detail::log_psi_gradient(pb, f, theta, nug, true);
      const double h = 1e-6;
      for (int k = 0; k < 4; ++k) {
        Eigen::VectorXd tp = theta, tm = theta;
        double np = nug, nm = nug;
        if (k < 3)
          tp[k] *= std::exp(h), tm[k] *= std::exp(-h);
        else
          np *= std::exp(h), nm *= std::exp(-h);
        const double fd = (detail::factorize(pb, tp, np).log_psi - detail::factorize(pb, tm, nm).log_psi) / (2 * h);
        INFO("corr " << corr_name(c) << " trend " << trend_name(t) << " component " << k);
        CHECK(std::abs(g[k] - fd) < 1e-6 * (1 + std::abs(fd)));
      }
    }
  }
}
