// SPDX-License-Identifier: MIT
// The fused Gaussian-mean kernel against a direct long-double sum, its independence of how
// rows are blocked, and the thread-count independence of the CRN sample.
#include <catch2/catch.hpp>
#include <cmath>

#include "kernels/stats/families.hpp"
#include "kernels/surrogate/fused_mean.hpp"
#include "kernels/surrogate/kriging.hpp"
#include "kernels/surrogate/propagate.hpp"
#include "platform/core/rng.hpp"

using namespace smi::surrogate::kriging;

TEST_CASE("fused Gaussian sum equals the direct sum in long double") {
  if (!detail::fused_gauss_available()) return;  // CPU without AVX2/FMA: the GEMM path is used
  smi::Rng rng(5, smi::hash_label("test/fused"));
  const Eigen::Index nr = 19, m = 37, d = 5;  // neither a multiple of the 8 points / 4 sites
  const Eigen::MatrixXd Xw = rng.uniform_matrix(nr, d) * 2.0;
  const detail::RowMatrix Sw = rng.uniform_matrix(m, d) * 2.0;
  const Eigen::VectorXd g = rng.uniform(m, -1.0, 1.0);
  Eigen::VectorXd out(nr);
  detail::fused_gauss_sum(Xw, Sw, g, out.data());
  for (Eigen::Index i = 0; i < nr; ++i) {
    long double ref = 0, scale = 0;
    for (Eigen::Index k = 0; k < m; ++k) {
      long double s = 0;
      for (Eigen::Index j = 0; j < d; ++j) s += (static_cast<long double>(Xw(i, j)) - Sw(k, j)) * (Xw(i, j) - Sw(k, j));
      ref += g[k] * std::exp(-s);
      scale += std::abs(g[k]) * std::exp(-s);
    }
    CHECK(std::abs(out[i] - static_cast<double>(ref)) <= 1e-15 * static_cast<double>(scale) * m);
  }
  // Each row's value depends on that row only: computed alone it is the same to the bit.
  for (Eigen::Index i : {0, 7, 8, 18}) {
    double one = 0;
    detail::fused_gauss_sum(Xw.row(i), Sw, g, &one);
    CHECK(one == out[i]);
  }
}

TEST_CASE("predict_mean equals predict's mean and the correlation-matrix form") {
  smi::Rng rng(9, smi::hash_label("test/fused-model"));
  const Eigen::MatrixXd X = rng.uniform_matrix(30, 3);
  Eigen::VectorXd y(30);
  for (int i = 0; i < 30; ++i) y[i] = std::sin(3 * X(i, 0)) + X(i, 1) * X(i, 2);
  FitOptions o;
  o.theta = Eigen::VectorXd::Constant(3, 2.0);
  const Model md = fit(X, y, o);
  const Eigen::MatrixXd Z = rng.uniform_matrix(301, 3);
  const Eigen::VectorXd a = predict_mean(md, Z, 2), b = predict_mean(md, Z, 1);
  const Prediction p = predict(md, Z);
  CHECK(a == b);
  CHECK(a == p.mean);
  const Eigen::MatrixXd Zn = (Z.rowwise() - md.mS).array().rowwise() / md.sS.array();
  const Eigen::VectorXd ref =
      (md.mY + md.sY * (trend_basis(md.trend, Zn) * md.beta + cross_correlation(md.corr, md.theta, Zn, md.S) * md.gamma).array())
          .matrix();
  CHECK((a - ref).cwiseAbs().maxCoeff() <= 1e-12 * ref.cwiseAbs().maxCoeff());
}

TEST_CASE("crn_sample does not depend on the thread count") {
  std::vector<smi::surrogate::propagate::Input> in = {{"a", std::make_shared<smi::stats::Normal>(1.0, 2.0), 0.0},
                                           {"c", nullptr, 3.5},
                                           {"b", std::make_shared<smi::stats::Normal>(0.0, 1.0), 0.0}};
  const Eigen::MatrixXd s1 = smi::surrogate::propagate::crn_sample(in, 100003, 7, "base", 1);
  const Eigen::MatrixXd s2 = smi::surrogate::propagate::crn_sample(in, 100003, 7, "base", 2);
  CHECK(s1 == s2);
  CHECK((s1.col(1).array() == 3.5).all());
  const Eigen::VectorXd u = smi::surrogate::propagate::crn_uniforms("b", 100003, 7, "base");
  CHECK(s1.col(2) == in[2].dist->quantile(u));
}
