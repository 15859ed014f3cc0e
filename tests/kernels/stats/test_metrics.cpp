// SPDX-License-Identifier: MIT
// PR, intersection area, area metric and log-likelihood against closed forms and spec §8.
#include <catch2/catch.hpp>
#include <cmath>

#include "kernels/stats/ecdf.hpp"
#include "kernels/stats/kde.hpp"
#include "kernels/stats/metrics.hpp"
#include "kernels/stats/quadrature.hpp"
#include "platform/core/normal.hpp"

using Catch::Matchers::WithinAbs;

namespace {
// N(m, s²) as a one-point KDE (exactly normal).
std::shared_ptr<smi::stats::Kde> normal(double m, double s) { return std::make_shared<smi::stats::Kde>(Eigen::VectorXd::Constant(1, m), s); }
Eigen::VectorXd spec_x() {
  Eigen::VectorXd x(9);
  x << 30.12, 30.45, 29.88, 30.61, 30.02, 29.75, 30.33, 30.90, 30.20;
  return x;
}
}  // namespace

TEST_CASE("Gauss-Kronrod is exact for polynomials and accurate for smooth functions") {
  CHECK_THAT(smi::stats::integrate([](double x) { return std::pow(x, 20); }, 0.0, 1.0), WithinAbs(1.0 / 21.0, 1e-15));
  CHECK_THAT(smi::stats::integrate([](double x) { return std::exp(x); }, 0.0, 1.0), WithinAbs(std::exp(1.0) - 1.0, 1e-14));
  CHECK_THAT(smi::stats::integrate([](double x) { return std::abs(x - 0.3); }, 0.0, 1.0), WithinAbs(0.29, 1e-11));
}

TEST_CASE("PR closed forms (spec 8.2)") {
  // Trapezoid on the default 4001-node grid: the kinks of |f − g| cost ~1e-6.
  CHECK_THAT(smi::stats::pr(*normal(0, 1), *normal(1, 1)), WithinAbs(0.7658498451, 3e-6));
  CHECK_THAT(smi::stats::pr(*normal(0, 1), *normal(0, 2)), WithinAbs(0.6453491377, 3e-6));
  CHECK_THAT(smi::stats::pr(*normal(0, 1), *normal(3, 0.5)), WithinAbs(1.9148256636, 1e-8));
  CHECK_THAT(smi::stats::pr(*normal(0, 1), *normal(0, 1)), WithinAbs(0.0, 1e-15));
  smi::stats::Kde kx(spec_x(), 0.2481836818);
  const smi::stats::Grid g{27.0, 33.5, 26001};
  CHECK_THAT(smi::stats::pr(kx, *normal(30.25, 0.36), g), WithinAbs(0.2050389, 1e-7));
  // On grid values directly.
  const Eigen::VectorXd f = smi::stats::pdf_grid(*normal(0, 1), smi::stats::Grid{-10, 11, 4001});
  const Eigen::VectorXd h = smi::stats::pdf_grid(*normal(1, 1), smi::stats::Grid{-10, 11, 4001});
  CHECK_THAT(smi::stats::l1_area_on_grid(f, h, smi::stats::Grid{-10, 11, 4001}), WithinAbs(0.7658498451, 3e-6));
  CHECK_THAT(smi::stats::intersection_area_on_grid(f, h, smi::stats::Grid{-10, 11, 4001}), WithinAbs(1 - 0.7658498451 / 2, 1e-6));
}

TEST_CASE("intersection area of KDE_X and KDE_T (spec 8.1)") {
  Eigen::VectorXd t(11);
  t << spec_x(), 29.6, 31.0;
  smi::stats::Kde kx(spec_x(), 0.2481836818), kt(t, 0.2962746807);
  const smi::stats::Grid g = smi::stats::Grid::covering(t, 0.2962746807, 20001);
  CHECK_THAT(smi::stats::intersection_area(kx, kt, g), WithinAbs(0.88453, 1e-5));
}

TEST_CASE("area metric: closed forms") {
  // ECDF of one point at 0 vs N(0,1): ∫ F over (−∞,0) + ∫ (1−F) over (0,∞) = 2 φ(0).
  CHECK_THAT(smi::stats::area_metric(Eigen::VectorXd::Zero(1), *normal(0, 1)), WithinAbs(2 * smi::kInvSqrt2Pi, 1e-9));
  // Shift of a normal by d: area = |d|.
  CHECK_THAT(smi::stats::area_metric(*normal(0, 1), *normal(0.7, 1)), WithinAbs(0.7, 1e-9));
  // Two step CDFs, exact.
  Eigen::VectorXd a(3), b(2);
  a << 0, 1, 2;
  b << 0.5, 3;
  // S_a − S_b on [0,.5):1/3, [.5,1):1/3−1/2, [1,2):2/3−1/2, [2,3):1−1/2.
  CHECK_THAT(smi::stats::area_metric_samples(a, b), WithinAbs(0.5 / 3 + 0.5 / 6 + 1.0 / 6 + 0.5, 1e-15));
  smi::stats::Ecdf ea(a), eb(b);
  CHECK_THAT(smi::stats::area_metric(ea, eb), WithinAbs(0.5 / 3 + 0.5 / 6 + 1.0 / 6 + 0.5, 1e-15));
  CHECK_THROWS_WITH(ea.pdf(0.0), Catch::Contains("no density"));
}

