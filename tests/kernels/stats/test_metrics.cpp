// PR, intersection area, area metric and log-likelihood against closed forms and spec §8.
#include <catch2/catch.hpp>
#include <cmath>

#include "core/normal.hpp"
#include "stats/ecdf.hpp"
#include "stats/kde.hpp"
#include "stats/metrics.hpp"
#include "stats/quadrature.hpp"

using Catch::Matchers::WithinAbs;

namespace {
// N(m, s²) as a one-point KDE (exactly normal).
std::shared_ptr<smi::Kde> normal(double m, double s) { return std::make_shared<smi::Kde>(Eigen::VectorXd::Constant(1, m), s); }
Eigen::VectorXd spec_x() {
  Eigen::VectorXd x(9);
  x << 30.12, 30.45, 29.88, 30.61, 30.02, 29.75, 30.33, 30.90, 30.20;
  return x;
}
}  // namespace

TEST_CASE("Gauss-Kronrod is exact for polynomials and accurate for smooth functions") {
  CHECK_THAT(smi::integrate([](double x) { return std::pow(x, 20); }, 0.0, 1.0), WithinAbs(1.0 / 21.0, 1e-15));
  CHECK_THAT(smi::integrate([](double x) { return std::exp(x); }, 0.0, 1.0), WithinAbs(std::exp(1.0) - 1.0, 1e-14));
  CHECK_THAT(smi::integrate([](double x) { return std::abs(x - 0.3); }, 0.0, 1.0), WithinAbs(0.29, 1e-11));
}

TEST_CASE("PR closed forms (spec 8.2)") {
  // Trapezoid on the default 4001-node grid: the kinks of |f − g| cost ~1e-6.
  CHECK_THAT(smi::pr(*normal(0, 1), *normal(1, 1)), WithinAbs(0.7658498451, 3e-6));
  CHECK_THAT(smi::pr(*normal(0, 1), *normal(0, 2)), WithinAbs(0.6453491377, 3e-6));
  CHECK_THAT(smi::pr(*normal(0, 1), *normal(3, 0.5)), WithinAbs(1.9148256636, 1e-8));
  CHECK_THAT(smi::pr(*normal(0, 1), *normal(0, 1)), WithinAbs(0.0, 1e-15));
  smi::Kde kx(spec_x(), 0.2481836818);
  const smi::Grid g{27.0, 33.5, 26001};
  CHECK_THAT(smi::pr(kx, *normal(30.25, 0.36), g), WithinAbs(0.2050389, 1e-7));
  // On grid values directly.
  const Eigen::VectorXd f = smi::pdf_grid(*normal(0, 1), smi::Grid{-10, 11, 4001});
  const Eigen::VectorXd h = smi::pdf_grid(*normal(1, 1), smi::Grid{-10, 11, 4001});
  CHECK_THAT(smi::l1_area_on_grid(f, h, smi::Grid{-10, 11, 4001}), WithinAbs(0.7658498451, 3e-6));
  CHECK_THAT(smi::intersection_area_on_grid(f, h, smi::Grid{-10, 11, 4001}), WithinAbs(1 - 0.7658498451 / 2, 1e-6));
}

TEST_CASE("intersection area of KDE_X and KDE_T (spec 8.1)") {
  Eigen::VectorXd t(11);
  t << spec_x(), 29.6, 31.0;
  smi::Kde kx(spec_x(), 0.2481836818), kt(t, 0.2962746807);
  const smi::Grid g = smi::Grid::covering(t, 0.2962746807, 20001);
  CHECK_THAT(smi::intersection_area(kx, kt, g), WithinAbs(0.88453, 1e-5));
}

TEST_CASE("area metric: closed forms") {
  // ECDF of one point at 0 vs N(0,1): ∫ F over (−∞,0) + ∫ (1−F) over (0,∞) = 2 φ(0).
  CHECK_THAT(smi::area_metric(Eigen::VectorXd::Zero(1), *normal(0, 1)), WithinAbs(2 * smi::kInvSqrt2Pi, 1e-9));
  // Shift of a normal by d: area = |d|.
  CHECK_THAT(smi::area_metric(*normal(0, 1), *normal(0.7, 1)), WithinAbs(0.7, 1e-9));
  // Two step CDFs, exact.
  Eigen::VectorXd a(3), b(2);
  a << 0, 1, 2;
  b << 0.5, 3;
  // S_a − S_b on [0,.5):1/3, [.5,1):1/3−1/2, [1,2):2/3−1/2, [2,3):1−1/2.
  CHECK_THAT(smi::area_metric_samples(a, b), WithinAbs(0.5 / 3 + 0.5 / 6 + 1.0 / 6 + 0.5, 1e-15));
  smi::Ecdf ea(a), eb(b);
  CHECK_THAT(smi::area_metric(ea, eb), WithinAbs(0.5 / 3 + 0.5 / 6 + 1.0 / 6 + 0.5, 1e-15));
  CHECK_THROWS_WITH(ea.pdf(0.0), Catch::Contains("no density"));
}

TEST_CASE("log-likelihood (spec 8.2)") {
  CHECK_THAT(-smi::loglik(spec_x(), *normal(30.25, 0.36)), WithinAbs(3.1562182871, 1e-9));
  int floored = 0;
  smi::loglik(Eigen::VectorXd::Constant(1, 1e6), *normal(0, 1), 1e-300, &floored);
  CHECK(floored == 1);
}