TEST_CASE("log-likelihood (spec 8.2)") {
  CHECK_THAT(-smi::stats::loglik(spec_x(), *normal(30.25, 0.36)), WithinAbs(3.1562182871, 1e-9));
  int floored = 0;
  smi::stats::loglik(Eigen::VectorXd::Constant(1, 1e6), *normal(0, 1), 1e-300, &floored);
  CHECK(floored == 1);
}

// ---- pdfs infinite at a bound, narrow, skewed; never NaN ----------------

#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "kernels/stats/families.hpp"
#include "kernels/stats/pdf_overlap.hpp"

namespace {
using DPtr = std::shared_ptr<smi::stats::Distribution>;
// The pairs of tests/reference/metrics_overlap.py (same parameters).
std::map<std::string, std::pair<DPtr, DPtr>> overlap_pairs() {
  using namespace smi;
  const double inf = std::numeric_limits<double>::infinity();
  return {
      {"gamma05_gamma2", {std::make_shared<stats::Gamma>(0.5, 1.0), std::make_shared<stats::Gamma>(2.0, 1.0)}},
      {"gamma03_gamma03s15", {std::make_shared<stats::Gamma>(0.3, 1.0), std::make_shared<stats::Gamma>(0.3, 1.5)}},
      {"beta05_beta2", {std::make_shared<stats::Beta>(0.5, 0.5), std::make_shared<stats::Beta>(2.0, 2.0)}},
      {"weibull07_lognormal",
       {std::make_shared<stats::Weibull>(0.7, 1.0), std::make_shared<stats::LogNormal>(stats::LogNormal::from_log_params(0.0, 0.8))}},
      {"normal_narrow", {std::make_shared<stats::Normal>(0.0, 1.0), std::make_shared<stats::Normal>(0.0, 0.01)}},
      {"lognormal_mode009_gamma",
       {std::make_shared<stats::LogNormal>(stats::LogNormal::from_log_params(0.0, 1.55)), std::make_shared<stats::Gamma>(2.0, 0.5)}},
      {"truncnormal_uniform", {std::make_shared<stats::TruncNormal>(0.0, 1.0, 0.0, inf), std::make_shared<stats::Uniform>(0.0, 2.0)}},
  };
}

/// A density that is NaN on (1, 2): it cannot be integrated.
struct BrokenPdf : smi::stats::Normal {
  BrokenPdf() : smi::stats::Normal(0.0, 1.0) {}
  using smi::stats::Normal::pdf;
  double pdf(double x) const override { return x > 1 && x < 2 ? std::nan("") : smi::stats::Normal::pdf(x); }
  Eigen::VectorXd pdf(const Eigen::VectorXd& x) const override { return x.unaryExpr([&](double v) { return pdf(v); }); }
  std::string describe() const override { return "broken(nan on (1, 2))"; }
};
}  // namespace

TEST_CASE("PR and intersection match SciPy quad for singular, narrow and skewed pdfs") {
  const auto pairs = overlap_pairs();
  std::ifstream in(std::string(SMI_TEST_REFERENCE_DIR) + "/metrics_overlap.csv");
  REQUIRE(in.good());
  std::string line;
  std::getline(in, line);
  int n = 0;
  while (std::getline(in, line)) {
    std::stringstream ss(line);
    std::string name, spr, sia;
    std::getline(ss, name, ',');
    std::getline(ss, spr, ',');
    std::getline(ss, sia, ',');
    REQUIRE(pairs.count(name) == 1);
    const auto& [a, b] = pairs.at(name);
    INFO(name);
    CHECK_THAT(smi::stats::pr(*a, *b), WithinAbs(std::stod(spr), 1e-9));
    CHECK_THAT(smi::stats::intersection_area(*a, *b), WithinAbs(std::stod(sia), 1e-9));
    ++n;
  }
  CHECK(n == static_cast<int>(pairs.size()));
}

TEST_CASE("PR and intersection: closed forms") {
  // Equal stds: the crossing is the midpoint, IA = 2 Φ(−|Δ|/2σ).
  const smi::stats::Normal n0(0.0, 1.0), n1(1.3, 1.0), n2(0.0, 2.0);
  CHECK_THAT(smi::stats::intersection_area(n0, n1), WithinAbs(std::erfc(0.65 / smi::kSqrt2), 1e-13));
  CHECK_THAT(smi::stats::pr(n0, n1), WithinAbs(2.0 - 2.0 * std::erfc(0.65 / smi::kSqrt2), 1e-13));
  // N(0,1) vs N(0,2) cross at ±c, c² = 8 ln 2 / 3; inside N(0,2) is lower, outside N(0,1).
  const double c = std::sqrt(8.0 * std::log(2.0) / 3.0);
  const double ia = (1.0 - std::erfc(c / 2.0 / smi::kSqrt2)) + std::erfc(c / smi::kSqrt2);
  CHECK_THAT(smi::stats::intersection_area(n0, n2), WithinAbs(ia, 1e-13));
  // Identical pdfs (one infinite at its bound): exactly 0; disjoint uniforms: exactly 2.
  const smi::stats::Gamma g(0.5, 1.0);
  CHECK(smi::stats::pr(g, g) == 0.0);
  CHECK(smi::stats::intersection_area(g, g) == Approx(1.0).epsilon(1e-15));
  CHECK(smi::stats::pr(smi::stats::Uniform(0, 1), smi::stats::Uniform(2, 3)) == 2.0);
  CHECK(smi::stats::intersection_area(smi::stats::Uniform(0, 1), smi::stats::Uniform(2, 3)) == 0.0);
}

TEST_CASE("PR on a grid never passes NaN on and stays in [0, 2]") {
  const auto pairs = overlap_pairs();
  const auto& [ga, gb] = pairs.at("gamma05_gamma2");
  // The case: a grid from 1e-9 gave PR = 79; from the bound 0 it gave NaN.
  for (const double lo : {1e-9, 0.0}) {
    const smi::stats::Grid grid{lo, 30.0, 4001};
    const auto c = smi::stats::compare_on_grid(*ga, *gb, grid);
    INFO("grid from " << lo);
    CHECK(c.warnings.size() == 1);
    CHECK_THAT(c.pr, WithinAbs(smi::stats::pdf_overlap(*ga, *gb, lo, 30.0).l1, 1e-15));
    // From 0 the window holds all but ~1e-13 of both masses; from 1e-9 it misses gamma(1/2)'s
    // P(X < 1e-9) = erf(sqrt(1e-9)) = 3.57e-5.
    CHECK_THAT(c.pr + (lo > 0 ? std::erf(std::sqrt(lo)) : 0.0), WithinAbs(1.2151640199055147, 1e-9));
    CHECK(c.intersection >= 0.0);
    CHECK(c.intersection <= 1.0);
  }
  // Lognormal with its mode at 0.09 on a step of 0.36: it integrates to ~1.06 there; warned.
  const auto& [la, lb] = pairs.at("lognormal_mode009_gamma");
  const auto c = smi::stats::compare_on_grid(*la, *lb, smi::stats::Grid{0.0, 36.0, 101});
  REQUIRE(c.warnings.size() >= 1);
  CHECK_THAT(c.warnings[0], Catch::Contains("lognormal") && Catch::Contains("not 1"));
  // Beyond 36 only the lognormal has mass (1.04e-2): the window's PR plus that is the full PR.
  CHECK_THAT(c.pr + la->sf(36.0) - lb->sf(36.0), WithinAbs(0.6724439598420426, 1e-9));
  // A grid that resolves both pdfs keeps the trapezoid and says nothing.
  const smi::stats::Normal n0(0.0, 1.0), n1(1.0, 1.0);
  const auto ok = smi::stats::compare_on_grid(n0, n1, smi::stats::Grid{-10, 11, 4001});
  CHECK(ok.warnings.empty());
  CHECK_THAT(ok.pr, WithinAbs(0.7658498451, 3e-6));
  // pdf_grid gives a finite cell mean at an infinite node.
  const Eigen::VectorXd f = smi::stats::pdf_grid(*ga, smi::stats::Grid{0.0, 1.0, 11});
  CHECK(f.allFinite());
  CHECK_THAT(f[0], WithinAbs(std::erf(std::sqrt(0.05)) / 0.1, 1e-12));  // P(X < 0.05)/0.1 for gamma(1/2)
}

TEST_CASE("a pdf that cannot be integrated is named") {
  const BrokenPdf bad;
  const smi::stats::Normal n(0.0, 1.0);
  CHECK_THROWS_WITH(smi::stats::pr(bad, n), Catch::Contains("broken(nan on (1, 2))") && Catch::Contains("cannot be integrated"));
  CHECK_THROWS_WITH(smi::stats::pr(bad, n, smi::stats::Grid{-5, 5, 4001}), Catch::Contains("broken(nan on (1, 2))"));
  Eigen::VectorXd y(2);
  y << 0.0, 1.5;
  CHECK_THROWS_WITH(smi::stats::loglik(y, bad), Catch::Contains("data[2] = 1.5"));
  // A density infinite at an observation: the likelihood is unbounded, said so.
  CHECK_THROWS_WITH(smi::stats::loglik(Eigen::VectorXd::Zero(1), smi::stats::Gamma(0.5, 1.0)), Catch::Contains("unbounded"));
  // Far tails through logpdf: N(0,1) at 30 has log density −450.92, no floor needed.
  int floored = 0;
  CHECK_THAT(smi::stats::loglik(Eigen::VectorXd::Constant(1, 30.0), n, 1e-300, &floored), WithinAbs(-450.0 - 0.9189385332046727, 1e-9));
  CHECK(floored == 0);
}
